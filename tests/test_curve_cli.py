"""``spsc curve --model X``: one verb for every model; ``spsc membrane`` and ``spsc fem`` are
its short forms and write the same JSON (timing apart); the model table; the error contract."""

import json
from dataclasses import dataclass

import numpy as np
import pytest

from spsc import models
from spsc.core.curve import Curve, SolveInfo
from spsc.models import Outcome, cli_options, option
from spsc.cli import curve as cmd_curve
from spsc.cli.main import build_parser, main

#: The only field allowed to differ between two runs of the same inputs: the wall-clock time,
#: kept in one place.
TIMING = (("solver", "seconds"),)


def _json_without_timing(path):
    d = json.loads(path.read_text(encoding="utf-8"))
    for keys in TIMING:
        node = d
        for k in keys[:-1]:
            node = node.get(k, {})
        node.pop(keys[-1], None)
    return d


def _same_json(tmp_path, short: list[str], long: list[str]):
    a, b = tmp_path / "short.json", tmp_path / "long.json"
    assert main([*short, "--json", str(a)]) == 0
    assert main([*long, "--json", str(b)]) == 0
    da, db = _json_without_timing(a), _json_without_timing(b)
    assert da == db  # exact: same code, same inputs, deterministic solvers
    return da


def test_membrane_short_form_is_curve_model_membrane(tmp_path):
    args = ["--type", "D", "--pressure", "30", "--reservoir", "40000", "--points", "5",
            "--meridians"]
    d = _same_json(tmp_path, ["membrane", *args], ["curve", "--model", "membrane", *args])
    assert d["model"] == "membrane" and len(d["curve"]["y_mm"]) == 5
    assert d["curve"]["y_mm"][-1] == 6.0  # the membrane's default stroke in both forms
    assert len(d["extra"]["meridians_mm"]) == 5
    assert d["solver"]["converged"] and d["solver"]["iterations"] > 0


def test_simplified_through_both_verbs(tmp_path):
    args = ["--type", "B", "--points", "7", "--stroke", "3"]
    d = _same_json(tmp_path, ["membrane", "--model", "simplified", *args],
                   ["curve", "--model", "simplified", *args])
    assert d["model"] == "simplified" and d["solver"]["converged"]


