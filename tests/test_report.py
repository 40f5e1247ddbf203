"""The validation report: its metrics on curves with known answers, the HTML (offline, local
figures, failed runs listed) and the ``spsc report`` verb."""

import json
import re
from pathlib import Path

import numpy as np
import pytest

from spsc.core.curve import Curve
from spsc.pipeline.cache import Cache
from spsc.pipeline.cli import main
from spsc.pipeline.report import PAPER, build_report, errors, headline, with_f_el
from spsc.pipeline.runner import run_all
from spsc.pipeline.study import Run, Study


def _curve(y, F, P, A=None, dV=None, model="membrane"):
    y = np.asarray(y, float)
    z = np.zeros_like(y)
    return Curve(y, F, P, z if A is None else A, z if dV is None else dV, model=model)


def test_headline_is_the_mean_slope_over_stroke_pressures_and_types():
    y = np.linspace(0, 6, 13)
    # type X: slopes 2 and 4 N/mm at two pressures; type Y: 6 N/mm; sensitivities 1, 3, 5
    cs = {"X": [_curve(y, 2 * y, 1 * y), _curve(y, 4 * y, 3 * y)], "Y": [_curve(y, 6 * y, 5 * y)]}
    h = headline(cs)
    assert h["types"]["X"]["stiffness"] == pytest.approx(3.0, rel=1e-12)
    assert h["types"]["X"]["sensitivity"] == pytest.approx(2.0, rel=1e-12)
    assert h["stiffness"] == pytest.approx(4.5, rel=1e-12)  # (3 + 6) / 2: types weigh equally
    assert h["sensitivity"] == pytest.approx(3.5, rel=1e-12)


def test_errors_at_the_fem_points_and_f_el_added_on_the_membrane_grid():
    yf = np.linspace(0, 6, 4)
    ym = np.linspace(0, 6, 7)
    fem = _curve(yf, 3 * yf, 40 + yf, model="fem")
    f_el = _curve(yf, yf, 0 * yf, model="fem")
    mem = _curve(ym, 2 * ym, 40 + ym + 0.5 * (ym == 6))
    comb = with_f_el(mem, f_el)
    np.testing.assert_allclose(comb.force_N, 3 * ym, rtol=1e-12)
    e = errors(fem, comb)
    assert e["force_N"]["max"] == pytest.approx(0.0, abs=1e-12)
    assert e["pressure_kPa"]["max"] == pytest.approx(0.5)
    assert e["pressure_kPa"]["rms"] == pytest.approx(np.sqrt(0.25 / 4))
    assert e["pressure_kPa"]["n"] == 4
    # a non-converged FEM point is left out, never compared
    fem_nan = fem.replace(pressure_kPa=np.where(yf == 6, np.nan, fem.pressure_kPa))
    assert errors(fem_nan, comb)["pressure_kPa"]["max"] == pytest.approx(0.0, abs=1e-12)


SMALL = Study(name="small", types=("B",), pressures_kPa=(10.0, 40.0), fem_points=4, fem=False)


def test_report_is_offline_html_with_local_figures_and_lists_failures(tmp_path):
    bad = Run("membrane", "B", "no-such-material", 40, 0, 6, 7)
    outcomes = run_all(SMALL.runs() + [bad], Cache(tmp_path / "cache"), progress=False)
    out = tmp_path / "report"
    path = build_report(SMALL, outcomes, out, command="spsc report --test")
    page = path.read_text(encoding="utf-8")
    srcs = re.findall(r'src="([^"]+)"', page)
    assert srcs and all((out / s).is_file() for s in srcs)
    assert "http://" not in page and "https://" not in page  # no CDN, opens offline
    assert "Failed runs" in page and bad.label in page and "material" in page
    assert "spsc report --test" in page and "numpy" in page and "scipy" in page
    for word in ("Headline", "JND", "paper, bench"):
        assert word in page
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))  # strict JSON (no NaN)
    assert summary["failed"][0]["label"] == bad.label
    h = summary["headline"]["tpu60a"]
    assert h["high"]["membrane+F_el"]["stiffness"] > h["low"]["membrane+F_el"]["stiffness"] > 0
    assert h["high"]["membrane+F_el"]["sensitivity"] > 5 * h["low"]["membrane+F_el"]["sensitivity"]
    assert PAPER["stiffness_N_per_mm"] == {"low": 5.0, "high": 8.0}
    data = sorted(p.name for p in (out / "data").iterdir())
    assert len(data) == 2 * len(SMALL.runs())
    c = Curve.from_json(out / "data" / f"{SMALL.runs()[0].label}.json")
    assert c.model == "membrane" and len(c) == SMALL.membrane_points


