"""The HTML page of a design run: ``OUT/index.html`` with its figures in ``OUT/figures``
(self-contained: local PNGs, no CDN), from the ``design.json`` document, the trial rows and the
best design's curves. Layout in ``templates/design.html.j2`` (Jinja2, autoescaped, like the
report's); numbers here, figures in :mod:`.design_figures`.
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

from spsc.design.goal import METRIC_NAMES, Goal
from spsc.report.render import draw_figures, render_page

__all__ = ["write_page", "TOP_ROWS"]

#: Rows of the best trials' table.
TOP_ROWS = 15


def write_page(doc: dict, rows: list[dict], curves: dict | None, out) -> Path:
    """Draw the figures and write ``out/index.html``; returns its path. A figure that cannot
    be drawn (a render without an OpenGL context) is left out with a note, never the page."""
    out = Path(out)
    figs = out / "figures"
    figs.mkdir(parents=True, exist_ok=True)
    goal = Goal.from_dict(doc["goal"])
    searched = [k for k, v in doc["space"].items() if ("," in v or ":" in v)]
    best = _row(rows, doc["best"])
    pareto = [_row(rows, e) for e in doc["pareto"]]
    from spsc.report import design_figures as f

    specs = [("history", f.history_figure, rows, goal),
             ("front", f.front_figure, rows, goal, pareto, best),
             ("parallel", f.parallel_figure, rows, searched, goal, best)]
    if curves:
        specs.append(("curves", f.curves_figure, curves["fast"], curves.get("fem"),
                      doc["model"]))
    build = doc.get("build")
    if build:
        specs.append(("part", f.render_part, out / "part" / build["files"]["stl"]))
    figures, notes = draw_figures(figs, specs)
    ctx = {"doc": doc, "goal": goal, "figures": figures, "notes": notes,
           "metrics": METRIC_NAMES, "targets": _targets(goal),
           "top": _top(rows, goal), "searched": searched,
           "failures": _failures(rows), "labels": _LABELS,
           "needed_labels": [_LABELS[k] for k in goal.needed],
           "files": [(n, what) for n, what in _FILES if (out / n).is_file()]}
    path = out / "index.html"
    path.write_text(render_page(ctx, "design.html.j2"), encoding="utf-8")
    for n in notes:
        print(f"spsc design: warning: {n}", file=sys.stderr)
    return path


_LABELS = {"stiffness_high": "stiffness high (N/mm)", "stiffness_low": "stiffness low (N/mm)",
           "sensitivity_high": "sensitivity high (kPa/mm)",
           "sensitivity_low": "sensitivity low (kPa/mm)", "jnd_mm": "JND depth (mm)",
           "cavity_mm3": "cavity (mm³)"}


#: The run's files beside its page, linked when present.
_FILES = (("design.json", "the result"), ("trials.parquet", "every trial"),
          ("study.journal", "the Optuna study: a re-run with the same --out continues it"))


def _row(rows, entry):
    if entry is None:
        return None
    return next(r for r in rows if r["trial"] == entry["trial"])


def _targets(goal: Goal) -> dict:
    """metric → the targets' text on it (for the metrics table)."""
    out: dict = {}
    for t in goal.targets:
        out.setdefault(t.metric, []).append(f"{t.relation} {t.value:g}")
    for m, d in goal.objectives:
        out.setdefault(m, []).append(d)
    return {k: ", ".join(v) for k, v in out.items()}


def _top(rows, goal: Goal) -> list[dict]:
    """The best complete trials: feasible first, then by miss (several objectives: by the
    first objective)."""
    done = [r for r in rows if r["state"] == "COMPLETE"]
    if goal.multi:  # feasible first, then by the first objective
        m, d = goal.objectives[0]
        key = (lambda r: (not r["feasible"], r[m] if d == "minimize" else -r[m], r["trial"]))
    else:
        key = (lambda r: (not r["feasible"], r["miss"], r["trial"]))
    return sorted(done, key=key)[:TOP_ROWS]


def _failures(rows) -> list[tuple[str, int]]:
    """Failed trials grouped by the start of their reason (up to its first ' = ' or ':')."""
    c = Counter()
    for r in rows:
        if r["state"] == "FAIL":
            reason = str(r.get("reason") or "")
            c[reason.split(" is invalid")[0][:120]] += 1
    return c.most_common()
