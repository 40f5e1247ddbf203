"""The detectors' protocol (issue 47): a detector added as one class and one registry line runs
through ``spsc sense`` end to end —

* named by ``--detectors``, its events land in events.json beside the built-in ones (which it
  leaves as they were), at the sample the :class:`~spsc.sensing.protocol.Sample` it reads says,
  and in sense.png in the colour it declares;
* a name the registry does not hold (or a built-in one, or one twice) is refused in one line
  naming ``--detectors`` with exit 2, before the chamber is mapped;
* ``SenseParams`` keeps its keyword fields and lists the detectors in the order they run; the
  figure draws a kind no detector declares in the default colour.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import matplotlib.axes
import pandas as pd
import pytest

from spsc.cli.main import main
from spsc.core.errors import ParameterError
from spsc.sensing import EstimatorParams, SenseParams
from spsc.sensing.chamber import chamber_map
from spsc.sensing.detectors import (DETECTORS, ComplianceParams, ContactParams, LeakParams,
                                    SlipParams)
from spsc.sensing.output import DEFAULT_COLOUR, figure
from spsc_support import sense_traces as st

CHAMBER = ["--type", "B", "--l", "0", "--pressure", "40", "--reservoir", "40000", "--stroke",
           "3", "--mesh-size", "1.0", "--quiet"]


class OverPressure:
    """The toy: in contact, the filtered pressure above ``level_kPa``, once per contact."""

    name, kinds = "over_pressure", {"over_pressure": "C7"}

    @dataclass(frozen=True)
    class Params:
        level_kPa: float = 41.0

    def __init__(self, params, context):
        self.level, self.armed = params.level_kPa, True

    def detect(self, s):
        if not s.in_contact:
            self.armed = True
        elif self.armed and s.filtered_kPa > self.level:
            self.armed = False
            return {"t_s": s.t_s, "kind": "over_pressure",
                    "trigger": f"P_f {s.filtered_kPa:.4g} kPa > {self.level:g} kPa"}
        return None


@pytest.fixture
def registered(monkeypatch):
    monkeypatch.setitem(DETECTORS, "over_pressure", OverPressure)  # the one registry line


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("sense-cache")


@pytest.fixture(scope="module")
def press_log(cache, tmp_path_factory):
    """A 2 mm press of the Type B dome at 20 mm/s (the 1 mm mesh's map: a few seconds)."""
    m = chamber_map({"type": "B", "l": 0}, setup_kPa=40.0, reservoir_mm3=40000.0,
                    stroke_mm=3.0, mesh_size=1.0, cache_dir=cache)
    trial = st.press(m, depth_mm=2.0, speed_mm_s=20.0, hold_s=0.3, seed=11)
    path = tmp_path_factory.mktemp("logs") / "press.csv"
    trial.log.to_csv(path, index=False)
    return path


def _sense(log, out, cache, *extra):
    assert main(["sense", str(log), "--out", str(out), "--cache", str(cache), *CHAMBER,
                 *extra]) == 0
    run = json.loads((out / "events.json").read_text())
    return run["events"], run["run"], pd.read_parquet(out / "estimate.parquet")


def test_a_toy_detector_runs_through_spsc_sense(registered, press_log, cache, tmp_path,
                                               monkeypatch):
    lines = []  # (t, colour) of each event line sense.png draws
    draw = matplotlib.axes.Axes.axvline

    def spy(ax, x=0, *args, **kw):
        lines.append((x, kw.get("color")))
        return draw(ax, x, *args, **kw)

    monkeypatch.setattr(matplotlib.axes.Axes, "axvline", spy)
    plain, run0, _ = _sense(press_log, tmp_path / "plain", cache)
    assert [e["kind"] for e in plain] == ["contact", "release"] and run0["detectors"] == ["slip", "leak"]
    lines.clear()
    events, run, est = _sense(press_log, tmp_path / "toy", cache, "--detectors", "over_pressure")
    assert [e["kind"] for e in events] == ["contact", "over_pressure", "release"]
    assert run["detectors"] == ["slip", "leak", "over_pressure"]
    assert [e for e in events if e["kind"] != "over_pressure"] == plain  # the others as they were
    # the sample the toy fired on: the first in contact above its level (the gas is isothermal:
    # the filtered pressure it reads is the estimate's)
    above = est[est.in_contact & (est.pressure_filtered_kPa > OverPressure.Params().level_kPa)]
    toy = events[1]
    assert toy["t_s"] == above.t_s.iloc[0] and "> 41 kPa" in toy["trigger"]
    assert (toy["t_s"], "C7") in lines and (events[0]["t_s"], "C2") in lines


@pytest.mark.parametrize("value, needle", [
    ("psychic", "'psychic' is invalid: allowed a comma list of the registered detectors"),
    ("over_pressure,psychic", "'psychic' is invalid"),
    ("over_pressure,,over_pressure", "'over_pressure,,over_pressure' is invalid"),
    ("over_pressure, over_pressure", "each name once (over_pressure twice)"),
    ("slip", "'slip' is invalid: allowed a detector not already on (slip runs always)"),
    ("compliance", "compliance runs with --stiff-mm-per-deg"),
])
def test_a_bad_name_is_one_line_before_any_work(registered, press_log, tmp_path, monkeypatch,
                                                capsys, value, needle):
    def work(*args):
        raise AssertionError("the chamber was checked before --detectors")

    monkeypatch.setattr("spsc.cli.sense._check_chamber", work)
    assert main(["sense", str(press_log), "--out", str(tmp_path / "o"), *CHAMBER,
                 "--detectors", value]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("spsc sense: error: --detectors = ")
    assert needle in err
    if "comma list" in needle:
        assert err.endswith(": over_pressure")  # the allowed names
    assert not (tmp_path / "o").exists()


def test_sense_params_keep_their_fields_and_list_the_detectors(registered):
    est = EstimatorParams(40.0, 40000.0, 0.086, 0.05)
    toy, comp = OverPressure.Params(42.0), ComplianceParams(0.06)
    prm = SenseParams(est, contact=ContactParams(method="threshold"), slip=SlipParams(),
                      compliance=comp, extra_detectors=[toy])
    assert prm.detectors == (SlipParams(), comp, LeakParams(), toy)
    assert prm.extra_detectors == (toy,)
    assert SenseParams(est).detectors == (SlipParams(), LeakParams())
    assert SenseParams(est, slip=None, leak=None).detectors == ()


def test_parameters_of_no_registered_detector_are_refused():
    est = EstimatorParams(40.0, 40000.0, 0.086, 0.05)
    with pytest.raises(ParameterError, match="detector parameters = 'Params' is invalid: "
                       "allowed the Params of a registered detector"):
        SenseParams(est, extra_detectors=(OverPressure.Params(),))  # not registered here


def test_an_undeclared_kind_is_drawn_in_the_default_colour(tmp_path, monkeypatch):
    lines = []
    monkeypatch.setattr(matplotlib.axes.Axes, "axvline",
                        lambda ax, x=0, *a, **kw: lines.append((x, kw.get("color"))))
    t = [0.0, 0.001, 0.002]
    table = pd.DataFrame({"t_s": t, "pressure_kPa": 40.0, "pressure_filtered_kPa": 40.0,
                          "force_N": 0.0, "force_lo_N": 0.0, "force_hi_N": 0.0,
                          "mode": "high"})
    figure(table, [{"t_s": 0.001, "kind": "contact"}, {"t_s": 0.002, "kind": "mystery"}],
           tmp_path / "f.png", {"contact": "C2"})
    assert set(lines) == {(0.001, "C2"), (0.002, DEFAULT_COLOUR)}
