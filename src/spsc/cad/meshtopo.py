"""Mesh measures the printability gate builds on: shells, their nesting, port capping, distances.

Library work is delegated: topology and self-intersections to pymeshlab, the port-capping boolean
to manifold3d, exact point-to-triangle distances to VTK (through pyvista). What is left here is
numpy glue: shells, generalised winding numbers for nesting, areas and volumes. Lengths in mm.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import sparse
from scipy.sparse.csgraph import connected_components

__all__ = ["meshset", "topology", "self_intersecting_faces", "shells", "nesting_depth",
           "signed_volume", "face_areas", "face_normals", "cap_port", "cap_ports", "surface_distance",
           "sample_surface"]


def meshset(v, f):
    """A pymeshlab ``MeshSet`` holding the mesh (vertices ``v`` (n, 3) mm, faces ``f`` (m, 3)),
    for pymeshlab's filters (the gate's topology and self-intersection checks use it)."""
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=np.asarray(v, dtype=np.float64),
                               face_matrix=np.asarray(f, dtype=np.int32)))
    return ms


def topology(v, f) -> dict:
    """pymeshlab's topological measures (boundary and non-manifold edges/vertices, genus, ...)."""
    return dict(meshset(v, f).get_topological_measures())


def self_intersecting_faces(v, f, *, max_refine: int = 1500) -> int:
    """Number of faces that cross a non-adjacent face.

    pymeshlab (vcg's Möller test) selects the faces; it also flags pairs of disjoint faces lying
    in one plane to rounding (the facets of a bore a boolean has split, e.g.), where the line of
    the two planes is ill-conditioned. A selected face counts only if another selected face that
    shares no vertex with it, with overlapping bounding boxes, is not coplanar with it (to 1e-9
    of the part size). Above ``max_refine`` selected faces the selection is taken as is.
    """
    ms = meshset(v, f)
    ms.compute_selection_by_self_intersections_per_face()
    sel = np.flatnonzero(ms.current_mesh().face_selection_array())
    if len(sel) == 0 or len(sel) > max_refine:
        return int(len(sel))
    tri = v[f[sel]]
    eps = 1e-9 * float(np.ptp(v, axis=0).max())
    lo, hi = tri.min(axis=1) - eps, tri.max(axis=1) + eps
    overlap = np.all((lo[:, None] <= hi[None]) & (lo[None] <= hi[:, None]), axis=2)
    fs = f[sel]
    shares = (fs[:, None, :, None] == fs[None, :, None, :]).any(axis=(2, 3))
    n = face_normals(v, fs)
    off = np.einsum("ij,ij->i", n, tri[:, 0])
    # distance of each face's vertices to each other face's plane: (i plane, j vertex)
    dist = np.abs(np.einsum("ik,jvk->ijv", n, tri) - off[:, None, None]).max(axis=2)
    coplanar = (dist <= eps) & (dist.T <= eps)
    real = overlap & ~shares & ~coplanar
    return int(np.count_nonzero(real.any(axis=1)))


def shells(v, f) -> list[np.ndarray]:
    """Face indices of each connected surface (faces joined through shared vertices)."""
    nv = len(v)
    rows = np.concatenate([f[:, 0], f[:, 1], f[:, 2]])
    cols = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])
    graph = sparse.coo_matrix((np.ones(len(rows), dtype=np.int8), (rows, cols)), shape=(nv, nv))
    _, label = connected_components(graph, directed=False)
    face_label = label[f[:, 0]]
    order = np.argsort(face_label, kind="stable")
    cuts = np.flatnonzero(np.diff(face_label[order])) + 1
    return [np.sort(part) for part in np.split(order, cuts)]


def face_areas(v, f) -> np.ndarray:
    return 0.5 * np.linalg.norm(_cross(v, f), axis=1)


def face_normals(v, f) -> np.ndarray:
    """Unit normals by the right-hand rule of each face's vertex order (zero for degenerate)."""
    c = _cross(v, f)
    n = np.linalg.norm(c, axis=1, keepdims=True)
    return np.divide(c, n, out=np.zeros_like(c), where=n > 0)


