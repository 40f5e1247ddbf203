"""Figures of a sweep's page: both modes in the stiffness–sensitivity plane, a Pareto front of two
metrics over the printable designs, each metric against each varied input, and parallel
coordinates of the whole table. PNG files, matplotlib (Agg).

Rows are the sweep table's (:data:`~.sweep_eval.COLUMNS`) as dicts; metrics in N/mm, kPa/mm,
mm, mm³.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from spsc.study.parallel import CATEGORICAL, parallel_coordinates
from spsc.cad.geometry import LENGTHS

__all__ = ["LABEL", "Front", "pareto_mask", "modes_figure", "front_figure", "effects_figure",
           "parallel_figure"]

LABEL = {"stiffness_high": "stiffness, high mode (N/mm)",
         "stiffness_low": "stiffness, low mode (N/mm)",
         "sensitivity_high": "sensitivity, high mode (kPa/mm)",
         "sensitivity_low": "sensitivity, low mode (kPa/mm)", "jnd_mm": "JND depth (mm)",
         "cavity_mm3": "cavity volume (mm³)"}
#: Metrics drawn against the varied inputs (rows of the effects figure).
EFFECT_METRICS = ("stiffness_high", "sensitivity_high", "sensitivity_low", "jnd_mm")
_MARKERS = "osD^v<>p*h"


class Front:
    """Two metrics and their senses, e.g. ``Front.parse("sensitivity_high:max,cavity_mm3:min")``:
    the Pareto front of the printable, computed designs on them."""

    def __init__(self, metrics: tuple[str, str], senses: tuple[str, str]):
        self.metrics, self.senses = tuple(metrics), tuple(senses)

    @classmethod
    def parse(cls, text: str) -> Front:
        """``"m1:max|min,m2:max|min"``; ParameterError naming ``front`` otherwise."""
        from spsc.core.errors import ParameterError

        allowed = ("two metrics with a sense, e.g. sensitivity_high:max,cavity_mm3:min "
                   f"(metrics: {', '.join(LABEL)})")
        parts = [p.strip() for p in str(text).split(",")]
        if len(parts) != 2:
            raise ParameterError("front", text, allowed)
        metrics, senses = [], []
        for p in parts:
            m, _, s = p.partition(":")
            if m not in LABEL or s not in ("max", "min") or m in metrics:
                raise ParameterError("front", text, allowed)
            metrics.append(m)
            senses.append(s)
        return cls(tuple(metrics), tuple(senses))

    def __str__(self) -> str:
        return ",".join(f"{m}:{s}" for m, s in zip(self.metrics, self.senses))

    def describe(self) -> str:
        word = {"max": "highest", "min": "lowest"}
        return " against ".join(f"{word[s]} {LABEL[m].split(' (')[0]}"
                                for m, s in zip(self.metrics, self.senses))


def pareto_mask(values, senses) -> np.ndarray:
    """Rows of ``values`` (n × k) that no other row dominates (at least as good in every
    column and better in one); ``senses`` "max"/"min" per column; rows with NaN are not on
    the front."""
    v = np.asarray(values, float) * np.array([-1.0 if s == "max" else 1.0 for s in senses])
    ok = np.isfinite(v).all(axis=1)
    mask = np.zeros(len(v), bool)
    idx = np.flatnonzero(ok)
    w = v[idx]
    for j, i in enumerate(idx):
        dominated = np.all(w <= w[j], axis=1) & np.any(w < w[j], axis=1)
        mask[i] = not dominated.any()
    return mask


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path) -> Path:
    fig.savefig(path, dpi=95)
    _plt().close(fig)
    return Path(path)


def _computed(rows):
    return [r for r in rows if r["status"] in ("ok", "partial")]


def _groups(rows, by: str | None):
    """(label, rows) per value of the categorical column ``by`` (None: one group)."""
    if by is None:
        return [("", rows)]
    keys = sorted({str(r[by]) for r in rows})
    return [(f"{by} {k}" if by == "type" else k, [r for r in rows if str(r[by]) == k])
            for k in keys]


def _points(a, rows, x, y, by, *, legend=True) -> None:
    """Filled markers for printable rows, hollow for the rest, one colour and marker per group."""
    for i, (label, group) in enumerate(_groups(rows, by)):
        colour, marker = f"C{i % 10}", _MARKERS[i % len(_MARKERS)]
        for printable, face in ((True, colour), (False, "none")):
            g = [r for r in group if bool(r["printable"]) is printable]
            if g:
                a.plot([r[x] for r in g], [r[y] for r in g], marker, color=colour, mfc=face,
                       ms=4, alpha=0.8, ls="none",
                       label=(label or "designs") + ("" if printable else ", not printable")
                       if legend else None)
    a.grid(alpha=0.3)


def modes_figure(path, rows: list[dict], by: str | None) -> Path | None:
    """Stiffness against sensitivity in the high (closed) and low (reservoir) modes, side by
    side on shared axes: how far the valve moves each design. None if nothing was computed."""
    plt = _plt()
    rows = _computed(rows)
    if not rows:
        return None
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True, sharex=True,
                           sharey=True)
    for a, mode in zip(ax, ("high", "low")):
        _points(a, rows, f"stiffness_{mode}", f"sensitivity_{mode}", by, legend=mode == "high")
        a.set_xlabel(f"stiffness, {mode} mode (N/mm)")
        a.set_ylabel(f"sensitivity, {mode} mode (kPa/mm)")
        a.set_title(f"{mode} mode" + (" (closed chamber)" if mode == "high" else
                                      " (with the reservoir)"), fontsize=10)
    ax[0].legend(fontsize=7, ncol=2)
    return _save(fig, path)


def front_figure(path, rows: list[dict], front: Front, mask, by: str | None) -> Path | None:
    """The two front metrics of every computed design, the Pareto front of the printable ones
    joined and squared."""
    plt = _plt()
    rows_c = [(r, m) for r, m in zip(rows, mask) if r["status"] in ("ok", "partial")]
    if not rows_c:
        return None
    (mx, my) = front.metrics
    fig, a = plt.subplots(figsize=(7.5, 5), constrained_layout=True)
    _points(a, [r for r, _ in rows_c], mx, my, by)
    on = sorted((r for r, m in rows_c if m), key=lambda r: r[mx])
    if on:
        a.plot([r[mx] for r in on], [r[my] for r in on], "s-", color="k", mfc="none", ms=8,
               lw=1, label=f"Pareto front, printable ({len(on)})")
    a.set_xlabel(LABEL[mx])
    a.set_ylabel(LABEL[my])
    a.set_title(front.describe(), fontsize=10)
    a.legend(fontsize=7, ncol=2)
    return _save(fig, path)


def effects_figure(path, rows: list[dict], inputs: list[str], by: str | None) -> Path | None:
    """Each metric of :data:`EFFECT_METRICS` (rows) against each varied numeric input
    (columns): a scatter per panel, coloured by ``by``; the spread at one input value is what
    the other inputs do."""
    plt = _plt()
    rows = _computed(rows)
    inputs = [n for n in inputs if n not in CATEGORICAL]
    if not rows or not inputs:
        return None
    nr, nc = len(EFFECT_METRICS), len(inputs)
    fig, ax = plt.subplots(nr, nc, figsize=(2.9 * nc + 0.6, 2.3 * nr), squeeze=False,
                           constrained_layout=True, sharex="col", sharey="row")
    for i, m in enumerate(EFFECT_METRICS):
        for j, n in enumerate(inputs):
            _points(ax[i][j], rows, n, m, by, legend=(i, j) == (0, 0))
            if i == nr - 1:
                ax[i][j].set_xlabel(_input_label(n))
            if j == 0:
                ax[i][j].set_ylabel(LABEL[m].replace(", ", ",\n"), fontsize=8)
    ax[0][0].legend(fontsize=6)
    return _save(fig, path)


def parallel_figure(path, rows: list[dict], inputs: list[str], front: Front) -> Path | None:
    """Parallel coordinates over the varied inputs and the metrics, coloured by the front's
    first metric; designs not printable grey."""
    plt = _plt()
    rows = _computed(rows)
    if not rows:
        return None
    metrics = list(dict.fromkeys(list(front.metrics) + list(LABEL)))
    axes = list(inputs) + metrics
    key, sense = front.metrics[0], front.senses[0]
    fig, a = plt.subplots(figsize=(max(8.0, 1.1 * len(axes)), 4.8), constrained_layout=True)
    parallel_coordinates(fig, a, rows, axes, [float(r[key]) for r in rows],
                         [bool(r["printable"]) for r in rows],
                         cmap="viridis" if sense == "max" else "viridis_r", label=LABEL[key],
                         better="high" if sense == "max" else "low")
    return _save(fig, path)


def _input_label(name: str) -> str:
    unit = {"pressure": "kPa", "reservoir": "mm³"}.get(name, "mm" if name in LENGTHS
                                                         else "")
    return f"{name} ({unit})" if unit else name


def _has_band(row: dict) -> bool:
    v = row.get("stiffness_high_p50")
    return v is not None and v == v  # a missing metric is NaN


def band_figure(path, rows: list[dict], by: str | None) -> Path | None:
    """Each design's nominal stiffness and sensitivity (high mode, low mode) with its band
    under the sweep's tolerance: P5–P95 bars about the P50, against the nominal value (the
    bars' length is what the prints spread). None without bands."""
    plt = _plt()
    rows = [r for r in _computed(rows) if _has_band(r)]
    if not rows:
        return None
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True)
    for a, (metric, unit) in zip(ax, (("stiffness", "N/mm"), ("sensitivity", "kPa/mm"))):
        for i, (label, group) in enumerate(_groups(rows, by)):
            for j, mode in enumerate(("high", "low")):
                x = np.array([r[f"{metric}_{mode}"] for r in group], float)
                mid = np.array([r[f"{metric}_{mode}_p50"] for r in group], float)
                lo = mid - np.array([r[f"{metric}_{mode}_p5"] for r in group], float)
                hi = np.array([r[f"{metric}_{mode}_p95"] for r in group], float) - mid
                a.errorbar(x, mid, yerr=[lo, hi], fmt=_MARKERS[j % len(_MARKERS)], ms=3,
                           color=f"C{(2 * i + j) % 10}", elinewidth=0.8, alpha=0.8,
                           label=f"{label + ', ' if label else ''}{mode} mode")
        lim = a.get_xlim()
        a.plot(lim, lim, color="0.6", lw=0.8, ls="--")
        a.set_xlabel(f"nominal {metric} ({unit})")
        a.set_ylabel(f"its prints: P50 and P5–P95 ({unit})")
        a.grid(alpha=0.3)
    ax[0].legend(fontsize=7)
    return _save(fig, path)
