"""Figures of a design run's page: the history of the best miss, the Pareto front (or the
trials in the plane of the targets' metrics), parallel coordinates of the trials, the best
design's curves with the fast model and the FEM, and a render of the built part. PNG files,
matplotlib (Agg) and pyvista off screen.

Rows are :func:`~.design.trial_rows`'s dicts; metrics in N/mm, kPa/mm, mm, mm³.
"""

from __future__ import annotations

import math
from pathlib import Path

from spsc.design.goal import Goal
from spsc.study.parallel import parallel_coordinates

__all__ = ["history_figure", "front_figure", "parallel_figure", "curves_figure", "render_part"]

_LABEL = {"stiffness_high": "stiffness, high mode (N/mm)",
          "stiffness_low": "stiffness, low mode (N/mm)",
          "sensitivity_high": "sensitivity, high mode (kPa/mm)",
          "sensitivity_low": "sensitivity, low mode (kPa/mm)", "jnd_mm": "JND depth (mm)",
          "cavity_mm3": "cavity volume (mm³)", "miss": "largest target miss"}
_FLOOR = 1e-4  # a miss of 0 on a log axis
_FEASIBLE = "feasible (printable, targets met)"


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _complete(rows):
    return [r for r in rows if r["state"] == "COMPLETE"]


def _save(fig, path) -> Path:
    fig.savefig(path, dpi=95)
    _plt().close(fig)
    return Path(path)


def history_figure(path, rows: list[dict], goal: Goal) -> Path:
    """Single objective: every trial's miss (printable or not; failed trials as ticks) and the
    best printable miss so far, against the trial number, with the tolerance. Several
    objectives: each objective's values against the trial number."""
    plt = _plt()
    done = _complete(rows)
    if goal.multi:
        names = [m for m, _ in goal.objectives]
        fig, axes = plt.subplots(1, len(names), figsize=(5.2 * len(names), 3.6),
                                 constrained_layout=True, squeeze=False)
        for a, m in zip(axes[0], names):
            _scatter_by_feasibility(a, [(r["trial"], r[m], r["feasible"]) for r in done],
                                    _FEASIBLE)
            a.set_xlabel("trial")
            a.set_ylabel(_LABEL[m])
        _failed_ticks(axes[0][0], rows)
        return _save(fig, path)
    fig, a = plt.subplots(figsize=(8, 4), constrained_layout=True)
    _scatter_by_feasibility(a, [(r["trial"], max(r["miss"], _FLOOR), r["feasible"])
                                for r in done])
    best, xs, ys = math.inf, [], []
    for r in sorted(done, key=lambda r: r["trial"]):
        if r["feasible"]:
            best = min(best, r["miss"])
        if math.isfinite(best):
            xs.append(r["trial"])
            ys.append(max(best, _FLOOR))
    if xs:
        a.step(xs, ys, where="post", color="C3", lw=2, label="best printable so far")
    a.axhline(max(goal.tol, _FLOOR), color="k", ls="--", lw=1,
              label=f"tolerance {100 * goal.tol:g} %")
    _failed_ticks(a, rows)
    a.set_yscale("log")
    a.set_xlabel("trial")
    a.set_ylabel("largest relative miss of the targets")
    a.grid(alpha=0.3, which="both")
    a.legend(fontsize=8)
    return _save(fig, path)


def _scatter_by_feasibility(a, pts, ok_label="printable") -> None:
    ok = [(x, y) for x, y, f in pts if f]
    bad = [(x, y) for x, y, f in pts if not f]
    if ok:
        a.plot(*zip(*ok), "o", color="C0", ms=4, label=ok_label)
    if bad:
        a.plot(*zip(*bad), "x", color="0.55", ms=5, label="infeasible")
    a.grid(alpha=0.3)


def _failed_ticks(a, rows) -> None:
    failed = [r["trial"] for r in rows if r["state"] == "FAIL"]
    if failed:
        a.plot(failed, [0.02] * len(failed), "|", color="C3", ms=10,
               transform=a.get_xaxis_transform(), label=f"failed ({len(failed)})")
    a.legend(fontsize=8)


def front_figure(path, rows: list[dict], goal: Goal, pareto: list[dict],
                 best: dict | None) -> Path | None:
    """Several objectives: the first two against each other, the Pareto front joined, the
    best starred. Targets only: the trials in the plane of the first two targets' metrics
    (one target: against the trial number), coloured by miss, with the targets drawn. None
    when there is nothing to plot."""
    plt = _plt()
    done = _complete(rows)
    if not done:
        return None
    fig, a = plt.subplots(figsize=(7, 5), constrained_layout=True)
    if goal.multi and len(goal.objectives) >= 2:
        (mx, _), (my, _) = goal.objectives[:2]
        _scatter_by_feasibility(a, [(r[mx], r[my], r["feasible"]) for r in done], _FEASIBLE)
        front = sorted(pareto, key=lambda r: r[mx])
        a.plot([r[mx] for r in front], [r[my] for r in front], "s-", color="C3", ms=5,
               label=f"Pareto front ({len(front)})")
    else:
        metrics = [t.metric for t in goal.targets] or [m for m, _ in goal.objectives]
        mx = metrics[0]
        my = metrics[1] if len(metrics) > 1 else None
        xs = [r[mx] for r in done]
        ys = [r[my] for r in done] if my else [r["trial"] for r in done]
        colour = [max(r["miss"], _FLOOR) for r in done]
        from matplotlib.colors import LogNorm

        sc = a.scatter(xs, ys, c=colour, cmap="viridis_r", s=22,
                       norm=LogNorm(vmin=min(colour), vmax=max(max(colour), 2 * min(colour))),
                       marker="o", edgecolors=["none" if r["feasible"] else "k" for r in done])
        fig.colorbar(sc, ax=a, label="largest miss (black edge: not printable)")
        for t in goal.targets:
            if t.metric == mx:
                _target_line(a, t, "x")
            elif t.metric == my:
                _target_line(a, t, "y")
    if best is not None:
        by = best[my] if my else best["trial"]
        a.plot([best[mx]], [by], "*", color="C1", ms=16, mec="k", label=f"best (trial {best['trial']})")
    a.set_xlabel(_LABEL[mx])
    a.set_ylabel(_LABEL[my] if my else "trial")
    a.grid(alpha=0.3)
    a.legend(fontsize=8)
    return _save(fig, path)


