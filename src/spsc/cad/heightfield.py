"""Any rigid body from a file (``--indenter FILE.stl|.3mf|.step``): its lower surface as a
smooth height field over the plate's plane, pressing as the analytic bodies of
:mod:`spsc.core.indenter` do.

The body's triangles are rasterised onto a lateral grid (each grid point takes the lowest
triangle above or below it: the surface a body lowered along −z first meets), and a bicubic
interpolating spline through the grid gives S, ∇S and ∇²S. The body is placed with its lowest
point (its tip; the centre of a flat bottom, the centroid of the points within 1 nm of the
lowest) over the chamber's axis, or over ``--plate-at`` on a part, in the file's own
orientation (z up: it moves along −z). Points outside its footprint (and within one grid cell
of its edge, where the surface turns vertical) have no lower surface: S = +inf there.

A contact point a gap g above the node meets the surface offset along its normal, which is
g·(√(1 + |∇S|²) − 1) lower than the surface shifted down by g (exact for a plane; its
derivatives are left out, so with a gap the tangent is not exact: the gap is zero on
chambers, and on a part only an FSR insert carries one).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError
from spsc.core.indenter import FileBody

__all__ = ["HeightField", "height_field", "resolve"]

#: grid points across the body's smaller lateral extent (at most 0.05 mm apart), and at most
#: MAX_CELLS along either side (a large body gets a coarser grid)
CELLS = 400
MAX_CELLS = 2000
#: points this close to the lowest (mm) make the tip: their centroid (a flat bottom's centre)
TIP_BAND_MM = 1e-6
#: the Gaussian smoothing of the rasterised surface (grid cells)
SMOOTH = 2.0


@dataclass(frozen=True, eq=False)
class HeightField:
    """The lower surface of a body read from ``path``: a spline of z over the grid ``xs``,
    ``ys`` (mm, the file's frame), the grid's ``inside`` mask, the tip (lowest point)
    ``tip`` (x, y, z); ``at``: where the tip is placed (mm, the press frame)."""

    path: str
    spline: object
    xs: np.ndarray
    ys: np.ndarray
    inside: np.ndarray
    tip: tuple
    at: tuple = (0.0, 0.0)

    kind = "file"
    curved = True
    axisymmetric = False
    mirrored = False

    @property
    def spec(self) -> str:
        return self.path

    def placed(self, at) -> "HeightField":
        return replace(self, at=(float(at[0]), float(at[1])))

    def surface(self, lateral, gap=0.0):
        """(S, ∇S, ∇²S) at the lateral positions (2, n) in mm (see the module)."""
        lateral = np.atleast_2d(np.asarray(lateral, float))
        if lateral.shape[0] != 2:
            raise ParameterError("indenter", self.path, "a body pressing a 3D model (not an "
                                 "axisymmetric section)")
        n = lateral.shape[1]
        x = lateral[0] - self.at[0] + self.tip[0]
        y = lateral[1] - self.at[1] + self.tip[1]
        i = np.clip(np.round((x - self.xs[0]) / (self.xs[1] - self.xs[0])).astype(int), -1,
                    len(self.xs))
        j = np.clip(np.round((y - self.ys[0]) / (self.ys[1] - self.ys[0])).astype(int), -1,
                    len(self.ys))
        ok = (i >= 0) & (i < len(self.xs)) & (j >= 0) & (j < len(self.ys))
        ok[ok] = self.inside[i[ok], j[ok]]
        ev = self.spline.ev
        S = np.where(ok, ev(x, y) - self.tip[2], np.inf)
        grad = np.stack([ev(x, y, dx=1), ev(x, y, dy=1)])
        hess = np.empty((2, 2, n))
        hess[0, 0], hess[1, 1] = ev(x, y, dx=2), ev(x, y, dy=2)
        hess[0, 1] = hess[1, 0] = ev(x, y, dx=1, dy=1)
        gap = np.broadcast_to(np.asarray(gap, float), (n,))
        if np.any(gap):
            S = S - gap * (np.sqrt(1.0 + np.sum(grad * grad, axis=0)) - 1.0)
        return S, grad, hess


def _lower_envelope(tri, xs, ys) -> np.ndarray:
    """The lowest z of the triangles (m, 3, 3) over each grid point (nx, ny); inf where none
    covers it."""
    z = np.full((len(xs), len(ys)), np.inf)
    hx, hy = xs[1] - xs[0], ys[1] - ys[0]
    for a, b, c in tri:
        det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if abs(det) < 1e-14:
            continue  # vertical: seen edge-on from below
        lo = np.minimum(np.minimum(a, b), c)
        hi = np.maximum(np.maximum(a, b), c)
        i0, i1 = int(math.ceil((lo[0] - xs[0]) / hx)), int(math.floor((hi[0] - xs[0]) / hx))
        j0, j1 = int(math.ceil((lo[1] - ys[0]) / hy)), int(math.floor((hi[1] - ys[0]) / hy))
        if i1 < i0 or j1 < j0:
            continue
        X, Y = np.meshgrid(xs[i0:i1 + 1], ys[j0:j1 + 1], indexing="ij")
        l1 = ((b[1] - c[1]) * (X - c[0]) + (c[0] - b[0]) * (Y - c[1])) / det
        l2 = ((c[1] - a[1]) * (X - c[0]) + (a[0] - c[0]) * (Y - c[1])) / det
        l3 = 1.0 - l1 - l2
        on = (l1 >= -1e-12) & (l2 >= -1e-12) & (l3 >= -1e-12)
        zt = np.where(on, l1 * a[2] + l2 * b[2] + l3 * c[2], np.inf)
        block = z[i0:i1 + 1, j0:j1 + 1]
        np.minimum(block, zt, out=block)
    return z


def height_field(path) -> HeightField:
    """Read the body at ``path`` (STL, 3MF or STEP) and build its lower surface; one-line
    ParameterError naming ``indenter`` if it cannot be read or has no lower surface."""
    from scipy.interpolate import RectBivariateSpline
    from scipy.ndimage import binary_erosion, distance_transform_edt, gaussian_filter

    from .meshload import load_surface

    v, f = load_surface(path, "indenter")
    lo, hi = v.min(axis=0), v.max(axis=0)
    span = hi[:2] - lo[:2]
    if np.any(span <= 0):
        raise ParameterError("indenter", str(path), "a solid body (it is flat in x or y)")
    h = max(min(float(span.min()) / CELLS, 0.05), float(span.max()) / MAX_CELLS)
    xs = np.arange(lo[0], hi[0] + h, h)
    ys = np.arange(lo[1], hi[1] + h, h)
    z = _lower_envelope(v[f], xs, ys)
    covered = np.isfinite(z)
    inside = binary_erosion(covered, iterations=1)
    if inside.sum() < 16:
        raise ParameterError("indenter", str(path), "a body with a lower surface (no "
                             "triangle faces down)")
    # fill outside the footprint with the nearest covered value: the spline needs a full grid
    idx = distance_transform_edt(~covered, return_distances=False, return_indices=True)
    # a facet's kinks smoothed over SMOOTH cells: the slopes and curvatures of a tessellated
    # body are then those of the body it approximates, not of its facets
    filled = gaussian_filter(z[tuple(idx)], SMOOTH, mode="nearest")
    spline = RectBivariateSpline(xs, ys, filled, kx=3, ky=3, s=0)
    low = np.where(inside, z, np.inf)
    i, j = np.nonzero(low <= low.min() + TIP_BAND_MM)
    x0, y0 = float(xs[i].mean()), float(ys[j].mean())
    tip = (x0, y0, float(spline.ev(x0, y0)))
    return HeightField(str(path), spline, xs, ys, inside, tip)


@lru_cache(maxsize=4)
def _read(path: str, mtime: float) -> HeightField:
    return height_field(path)


def resolve(body):
    """The body a model presses with: a file's :class:`HeightField` (read once per file
    version), else ``body`` itself (an :class:`~spsc.core.indenter.Indenter` or None)."""
    if isinstance(body, FileBody):
        path = Path(body.path)
        field = _read(str(path.resolve()), path.stat().st_mtime)
        field = replace(field, path=body.path)
        return field.placed(body.at) if body.at != (0.0, 0.0) else field
    return body
