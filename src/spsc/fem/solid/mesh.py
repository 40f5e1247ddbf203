"""Quadratic tetrahedral meshes of the bladder wall, with tagged boundaries.

Two paths:

* :func:`spsc_wall` — a structured mesh of the wall of a parametric chamber, swept from its
  meridional section (cavity profile to outer profile, ``layers`` elements through the
  thickness): extruded along y over the middle part of length l and revolved about the end axes.
  Symmetry and base planes are exact, the 10-node elements are isoparametric (edge nodes on the
  curved surfaces), and the thickness resolution is controlled.
* :func:`spsc.fem.solid.tetwild.tetwild_mesh` — pytetwild tetrahedra of any closed surface (e.g. a
  CAD STL), promoted to P2; facets are tagged by a caller's classifier.

A hexahedral grid is split into six tetrahedra along its main diagonal (consistent across
neighbours); coincident nodes (the revolution axis, a sphere's pole) are merged and the
tetrahedra that collapse are dropped. Facet tags: ``base`` (z = 0), ``sym_x`` (x = 0), ``sym_y``
(y = 0), ``cavity`` (inner surface), ``outer``. Facets are 6-node triangles ordered so that their
normal points out of the solid.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
import uuid
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError, require, require_integer
from spsc.cad.geometry import SPSCGeometry

from .element import TET_EDGES, TET_FACES

__all__ = ["TetMesh", "check_mesh_size", "wall_mesh_counts", "spsc_wall", "wall_section",
           "graded_fractions", "sphere_shell", "block", "boundary_facets", "orient_tets",
           "cached_mesh", "CACHE_DIR"]

CACHE_DIR = Path("build/cache/fem")
#: part of every cache key: bump it when a mesh generator changes its output
MESH_VERSION = 1


@dataclass(frozen=True, eq=False)
class TetMesh:
    """P2 tetrahedral mesh: ``nodes`` (N, 3) in mm, ``tets`` (nel, 10) in VTK order,
    ``facets`` tag -> (nf, 6) outward-oriented boundary triangles, ``symmetry`` the number of
    copies of the mesh that make the full part (4 for a quarter model, 8 for a sphere octant)."""

    nodes: np.ndarray
    tets: np.ndarray
    facets: dict = field(default_factory=dict)
    symmetry: int = 1

    @property
    def n_tets(self) -> int:
        return self.tets.shape[0]

    def nodes_on(self, *tags: str) -> np.ndarray:
        """Sorted node indices on the facets of the given tags."""
        return np.unique(np.concatenate([self.facets[t].ravel() for t in tags]))

    def to_pyvista(self, displacement=None):
        """A pyvista UnstructuredGrid of quadratic tetrahedra (optionally with point data)."""
        import pyvista as pv

        cells = np.hstack([np.full((self.n_tets, 1), 10), self.tets]).ravel()
        types = np.full(self.n_tets, pv.CellType.QUADRATIC_TETRA, dtype=np.uint8)
        grid = pv.UnstructuredGrid(cells, types, self.nodes.copy())
        if displacement is not None:
            grid.point_data["displacement"] = np.asarray(displacement)
        return grid

    def save(self, path) -> None:
        """Write the mesh as ``.npz`` at ``path`` (exactly that name), through a temporary file
        beside it renamed over it: a process loading it at the same time (another worker
        sharing the mesh cache) reads the old file or the new one, never half of one."""
        path = Path(path)
        tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex[:12]}.tmp")
        try:
            with open(tmp, "xb") as f:
                np.savez_compressed(f, nodes=self.nodes, tets=self.tets, symmetry=self.symmetry,
                                    **{f"facets_{k}": v for k, v in self.facets.items()})
            os.replace(tmp, path)
        except BaseException:
            tmp.unlink(missing_ok=True)
            raise

    @classmethod
    def load(cls, path) -> "TetMesh":
        with np.load(path) as z:
            facets = {k[7:]: z[k] for k in z.files if k.startswith("facets_")}
            return cls(z["nodes"], z["tets"], facets, int(z["symmetry"]))


# -- topology -----------------------------------------------------------------------------------
def boundary_facets(tets: np.ndarray) -> np.ndarray:
    """6-node boundary triangles (nf, 6) of positively oriented P2 tetrahedra, normal outward."""
    faces = []
    for verts, edges in TET_FACES:
        faces.append(np.hstack([tets[:, list(verts)], tets[:, [4 + e for e in edges]]]))
    faces = np.vstack(faces)
    key = np.sort(faces[:, :3], axis=1)
    _, idx, count = np.unique(key, axis=0, return_index=True, return_counts=True)
    return faces[idx[count == 1]]


def orient_tets(nodes, tets):
    """Flip negatively oriented tetrahedra (swap vertices 1 and 2 and their edges)."""
    a, b, c, d = (nodes[tets[:, i]] for i in range(4))
    vol = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)
    flip = vol < 0
    tets = tets.copy()
    tets[flip] = tets[flip][:, [0, 2, 1, 3, 6, 5, 4, 7, 9, 8]]
    return tets, np.abs(vol) / 6.0


def _merge(points, tets, tol):
    """Merge coincident points, drop collapsed tetrahedra, renumber compactly."""
    key = np.round(points / tol).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    tets = inverse.ravel()[tets]
    ok = np.all(np.diff(np.sort(tets[:, :4], axis=1), axis=1) != 0, axis=1)
    tets = tets[ok]
    used, tets = np.unique(tets, return_inverse=True)
    return first[used], tets.reshape(-1, 10)


def _kuhn_p2(shape):
    """P2 tetrahedra (flat fine-grid indices) of a coarse grid with ``shape`` cells, whose fine
    grid has (2a+1, 2b+1, 2c+1) points: six per cell along its main diagonal."""
    a, b, c = shape
    fine = (2 * a + 1, 2 * b + 1, 2 * c + 1)
    cell = np.stack(np.meshgrid(np.arange(a), np.arange(b), np.arange(c), indexing="ij"),
                    axis=-1).reshape(-1, 3) * 2
    out = []
    for perm in itertools.permutations(range(3)):
        steps = [np.zeros(3, int)]
        for axis in perm:
            s = steps[-1].copy()
            s[axis] += 2
            steps.append(s)
        verts = [cell + s for s in steps]
        mids = [(verts[i] + verts[j]) // 2 for i, j in TET_EDGES]
        out.append(np.stack([np.ravel_multi_index(tuple(v.T), fine) for v in verts + mids],
                            axis=1))
    return np.vstack(out)


def _swept(section, y_half, n_y, n_phi, tol=1e-7):
    """Sweep a fine section grid (2m+1, 2k+1, 2) of (ρ, z) points: extruded along y over
    [0, y_half] with n_y cells, then revolved by φ ∈ [0, π/2] about the axis (x = 0, y = y_half)
    with n_phi cells. Returns nodes, tets and the through-thickness fine index of each node."""
    rho, z = section[..., 0], section[..., 1]
    ys = np.linspace(0.0, y_half, 2 * n_y + 1) if n_y else np.zeros(0)
    phis = np.linspace(0.0, math.pi / 2, 2 * n_phi + 1)
    slabs = [np.stack([rho, np.full_like(rho, y), z], axis=-1) for y in ys[:-1]]
    slabs += [np.stack([rho * math.cos(f), y_half + rho * math.sin(f), z], axis=-1) for f in phis]
    grid = np.stack(slabs, axis=2)  # (2m+1, 2k+1, 2K+1, 3)
    axis_fix = (rho, 2 * n_y)
    return _grid_mesh(grid, axis_fix, tol)


def _grid_mesh(grid, axis_fix=None, tol=1e-7):
    """P2 tetrahedra of a fine point grid (2a+1, 2b+1, 2c+1, 3): nodes, tets and the fine index
    along the second axis (through the thickness) of each node."""
    m2, k2, c2, _ = grid.shape
    layer = np.broadcast_to(np.arange(k2)[None, :, None], (m2, k2, c2)).ravel()
    tets = _kuhn_p2(((m2 - 1) // 2, (k2 - 1) // 2, (c2 - 1) // 2))
    if axis_fix is not None:
        # An edge from the revolution axis takes the angle of its other end: the index
        # midpoint would put its node off the meridian plane the edge lies in.
        rho, k_rev = axis_fix
        I, J, K = np.unravel_index(tets, grid.shape[:3])
        on_axis = rho[I, J] < tol
        revolved = K >= k_rev
        for e, (a, b) in enumerate(TET_EDGES):
            for s, o in ((a, b), (b, a)):
                fix = on_axis[:, s] & ~on_axis[:, o] & revolved[:, s] & revolved[:, o]
                K[fix, 4 + e] = K[fix, o]
        tets = np.ravel_multi_index((I, J, K), grid.shape[:3])
    pts = grid.reshape(-1, 3)
    pts = np.where(np.abs(pts) < tol, 0.0, pts)
    keep, tets = _merge(pts, tets, tol)
    nodes = pts[keep]
    tets, vol = orient_tets(nodes, tets)
    if np.any(vol <= 1e-12 * np.max(vol)):
        raise ValueError("degenerate tetrahedra in the structured mesh")
    return nodes, tets, layer[keep]


def _tag(nodes, tets, layer, tol, planes=("base", "sym_x", "sym_y")):
    facets = boundary_facets(tets)
    v = nodes[facets[:, :3]]
    lay = layer[facets[:, :3]]
    tests = {"base": np.all(np.abs(v[..., 2]) < tol, axis=1),
             "sym_x": np.all(np.abs(v[..., 0]) < tol, axis=1),
             "sym_y": np.all(np.abs(v[..., 1]) < tol, axis=1)}
    out, taken = {}, np.zeros(len(facets), bool)
    for name in planes:
        out[name] = facets[tests[name] & ~taken]
        taken |= tests[name]
    for name, sel in (("cavity", np.all(lay == 0, axis=1)),
                      ("outer", np.all(lay == layer.max(), axis=1))):
        out[name] = facets[sel & ~taken]
        taken |= sel
    if not np.all(taken):
        raise ValueError(f"{int(np.sum(~taken))} boundary facets without a tag")
    return out


# -- the parametric chamber ---------------------------------------------------------------------
def wall_section(g: SPSCGeometry, n_profile: int, layers: int,
                 fractions: np.ndarray | None = None) -> np.ndarray:
    """Fine section grid (2n+1, 2·layers+1, 2) of (x, z): cavity profile to the outer wall,
    straight lines through the thickness, ending exactly on the axis and on z = 0.

    ``fractions`` (2n+1,), increasing from 0 to 1: where the grid's points lie along each
    profile as fractions of its arc length (:func:`graded_fractions`); None: evenly (the
    cavity in the arc length of its offset curve, the outer wall in its own)."""
    outer = g.outer_profile_points(4001)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(outer, axis=0).T))])
    if fractions is None:
        inner, _ = g.profile_points(2 * n_profile + 1)
        if len(inner) != 2 * n_profile + 1:
            # points closer than 1e-6 w were merged (a near-corner profile, n2 -> 1 with
            # c_y > 0, crowds its samples at the corner): back to the grid's count along the
            # kept points
            k = np.linspace(0.0, len(inner) - 1.0, 2 * n_profile + 1)
            inner = np.column_stack([np.interp(k, np.arange(len(inner)), inner[:, j])
                                     for j in (0, 1)])
        t = np.linspace(0.0, 1.0, 2 * n_profile + 1)
    else:
        t = np.asarray(fractions, float)
        if t.shape != (2 * n_profile + 1,) or t[0] != 0.0 or t[-1] != 1.0 or \
                np.any(np.diff(t) <= 0):
            raise ValueError(f"fractions: {2 * n_profile + 1} increasing values from 0 to 1")
        dense, _ = g.profile_points(8001)  # evenly spaced along the cavity's offset arc
        k = t * (len(dense) - 1.0)
        inner = np.column_stack([np.interp(k, np.arange(len(dense)), dense[:, j])
                                 for j in (0, 1)])
    t = t * s[-1]
    outer = np.column_stack([np.interp(t, s, outer[:, 0]), np.interp(t, s, outer[:, 1])])
    outer[0, 0], outer[-1, 1], inner[0, 0], inner[-1, 1] = 0.0, 0.0, 0.0, 0.0
    f = np.linspace(0.0, 1.0, 2 * layers + 1)[None, :, None]
    return inner[:, None, :] + f * (outer - inner)[:, None, :]


#: growth of the element length from one element to the next in a graded profile
GRADING_RATIO = 1.2


def graded_fractions(length: float, size: float, apex: float,
                     ratio: float = GRADING_RATIO) -> np.ndarray:
    """Fractions of a profile of ``length`` (mm) at the fine grid's 2n+1 points, the
    elements ``apex`` mm long at the apex (the first) growing by ``ratio`` per element up to
    ``size`` mm, then even; the fine grid's middle points halve each element. The elements
    are scaled by one factor so they end on the profile's end."""
    edges = [0.0]
    h = min(apex, size)
    while edges[-1] < length:
        edges.append(edges[-1] + h)
        h = min(h * ratio, size)
    edges = np.asarray(edges)
    if len(edges) > 2 and edges[-1] - length > 0.5 * (edges[-1] - edges[-2]):
        edges = edges[:-1]  # a last sliver: drop it and stretch the rest
    edges = edges / edges[-1]
    mid = 0.5 * (edges[:-1] + edges[1:])
    return np.append(np.column_stack([edges[:-1], mid]).ravel(), 1.0)


