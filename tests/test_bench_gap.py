"""The bench-gap study (:mod:`spsc.studies.bench_gap`) and its report section
(:mod:`spsc.report.gap`): each factor's row is the headline means of its runs over its window,
against the bench and the baseline; the section says what the rows say."""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.curve import Curve
from spsc.studies import bench_gap

#: a fake chamber per run set: F = a y + C y², P = p_i + b y (any type and mode)
A = {"long": 4.0, "mu0.3": 4.05, "mu0.6": 4.1, "stick": 4.2, "thin": 3.6, "thick": 4.4,
     "stiffest": 4.6, "material:fit": 5.0, "stiffest:fit": 6.5}
B = {"long": 4.0, "mu0.3": 3.8, "mu0.6": 3.7, "stick": 3.5, "thin": 4.1, "thick": 3.9,
     "stiffest": 3.4, "material:fit": 4.8, "stiffest:fit": 4.4}
C = 0.1
#: the paper's (sec. 3.1)
BENCH = {"stiffness_high": 8.0, "stiffness_low": 5.0, "sensitivity_high": 6.1,
         "sensitivity_low": 0.5}


def _fake(spec, type_name, pressure_kPa, mode, material_name):
    y = np.linspace(0.0, spec.stroke, int(round(spec.stroke * bench_gap.POINTS_PER_MM)) + 1)
    scale = 0.5 if mode == "low" else 1.0
    assert spec.material.endswith("fit.json") == spec.name.endswith(":fit")
    return Curve(y, scale * (A[spec.name] * y + C * y ** 2), pressure_kPa + scale * B[spec.name] * y,
                 y, y, model="wall", geometry={}, material=material_name, setup={},
                 nominal_volume_mm3=1.0, inflated_volume_mm3=1.0, inflated_height_mm=13.0)


#: where the fit's data came from: the data file's '#' line, kept in the material file
CITED = "TPU 60A tension tests, example.org/data (mean of 3)"


def _fit_file(folder):
    from spsc.materials.file import material_record

    path = folder / "fit.json"
    path.write_text(json.dumps(material_record(
        "fit", "neo-hookean", {"C10": 1.2}, source="spsc fit-material: fitted to t.csv",
        data=[{"file": "t.csv", "notes": [CITED]}])))
    return path


@pytest.fixture
def summary(tmp_path, monkeypatch):
    monkeypatch.setattr(bench_gap, "curve_of", _fake)
    return bench_gap.run_gap(tmp_path, BENCH, types="AB", pressures=(10.0, 40.0),
                             materials=[_fit_file(tmp_path)])


def test_each_row_is_the_mean_slope_of_its_runs_over_its_window(summary):
    """The integral mean of F = a y + C y² over [0, Y] is a + C Y: the baseline reads the 8 mm
    runs over 0-6 mm, the stroke rows over 0-4 and 0-8 mm; the low mode's fake is half."""
    rows = {r["factor"]: r for r in summary["rows"]}
    assert_allclose(rows["baseline"]["stiffness_high"], A["long"] + 6 * C, rtol=1e-12)
    assert_allclose(rows["y_0-4"]["stiffness_high"], A["long"] + 4 * C, rtol=1e-12)
    assert_allclose(rows["y_0-8"]["stiffness_low"], 0.5 * (A["long"] + 8 * C), rtol=1e-12)
    assert_allclose(rows["stick"]["stiffness_high"], A["stick"] + 6 * C, rtol=1e-12)
    assert_allclose(rows["stiffest"]["stiffness_high"], A["stiffest"] + 8 * C, rtol=1e-12)
    assert_allclose(rows["t0_1.1"]["sensitivity_high"], B["thick"], rtol=1e-12)
    assert_allclose(rows["stick"]["against_baseline_pct"]["stiffness_high"],
                    100 * ((A["stick"] + 6 * C) / (A["long"] + 6 * C) - 1), rtol=1e-12)
    assert_allclose(rows["baseline"]["against_bench_pct"]["stiffness_high"],
                    100 * ((A["long"] + 6 * C) / 8.0 - 1), rtol=1e-12)
    assert_allclose(rows["mu_0.6"]["stiffness_low"], 0.5 * (A["mu0.6"] + 6 * C), rtol=1e-12)
    assert_allclose(rows["material_fit"]["sensitivity_low"], 0.5 * B["material:fit"],
                    rtol=1e-12)
    assert_allclose(rows["stiffest_fit"]["stiffness_high"], A["stiffest:fit"] + 8 * C,
                    rtol=1e-12)
    assert rows["material_fit"]["label"] == "material fit (μ0 2.40 MPa)"
    assert CITED in rows["material_fit"]["source"] and not rows["stick"]["source"]
    assert all(not r["partial"] for r in rows.values())
    assert summary["curves"] == 9 * 2 * 2 * 2  # run sets × modes × types × pressures


