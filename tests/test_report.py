"""The validation report: its metrics on curves with known answers, the HTML (offline, local
figures, failed runs listed) and the ``spsc report`` verb."""

import html
import json
import re
from pathlib import Path

import pytest

from spsc.core.curve import Curve
from spsc.study.cache import Cache
from spsc.cli.main import main
from spsc.report.paper import paper_bench
from spsc.study.provenance import Provenance
from spsc.report.build import build_report
from spsc.study.runner import run_all
from spsc.study.runs import Run, Study

PAPER_TEXT = Path(__file__).resolve().parents[2] / "shared" / "paper" / "spsc-paper.txt"
CLEAN = Provenance("0123456789abcdef0123456789abcdef01234567")


def test_paper_figures_are_quoted_from_the_text():
    """Every number is printed in its quoted sentence, and the sentence is in the paper."""
    bench = paper_bench()
    assert {f.key for f in bench.figures} == {"stiffness_low", "stiffness_high",
                                              "sensitivity_low", "sensitivity_high", "jnd_mm"}
    text = " ".join(PAPER_TEXT.read_text(encoding="utf-8").split()) \
        if PAPER_TEXT.is_file() else None
    for f in bench.figures:
        assert float(f.printed) == f.value and f"{f.printed} {f.unit}" in f.quote, f.key
        assert "sec. " in f.cite
        if text is not None:
            assert f.quote in text, f.key


SMALL = Study(name="small", types=("B",), pressures_kPa=(10.0, 40.0), fem_points=4, fem=False,
              wall_mesh=(2.0, 1))


@pytest.mark.slow
def test_report_is_offline_html_with_local_figures_and_lists_failures(tmp_path):
    bad = Run("membrane", "B", "no-such-material", 40, 0, 6, 7)
    outcomes = run_all(SMALL.runs() + [bad], Cache(tmp_path / "cache"), progress=False)
    out = tmp_path / "report"
    path = build_report(SMALL, outcomes, out, command="spsc report --test", source=CLEAN)
    page = path.read_text(encoding="utf-8")
    srcs = re.findall(r'src="([^"]+)"', page)
    assert srcs and all((out / s).is_file() for s in srcs)
    assert "http://" not in page and "https://" not in page  # no CDN, opens offline
    assert "Failed runs" in page and bad.label in page and "material" in page
    assert "spsc report --test" in page and "numpy" in page and "scipy" in page
    for word in ("Headline", "JND", "paper, bench"):
        assert word in page
    assert CLEAN.commit in page and "NOT REPRODUCIBLE" not in page
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))  # strict JSON (no NaN)
    assert summary["failed"][0]["label"] == bad.label
    h = summary["headline"]["tpu60a"]["membrane p·A"]  # no FEM: no F_el to add
    assert h["high"]["stiffness"] > h["low"]["stiffness"] > 0
    assert h["high"]["sensitivity"] > 5 * h["low"]["sensitivity"]
    assert summary["provenance"]["commit"] == CLEAN.commit
    data = sorted(p.name for p in (out / "data").iterdir())
    assert len(data) == 2 * len(SMALL.runs())
    c = Curve.from_json(out / "data" / f"{SMALL.runs()[0].label}.json")
    assert c.model == "membrane" and len(c) == SMALL.membrane_points


def _headline_section(page: str) -> str:
    return page[page.index('<h2 id="headline">'):page.index('<h2 id="comparison">')
                if '<h2 id="comparison">' in page else page.index('<h2 id="curves">')]


@pytest.mark.slow
def test_headline_shows_the_paper_figures_with_their_citation(tmp_path):
    outcomes = run_all(SMALL.runs(), Cache(tmp_path / "cache"), progress=False)
    page = build_report(SMALL, outcomes, tmp_path / "r", source=CLEAN).read_text(encoding="utf-8")
    head = _headline_section(page)
    bench = paper_bench()
    row = re.search(r'<tr class="paper">(.*?)</tr>', head, re.S).group(1)
    cells = re.findall(r"<td>(.*?)</td>", row)
    assert cells[1:] == ["5.0", "8.0", "1.6", "0.5", "6.1", "12.2"]
    for f in bench.figures:
        assert html.escape(f"{f.key} = {f.printed} {f.unit}: {f.cite}", quote=True) in head
        assert html.escape(f.quote, quote=True) in head
    jnd = paper_bench().get("jnd_mm")
    assert html.escape(jnd.quote, quote=True) in page[page.index('<h2 id="jnd">'):]
    # a material the paper did not test gets no paper row
    other = build_report(SMALL.replace(materials=("elastic50a",)), {}, tmp_path / "o",
                         source=CLEAN).read_text(encoding="utf-8")
    assert 'class="paper"' not in other