#: Most elements through the wall of the solid models (fem, wall).
LAYERS_MAX = 32


def check_mesh_size(g: SPSCGeometry, size, layers) -> tuple[float, int]:
    """Validate a wall mesh request (mm, count) on chamber ``g``: 0 < size <= min(w, h)/2 (at
    least two elements across the cavity's semi-width and height) and 1 <= layers <= 32.
    Returns (size, layers); ParameterError naming ``mesh size`` or ``layers``. What it costs is
    :func:`wall_mesh_counts`' business."""
    top = min(g.w, g.h) / 2
    size = require("mesh size", size, gt=0, le=top, unit=f"mm; at most min(w, h)/2 = {top:g} "
                   "mm, two elements across the cavity")
    lv = float(layers) if isinstance(layers, (int, float)) else math.nan
    if not (math.isfinite(lv) and lv == int(lv) and 1 <= lv <= LAYERS_MAX):
        raise ParameterError("layers", layers, f"an integer from 1 to {LAYERS_MAX}")
    return size, int(lv)


def wall_mesh_counts(g: SPSCGeometry, size: float, layers: int, *, full: bool = False) -> dict:
    """Elements, nodes and unknowns of :func:`spsc_wall` (before merging the nodes on the axis,
    so an upper bound within a few per cent), without building it: what a run costs is known
    before it starts. ``unknowns``: three displacements per P2 node plus one pressure per
    vertex (P2/P1)."""
    n_profile, n_phi, n_y = _wall_cells(g, size)
    cols = n_y + n_phi
    copies = 4 if full else 1
    nodes = (2 * n_profile + 1) * (2 * layers + 1) * (2 * cols + 1) * copies
    vertices = (n_profile + 1) * (layers + 1) * (cols + 1) * copies
    tets = 6 * n_profile * layers * cols * copies
    return {"tetrahedra": tets, "nodes": nodes, "unknowns": 3 * nodes + vertices}