def test_factors_are_picked_by_name_and_a_wrong_name_is_refused():
    from spsc.core.errors import ParameterError

    assert [f.name for f in bench_gap.select(["stick", "mu_0.3"])] == \
        ["baseline", "mu_0.3", "stick"]
    assert bench_gap.select(None) == bench_gap.FACTORS
    with pytest.raises(ParameterError, match="factors.*mu_0.4.*names among baseline"):
        bench_gap.select(["mu_0.4"])


def test_the_summary_and_figure_are_written(summary, tmp_path):
    assert json.loads((tmp_path / "summary.json").read_text())["rows"][0]["factor"] == \
        "baseline"
    assert (tmp_path / "bench-gap.png").stat().st_size > 10_000


def test_the_report_section_says_which_factor_closes_most_of_the_gap(summary, tmp_path):
    from spsc.report.gap import gap_section
    from spsc.report.render import environment

    out = tmp_path / "report"
    sec = gap_section(tmp_path, out)
    assert (out / sec["figure"]).is_file()
    high = sec["findings"][0]
    gap = 8.0 - (A["long"] + 6 * C)
    best = max(("t0_1.1", A["thick"] + 6 * C), ("y_0-8", A["long"] + 8 * C),
               ("stick", A["stick"] + 6 * C), ("material_fit", A["material:fit"] + 6 * C),
               key=lambda kv: kv[1])
    assert "“material fit (μ0 2.40 MPa)”" in high
    assert f"({100 * (best[1] - (A['long'] + 6 * C)) / gap:.0f} % of it)" in high
    stiffest = 100 * (A["stiffest"] + 8 * C - (A["long"] + 6 * C)) / gap
    assert f"{stiffest:.0f} % of the gap" in high
    with_fit = 100 * (A["stiffest:fit"] + 8 * C - (A["long"] + 6 * C)) / gap
    assert f"“Fit and all stiffening ones” give {A['stiffest:fit'] + 8 * C:.2f} N/mm: " \
        f"{with_fit:.0f} % of the gap" in high
    friction = sec["findings"][-1]
    assert "μ = 0.6: +2.2 %, +2.2 %;" in friction  # (4.1 + 0.6) / (4.0 + 0.6)
    assert f"at most {100 * (A['stick'] - A['long']) / gap:.0f} % of the high mode's gap" \
        in friction
    html = environment().from_string('{% import "macros.html.j2" as m with context %}'
                                     '{% include "gap_section.html.j2" %}').render(gap=sec)
    assert 'id="gap"' in html and "the paper's bench" in html and "wall 0.9 mm" in html
    assert CITED in html and "Not in this study: the material" not in html
    base = sec["rows"][0]  # 4.6 and 2.3 N/mm: 42.5 % and 54 % below 8 and 5
    below = 100 * (1 - base["stiffness_high"] / 8.0), 100 * (1 - base["stiffness_low"] / 5.0)
    assert_allclose(below, (42.5, 54.0), rtol=1e-9)
    assert f"{min(below):.0f}–{max(below):.0f} % below the paper" in html
    assert "Which model to trust for what" in html


def test_no_study_renders_how_to_make_it():
    from spsc.report.render import environment

    html = environment().from_string('{% import "macros.html.j2" as m with context %}'
                                     '{% include "gap_section.html.j2" %}').render(gap=None)
    assert "make bench-gap" in html


@pytest.mark.slow
def test_the_real_study_on_one_type_and_pressure(tmp_path):
    """Type B at 40 kPa, the real wall model: the sticking plate and the thicker wall are
    stiffer than the report's setup, the thinner wall softer, every curve complete."""
    factors = [f for f in bench_gap.FACTORS if f.name in ("baseline", "stick", "t0_0.9",
                                                          "t0_1.1")]
    s = bench_gap.run_gap(tmp_path, BENCH, types="B", pressures=(40.0,), factors=factors)
    rows = {r["factor"]: r for r in s["rows"]}
    for mode in ("high", "low"):
        k = f"stiffness_{mode}"
        assert rows["t0_0.9"][k] < rows["baseline"][k] < rows["t0_1.1"][k]
        assert rows["stick"][k] > rows["baseline"][k]
    assert all(not r["partial"] for r in rows.values())


def test_a_change_that_rounds_to_zero_has_no_sign():
    """The table's "(-0 %)": a change of −0.3 % printed to 0 decimals is 0, not −0; a real
    change keeps its sign, and a small value in significant digits is not rounded away."""
    from spsc.report.render import num

    assert [num(v, "+.0f") for v in (-0.3, 0.2, 0.0, 3.4, -2.6)] == ["0", "0", "0", "+3", "-3"]
    assert num(-0.0004, ".3g") == "-0.0004" and num(-1e-20, ".2f") == "0.00"
    assert num(float("nan")) == "—"