def _target_line(a, t, axis: str) -> None:
    line = a.axvline if axis == "x" else a.axhline
    line(t.value, color="C3", ls="--" if t.relation == "=" else "-", lw=1, label=f"target {t}")
    if t.relation != "=":
        span = a.axvspan if axis == "x" else a.axhspan
        lo, hi = (t.value, 1e12) if t.relation == ">=" else (-1e12, t.value)
        lim = a.get_xlim() if axis == "x" else a.get_ylim()
        span(max(lo, min(lim)), min(hi, max(lim)), color="C2", alpha=0.08)
        (a.set_xlim if axis == "x" else a.set_ylim)(lim)


def parallel_figure(path, rows: list[dict], searched: list[str], goal: Goal,
                    best: dict | None) -> Path | None:
    """Parallel coordinates of the complete trials over the searched inputs, the goal's
    metrics and (targets) the miss; each axis scaled to its range, the type as a category.
    Lines coloured by the miss (targets) or by the first objective; infeasible ones grey;
    the best in red."""
    plt = _plt()
    done = _complete(rows)
    if not done:
        return None
    axes = list(searched) + list(goal.needed) + (["miss"] if goal.targets else [])
    key = "miss" if goal.targets else goal.objectives[0][0]
    low = key == "miss" or goal.objectives[0][1] == "minimize"
    fig, a = plt.subplots(figsize=(max(7, 1.25 * len(axes)), 4.6), constrained_layout=True)
    k = None if best is None else next(i for i, r in enumerate(done)
                                       if r["trial"] == best["trial"])
    parallel_coordinates(fig, a, done, axes, [float(r[key]) for r in done],
                         [r["feasible"] for r in done], cmap="viridis_r" if low else "viridis",
                         label=_LABEL.get(key, key), better="low" if low else "high",
                         highlight=k, highlight_label="" if best is None
                         else f"best (trial {best['trial']})")
    return _save(fig, path)


def curves_figure(path, fast: dict, fem: dict, fast_name: str) -> Path:
    """F(y) and P(y) of the best design in both modes: the fast model (lines) and the FEM
    (markers), when it ran."""
    plt = _plt()
    fig, ax = plt.subplots(1, 2, figsize=(11, 4), constrained_layout=True)
    for a, (col, lab) in zip(ax, (("force_N", "force F (N)"),
                                  ("pressure_kPa", "gauge pressure P (kPa)"))):
        for mode, colour in (("high", "C0"), ("low", "C1")):
            c = fast.get(mode)
            if c is not None:
                a.plot(c.y_mm, getattr(c, col), "-", color=colour, label=f"{fast_name}, {mode}")
            c = (fem or {}).get(mode)
            if c is not None:
                a.plot(c.y_mm, getattr(c, col), "o", color=colour, mfc="none", ms=5,
                       label=f"3D FEM, {mode}")
        a.set_xlabel("plate travel y (mm)")
        a.set_ylabel(lab)
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    return _save(fig, path)


def render_part(png, stl, window=(1000, 420)) -> Path:
    """Off-screen render of the built part: whole (iso view) and cut in half on the y = 0
    plane, seen from the cut, which shows the wall and the cavity."""
    import warnings

    import pyvista as pv

    part = pv.read(str(stl))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        half = part.clip(normal=(0, 1, 0), origin=(0, 0, 0))
    with pv.vtk_verbosity("off"):  # VTK's notice of no X display when it falls back off screen
        _render(pv, (part, half), png, window)
    return Path(png)


def _render(pv, meshes, png, window) -> None:
    pl = pv.Plotter(off_screen=True, window_size=window, shape=(1, 2), border=False)
    for i, mesh in enumerate(meshes):
        pl.subplot(0, i)
        pl.add_mesh(mesh, color="#8fb9d6", smooth_shading=True, split_sharp_edges=True,
                    specular=0.3)
        if i == 0:
            pl.camera_position = "iso"
        else:
            b = mesh.bounds
            centre = ((b[0] + b[1]) / 2, 0.0, (b[4] + b[5]) / 2)
            d = max(b[1] - b[0], b[5] - b[4])
            pl.camera_position = [(centre[0] + 0.5 * d, 2.2 * d, centre[2] + 1.2 * d), centre,
                                  (0, 0, 1)]
    pl.set_background("white")
    pl.screenshot(str(png))
    pl.close()