def test_a_dirty_tree_is_marked_not_reproducible(tmp_path):
    dirty = Provenance(CLEAN.commit, (" M membrane/solver.py",))
    page = build_report(SMALL, {}, tmp_path / "r", source=dirty).read_text(encoding="utf-8")
    banner = re.search(r'<div class="not-reproducible">(.*?)</div>', page, re.S)
    assert banner and banner.group(1).startswith("NOT REPRODUCIBLE")
    assert "membrane/solver.py" in banner.group(1)
    nogit = build_report(SMALL, {}, tmp_path / "n", source=Provenance(None))
    assert "NOT REPRODUCIBLE" in nogit.read_text(encoding="utf-8")


@pytest.mark.slow
def test_spsc_report_refuses_the_committed_report_from_a_dirty_tree(tmp_path, monkeypatch,
                                                                    capsys):
    from spsc.cli import report as cmd_report
    from spsc.study import provenance
    from spsc.study import runner

    dirty = Provenance(CLEAN.commit, ("?? stray.py",))
    monkeypatch.setattr(provenance, "provenance", lambda *a: dirty)
    monkeypatch.setattr(provenance, "committed_report_dir", lambda *a: tmp_path / "committed")
    ran = []
    monkeypatch.setattr(runner, "run_all", lambda runs, *a, **k: ran.append(1) or {})
    args = ["report", "--no-fem", "--no-sweep", "--no-band", "--types", "C", "--cache",
            str(tmp_path / "c"),
            "--quiet"]
    assert main(args + ["--out", str(tmp_path / "committed")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "clean tree" in err[0] and "--allow-dirty" in err[0]
    assert not ran and not (tmp_path / "committed").exists()
    assert main(args + ["--out", str(tmp_path / "committed"), "--allow-dirty"]) == 0
    page = (tmp_path / "committed" / "index.html").read_text(encoding="utf-8")
    assert "NOT REPRODUCIBLE" in page
    assert main(args + ["--out", str(tmp_path / "elsewhere")]) == 0  # e.g. --quick's build/
    assert "NOT REPRODUCIBLE" in (tmp_path / "elsewhere" / "index.html").read_text(encoding="utf-8")
    assert cmd_report.DEFAULT_OUT[True] == Path("build/report-quick")


@pytest.mark.slow  # 8-15 s: make test stays under 3 min on a 2-core machine
def test_a_new_model_plugs_in_with_one_registry_entry(tmp_path, monkeypatch):
    """A model with bending (like the wall model) added to the registry is run at every setup
    pressure, drawn, and enters the headline and the JND table without F_el."""
    from dataclasses import replace

    from spsc.models import MODELS

    toy = replace(MODELS["simplified"], name="toy", bending=True, color="C4", style=":")
    monkeypatch.setitem(MODELS, "toy", toy)
    outcomes = run_all(SMALL.runs(), Cache(tmp_path / "cache"), progress=False)
    assert sum(r.model == "toy" for r in outcomes) == len(SMALL.all_pressures) * 2
    path = build_report(SMALL, outcomes, tmp_path / "r", source=CLEAN)
    summary = json.loads((path.parent / "summary.json").read_text(encoding="utf-8"))
    h = summary["headline"]["tpu60a"]
    # the same function as the simplified model: the same means, and no F_el added
    assert h["toy"]["high"]["stiffness"] == pytest.approx(h["simplified p·A"]["high"]["stiffness"],
                                                          rel=1e-12)
    assert "toy" in _headline_section(path.read_text(encoding="utf-8"))
    assert "toy p10" in summary["jnd_mm"]["B-tpu60a"]


@pytest.mark.slow
def test_spsc_report_verb_membrane_only(tmp_path, capsys):
    out, cache = tmp_path / "r", tmp_path / "c"
    args = ["report", "--quick", "--no-fem", "--types", "C", "--out", str(out),
            "--cache", str(cache), "--quiet"]
    assert main(args) == 0
    assert (out / "index.html").is_file()
    assert "0 from the cache" in capsys.readouterr().out
    # the design-space sweep: its page linked, its table cached by its space and code
    page = (out / "index.html").read_text(encoding="utf-8")
    assert '<a href="sweep/index.html">' in page and (out / "sweep" / "index.html").is_file()
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))["sweep"]
    assert summary["designs"] == 6 and summary["ok"] == 6  # C × 3 widths × 2 walls
    tables = list((cache / "sweeps").glob("report-quick-*.parquet"))
    assert len(tables) == 1
    assert main(args) == 0
    # membrane, simplified and wall × 2 pressures × 2 modes
    assert "12 from the cache" in capsys.readouterr().out
    again = json.loads((out / "summary.json").read_text(encoding="utf-8"))["sweep"]
    assert (summary["evaluated"], again["evaluated"], again["ok"]) == (6, 0, 6)
    from spsc.cli.report import DEFAULT_OUT
    assert DEFAULT_OUT == {False: Path("reports/validation"), True: Path("build/report-quick")}


