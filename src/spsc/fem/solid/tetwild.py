"""Unstructured quadratic tetrahedra of any closed surface by pytetwild (fTetWild), with
tagged boundary facets: the path for parts that are not a parametric chamber (a CAD STL), and
the cross-check of the structured chamber mesh (:func:`spsc_wall_tetwild`).
"""

from __future__ import annotations

import numpy as np

from spsc.cad.geometry import SPSCGeometry

from .element import TET_EDGES
from .mesh import TetMesh, boundary_facets, orient_tets, spsc_wall

__all__ = ["p1_to_p2", "tetwild_mesh", "spsc_wall_tetwild"]


def p1_to_p2(nodes, tets4):
    """Add straight edge nodes to 4-node tetrahedra: (nodes, (nel, 10) tets)."""
    edges = np.stack([np.sort(tets4[:, [i, j]], axis=1) for i, j in TET_EDGES], axis=1)
    uniq, inv = np.unique(edges.reshape(-1, 2), axis=0, return_inverse=True)
    mid = 0.5 * (nodes[uniq[:, 0]] + nodes[uniq[:, 1]])
    tets = np.hstack([tets4, len(nodes) + inv.reshape(-1, 6)])
    return np.vstack([nodes, mid]), tets


def tetwild_mesh(vertices, faces, size: float, classify, *, symmetry: int = 1,
                 planes=None, epsilon: float = 1e-3, threads: int = 1) -> TetMesh:
    """pytetwild tetrahedra of the closed triangle surface (vertices (n, 3), faces (m, 3)),
    target edge length ``size`` (mm), promoted to P2 (straight edges).

    ``classify(centroids (k, 3)) -> array of tags`` names each boundary facet; ``planes`` maps a
    tag to (axis, value): the nodes of those facets are snapped onto that plane (TetWild keeps
    the surface only within its envelope ``epsilon`` × the bounding-box diagonal).
    """
    import contextlib
    import tempfile

    import pytetwild

    v = np.asarray(vertices, float)
    # fTetWild writes __tracked_surface.stl into the working directory: keep it out of ours
    with tempfile.TemporaryDirectory() as tmp, contextlib.chdir(tmp):
        nodes, tets4 = pytetwild.tetrahedralize(v, np.asarray(faces, np.int32),
                                                edge_length_abs=float(size), epsilon=epsilon,
                                                optimize=True, num_threads=threads, quiet=True)
    nodes = np.asarray(nodes, float)
    tets4 = np.asarray(tets4, np.int64)
    used, tets4 = np.unique(tets4, return_inverse=True)
    nodes, tets4 = nodes[used], tets4.reshape(-1, 4)
    face_nodes = boundary_facets(np.hstack([tets4, np.zeros((len(tets4), 6), np.int64)]))[:, :3]
    tags = np.asarray(classify(nodes[face_nodes].mean(axis=1)))
    for tag, (axis, value) in (planes or {}).items():
        nodes[np.unique(face_nodes[tags == tag]), axis] = value
    nodes, tets = p1_to_p2(nodes, tets4)
    tets, vol = orient_tets(nodes, tets)
    facets = boundary_facets(tets)
    tags = np.asarray(classify(nodes[facets[:, :3]].mean(axis=1)))
    return TetMesh(nodes, tets, {str(t): facets[tags == t] for t in np.unique(tags)}, symmetry)


def spsc_wall_tetwild(g: SPSCGeometry, size: float = 1.0, *, epsilon: float = 2e-4) -> TetMesh:
    """Quarter wall of a parametric chamber meshed by pytetwild (unstructured, straight P2),
    from the boundary of a fine structured mesh; facets tagged like :func:`spsc_wall`."""
    from scipy.spatial import cKDTree

    ref = spsc_wall(g, size / 3, layers=1)
    f = boundary_facets(ref.tets)[:, :3]
    tags_ref = {}
    for tag, fac in ref.facets.items():
        for row in np.sort(fac[:, :3], axis=1):
            tags_ref[tuple(row)] = tag
    ref_tags = np.array([tags_ref[tuple(r)] for r in np.sort(f, axis=1)])
    used, faces = np.unique(f, return_inverse=True)
    faces = faces.reshape(-1, 3)
    tree = cKDTree(ref.nodes[f].mean(axis=1))
    tol = 1e-6 * max(g.w, g.h)

    def classify(c):
        out = ref_tags[tree.query(c)[1]].astype(object)
        out[np.abs(c[:, 0]) < tol] = "sym_x"
        out[np.abs(c[:, 1]) < tol] = "sym_y"
        out[np.abs(c[:, 2]) < tol] = "base"
        return out

    planes = {"base": (2, 0.0), "sym_x": (0, 0.0), "sym_y": (1, 0.0)}
    return tetwild_mesh(ref.nodes[used], faces, size, classify, symmetry=4, planes=planes,
                        epsilon=epsilon)
