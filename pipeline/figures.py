"""Figures of the validation report: curves of the three models, deformed shapes (FEM render
from its VTU beside the membrane meridian), mesh convergence. PNG files, matplotlib (Agg) and
pyvista off screen; no display needed."""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["curves_figure", "render_vtu", "shapes_figure", "convergence_figure"]

_COLORS = {"fem": "C3", "membrane": "C0", "simplified": "C2", "f_el": "0.45"}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def curves_figure(path, title: str, *, fem=None, membrane=None, simplified=None, f_el=None):
    """F(y), P(y), A(y), ΔV(y) of the models on one plot each. ``membrane`` and
    ``simplified`` force is p·A plus the FEM open-chamber F_el (interpolated on their grid)
    when ``f_el`` is given; F_el itself is drawn too. Curves may be None (failed runs)."""
    plt = _plt()
    fig, ax = plt.subplots(2, 2, figsize=(10, 7), constrained_layout=True)
    panels = (("force_N", "force F (N)"), ("pressure_kPa", "gauge pressure P (kPa)"),
              ("contact_area_mm2", "contact area A (mm²)"),
              ("volume_change_mm3", "volume change ΔV (mm³)"))
    fel = None if f_el is None else interp(f_el.y_mm, f_el.force_N)
    for a, (col, lab) in zip(ax.flat, panels):
        for name, c, style in (("membrane", membrane, "-"), ("simplified", simplified, "--")):
            if c is None:
                continue
            v = getattr(c, col)
            label = name
            if col == "force_N" and fel is not None:
                a.plot(c.y_mm, v, style, color=_COLORS[name], lw=0.8, alpha=0.5,
                       label=f"{name} p·A")
                v = v + fel(c.y_mm)
                label = f"{name} p·A + FEM F_el"
            a.plot(c.y_mm, v, style, color=_COLORS[name], label=label)
        if fem is not None:
            a.plot(fem.y_mm, getattr(fem, col), "o", color=_COLORS["fem"], ms=4, label="FEM")
        if col == "force_N" and f_el is not None:
            a.plot(f_el.y_mm, f_el.force_N, "s:", color=_COLORS["f_el"], ms=3,
                   label="FEM open chamber F_el")
        a.set_xlabel("plate travel y (mm)")
        a.set_ylabel(lab)
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return Path(path)


def interp(y, v):
    """Linear interpolation of the finite samples of v(y); NaN outside them."""
    y, v = np.asarray(y, float), np.asarray(v, float)
    ok = np.isfinite(v)

    def f(x):
        x = np.asarray(x, float)
        if ok.sum() < 2:
            return np.full_like(x, np.nan)
        out = np.interp(x, y[ok], v[ok])
        out[(x < y[ok][0] - 1e-12) | (x > y[ok][-1] + 1e-12)] = np.nan
        return out

    return f


def render_vtu(vtu, png, *, plate: bool = False, window=(640, 480)) -> Path:
    """Off-screen render of a quarter-model VTU warped by its displacement, mirrored to the
    full part, coloured by |u| (mm); with ``plate``, the plate (at the top of the deformed
    part) as a translucent square."""
    import pyvista as pv

    import warnings

    grid = pv.read(str(vtu))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pyvista's notice of a future default
        surf = grid.extract_surface(nonlinear_subdivision=1)
    warped = surf.warp_by_vector("displacement")
    warped["|u| (mm)"] = np.linalg.norm(warped["displacement"], axis=1)
    parts = [warped, warped.reflect((1, 0, 0), point=(0, 0, 0)),
             warped.reflect((0, 1, 0), point=(0, 0, 0))]
    parts.append(parts[1].reflect((0, 1, 0), point=(0, 0, 0)))
    pl = pv.Plotter(off_screen=True, window_size=window)
    for p in parts:
        pl.add_mesh(p, scalars="|u| (mm)", clim=(0.0, max(float(warped["|u| (mm)"].max()), 1e-9)),
                    cmap="viridis", show_scalar_bar=p is parts[0], smooth_shading=True,
                    scalar_bar_args={"title": "|u| (mm)", "vertical": True})
    if plate:
        b = warped.bounds
        plate_z = b[5]
        s = 1.3 * max(abs(b[0]), abs(b[1]), abs(b[2]), abs(b[3]))
        pl.add_mesh(pv.Plane(center=(0, 0, plate_z), direction=(0, 0, 1), i_size=2 * s,
                             j_size=2 * s), color="lightgray", opacity=0.35)
    pl.camera_position = "iso"
    pl.camera.elevation = -10
    pl.set_background("white")
    pl.screenshot(str(png))
    pl.close()
    return Path(png)


def shapes_figure(path, title: str, *, renders=(), membrane=None, fem=None,
                  plates=()) -> Path:
    """FEM renders (PNG paths with captions) beside the meridians: membrane (cavity
    surface, ρ–η) and the FEM cavity section in the plane y = 0, nominal, inflated and pressed;
    plate heights as horizontal lines."""
    plt = _plt()
    n = len(renders) + 1
    fig, ax = plt.subplots(1, n, figsize=(4.2 * n, 4.2), constrained_layout=True)
    ax = np.atleast_1d(ax)
    for a, (png, caption) in zip(ax, renders):
        a.imshow(plt.imread(str(png)))
        a.set_title(caption, fontsize=9)
        a.axis("off")
    a = ax[-1]
    styles = {"inflated": "-", "pressed": "-"}
    colors = {"inflated": "C0", "pressed": "C1"}
    if membrane:
        nom = membrane.get("nominal")
        if nom:
            a.plot(nom["x"], nom["y"], "k:", lw=1, label="nominal")
        for k in ("inflated", "pressed"):
            m = membrane.get(k)
            if m:
                a.plot(m["rho"], m["eta"], styles[k], color=colors[k], label=f"membrane {k}")
    if fem:
        for k in ("inflated", "pressed"):
            s = fem.get(k)
            if s:
                a.plot(s["rho"], s["eta"], "o", color=colors[k], ms=2.5, mfc="none",
                       label=f"FEM {k} (cavity, y = 0)")
    for z in plates:
        if z is not None and np.isfinite(z):
            a.axhline(z, color="0.5", lw=0.8)
    a.set_aspect("equal")
    a.set_xlabel("radius (mm)")
    a.set_ylabel("height (mm)")
    a.grid(alpha=0.3)
    a.legend(fontsize=7, loc="lower left")
    fig.suptitle(title, fontsize=10)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return Path(path)


def convergence_figure(path, title: str, curves) -> Path:
    """Force and pressure of one chamber on several meshes: ``curves`` [(label, Curve)]."""
    plt = _plt()
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    for label, c in curves:
        ax[0].plot(c.y_mm, c.force_N, "o-", ms=3, label=label)
        ax[1].plot(c.y_mm, c.pressure_kPa, "o-", ms=3, label=label)
    for a, lab in zip(ax, ("force F (N)", "gauge pressure P (kPa)")):
        a.set_xlabel("plate travel y (mm)")
        a.set_ylabel(lab)
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return Path(path)