def _wall_cells(g: SPSCGeometry, size: float) -> tuple[int, int, int]:
    """Cells along the profile, around the quarter end cap and along the half middle."""
    outer = g.outer_profile_points(2001)
    length = float(np.sum(np.hypot(*np.diff(outer, axis=0).T)))
    n_profile = max(2, math.ceil(length / size))
    n_phi = max(2, math.ceil(math.pi / 2 * (g.w + g.t0) / size))
    n_y = math.ceil(g.l / 2 / size) if g.l > 0 else 0
    return n_profile, n_phi, n_y


def spsc_wall(g: SPSCGeometry, size: float = 1.0, *, layers: int | None = None,
              full: bool = False) -> TetMesh:
    """Structured P2 mesh of the chamber wall, clamped-base model (docs/design.md).

    ``size`` (mm) is the target element edge along the surfaces; ``layers`` the number of
    elements through the thickness (default: t0/size rounded, at least 1). Quarter model on
    x ≥ 0, y ≥ 0 (``symmetry = 4``) unless ``full``.
    """
    size = require("size", size, gt=0, unit="mm")
    if layers is None:
        layers = max(1, round(g.t0 / size))
    layers = require_integer("layers", layers, ge=1)
    n_profile, n_phi, n_y = _wall_cells(g, size)
    nodes, tets, layer = _swept(wall_section(g, n_profile, layers), g.l / 2, n_y, n_phi)
    tol = 1e-7 * max(g.w, g.h)
    if full:
        nodes, tets, layer = _mirror(nodes, tets, layer, tol)
        return TetMesh(nodes, tets, _tag(nodes, tets, layer, tol, ("base",)), 1)
    return TetMesh(nodes, tets, _tag(nodes, tets, layer, tol), 4)