def test_fem_short_form_is_curve_model_fem(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # mesh cache under build/cache/fem here
    args = ["--type", "B", "--mesh-size", "3", "--layers", "1", "--stroke", "1", "--points",
            "3", "--quiet"]
    d = _same_json(tmp_path, ["fem", *args], ["curve", "--model", "fem", *args])
    assert d["model"] == "fem" and d["solver"]["details"]["dofs"] > 0
    assert d["solver"]["converged"] and d["curve"]["force_N"][-1] > 0


@pytest.mark.parametrize("short, long, stroke, points", [
    (["fem"], ["curve", "--model", "fem"], 4.0, 11),
    (["membrane"], ["curve", "--model", "membrane"], 6.0, 41),
    (["membrane", "--model", "simplified"], ["curve", "--model", "simplified"], 6.0, 41),
])
def test_short_forms_have_the_model_defaults(short, long, stroke, points):
    """Defaults resolved as the verb resolves them: the short form and the long form agree,
    and every option of the model has a value."""
    parser = build_parser()
    resolved = []
    for argv in (short, long):
        args = parser.parse_args([*argv, "--type", "B"])
        options = cmd_curve.model_options(args, models.MODELS[args.model])
        resolved.append(({k: v for k, v in vars(args).items()
                          if k not in ("command", "models", "func")}, options))
    (a, opt_a), (b, opt_b) = resolved
    assert a["stroke"] == b["stroke"] == stroke and a["points"] == b["points"] == points
    for key in set(a) & set(b):
        assert a[key] == b[key], key
    assert opt_a == opt_b == models.MODELS[a["model"]].Options()


def _toy_curve(geometry, material, load, converged=True):
    y = np.linspace(0.0, load.stroke_mm, load.points)
    conv = np.ones(y.size, bool)
    msg = [""] * y.size
    if not converged:
        conv[-1], msg[-1] = False, "toy: no equilibrium at the last point"
    f = np.where(conv, 2.0 * y, np.nan)
    info = SolveInfo(converged=converged, message="converged" if converged else msg[-1],
                     y_reached_mm=y[conv][-1], seconds=0.0, iterations=3)
    return Curve(y, f, 40 + y, 10 * y, 5 * y, model="toy", geometry=geometry.as_dict(),
                 material=material.name,
                 setup={"p_i_kPa": load.pressure_kPa, "reservoir_mm3": load.reservoir_mm3,
                        "polytropic_n": load.polytropic_n},
                 nominal_volume_mm3=100.0, inflated_volume_mm3=110.0, inflated_height_mm=13.0,
                 converged=conv, message=tuple(msg), solver=info)


# -- adding a model: this module (its options and its class) and one line of the registry ----
@dataclass(frozen=True)
class ToyOptions:
    """A toy model's one option (it converges while the knob is below 5)."""

    toy_knob: float = option(1.0, "--toy-knob", "a toy option", kind="number")


@dataclass(frozen=True)
class ToyModel:
    """F = 2y: a model that only says what the interface asks of a model."""

    calls: list
    name: str = "toy"
    help: str = "a toy model"
    module: str = __name__
    Options = ToyOptions
    stroke_mm: float = 2.0
    points: int = 5
    bending: bool = False
    meshed: bool = False
    fast: bool = True
    sweep: bool = True
    study: bool = True
    color: str = "C4"
    style: str = ":"
    seconds_per_point: float = 1e-3
    zero_stroke: bool = False
    contact: bool = False
    parametric: bool = True

    def load_steps(self, setup, options) -> int:
        return 0

    def check(self, setup, options, *, verb, quiet) -> None:
        pass

    def curve(self, setup, options, *, progress=None, cache_dir=None):
        self.calls.append(setup.load)
        return Outcome(_toy_curve(setup.body, setup.material, setup.load,
                                  converged=options.toy_knob < 5), {"knob": options.toy_knob})


@pytest.fixture
def toy(monkeypatch):
    """The toy model in the registry: the one line adding a model."""
    calls = []
    monkeypatch.setitem(models.MODELS, "toy", ToyModel(calls))
    return calls


def test_the_toy_model_is_a_curve_model():
    assert isinstance(ToyModel([]), models.CurveModel)
    assert set(cli_options(ToyOptions)) == {"toy_knob"}


def test_a_model_is_one_module_and_one_registry_line(toy, tmp_path, capsys):
    j, c = tmp_path / "t.json", tmp_path / "t.csv"
    assert main(["curve", "--model", "toy", "--type", "A", "--json", str(j), "--csv", str(c)]) == 0
    assert len(toy) == 1 and toy[0].stroke_mm == 2.0 and toy[0].points == 5  # its defaults
    d = json.loads(j.read_text(encoding="utf-8"))
    assert d["model"] == "toy" and d["extra"] == {"knob": 1.0}
    assert Curve.from_csv(c).force_N[-1] == 4.0
    assert "--toy-knob" in _help(["curve"], capsys)
    # its option belongs to it: refused with another model, before any work
    assert main(["curve", "--model", "membrane", "--type", "A", "--toy-knob", "2"]) == 2
    assert "--toy-knob = 2.0 is invalid: allowed only with --model toy" in capsys.readouterr().err


def test_not_converged_exits_1_and_keeps_what_was_computed(toy, tmp_path, capsys):
    j = tmp_path / "t.json"
    assert main(["curve", "--model", "toy", "--type", "A", "--toy-knob", "9",
                 "--json", str(j)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["spsc curve: not converged: toy: no equilibrium at the last point"]
    c = Curve.from_json(j)
    assert c.converged.tolist() == [True] * 4 + [False] and np.isnan(c.force_N[-1])
    assert c.force_N[3] == pytest.approx(3.0) and not c.solver.converged


@pytest.mark.parametrize("argv, message", [
    (["--json", "{tmp}/no/such/folder/x.json"], "--json = "),
    (["--json", "{tmp}"], "this is a folder"),
    (["--png", "{tmp}/plot.xyz"], "--png = "),
    (["--csv", "{tmp}/x.json/y.csv"], "--csv = "),
])
def test_output_paths_are_checked_before_the_work(toy, tmp_path, capsys, argv, message):
    (tmp_path / "x.json").write_text("{}", encoding="utf-8")
    argv = [a.format(tmp=tmp_path) for a in argv]
    assert main(["curve", "--model", "toy", "--type", "A", *argv]) == 2
    err = capsys.readouterr().err
    assert not toy and err.count("\n") == 1 and message in err
    assert err.startswith("spsc curve: error: ")


def test_an_os_error_while_writing_is_one_line(toy, tmp_path, capsys, monkeypatch):
    def full_disk(self, *a, **k):
        raise OSError(28, "No space left on device", str(tmp_path / "t.json"))
    monkeypatch.setattr(Curve, "to_json", full_disk)
    assert main(["curve", "--model", "toy", "--type", "A", "--json",
                 str(tmp_path / "t.json")]) == 2
    err = capsys.readouterr().err
    assert err == f"spsc curve: error: {tmp_path / 't.json'}: No space left on device\n"


def test_warnings_go_to_stderr(toy, capsys):
    # l/w = 3.6 is outside the covered design space (l/w <= 3): a warning, not an error
    assert main(["curve", "--model", "toy", "--type", "A", "--l", "40"]) == 0
    out, err = capsys.readouterr()
    assert "warning" not in out and "toy model" in out
    assert err.startswith("spsc curve: warning: ") and err.count("\n") == 1


def _help(argv, capsys) -> str:
    assert main([*argv, "--help"]) == 0
    return capsys.readouterr().out


def test_json_holds_the_plate_positions_as_decimals(tmp_path):
    """3 mm in 21 points is a 0.15 mm grid: the JSON text holds 0.45, not np.linspace's
    0.44999999999999996 (exact equality: each y is the float nearest the decimal k * 0.15)."""
    from decimal import Decimal

    path = tmp_path / "s.json"
    assert main(["curve", "--model", "simplified", "--type", "B", "--stroke", "3",
                 "--points", "21", "--json", str(path), "--quiet"]) == 0
    text = path.read_text(encoding="utf-8")
    assert "0.44999999999999996" not in text and "0.45," in text
    ys = json.loads(text)["curve"]["y_mm"]
    assert ys == [float(Decimal("0.15") * k) for k in range(21)]
    assert np.linspace(0.0, 3.0, 21)[3] != 0.45  # what the models compute before the curve


def test_plot_title_names_every_geometry_parameter_and_the_load(tmp_path):
    """The PNG's title holds the seven parameters (t0 was missing) and the load case."""
    from spsc.cad.geometry import preset

    g = preset("D").as_dict()
    z = np.zeros(3)
    curve = Curve(y_mm=[0.0, 0.5, 1.0], force_N=z, pressure_kPa=z, contact_area_mm2=z,
                  volume_change_mm3=z, model="simplified", geometry=g, material="tpu60a",
                  setup={"p_i_kPa": 40.0, "reservoir_mm3": 0.0, "polytropic_n": 1.0})
    t = cmd_curve.title(curve)
    for k in ("w", "h", "l", "t0", "n1", "n2", "cy"):
        assert f"{k}={g[k]:g}" in t, k
    assert "p_i=40 kPa" in t and "V_r=0 mm³" in t and "n=1" in t and "tpu60a" in t
