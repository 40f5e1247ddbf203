"""The fingertip study's plumbing (issue 14): cases run or reused, the summary's comparisons,
the figures. The FEM and the single chamber are replaced by stand-in curves here (the real ones
take hours; ``make fingertip-fem``); the fast estimate is real (membrane)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from spsc.cad.specs import FingertipSpec
from spsc.core.curve import Curve
from spsc.studies import fingertip as ff
from spsc.studies.fingertip_figures import draw_all

POCKETS = ("pulp1", "pulp2", "pulp3", "distal1", "distal2")


def _stand_in(site, pressure, scale=1.0, with_pockets=True):
    y = np.linspace(0, 3, 7)
    F = scale * 2.0 * y**1.3
    P = pressure + scale * 1.5 * y
    series = {}
    if with_pockets:
        for k, name in enumerate(POCKETS):
            share = (0.6 if name == f"{site}2" or name == f"{site}1" else 0.05)
            series[f"force_{name}_N"] = share * F
    return Curve(y, F, P, 10 * y, 5 * y, model="fem-part", series=series)


@pytest.fixture
def study_dir(tmp_path, monkeypatch):
    calls = []

    def fem_case(study, stl, design, site, mode, p, path, vtu, log):
        calls.append((site, mode, p))
        c = _stand_in(site, p)
        c.to_json(path)
        return c

    def single_case(study, g, mode, p, path):
        c = _stand_in("x", p, scale=1.6, with_pockets=False)
        c.to_json(path)
        return c

    monkeypatch.setattr(ff, "_fem_case", fem_case)
    monkeypatch.setattr(ff, "_single_case", single_case)
    spec = FingertipSpec()
    design = {"cavity_volume_mm3": spec.pulp.cavity_volume() + spec.distal.cavity_volume() + 200}
    (tmp_path / "x.stl").write_bytes(b"solid stand-in\nendsolid stand-in\n")
    return tmp_path, spec, design, calls


def test_the_study_runs_each_case_once_and_compares(study_dir):
    out, spec, design, calls = study_dir
    study = ff.FingertipStudy(cases=(("pulp", "high", 40.0), ("distal", "low", 10.0)),
                              fast_model="membrane")
    s = ff.run_study(study, out, stl=out / "x.stl", design=design, spec=spec, log=lambda m: None)
    assert calls == [("pulp", "high", 40.0), ("distal", "low", 10.0)]
    assert abs(s["channel_mm3"] - 200) < 1e-9
    row = s["cases"]["pulp-high-40kPa"]
    # the stand-in single chamber is 1.6x as sensitive: the ratio is 1/1.6
    assert row["sensitivity_ratio_fused_to_single"] == pytest.approx(1 / 1.6, rel=1e-12)
    assert set(row["fem"]["pockets_N"]) == set(POCKETS)
    assert row["fast_error"]["force_max"] > 0 and "fast" in row
    assert json.loads((out / "summary.json").read_text())["cases"].keys() == s["cases"].keys()
    again = ff.run_study(study, out, stl=out / "x.stl", design=design, spec=spec,
                         log=lambda m: None)
    assert calls == [("pulp", "high", 40.0), ("distal", "low", 10.0)]  # reused, not re-run
    assert again["cases"] == s["cases"]
    # a curve is kept with the key of its inputs: another part file computes every case again
    (out / "x.stl").write_bytes(b"solid another\nendsolid another\n")
    ff.run_study(study, out, stl=out / "x.stl", design=design, spec=spec, log=lambda m: None)
    assert calls[2:] == [("pulp", "high", 40.0), ("distal", "low", 10.0)]


def test_the_figures_are_drawn(study_dir):
    out, spec, design, _ = study_dir
    study = ff.FingertipStudy(cases=(("pulp", "high", 40.0), ("distal", "high", 40.0)),
                              fast_model="membrane")
    s = ff.run_study(study, out, stl=out / "x.stl", design=design, spec=spec, log=lambda m: None)
    figs = draw_all(s, out)
    for name in ("curves", "pockets", "discrimination"):
        png = out / figs[name]
        assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"


def test_a_study_without_the_40_kpa_press_draws_without_an_empty_legend(study_dir):
    """``--cases pulp-high-10``: the discrimination panel has no 40 kPa high-mode curve to label;
    it says so instead of drawing an empty legend (matplotlib warned)."""
    import warnings

    out, spec, design, _ = study_dir
    study = ff.FingertipStudy(cases=(("pulp", "high", 10.0),), fast_model="membrane")
    s = ff.run_study(study, out, stl=out / "x.stl", design=design, spec=spec, log=lambda m: None)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        figs = draw_all(s, out)
    assert (out / figs["discrimination"]).read_bytes()[:4] == b"\x89PNG"