TINY = Study(name="tiny", types=("B",), pressures_kPa=(40.0,), modes=(("high", 0.0),),
             stroke_mm=2.0, fem_points=3, mesh=(3.0, 1), wall_mesh=(2.0, 1),
             convergence_meshes=())


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    """Membrane, simplified and a coarse FEM (pressed and open chamber) of Type B: ~10 s."""
    cache = Cache(tmp_path_factory.mktemp("cache"))
    return cache, run_all(TINY.runs(), cache, progress=False)


def test_fem_runs_store_vtus_and_the_cavity_section(tiny):
    cache, out = tiny
    fem = out[TINY.fem_run("B", "tpu60a", "high")]
    assert fem.ok and fem.solver.converged, fem.error or fem.solver.message
    assert fem.solver.details["dofs"] > 0 and fem.solver.iterations > 0
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
    path = build_report(TINY, out, tmp_path / "a", fig_cache=figs, source=CLEAN)
    page = path.read_text(encoding="utf-8")
    for word in ("Models vs FEM", "mesh convergence", "shapes-B-tpu60a-high.png",
                 "curves-B-tpu60a-high.png"):
        assert word in page
    srcs = re.findall(r'src="([^"]+)"', page)
    assert all((path.parent / s).is_file() for s in srcs)
    comp = json.loads((path.parent / "summary.json").read_text(encoding="utf-8"))["comparison"]
    # models without bending get the FEM's F_el added; the wall carries its own
    assert set(comp["B-tpu60a-high"]) == {"membrane+F_el", "simplified+F_el", "wall"}
    e = comp["B-tpu60a-high"]["membrane+F_el"]
    assert e["force_N"]["n"] == 3 and e["pressure_kPa"]["rms"] >= 0
    assert len(list(figs.iterdir())) == 3  # curves, shapes, convergence

    from spsc.report import figures

    def no_drawing(*a, **k):
        raise AssertionError("a cached figure was drawn again")

    for name in ("curves_figure", "shapes_figure", "render_vtu", "convergence_figure"):
        monkeypatch.setattr(figures, name, no_drawing)
    again = build_report(TINY, out, tmp_path / "b", fig_cache=figs, source=CLEAN)
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
    for word in ("Headline", "JND depth", "Models vs FEM", "mesh convergence", "Provenance and versions",
                 "shapes-D-tpu60a-low.png", "curves-A-tpu60a-high.png"):
        assert word in page
    capsys.readouterr()
    assert main(args) == 0
    n = len(__import__("spsc.study.runs", fromlist=["quick_study"]).quick_study().runs())
    assert f"{n} runs, {n} from the cache, 0 failed" in capsys.readouterr().out