def _mirror(nodes, tets, layer, tol):
    for axis in (0, 1):
        m = nodes.copy()
        m[:, axis] *= -1
        pts = np.vstack([nodes, m])
        lay = np.concatenate([layer, layer])
        keep, tt = _merge(pts, np.vstack([tets, tets + len(nodes)]), tol)
        nodes, layer = pts[keep], lay[keep]
        tets, _ = orient_tets(nodes, tt)
    return nodes, tets, layer


def sphere_shell(inner: float, outer: float, *, n_theta: int = 6, layers: int = 3) -> TetMesh:
    """Octant (x, y, z ≥ 0) of a thick spherical shell, radii ``inner`` < ``outer`` (mm):
    ``cavity`` r = inner, ``outer`` r = outer, symmetry planes tagged ``sym_x``, ``sym_y`` and
    ``base`` (z = 0). ``symmetry = 8``."""
    require("inner", inner, gt=0, unit="mm")
    require("outer", outer, gt=inner, unit="mm")
    th = np.linspace(0.0, math.pi / 2, 2 * n_theta + 1)[:, None]
    r = np.linspace(inner, outer, 2 * layers + 1)[None, :]
    section = np.stack([r * np.sin(th), r * np.cos(th) + 0 * r], axis=-1)
    nodes, tets, layer = _swept(section, 0.0, 0, n_theta)
    return TetMesh(nodes, tets, _tag(nodes, tets, layer, 1e-7 * outer), 8)


