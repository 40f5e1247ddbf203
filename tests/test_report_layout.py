"""The report reads at a glance: a summary first (what was validated, against what, the gap to
the bench in words computed from the numbers), a table of contents whose every entry has its
anchor, a figure before any long table, long tables collapsed; and an output folder (report,
sweep page, design page) moved elsewhere still resolves every link (paths relative to it)."""

import html
import json
import shutil

import pytest

from spsc.report.build import build_report
from spsc.report.overview import bench_gap, gap_sentences, gap_summary, softer_everywhere
from spsc.report.page_check import LONG_TABLE_ROWS, broken_links, outline
from spsc.report.paper import paper_bench
from spsc.study.cache import Cache
from spsc.study.provenance import Provenance
from spsc.study.runner import run_all
from spsc.study.runs import Study

CLEAN = Provenance("0123456789abcdef0123456789abcdef01234567")
#: Two types at four pressures in both modes: 16 runs, more rows than a table shows open.
STUDY = Study(name="layout", types=("B", "C"), pressures_kPa=(10.0, 20.0, 30.0, 40.0),
              fem=False, fem_points=4)


def _means(values=None, **more):
    """Headline means {variant: {mode: {quantity: value}}} from {variant: (k_high, k_low,
    s_high, s_low)} or keywords like ``wall=(…)``."""
    return {v: {"high": {"stiffness": k1, "sensitivity": s1},
             "low": {"stiffness": k0, "sensitivity": s0}}
            for v, (k1, k0, s1, s0) in {**(values or {}), **more}.items()}


def test_the_gap_to_the_bench_is_said_from_the_numbers():
    paper = paper_bench()
    k1, k0 = paper.get("stiffness_high").value, paper.get("stiffness_low").value
    s1, s0 = paper.get("sensitivity_high").value, paper.get("sensitivity_low").value
    means = _means(wall=(0.6 * k1, 0.7 * k0, 0.9 * s1, 1.2 * s0),
                   fem=(0.5 * k1, 0.8 * k0, 0.75 * s1, s0))
    gap = bench_gap(means, paper, 40.0)
    assert gap["stiffness"]["high"]["models"]["wall"] == pytest.approx(-0.4)
    assert softer_everywhere(gap)
    text = gap_summary(gap, "fem")
    assert text.startswith("Every model is softer than the paper's bench in stiffness")
    assert f"40–50 % below the bench's {paper.get('stiffness_high').printed} N/mm" in text
    assert "20–30 % below" in text  # low mode
    assert "the 3D FEM (40 kPa only) is 25 % below the bench's 6.1 kPa/mm" in text
    assert "within 0.5 % of the bench's 0.5 kPa/mm in the low mode" in text
    sens = gap_sentences(gap)[1]  # the models fall on both sides: each by name
    assert "the wall model 20 % above" in sens and "the 3D FEM (40 kPa only) within 0.5 %" in sens
    # one model above the bench in stiffness: no "every model is softer"
    stiffer = bench_gap(_means(wall=(1.1 * k1, 0.7 * k0, s1, s0)), paper)
    assert not softer_everywhere(stiffer)
    assert "Every model" not in gap_summary(stiffer, None)
    assert "the wall model is 10 % above the bench's 8.0 N/mm" in gap_summary(stiffer, None)


def test_a_models_p_a_alone_is_not_compared_when_it_has_f_el():
    paper = paper_bench()
    means = _means({"membrane p·A": (1, 1, 1, 1), "membrane+F_el": (2, 2, 2, 2),
                    "simplified p·A": (3, 3, 3, 3)})
    gap = bench_gap(means, paper)
    assert set(gap["stiffness"]["high"]["models"]) == {"membrane+F_el", "simplified p·A"}


def _sweep_table():
    """A four-design sweep of Type B with the simplified model (its page: four figures)."""
    from spsc.sweep.evaluate import evaluate
    from spsc.sweep.store import frame

    base = {"type": "B", "h": 13.0, "l": 3.0, "n1": 2.0, "n2": 2.2, "cy": 0.0,
            "material": "tpu60a", "pressure": 40.0, "reservoir": 40000.0}
    return frame([evaluate({**base, "w": w, "t0": t0}, model="simplified", process="fdm",
                           points=5, stroke_mm=4.0) for w in (9.0, 12.0) for t0 in (1.0, 1.3)])


