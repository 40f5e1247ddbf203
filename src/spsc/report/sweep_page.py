"""The HTML page of a sweep: ``DIR/index.html`` with its figures in ``DIR/figures`` and the whole
table as ``DIR/table.csv`` (self-contained: local files, no CDN), from the sweep's table. Layout
in ``templates/sweep.html.j2`` (Jinja2, autoescaped, like the report's); figures in
:mod:`.sweep_figures`.
"""

from __future__ import annotations

import math
import sys
from collections import Counter
from pathlib import Path

from spsc.design.output import rerun_commands
from spsc.report.render import draw_figures, render_page
from spsc.sweep.evaluate import INPUTS, METRICS, STATUSES
from spsc.report.sweep_figures import LABEL, Front, pareto_mask

__all__ = ["write_page", "DEFAULT_FRONT", "TOP_ROWS"]

#: The default front: the most pressure per mm of press for the least enclosed air (a small,
#: sensitive chamber).
DEFAULT_FRONT = "sensitivity_high:max,cavity_mm3:min"
#: Rows of the table of best designs.
TOP_ROWS = 25


def write_page(df, out, *, model: str, process: str, stroke_mm: float, points: int | None,
               front: Front | str = DEFAULT_FRONT, command: str = "", table: str = "",
               searched=None) -> Path:
    """Draw the figures, write ``out/table.csv`` and ``out/index.html`` for the sweep table
    ``df`` (pandas, :data:`~.sweep_eval.COLUMNS`); returns the page's path. ``searched``: the
    inputs the sweep spans (its axes; None: every input that differs between rows); inputs
    that differ only because the type's preset sets them are listed, not plotted. A figure
    that cannot be drawn is left out with a note on the page and stderr, never the page."""
    from spsc.report import sweep_figures as f

    front = Front.parse(front) if isinstance(front, str) else front
    out = Path(out)
    figs = out / "figures"
    figs.mkdir(parents=True, exist_ok=True)
    df.to_csv(out / "table.csv", index=False)
    rows = [_plain(r) for r in df.to_dict("records")]
    differ = [k for k in INPUTS if df[k].nunique(dropna=False) > 1]
    varied = differ if searched is None else [k for k in differ if k in set(searched)]
    by_type = [k for k in differ if k not in varied]
    fixed = {k: rows[0][k] for k in INPUTS if k not in differ} if rows else {}
    by = next((k for k in ("type", "material") if k in varied), None)
    computed = [r["status"] in ("ok", "partial") for r in rows]
    good = [c and bool(r["printable"]) for c, r in zip(computed, rows)]
    values = [[r[m] if g else math.nan for m in front.metrics] for r, g in zip(rows, good)]
    mask = pareto_mask(values, front.senses) if rows else []
    figures, notes = draw_figures(figs, [("modes", f.modes_figure, rows, by),
                                         ("front", f.front_figure, rows, front, mask, by),
                                         ("effects", f.effects_figure, rows, varied, by),
                                         ("parallel", f.parallel_figure, rows, varied, front),
                                         ("band", f.band_figure, rows, by)])
    on_front = sorted((r for r, m in zip(rows, mask) if m), key=lambda r: r[front.metrics[0]],
                      reverse=front.senses[0] == "max")
    ctx = {"model": model, "process": process, "stroke_mm": stroke_mm, "points": points,
           "command": command, "front": front, "labels": LABEL, **_table_ref(table, out),
           "metrics": METRICS, "varied": varied, "fixed": fixed, "by_type": by_type, "figures": figures,
           "notes": notes, "n": len(rows), "stats": dict(df.attrs.get("sweep", {})),
           "status_counts": _status_counts(rows),
           "printable": sum(bool(r["printable"]) for r in rows if r["printable"] is not None),
           "ranges": _ranges(rows, varied + by_type),
           "front_rows": [_with_rerun(r, model, points, stroke_mm) for r in on_front],
           "top": _top(rows, good, front), "problems": _problems(rows),
           "life": any(r.get("life_cycles") is not None for r in rows),
           "band": any(f._has_band(r) for r in rows)}
    path = out / "index.html"
    path.write_text(render_page(ctx, "sweep.html.j2"), encoding="utf-8")
    for n in notes:
        print(f"spsc sweep: warning: {n}", file=sys.stderr)
    return path


def _table_ref(table: str, out: Path) -> dict:
    """How the page names the sweep's own table: a link relative to the page when the table
    is inside the page's folder (it moves with it), else its absolute path as text (a link
    would lean on where the page was written)."""
    if not table:
        return {"table": "", "table_link": ""}
    path, folder = Path(table).resolve(), out.resolve()
    inside = path.is_relative_to(folder)
    return {"table": str(path), "table_link": path.relative_to(folder).as_posix() if inside
            else ""}


def _plain(row: dict) -> dict:
    """A table row with Python values: pandas' missing value (pd.NA: a string or the nullable
    ``printable``) as None, numpy scalars as floats; a missing metric stays NaN."""
    import pandas as pd

    out = {}
    for k, v in row.items():
        if v is pd.NA:
            v = None
        elif hasattr(v, "item"):  # numpy scalars
            v = v.item()
        out[k] = v
    return out


def _ranges(rows, varied) -> dict:
    """input → its values ("A, B, C") or range ("8–14, 1000 values") over the table."""
    out = {}
    for k in varied:
        vals = [r[k] for r in rows]
        uniq = sorted({str(v) for v in vals}) if k in ("type", "material") else \
            sorted({float(v) for v in vals if v is not None})
        if k in ("type", "material") or len(uniq) <= 8:
            out[k] = ", ".join(v if isinstance(v, str) else f"{v:g}" for v in uniq)
        else:
            out[k] = f"{uniq[0]:.4g} – {uniq[-1]:.4g} ({len(uniq)} values)"
    return out


def _with_rerun(row: dict, model: str, points, stroke_mm) -> dict:
    row = dict(row)
    row["rerun"] = rerun_commands(row, model, points, stroke_mm)
    return row


def _top(rows, good, front: Front) -> list[dict]:
    """The best printable computed designs by the front's first metric."""
    m, sense = front.metrics[0], front.senses[0]
    cand = [r for r, g in zip(rows, good) if g and math.isfinite(r[m])]
    return sorted(cand, key=lambda r: r[m], reverse=sense == "max")[:TOP_ROWS]


def _status_counts(rows) -> list[tuple[str, int]]:
    """(status, count) of the statuses present, in :data:`~.sweep_eval.STATUSES` order."""
    c = Counter(r["status"] for r in rows)
    return [(s, c[s]) for s in STATUSES if c[s]]


def _problems(rows) -> list[tuple[str, str, int]]:
    """(status, message start, count) of the rows that are not ok, commonest first."""
    c = Counter()
    for r in rows:
        if r["status"] != "ok":
            c[(r["status"], str(r.get("message") or "")[:140])] += 1
    return [(s, msg, n) for (s, msg), n in c.most_common()]