def test_a_bench_test_gets_its_own_section(tmp_path):
    # a vented Type B dome made by the wall model at 1.4 x tpu60a: the section calibrates it
    # back and predicts the study's setups (no identification: an open test has no pressure)
    from spsc.cad.geometry import preset
    from spsc.fem.wall.calibrate import scaled
    from spsc.fem.wall import wall_curve
    from spsc.materials import material
    from spsc.report.bench import BenchSpec

    c = wall_curve(preset("B", l=0.0), scaled(material("tpu60a"), 1.4), pressure_kPa=0.0,
                   stroke_mm=2.0, points=9)
    csv = tmp_path / "open.csv"
    csv.write_text("y_mm,force_N\n" + "".join(f"{y},{f}\n" for y, f in zip(c.y_mm, c.force_N)))
    spec = BenchSpec(str(csv), "B", 0.0, geometry=(("l", 0.0),))
    out = tmp_path / "r"
    page = build_report(SMALL, {}, out, source=CLEAN, bench=spec).read_text(encoding="utf-8")
    assert "Your bench test" in page and (out / "figures" / "bench-calibration.png").is_file()
    b = json.loads((out / "summary.json").read_text(encoding="utf-8"))["bench"]
    assert b["scale"] == pytest.approx(1.4, rel=5e-3)  # 13-point model on a 9-point bench
    assert len(b["rows"]) == len(SMALL.modes) * len(SMALL.pressures_kPa)
    assert not b["identified"] and all(r["k_ident"] is None for r in b["rows"])
    high = [r for r in b["rows"] if r["reservoir"] == 0]
    assert all(r["k_wall"] > 0 for r in high)
    assert "only with --bench" in _report_error(tmp_path, ["--bench-type", "B"])
    assert "bench-pressure" in _report_error(tmp_path, ["--bench", str(csv), "--bench-type", "B"])


def _report_error(tmp_path, argv) -> str:
    import contextlib
    import io

    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        rc = main(["report", "--out", str(tmp_path / "x"), "--cache", str(tmp_path / "c"),
                   "--quiet", *argv])
    assert rc == 2
    return err.getvalue()


@pytest.mark.slow
def test_spsc_report_runs_on_the_cluster_its_options_name(tmp_path, monkeypatch):
    """--workers N: a LocalCluster of N (1: this process, no cluster); --scheduler: that
    scheduler; neither: one worker per core. The report says where its runs were computed."""
    import functools

    from spsc.study import provenance

    from spsc.study import runner
    from spsc.study.executor import dask_client, default_workers

    monkeypatch.setattr(provenance, "provenance", lambda *a: CLEAN)
    seen = []
    monkeypatch.setattr(runner, "run_all",
                        lambda runs, *a, cluster=None, **k: seen.append(cluster) or {})
    base = ["report", "--no-fem", "--no-sweep", "--no-band", "--types", "C", "--cache",
            str(tmp_path / "c"),
            "--quiet", "--out", str(tmp_path / "r")]
    from distributed import LocalCluster

    # a real scheduler (no workers: run_all is replaced), since the address must answer Dask's
    # handshake (a bare listening socket is refused: issue 30)
    with LocalCluster(n_workers=0, processes=False, protocol="tcp://",
                      dashboard_address=None) as cluster:
        address = cluster.scheduler_address
        for extra in (["--workers", "1"], ["--workers", "3"], [], ["--scheduler", address]):
            assert main(base + extra) == 0
    page = (tmp_path / "r" / "index.html").read_text(encoding="utf-8")
    assert f"on the Dask scheduler at {address}" in page
    local, three, default, remote = seen
    assert local is None
    for factory, kw in ((three, {"workers": 3}), (remote, {"scheduler": address})):
        assert isinstance(factory, functools.partial) and factory.func is dask_client
        assert factory.keywords == kw and not factory.args
    n = default_workers()
    assert default is None if n == 1 else default.keywords == {"workers": n}