def test_spsc_report_verb_membrane_only(tmp_path, capsys):
    out, cache = tmp_path / "r", tmp_path / "c"
    args = ["report", "--quick", "--no-fem", "--types", "C", "--out", str(out),
            "--cache", str(cache), "--quiet"]
    assert main(args) == 0
    assert (out / "index.html").is_file()
    assert "0 from the cache" in capsys.readouterr().out
    assert main(args) == 0
    assert "8 from the cache" in capsys.readouterr().out
    from spsc.pipeline.cmd_report import DEFAULT_OUT
    assert DEFAULT_OUT == {False: Path("reports/validation"), True: Path("build/report-quick")}


TINY = Study(name="tiny", types=("B",), pressures_kPa=(40.0,), modes=(("high", 0.0),),
             stroke_mm=2.0, fem_points=3, mesh=(3.0, 1), convergence_meshes=())


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    """Membrane, simplified and a coarse FEM (pressed and open chamber) of Type B: ~10 s."""
    cache = Cache(tmp_path_factory.mktemp("cache"))
    return cache, run_all(TINY.runs(), cache, progress=False)


def test_fem_runs_store_vtus_and_the_cavity_section(tiny):
    cache, out = tiny
    fem = out[TINY.fem_run("B", "tpu60a", "high")]
    assert fem.ok and fem.payload["converged"], fem.error or fem.payload["message"]
    vtu = fem.payload["vtu"]
    assert set(vtu) == {"inflated", "pressed"} and all((fem.dir / v).is_file()
                                                       for v in vtu.values())
    sec = fem.payload["sections"]
    # the inflated cavity apex of the section is the curve's inflated height (stored to 1e-6 mm)
    assert max(sec["inflated"]["eta"]) == pytest.approx(fem.curve.inflated_height_mm, abs=1e-5)
    assert max(sec["pressed"]["eta"]) < max(sec["inflated"]["eta"]) - 1.0  # pressed 2 mm
    opened = out[TINY.fem_run("B", "tpu60a", "open")].curve
    assert opened.setup["p_i_kPa"] == 0 and opened.force_N[-1] > 0


def test_report_with_fem_renders_compares_and_reuses_its_figures(tiny, tmp_path, monkeypatch):
    cache, out = tiny
    figs = tmp_path / "figcache"
    path = build_report(TINY, out, tmp_path / "a", fig_cache=figs)
    page = path.read_text(encoding="utf-8")
    for word in ("Membrane vs FEM", "mesh convergence", "shapes-B-tpu60a-high.png",
                 "curves-B-tpu60a-high.png"):
        assert word in page
    srcs = re.findall(r'src="([^"]+)"', page)
    assert all((path.parent / s).is_file() for s in srcs)
    e = json.loads((path.parent / "summary.json").read_text(encoding="utf-8"))["comparison"]["B-tpu60a-high"]
    assert e["force_N"]["n"] == 3 and e["pressure_kPa"]["rms"] >= 0
    assert len(list(figs.iterdir())) == 3  # curves, shapes, convergence

    from spsc.pipeline import figures

    def no_drawing(*a, **k):
        raise AssertionError("a cached figure was drawn again")

    for name in ("curves_figure", "shapes_figure", "render_vtu", "convergence_figure"):
        monkeypatch.setattr(figures, name, no_drawing)
    again = build_report(TINY, out, tmp_path / "b", fig_cache=figs)
    assert sorted(p.name for p in (tmp_path / "b" / "figures").iterdir()) == \
        sorted(p.name for p in (tmp_path / "a" / "figures").iterdir())
    assert again.read_text(encoding="utf-8").count("<img") == page.count("<img")


@pytest.mark.slow
def test_quick_report_end_to_end(tmp_path, capsys):
    """``make report QUICK=1`` in a fresh cache: every run succeeds, the HTML has every
    section, and a second call is served from the cache (measured 169 s, then 3 s)."""
    args = ["report", "--quick", "--out", str(tmp_path / "r"), "--cache", str(tmp_path / "c"),
            "--quiet"]
    assert main(args) == 0
    page = (tmp_path / "r" / "index.html").read_text(encoding="utf-8")
    for word in ("Headline", "JND depth", "Membrane vs FEM", "mesh convergence", "Versions",
                 "shapes-D-tpu60a-low.png", "curves-A-tpu60a-high.png"):
        assert word in page
    capsys.readouterr()
    assert main(args) == 0
    n = len(__import__("spsc.pipeline.study", fromlist=["quick_study"]).quick_study().runs())
    assert f"{n} runs, {n} from the cache, 0 failed" in capsys.readouterr().out
