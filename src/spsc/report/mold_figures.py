"""Off-screen renders of a mold: closed (the halves see-through, the part and the core inside) and
exploded (every piece moved along its pull direction; the core drawn out of the part)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["render_mold"]

COLORS = {"half": "#9db4c8", "pin": "#6c7a89", "core": "#5aa469", "part": "#e8903c"}


def _poly(pv, solid):
    m = solid.to_mesh()
    v = np.asarray(m.vert_properties, float)[:, :3]
    f = np.asarray(m.tri_verts, np.int64)
    return pv.PolyData(v, np.hstack([np.full((len(f), 1), 3), f]).ravel())


def render_mold(mold, png, *, window=(1400, 560)) -> Path:
    """Closed and exploded views of ``mold`` (the mesh mold) in one PNG."""
    import pyvista as pv

    lo, hi = np.asarray(mold.block.bounding_box()).reshape(2, 3)
    size = float(np.max(hi - lo))
    part = _poly(pv, mold.part)
    with pv.vtk_verbosity("off"):
        pl = pv.Plotter(off_screen=True, window_size=window, shape=(1, 2), border=False)
        pl.subplot(0, 0)
        pl.add_text("closed", font_size=10, color="black")
        pl.add_mesh(part, color=COLORS["part"], smooth_shading=True)
        for p in mold.pieces:
            opacity = 0.25 if p.role == "half" else 1.0
            pl.add_mesh(_poly(pv, p.solid), color=COLORS[p.role], opacity=opacity,
                        smooth_shading=True)
        pl.camera_position = "iso"
        pl.subplot(0, 1)
        pl.add_text("exploded (pull directions)", font_size=10, color="black")
        pl.add_mesh(part, color=COLORS["part"], smooth_shading=True)
        for p in mold.pieces:
            if p.pull is not None:
                shift = np.asarray(p.pull, float) * 0.55 * size
            else:  # the core, drawn out of the part along −y (it leaves through the inlet)
                shift = np.array([0.0, -0.9 * size, 0.0])
            pl.add_mesh(_poly(pv, p.solid.translate(shift.tolist())), color=COLORS[p.role],
                        smooth_shading=True, split_sharp_edges=True)
        pl.camera_position = "iso"
        pl.camera.zoom(1.1)
        pl.set_background("white")
        pl.screenshot(str(png))
        pl.close()
    return Path(png)