def test_a_fingertip_study_gets_its_own_section(tmp_path):
    """The report shows the study ``spsc fingertip --fem`` wrote (table and copied figures),
    and says how to make it when there is none."""
    study = tmp_path / "fem"
    (study / "figures").mkdir(parents=True)
    (study / "figures" / "pockets.png").write_bytes(b"\x89PNG\r\n\x1a\nfake")
    fem = {"y_mm": [0, 1], "force_N": [0, 2.5], "pressure_kPa": [40, 43],
           "pockets_N": {"pulp1": [0, 0.1], "pulp2": [0, 1.9]}, "mean_stiffness_N_per_mm": 2.5,
           "mean_sensitivity_kPa_per_mm": 3.0, "converged": True, "seconds": 900.0,
           "dofs": 250000, "message": "converged"}
    summary = {"mesh_size_mm": 1.5, "material": "silicone40a", "stroke_mm": 3.0,
               "cases": {"pulp-high-40kPa": {"site": "pulp", "mode": "high",
                                             "pressure_kPa": 40.0, "fem": fem,
                                             "sensitivity_ratio_fused_to_single": 0.618,
                                             "fast_error": {"force_max": 0.123,
                                                            "pressure_rise_max": 0.045}}}}
    (study / "summary.json").write_text(json.dumps(summary), encoding="utf-8")
    page = build_report(SMALL, {}, tmp_path / "r", source=CLEAN,
                        fingertip=study).read_text(encoding="utf-8")
    section = page[page.index("The fused fingertip in the 3D FEM"):]
    assert "pulp-high-40kPa" in section and "0.618" in section and "12.3 %" in section
    assert "1.9" in section and 'src="fingertip/pockets.png"' in section
    assert (tmp_path / "r" / "fingertip" / "pockets.png").exists()
    none = build_report(SMALL, {}, tmp_path / "n", source=CLEAN,
                        fingertip=tmp_path / "nothing").read_text(encoding="utf-8")
    assert "make fingertip-fem" in none


def test_the_haptic_study_gets_its_own_section(tmp_path):
    """The report shows the study ``make haptic-fem`` wrote (each case against the plain Type
    D, the force through the motor, the copied figure), and says how to make it when there is
    none."""
    study = tmp_path / "haptic"
    study.mkdir()
    (study / "haptic-cost.png").write_bytes(b"\x89PNG\r\n\x1a\nfake")

    def row(F, dP, **extra):
        return dict({"converged": True, "y_mm": 4.0, "force_N": F, "dp_kPa": dP,
                     "stiffness_N_per_mm": F / 4, "sensitivity_kPa_per_mm": dP / 4,
                     "kPa_per_N": dP / F, "end_stiffness_N_per_mm": 5.0,
                     "end_sensitivity_kPa_per_mm": 4.0, "dofs": 118000, "seconds": 400.0,
                     "start_stiffness_N_per_mm": F / 8, "start_sensitivity_kPa_per_mm": dP / 8,
                     "vs_plain_pct": {"stiffness_N_per_mm": 100 * (F / 14.9 - 1),
                                      "start_stiffness_N_per_mm": 100 * (F / 14.9 - 1),
                                      "start_sensitivity_kPa_per_mm": 100 * (dP / 12.1 - 1),
                                      "sensitivity_kPa_per_mm": 100 * (dP / 12.1 - 1),
                                      "kPa_per_N": 100 * (dP / F / (12.1 / 14.9) - 1)}}, **extra)
    summary = {"plain": row(14.9, 12.1), "film": row(25.5, 17.2),
               "motor": row(31.0, 16.0, motor_force_N=7.25, motor_peak_N=7.75),
               "mesh_size_mm": 1.2,
               "motor_alone_pct": {"stiffness_N_per_mm": 21.6, "start_stiffness_N_per_mm": 51.0,
                                   "sensitivity_kPa_per_mm": -7.0, "kPa_per_N": -23.5}}
    (study / "summary.json").write_text(json.dumps(summary), encoding="utf-8")
    page = build_report(SMALL, {}, tmp_path / "r", source=CLEAN,
                        haptic=study).read_text(encoding="utf-8")
    section = page[page.index("The haptic chamber: what the motor costs"):]
    assert "haptic chamber with its motor" in section and "7.25 (7.75)" in section
    assert "stiffness +21.6 % over the stroke (+51 % in the first mm)" in " ".join(section.split())
    assert "(+108 %)" in section  # 31.0 / 14.9: the stiffness against the plain Type D
    assert 'src="haptic/haptic-cost.png"' in section
    assert (tmp_path / "r" / "haptic" / "haptic-cost.png").exists()
    none = build_report(SMALL, {}, tmp_path / "n", source=CLEAN,
                        haptic=tmp_path / "nothing").read_text(encoding="utf-8")
    assert "make haptic-fem" in none


