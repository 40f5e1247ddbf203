"""The sweep's HTML page: its Pareto front is the printable non-dominated set (checked against a
brute-force definition), each front design re-runs from the command the page gives, failures are
listed, and the figures and the CSV are written."""

import itertools
import re
import shlex
from pathlib import Path

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.cli.main import build_parser
from spsc.sweep.evaluate import COLUMNS, evaluate, failed_row
from spsc.report.sweep_figures import Front, pareto_mask
from spsc.report.sweep_page import write_page
from spsc.sweep.store import frame

FAST = dict(model="simplified", process="fdm", points=5, stroke_mm=4.0)


def _brute_front(values, senses):
    """Indices of rows no other row dominates, by the definition, in plain Python."""
    sign = [-1 if s == "max" else 1 for s in senses]
    pts = [[s * x for s, x in zip(sign, row)] for row in values]
    front = []
    for i, p in enumerate(pts):
        if any(np.isnan(p)):
            continue
        if not any(all(q[k] <= p[k] for k in range(len(p))) and
                   any(q[k] < p[k] for k in range(len(p)))
                   for j, q in enumerate(pts) if j != i and not any(np.isnan(q))):
            front.append(i)
    return front


@pytest.mark.parametrize("senses", [("max", "min"), ("min", "min"), ("max", "max")])
def test_pareto_mask_is_the_non_dominated_set(senses):
    rng = np.random.default_rng(3)
    values = rng.normal(size=(150, 2))
    values[::17, 1] = np.nan  # a metric a design never reached: not on any front
    values[5] = values[6]  # ties: neither dominates the other
    values[7, 0] = values[8, 0]  # equal in one metric: the other decides
    got = np.flatnonzero(pareto_mask(values, senses)).tolist()
    assert got == _brute_front(values.tolist(), senses)
    assert 2 <= len(got) < 150
    # equal in one metric, worse in the other: dominated
    assert pareto_mask([[1.0, 1.0], [1.0, 2.0], [0.5, 3.0]], ("min", "min")).tolist() == \
        [True, False, True]


def test_front_is_parsed_with_one_line_errors():
    f = Front.parse("sensitivity_high:max, cavity_mm3:min")
    assert f.metrics == ("sensitivity_high", "cavity_mm3") and f.senses == ("max", "min")
    assert str(Front.parse(str(f))) == str(f)
    for bad in ("sensitivity_high:max", "speed:max,cavity_mm3:min", "jnd_mm:min,jnd_mm:max",
                "jnd_mm:lowest,cavity_mm3:min", ""):
        with pytest.raises(ParameterError, match=r"^front = .* is invalid"):
            Front.parse(bad)


@pytest.fixture(scope="module")
def table():
    """A small real sweep (the simplified model, no cluster): Types A and B over w and t0
    (t0 = 0.5 mm is below FDM's minimum wall: not printable), one refused design and one
    failed row."""
    base = {"h": 13.0, "l": 3.0, "material": "tpu60a", "pressure": 40.0, "reservoir": 40000.0}
    presets = {"A": (3.0, 4.0, 0.0), "B": (2.0, 2.2, 0.0)}
    rows = []
    for t, w, t0 in itertools.product("AB", (9.0, 11.0, 13.0), (0.5, 1.0, 1.3)):
        n1, n2, cy = presets[t]
        rows.append(evaluate({**base, "type": t, "w": w, "t0": t0, "n1": n1, "n2": n2,
                              "cy": cy}, **FAST))
    bad = {**base, "type": "B", "w": 11.0, "t0": 20.0, "n1": 2.0, "n2": 2.2, "cy": 0.0}
    rows.append(evaluate(bad, **FAST))
    rows.append(failed_row({**bad, "t0": 1.1}, "KilledWorker: worker died", key="x"))
    return frame(rows)


def test_page_front_is_the_printable_non_dominated_designs(table, tmp_path):
    out = tmp_path / "page"
    path = write_page(table, out, front="sensitivity_high:max,cavity_mm3:min",
                      searched=["type", "w", "t0"], **{k: FAST[k] for k in
                                                        ("model", "process", "points")},
                      stroke_mm=FAST["stroke_mm"], command="spsc sweep ...")
    html = path.read_text(encoding="utf-8")
    assert sorted(p.name for p in (out / "figures").iterdir()) == \
        ["effects.png", "front.png", "modes.png", "parallel.png"]
    csv = (out / "table.csv").read_text(encoding="utf-8").splitlines()
    assert csv[0].split(",")[: len(COLUMNS)] == list(COLUMNS) and len(csv) == len(table) + 1
    ok = (table["status"] == "ok") & table["printable"].fillna(False)
    assert 0 < ok.sum() < (table["status"] == "ok").sum()  # some computed, not printable
    values = [[r.sensitivity_high, r.cavity_mm3] if good else [np.nan, np.nan]
              for r, good in zip(table.itertuples(), ok)]
    expected = table.iloc[_brute_front(values, ("max", "min"))]
    reruns = re.findall(r'<td class="c">(spsc curve [^<]*)</td>', html)
    assert len(reruns) == len(expected) > 0
    parser = build_parser()
    got = set()
    for cmd in reruns:
        args = parser.parse_args(shlex.split(cmd)[1:])
        assert (args.model, args.points, args.stroke, args.reservoir) == ("simplified", 5, 4.0,
                                                                          0.0)
        got.add((args.type, float(args.w), float(args.t0)))
    assert got == {(r.type, r.w, r.t0) for r in expected.itertuples()}
    assert "KilledWorker: worker died" in html and "t0 = 20.0 is invalid" in html
    assert "n1 (the type&#39;s preset)" in html or "n1 (the type's preset)" in html


def test_page_without_any_printable_design_says_so(table, tmp_path):
    thin = table[table["t0"] == 0.5].copy()
    path = write_page(thin, tmp_path / "p", model="simplified", process="fdm", stroke_mm=4.0,
                      points=5)
    assert "No printable design was computed" in path.read_text(encoding="utf-8")


def test_a_moved_page_folder_resolves_every_link(table, tmp_path):
    """Every path on the page is relative to it: the folder moved elsewhere still shows its
    figures and links its CSV and (inside the folder) the sweep's own table; a table outside
    the folder is named by its absolute path, not linked."""
    import shutil

    from spsc.report.page_check import broken_links, outline

    out = tmp_path / "a" / "page"
    out.mkdir(parents=True)
    table.to_parquet(out / "sweep.parquet")
    write_page(table, out, model="simplified", process="fdm", stroke_mm=4.0, points=5,
               table=str(out / "sweep.parquet"))
    moved = Path(shutil.move(str(out), str(tmp_path / "b" / "moved")))
    links = outline((moved / "index.html").read_text(encoding="utf-8")).links
    assert {"table.csv", "sweep.parquet", "figures/front.png"} <= set(links)
    assert broken_links(moved / "index.html") == []
    outside = tmp_path / "outside.parquet"
    page = write_page(table, tmp_path / "c", model="simplified", process="fdm", stroke_mm=4.0,
                      points=5, table=str(outside))
    assert broken_links(page) == [] and str(outside) in page.read_text(encoding="utf-8")