def block(lengths=(1.0, 1.0, 1.0), cells=(2, 2, 2)) -> TetMesh:
    """Box [0, a] × [0, b] × [0, c] (mm) of P2 tetrahedra, facets tagged ``x0, x1, y0, y1,
    z0, z1`` (for patch tests and locking studies)."""
    axes = [np.linspace(0.0, L, 2 * n + 1) for L, n in zip(lengths, cells)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    nodes, tets, _ = _grid_mesh(grid)
    facets = boundary_facets(tets)
    v = nodes[facets[:, :3]]
    tags = {}
    for c, name in enumerate("xyz"):
        tags[f"{name}0"] = facets[np.all(np.abs(v[..., c]) < 1e-9, axis=1)]
        tags[f"{name}1"] = facets[np.all(np.abs(v[..., c] - lengths[c]) < 1e-9, axis=1)]
    return TetMesh(nodes, tets, tags, 1)


# -- cache --------------------------------------------------------------------------------------
def cached_mesh(builder, *, cache_dir=None, **params) -> TetMesh:
    """``builder(**params)`` cached under ``cache_dir`` by a hash of its name and parameters
    (dataclass parameters by their fields)."""
    def plain(v):
        if hasattr(v, "as_dict"):
            return v.as_dict()
        return v
    key = json.dumps({"builder": builder.__name__, "version": MESH_VERSION,
                      **{k: plain(v) for k, v in params.items()}}, sort_keys=True, default=str)
    digest = hashlib.sha256(key.encode()).hexdigest()[:16]
    path = Path(cache_dir or CACHE_DIR) / f"{builder.__name__}-{digest}.npz"
    if path.exists():
        try:
            return TetMesh.load(path)
        except (OSError, ValueError, KeyError, zipfile.BadZipFile):
            pass  # a damaged file (e.g. from a version that wrote in place): build it again
    mesh = builder(**params)
    path.parent.mkdir(parents=True, exist_ok=True)
    mesh.save(path)
    return mesh