@pytest.mark.slow
def test_mold_section(tmp_path):
    """The report builds, gates and renders the molds itself, and shows the gate failing on the
    three broken molds with their reasons."""
    import json

    out = tmp_path / "r"
    page = build_report(SMALL, {}, out, source=CLEAN, molds=("B",)).read_text(encoding="utf-8")
    section = page[page.index('<h2 id="molds">Molds</h2>'):]
    assert "horizontal" in section and "passed" in section
    assert 'src="mold/mold-B.png"' in section and (out / "mold" / "mold-B.png").exists()
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    broken = {b["case"]: b["failed"] for b in summary["mold"]["broken"]}
    assert "overlap" in broken["Type B, upper half moved 1 mm along y"]
    assert "core_volume" in broken["Type B, core scaled by 0.98"]
    assert broken["Type D split horizontally (--parting z)"] == ["pull_upper"]
    assert "undercut" in section


def test_the_time_study_gets_its_own_section(tmp_path):
    """The report shows the study ``make time-study`` wrote (the switch under load, the
    hysteresis per type against the paper, the Bode limits, the copied figures), and says how
    to make it when there is none."""
    study = tmp_path / "time"
    for rel in ("trace/trace.png", "bode/bode.png", "hysteresis.png"):
        (study / rel).parent.mkdir(parents=True, exist_ok=True)
        (study / rel).write_bytes(b"\x89PNG\r\n\x1a\nfake")
    summary = {
        "scenario": {"chamber": {"type": "B"}, "circuit": {
            "setup_kPa": 40, "reservoir_mm3": 40000, "gas": {"n": 1.4, "thermal_time_s": 0.5}}},
        "complete": True, "material": "tpu60a", "prony_source": "CALIBRATED: on B",
        "switches": [{"t_s": 1.0, "valve": "open", "y_mm": 3.0, "pressure_before_kPa": 46.554,
                      "pressure_after_kPa": 40.709, "rise_ms": 8.0, "settle_2pct_ms": 12.0}],
        "hysteresis": [{"type": t, "hysteresis_N": h, "at_mm": 4.5, "dissipated_mJ": 10.0,
                        "paper_N": p, "error_pct": 100 * (h / p - 1), "complete": True}
                       for t, h, p in (("A", 4.9, 8.1), ("B", 3.8, 3.8))],
        "cycle": {"stroke_mm": 6.0, "speed_mm_s": 1.0},
        "bode": {"y_mm": 3.0, "valve_open": True, "stiffness_low_f_N_per_mm": 3.01,
                 "stiffness_high_f_N_per_mm": 4.45, "sensitivity_low_f_kPa_per_mm": 0.44,
                 "sensitivity_high_f_kPa_per_mm": 5.2, "sensitivity_halfway_Hz": 50.3}}
    (study / "summary.json").write_text(json.dumps(summary), encoding="utf-8")
    page = build_report(SMALL, {}, tmp_path / "r", source=CLEAN,
                        time_study=study).read_text(encoding="utf-8")
    section = " ".join(page[page.index("The chamber in time"):].split())
    assert "46.55" in section and "40.71" in section and "CALIBRATED: on B" in section
    assert "−40 %" in section or "-40 %" in section  # A: 4.9 against 8.1
    assert "halfway (in log) at 50.3 Hz" in section
    for name in ("trace", "bode", "hysteresis"):
        assert f'src="time/{name}.png"' in section
        assert (tmp_path / "r" / "time" / f"{name}.png").exists()
    none = build_report(SMALL, {}, tmp_path / "n", source=CLEAN,
                        time_study=tmp_path / "nothing").read_text(encoding="utf-8")
    assert "make time-study" in none