def signed_volume(v, f) -> float:
    """Enclosed volume (mm³) by the divergence theorem; positive for outward-facing triangles."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def winding_number(point, v, f) -> float:
    """Generalised winding number of a closed surface about ``point`` (van Oosterom–Strackee
    solid angles): ±1 inside, 0 outside, whatever the triangle orientation consistency."""
    a, b, c = (v[f[:, k]] - point for k in range(3))
    la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    den = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc + np.einsum("ij,ij->i", a, c) * lb
           + np.einsum("ij,ij->i", b, c) * la)
    return float(np.arctan2(det, den).sum() / (2.0 * math.pi))


def nesting_depth(v, f, parts: list[np.ndarray]) -> np.ndarray:
    """How many other shells enclose each shell: even = a solid's outer skin, odd = a cavity."""
    lo = np.array([v[f[p]].reshape(-1, 3).min(axis=0) for p in parts])
    hi = np.array([v[f[p]].reshape(-1, 3).max(axis=0) for p in parts])
    depth = np.zeros(len(parts), dtype=int)
    for i, p in enumerate(parts):
        point = v[f[p[0], 0]]
        for j, q in enumerate(parts):
            if i != j and np.all(lo[j] <= lo[i]) and np.all(hi[i] <= hi[j]):
                depth[i] += abs(winding_number(point, v, f[q])) > 0.5
    return depth


def cap_ports(v, f, ports, segments: int = 128):
    """:func:`cap_port` for one port dict or a list of them (a bladder's inlet, a haptic
    chamber's wire exit), one after the other; None as :func:`cap_port`."""
    for port in ([ports] if isinstance(ports, dict) else list(ports)):
        out = cap_port(v, f, port, segments)
        if out is None:
            return None
        v, f = out
    return v, f


def cap_port(v, f, port: dict, segments: int = 128):
    """Boolean union (manifold3d) of the solid with a cylinder plugging the port bore.

    The plug's polygon circumscribes a circle slightly wider than the bore (by 1 % of the radius,
    at least 0.01 mm), so it covers the bore's facets whatever their tessellation; the excess lies
    inside the port wall and adds nothing. Returns ``(vertices, faces)`` of the capped solid, or
    None if manifold3d rejects the input mesh (not a closed oriented 2-manifold).
    """
    import manifold3d as mf

    m = mf.Manifold(mf.Mesh64(vert_properties=np.array(v, dtype=np.float64),
                              tri_verts=np.array(f, dtype=np.uint64)))
    if m.status() != mf.Error.NoError:
        return None
    p0 = np.asarray(port["axis_point"], dtype=float)
    d = np.asarray(port["axis_dir"], dtype=float)
    d = d / np.linalg.norm(d)
    if "s_range" in port:
        s0, s1 = sorted(port["s_range"])
    else:
        s0, s1 = sorted((z - p0[2]) / d[2] for z in port["z_range"])
    r = port["radius"]
    r_plug = (r + max(0.01, 0.01 * r)) / math.cos(math.pi / segments)
    plug = mf.Manifold.cylinder(s1 - s0, r_plug, r_plug, segments)
    plug = plug.transform(_frame(d, p0 + s0 * d))
    out = (m + plug).to_mesh64()
    return np.asarray(out.vert_properties)[:, :3].astype(np.float64), \
        np.asarray(out.tri_verts).astype(np.int64)


def _frame(d, origin) -> np.ndarray:
    """3x4 affine taking +z to unit vector ``d`` and the origin to ``origin``."""
    z = np.array([0.0, 0.0, 1.0])
    axis = np.cross(z, d)
    s, c = np.linalg.norm(axis), float(d @ z)
    if s < 1e-12:
        rot = np.diag([1.0, 1.0 if c > 0 else -1.0, 1.0 if c > 0 else -1.0])
    else:
        k = axis / s
        kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        rot = np.eye(3) + s * kx + (1 - c) * kx @ kx
    return np.column_stack([rot, origin])


def sample_surface(v, f, spacing: float, *, max_random: int = 100_000, seed: int = 0):
    """Points on the surface: its vertices, face centroids and area-uniform random points at
    about one per ``spacing``² (seeded, so a check is reproducible)."""
    area = face_areas(v, f)
    n = int(min(max_random, math.ceil(area.sum() / spacing**2)))
    rng = np.random.default_rng(seed)
    pick = rng.choice(len(f), size=n, p=area / area.sum())
    u, w = rng.random(n), rng.random(n)
    flip = u + w > 1
    u[flip], w[flip] = 1 - u[flip], 1 - w[flip]
    a, b, c = v[f[pick, 0]], v[f[pick, 1]], v[f[pick, 2]]
    rand = a + u[:, None] * (b - a) + w[:, None] * (c - a)
    used = np.unique(f)
    return np.vstack([v[used], v[f].mean(axis=1), rand])


def surface_distance(points, v, f) -> np.ndarray:
    """Unsigned exact distance (mm) from each point to the nearest triangle (VTK cell locator)."""
    import pyvista as pv

    surf = pv.PolyData.from_regular_faces(np.asarray(v, dtype=np.float64),
                                          np.asarray(f, dtype=np.int64))
    cloud = pv.PolyData(np.asarray(points, dtype=np.float64))
    return np.abs(np.asarray(cloud.compute_implicit_distance(surf)["implicit_distance"]))


def _cross(v, f):
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return np.cross(b - a, c - a)
