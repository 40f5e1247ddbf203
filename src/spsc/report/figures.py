"""Figures of the validation report: curves of the models, deformed shapes (FEM render
from its VTU beside the membrane meridian), mesh convergence. PNG files, matplotlib (Agg) and
pyvista off screen; no display needed."""

from __future__ import annotations

import hashlib
import importlib.util
import json
import shutil
import sys
from pathlib import Path

import numpy as np

from spsc.study.metrics import interp

__all__ = ["FigureCache", "curves_figure", "render_vtu", "shapes_figure", "shapes_panel",
           "convergence_figure"]

_F_EL = {"color": "0.45", "label": "FEM open chamber F_el"}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


_PANELS = (("force_N", "force F (N)"), ("pressure_kPa", "gauge pressure P (kPa)"),
           ("contact_area_mm2", "contact area A (mm²)"),
           ("volume_change_mm3", "volume change ΔV (mm³)"))


def curves_figure(path, title: str, curves, *, f_el=None) -> Path:
    """F(y), P(y), A(y), ΔV(y) of the models on one plot each. ``curves``: (Model, Curve or
    None) pairs (None: a failed run, left out); a model without bending gets F_el(y) (the FEM
    open chamber, interpolated on its grid) added to its force p·A, which is drawn faintly."""
    plt = _plt()
    fig, ax = plt.subplots(2, 2, figsize=(10, 7), constrained_layout=True)
    fel = None if f_el is None else interp(f_el.y_mm, f_el.force_N)
    for a, (col, lab) in zip(ax.flat, _PANELS):
        for m, c in curves:
            if c is not None:
                _draw(a, m, c, col, fel)
        if col == "force_N" and f_el is not None:
            a.plot(f_el.y_mm, f_el.force_N, "s:", color=_F_EL["color"], ms=3,
                   label=_F_EL["label"])
        a.set_xlabel("plate travel y (mm)")
        a.set_ylabel(lab)
        a.grid(alpha=0.3)
        if a.get_legend_handles_labels()[0]:  # every run of the panel may have failed
            a.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return Path(path)


def _draw(a, m, c, col, fel) -> None:
    v, label = getattr(c, col), m.name
    marker = m.style not in ("-", "--", "-.", ":")
    kw = {"ms": 4} if marker else {}
    if col == "force_N" and fel is not None and not m.bending:
        a.plot(c.y_mm, v, m.style, color=m.color, lw=0.8, alpha=0.5, label=f"{m.name} p·A", **kw)
        v, label = v + fel(c.y_mm), f"{m.name} p·A + FEM F_el"
    a.plot(c.y_mm, v, m.style, color=m.color, label=label, **kw)


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
    with pv.vtk_verbosity("off"):  # VTK's notice of no X display when it falls back off screen
        _render_parts(pv, parts, warped, png, plate, window)
    return Path(png)


def _render_parts(pv, parts, warped, png, plate, window) -> None:
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


def shapes_panel(path, title: str, mem_payload, fem_payload) -> Path:
    """Renders of the FEM VTUs (inflated, pressed) beside the meridians, into ``path``."""
    renders = []
    if fem_payload:
        d = Path(fem_payload["dir"])
        for k, cap in (("inflated", "FEM inflated"), ("pressed", "FEM pressed")):
            name = fem_payload.get("vtu", {}).get(k)
            if not name or not (d / name).is_file():
                continue
            png = path.with_name(f"render-{path.stem}-{k}.png")
            try:
                render_vtu(d / name, png, plate=k == "pressed")
            except Exception as exc:  # noqa: BLE001 — a failed render must not stop the report
                print(f"spsc report: render of {d / name} failed: {exc}", file=sys.stderr)
                continue
            if k == "pressed" and fem_payload.get("pressed_y_mm") is not None:
                cap += f", y = {fem_payload['pressed_y_mm']:g} mm"
            renders.append((png, cap))
    mer = (mem_payload or {}).get("meridians")
    plates = [max(mer["pressed"]["eta"])] if mer and mer.get("pressed") else []
    shapes_figure(path, "Deformed shapes — " + title, renders=renders, membrane=mer,
                  fem=(fem_payload or {}).get("sections"), plates=plates)
    for png, _ in renders:  # composed into the figure; the HTML shows only that
        png.unlink(missing_ok=True)
    return Path(path)


#: the code a figure depends on besides its runs: drawing, interpolation, model styles, layout
#: the modules whose code a figure depends on (a changed one draws every figure again)
_FIGURE_SOURCES = ("spsc.report.figures", "spsc.study.metrics", "spsc.study.runs",
                   "spsc.report.sections")


class FigureCache:
    """Figures kept by a hash of what they show: the runs' cache keys (``run_key(run)``, None
    for a missing run), extra inputs (titles) and the plotting code. ``root`` None: always
    draw."""

    def __init__(self, run_key, root=None):
        self.run_key = run_key
        self.root = None if root is None else Path(root)
        h = hashlib.sha256()
        for name in _FIGURE_SOURCES:
            spec = importlib.util.find_spec(name)
            h.update(Path(spec.origin).read_bytes())
        self.code = h.hexdigest()[:16]

    def draw(self, path: Path, runs, make, *extra) -> Path:
        """``make(path)`` unless a figure of the same runs, extra inputs and code is cached."""
        parts = [path.name, list(map(str, extra)), self.code]
        parts += [self.run_key(r) if r is not None else None for r in runs]
        key = hashlib.sha256(json.dumps(parts, default=str).encode()).hexdigest()[:16]
        cached = None if self.root is None else self.root / f"{path.stem}-{key}.png"
        if cached is not None and cached.is_file():
            shutil.copyfile(cached, path)
            return path
        make(path)
        if cached is not None and path.is_file():
            cached.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, cached)
        return path
