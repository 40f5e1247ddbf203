"""Parallel coordinates of table rows (design trials, sweep rows): one vertical axis per column,
each scaled to its own range, categories (type, material) spread evenly; lines coloured by a
score, rows that fail a test (not printable, infeasible) grey underneath. matplotlib."""

from __future__ import annotations

import numpy as np

__all__ = ["CATEGORICAL", "parallel_coordinates"]

#: Columns drawn as categories.
CATEGORICAL = ("type", "material")


def _axis(values, name):
    """(values scaled to 0..1, ticks): ticks are (categories, top index) or (lo, hi)."""
    if name in CATEGORICAL:
        cats = sorted({str(v) for v in values})
        col = np.array([cats.index(str(v)) for v in values], float)
        top = len(cats) - 1 or 1
        return col / top if len(cats) > 1 else np.full_like(col, 0.5), (cats, top)
    col = np.array([np.nan if v is None else float(v) for v in values], float)
    if not np.isfinite(col).any():
        return np.full_like(col, np.nan), (np.nan, np.nan)
    lo, hi = np.nanmin(col), np.nanmax(col)
    return ((col - lo) / (hi - lo) if hi > lo else np.full_like(col, 0.5)), (lo, hi)


def parallel_coordinates(fig, a, rows: list[dict], axes: list[str], score, good, *,
                         cmap: str = "viridis", label: str = "", better: str = "high",
                         highlight=None, highlight_label: str = "") -> None:
    """Draw ``rows`` (dicts) over the columns ``axes`` on ``a``: ``score`` (one float per row)
    colours the ``good`` rows (bools), the others grey; the best score (``better``: "high" or
    "low") is drawn last, on top; ``highlight`` (a row index) in red, thick. NaN values leave
    a gap in a line."""
    import matplotlib.pyplot as plt

    cols, ticks = zip(*(_axis([r.get(n) for r in rows], n) for n in axes))
    data = np.array(cols).T
    score = np.asarray(score, float)
    finite = score[np.isfinite(score)]
    norm = plt.Normalize(*(finite.min(), finite.max()) if finite.size else (0.0, 1.0))
    colours = plt.get_cmap(cmap)
    x = np.arange(len(axes))
    sign = 1.0 if better == "high" else -1.0
    order = sorted(range(len(rows)),
                   key=lambda k: (bool(good[k]), np.nan_to_num(sign * score[k], nan=-np.inf)))
    for k in order:
        style = (dict(color=colours(norm(score[k])), lw=0.9, alpha=0.8)
                 if good[k] and np.isfinite(score[k]) else dict(color="0.75", lw=0.6, alpha=0.5))
        a.plot(x, data[k], **style)
    if highlight is not None:
        a.plot(x, data[highlight], color="C3", lw=2.5, label=highlight_label)
        a.legend(fontsize=8, loc="upper right")
    for i, t in enumerate(ticks):
        a.axvline(i, color="k", lw=0.6)
        if isinstance(t[0], list):
            for j, c in enumerate(t[0]):
                a.text(i, j / t[1] if len(t[0]) > 1 else 0.5, f" {c}", fontsize=8,
                       va="center")
        elif np.isfinite(t[0]):
            a.text(i, -0.06, f"{t[0]:.3g}", ha="center", va="top", fontsize=7)
            a.text(i, 1.04, f"{t[1]:.3g}", ha="center", va="bottom", fontsize=7)
    a.set_xticks(x, [n.replace("_", " ") for n in axes], fontsize=8)
    a.set_yticks([])
    a.set_ylim(-0.12, 1.1)
    for s in ("top", "right", "left"):
        a.spines[s].set_visible(False)
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=colours), ax=a, label=label)