def _paths(value):
    """Every string in a JSON value that names a file (a relative path with a suffix)."""
    if isinstance(value, dict):
        return [p for v in value.values() for p in _paths(v)]
    if isinstance(value, list):
        return [p for v in value for p in _paths(v)]
    ok = isinstance(value, str) and " " not in value and "/" in value
    return [value] if ok and value.rsplit(".", 1)[-1] in ("png", "html", "csv", "json") else []


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """The report of :data:`STUDY` with the simplified model only (the fastest: ~1 s of
    runs) and a small sweep, written to a temporary folder; (folder, page, summary.json)."""
    from dataclasses import replace

    from spsc.models import MODELS

    with pytest.MonkeyPatch.context() as mp:
        for name in [k for k in MODELS if k not in ("simplified", "membrane")]:
            mp.delitem(MODELS, name)
        # the sweep's model, named by its page's commands, but not run by the study
        mp.setitem(MODELS, "membrane", replace(MODELS["membrane"], sweep=False))
        outcomes = run_all(STUDY.runs(), Cache(tmp_path_factory.mktemp("cache")), progress=False)
        out = tmp_path_factory.mktemp("report") / "report"
        path = build_report(STUDY, outcomes, out, source=CLEAN,
                            sweep=(_sweep_table(), "spsc sweep ..."))
    page = path.read_text(encoding="utf-8")
    return out, page, json.loads((out / "summary.json").read_text(encoding="utf-8"))


def test_summary_comes_first_and_says_the_gap(report):
    out, page, summary = report
    o = outline(page)
    first_table = o.index("table")
    assert o.index("h2", lambda v: v[0] == "summary") < first_table
    assert o.index("section", lambda v: v == "contents") < first_table
    gap = summary["overview"]["gap"]
    assert gap.startswith("Simplified p·A is softer than the paper's bench")  # its one model
    head = html.unescape(page[:page.index('id="contents"')])
    assert gap in head and summary["overview"]["validated"] in head
    # the sentences are the numbers of the headline, not typed in
    k = summary["headline"]["tpu60a"]["simplified p·A"]["high"]["stiffness"]
    below = round(100 * (1 - k / paper_bench().get("stiffness_high").value))
    assert f"{below} % below the bench's 8.0 N/mm in the high mode" in gap


def test_contents_link_every_section(report):
    _, page, _ = report
    nav = page[page.index('<nav id="contents">'):page.index("</nav>")]
    o = outline(page)
    targets = [link[1:] for link in outline(nav).links]
    after = outline(page[page.index("</nav>"):])
    sections = [v[0] for k, v in after.events if k == "h2"]
    assert targets == sections and len(targets) >= 8
    assert all(t in o.ids for t in targets)
    assert not [link for link in o.links if link.startswith("#") and link[1:] not in o.ids]


def test_a_figure_before_any_long_table_and_long_tables_collapsed(report):
    _, page, _ = report
    o = outline(page)
    tables = o.tables()
    long = [i for i, (k, v) in enumerate(o.events) if k == "table" and v[0] > LONG_TABLE_ROWS]
    assert long, "the fixture has no long table: the test would prove nothing"
    assert o.index("img") < long[0]
    assert all(collapsed for rows, collapsed in tables if rows > LONG_TABLE_ROWS)
    assert not any(collapsed for rows, collapsed in tables if rows <= LONG_TABLE_ROWS)
    assert o.index("img", lambda s: s.endswith("bench-gap.png")) == o.index("img")


def test_a_moved_report_resolves_every_link(report, tmp_path):
    out, _, _ = report
    copy = tmp_path / "copy"
    shutil.copytree(out, copy)
    moved = shutil.move(str(copy), str(tmp_path / "elsewhere" / "validation"))
    assert broken_links(f"{moved}/index.html") == []
    summary = json.loads((tmp_path / "elsewhere" / "validation" / "summary.json")
                         .read_text(encoding="utf-8"))
    paths = _paths(summary)
    assert {summary["overview"]["figure"], "sweep/index.html", "sweep/figures/front.png"} <= \
        set(paths)
    assert [p for p in paths if not (tmp_path / "elsewhere" / "validation" / p).is_file()] == []
    assert broken_links(f"{moved}/sweep/index.html") == []


def test_broken_links_finds_what_points_nowhere(tmp_path):
    page = tmp_path / "index.html"
    (tmp_path / "a.png").write_bytes(b"")
    page.write_text('<h2 id="x">x</h2><a href="#x">x</a><img src="a.png"><a href="#y">y</a>'
                    '<img src="b.png"><a href="/abs/c.html">c</a><a href="https://e.org">e</a>',
                    encoding="utf-8")
    assert broken_links(page) == ["#y", "b.png", "/abs/c.html"]


def test_a_moved_design_folder_resolves_every_link(tmp_path):
    """``spsc design``'s folder (page, design.json, trials, journal, figures) moved elsewhere
    still resolves every link of its page; design.json names no path outside it."""
    from spsc.cli.main import main

    out = tmp_path / "a" / "run"
    assert main(["design", "--model", "simplified", "--points", "5", "--workers", "1",
                 "--verify", "none", "--no-build", "--trials", "2", "--seed", "1",
                 "--target", "stiffness_high=6", "--out", str(out), "--quiet"]) in (0, 1)
    moved = tmp_path / "b" / "moved"
    shutil.move(str(out), str(moved))
    links = set(outline((moved / "index.html").read_text(encoding="utf-8")).links)
    assert {"design.json", "trials.parquet", "figures/history.png"} <= links
    assert broken_links(moved / "index.html") == []
    doc = (moved / "design.json").read_text(encoding="utf-8")
    assert str(out) not in doc.replace(json.loads(doc)["command"], "")
