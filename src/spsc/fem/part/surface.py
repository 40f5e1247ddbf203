"""Any closed part in the 3D FEM: its surface read and checked, the enclosed cavity found, and a
curved quadratic tetrahedral mesh with the cavity and outer surfaces tagged.

The part is a closed, oriented 2-manifold triangle surface (STL, 3MF, or STEP tessellated)
with exactly one enclosed cavity: a shell nested inside the outer skin (odd nesting depth,
:func:`spsc.cad.meshtopo.nesting_depth`). A part exported by this toolchain opens its cavity
through the inlet bore; its design file names the bore, which is plugged first (the tube that
seals it in use), with the same boolean the printability gate uses
(:func:`spsc.cad.meshtopo.cap_port`).

The tetrahedra come from fTetWild (pytetwild) and are promoted to P2. fTetWild's time grows with
the input's triangle count, and an export STL is tessellated far finer (0.002 mm chord sag) than
any element, so a surface with more triangles than the mesh size needs is first simplified for
it (pymeshlab's quadric edge collapse, topology kept). The boundary nodes, vertices and edge
nodes, are then moved onto the part's own surface (closest point), so the quadratic elements
follow the curved walls instead of their chords (a chord's sag would shrink the cavity by about
(2/3)·δ·A) and neither the simplification nor fTetWild's envelope shows in the geometry. A move
that would spoil an element (its Jacobian at a node below a quarter of the straight element's)
is undone for that element's nodes.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from dataclasses import dataclass

import numpy as np

from spsc.cad.meshload import SURFACE_SUFFIXES
from spsc.core.errors import ParameterError

from ..solid.element import tet_p2
from ..solid.mesh import TetMesh, boundary_facets, orient_tets
from ..solid.tetwild import p1_to_p2

__all__ = ["PART_SUFFIXES", "PartSurface", "read_surface", "part_surface", "load_part",
           "part_mesh"]

#: the part files the FEM reads (STL, 3MF, STEP)
PART_SUFFIXES = SURFACE_SUFFIXES


@dataclass(frozen=True, eq=False)
class PartSurface:
    """A checked closed part surface (mm): ``vertices`` (n, 3), ``faces`` (m, 3) oriented
    outward from the solid, ``cavity`` the face indices of the one enclosed cavity shell,
    ``source`` where it came from, ``capped`` whether an inlet bore was plugged."""

    vertices: np.ndarray
    faces: np.ndarray
    cavity: np.ndarray
    source: str = ""
    capped: bool = False

    @property
    def cavity_volume(self) -> float:
        """Volume enclosed by the cavity shell (mm³), exact for the triangles."""
        from spsc.cad.meshtopo import signed_volume

        return abs(signed_volume(self.vertices, self.faces[self.cavity]))

    @property
    def bounds(self) -> np.ndarray:
        """[[xmin, ymin, zmin], [xmax, ymax, zmax]] (mm)."""
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    @property
    def diagonal(self) -> float:
        lo, hi = self.bounds
        return float(np.linalg.norm(hi - lo))


def read_surface(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, faces) of an STL, 3MF or STEP file
    (:func:`spsc.cad.meshload.load_surface`); one-line ParameterError naming ``part``
    otherwise."""
    from spsc.cad.meshload import load_surface

    return load_surface(path, "part")


def part_surface(vertices, faces, *, port: dict | None = None, source: str = "part",
                 name: str = "part") -> PartSurface:
    """Check a part's surface and find its cavity; ``port`` (a design file's ``port``) is
    plugged first. One-line ParameterError naming ``name`` if the surface is open,
    non-manifold or self-intersecting, holds more than one body, or has no enclosed cavity
    or more than one."""
    import manifold3d as mf

    from spsc.cad import meshtopo as mt

    v = np.array(vertices, np.float64, order="C")  # writable: nanobind refuses read-only
    f = np.array(faces, np.int64, order="C")
    if len(f) < 4:
        raise ParameterError(name, source, "a closed triangle surface (it has fewer than 4 "
                             "triangles)")
    m = mf.Manifold(mf.Mesh64(vert_properties=v, tri_verts=f.astype(np.uint64)))
    topo = mt.topology(v, f)  # the measures of spsc check's watertight and manifold checks
    defects = {k: int(topo.get(k, 0)) for k in ("boundary_edges", "non_two_manifold_edges",
                                                "non_two_manifold_vertices")}
    if m.status() != mf.Error.NoError or any(defects.values()):
        raise ParameterError(name, source, "a closed, oriented 2-manifold surface (it has "
                             f"{defects['boundary_edges']} open edges, "
                             f"{defects['non_two_manifold_edges']} non-manifold edges, "
                             f"{defects['non_two_manifold_vertices']} non-manifold vertices; "
                             f"manifold3d: {m.status().name})")
    crossing = mt.self_intersecting_faces(v, f)
    if crossing:
        raise ParameterError(name, source, f"a surface that does not cross itself "
                             f"({crossing} self-intersecting triangles)")
    capped = False
    if port is not None:
        out = mt.cap_ports(v, f, port)
        if out is None:
            raise ParameterError(name, source, "a surface manifold3d can plug the port of")
        v, f = out
        capped = True
    parts = mt.shells(v, f)
    depth = mt.nesting_depth(v, f, parts)
    solids = int(np.sum(np.asarray(depth) % 2 == 0))  # outer shells: the gate's one_part
    if solids != 1:
        raise ParameterError(name, source, f"one solid body (this file holds {solids} "
                             "separate bodies: give each its own file)")
    cavities = [p for p, d in zip(parts, depth) if d % 2 == 1]
    if len(cavities) != 1:
        hint = (" (with the port plugged)" if capped else
                "; an exported bladder's cavity opens through its inlet: give --design "
                "FILE.design.json to plug it") if not cavities else ""
        raise ParameterError(name, source, "a part with exactly one enclosed cavity (found "
                             f"{len(cavities)}{hint})")
    return PartSurface(v, f, cavities[0], source, capped)


def load_part(path, design: dict | None = None) -> PartSurface:
    """Read and check the part at ``path``; ``design`` (its design dict) plugs the port."""
    v, f = read_surface(path)
    port = (design or {}).get("port")
    return part_surface(v, f, port=port, source=str(path))


# -- meshing ------------------------------------------------------------------------------------
def _polydata(v, f):
    import pyvista as pv

    return pv.PolyData.from_regular_faces(np.asarray(v, np.float64), np.asarray(f, np.int64))


def _distance(points, surface) -> np.ndarray:
    import pyvista as pv

    cloud = pv.PolyData(np.asarray(points, np.float64))
    return np.abs(np.asarray(cloud.compute_implicit_distance(surface)["implicit_distance"]))


def _classifier(surface: PartSurface):
    """Facet centroids -> "cavity" or "outer", by which shell is nearer."""
    mask = np.zeros(len(surface.faces), bool)
    mask[surface.cavity] = True
    cav = _polydata(surface.vertices, surface.faces[mask])
    out = _polydata(surface.vertices, surface.faces[~mask])

    def classify(c):
        return np.where(_distance(c, cav) < _distance(c, out), "cavity", "outer").astype(object)

    return classify


def _jacobians(nodes, tets) -> np.ndarray:
    """det J (nel, 10) at the ten nodes of each P2 tetrahedron."""
    ref = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [.5, 0, 0], [.5, .5, 0],
                    [0, .5, 0], [0, 0, .5], [.5, 0, .5], [0, .5, .5]], float)
    _, dN = tet_p2(ref)
    J = np.einsum("eai,qaj->eqij", nodes[tets], dN)
    return np.linalg.det(J)


def _curve_boundary(nodes, tets, surface: PartSurface) -> tuple[np.ndarray, int]:
    """Move the nodes of boundary facets to the closest point of the part's surface; undo it
    on elements it would spoil. Returns (nodes, boundary nodes moved)."""
    facets = boundary_facets(tets)
    mid = np.unique(facets)
    surf = _polydata(surface.vertices, surface.faces)
    _, closest = surf.find_closest_cell(nodes[mid], return_closest_point=True)
    straight = _jacobians(nodes, tets)[:, 0]
    new = nodes.copy()
    new[mid] = closest
    for _ in range(3):
        bad = np.any(_jacobians(new, tets) < 0.25 * straight[:, None], axis=1)
        if not bad.any():
            break
        back = np.intersect1d(tets[bad], mid)
        new[back] = nodes[back]
    moved = int(np.count_nonzero(np.any(new[mid] != nodes[mid], axis=1)))
    return new, moved


def simplified(surface: PartSurface, size: float) -> tuple[np.ndarray, np.ndarray]:
    """The part's surface with about two triangles per size² of area (what a mesh of edge
    ``size`` can follow; the boundary nodes are projected onto the full surface afterwards), by
    quadric edge collapse that keeps the topology; the surface itself if it is that coarse
    already. (fTetWild took 289 s on Type B's 40k-triangle surface at 1 mm; on the
    fingertip's 5.7k from 254k at 1.5 mm, 122 s.)"""
    from spsc.cad import meshtopo as mt

    area = float(mt.face_areas(surface.vertices, surface.faces).sum())
    target = max(2000, int(2.0 * area / size**2))
    if len(surface.faces) <= 1.5 * target:
        return surface.vertices, surface.faces
    ms = mt.meshset(surface.vertices, surface.faces)
    ms.meshing_decimation_quadric_edge_collapse(
        targetfacenum=target, qualitythr=0.5, preserveboundary=True, preservenormal=True,
        preservetopology=True, planarquadric=True, optimalplacement=True)
    m = ms.current_mesh()
    return np.asarray(m.vertex_matrix(), float), np.asarray(m.face_matrix(), np.int64)


#: element size (× the mesh size) far from the cavity, and how fast it grows there (mm per mm)
GRADED_MAX, GRADED_SLOPE = 4.0, 0.5


def size_field(surface: PartSurface, size: float, *, graded: bool = True):
    """fTetWild's background size field: (points (n, 3), tets (m, 4), edge length (n,)) on a
    grid over the part. ``size`` (mm) within 2·size of the cavity (the sensing wall, where the
    wall bends), then growing by :data:`GRADED_SLOPE` per mm up to :data:`GRADED_MAX` · size in
    the bulk (a body block, a flange): the unknowns go where the response is made."""
    lo, hi = surface.bounds
    lo, hi = lo - 1.0, hi + 1.0
    step = max(size, float(np.max(hi - lo)) / 40)
    axes = [np.linspace(a, b, max(2, int(np.ceil((b - a) / step)) + 1)) for a, b in zip(lo, hi)]
    shape = tuple(len(a) for a in axes)
    pts = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    idx = np.arange(len(pts)).reshape(shape)
    c = [idx[i:i + shape[0] - 1, j:j + shape[1] - 1, k:k + shape[2] - 1].ravel()
         for i in (0, 1) for j in (0, 1) for k in (0, 1)]  # c[4i+2j+k]
    kuhn = ((0, 4, 6, 7), (0, 4, 5, 7), (0, 1, 5, 7), (0, 1, 3, 7), (0, 2, 3, 7), (0, 2, 6, 7))
    tets = np.vstack([np.column_stack([c[a] for a in t]) for t in kuhn]).astype(np.int32)
    a, b, cc, d = (pts[tets[:, i]] for i in range(4))
    neg = np.einsum("ij,ij->i", np.cross(b - a, cc - a), d - a) < 0
    tets[neg] = tets[neg][:, [0, 2, 1, 3]]
    if not graded:
        return pts, tets, np.full(len(pts), float(size))
    mask = np.zeros(len(surface.faces), bool)
    mask[surface.cavity] = True
    d = _distance(pts, _polydata(surface.vertices, surface.faces[mask]))
    h = size + GRADED_SLOPE * np.maximum(d - 2 * size, 0.0)
    return pts, tets, np.minimum(h, GRADED_MAX * size)


def part_mesh(surface: PartSurface, size: float, *, epsilon: float | None = None,
              curved: bool = True, graded: bool = True, threads: int = 1) -> TetMesh:
    """Quadratic tetrahedra of the part (edge ``size`` mm at the cavity's wall, graded away
    from it unless ``graded`` is False: :func:`size_field`), boundary facets tagged ``cavity``
    and ``outer``; ``epsilon``: fTetWild's envelope as a fraction of the bounding-box diagonal
    (default: 0.02 mm or size/50, whichever is smaller); ``curved``: boundary nodes on the
    part's surface."""
    import pytetwild

    diag = surface.diagonal
    if epsilon is None:
        epsilon = min(0.05, size / 20) / diag
    v, f = simplified(surface, size)
    bg, bg_tets, bg_h = size_field(surface, size, graded=graded)
    with tempfile.TemporaryDirectory() as tmp, contextlib.chdir(tmp):
        nodes, tets4 = pytetwild.tetrahedralize(
            v, f.astype(np.int32), edge_length_abs=float(size), bg_vertices=bg,
            bg_tets=bg_tets, bg_values=bg_h,
            epsilon=float(epsilon), optimize=True, num_threads=threads, quiet=True)
    nodes = np.asarray(nodes, float)
    tets4 = np.asarray(tets4, np.int64)
    used, tets4 = np.unique(tets4, return_inverse=True)
    nodes, tets4 = nodes[used], tets4.reshape(-1, 4)
    nodes, tets = p1_to_p2(nodes, tets4)
    tets, _ = orient_tets(nodes, tets)
    if curved:
        nodes, _ = _curve_boundary(nodes, tets, surface)
    facets = boundary_facets(tets)
    tags = _classifier(surface)(nodes[facets[:, :3]].mean(axis=1))
    return TetMesh(nodes, tets, {t: facets[tags == t] for t in ("cavity", "outer")}, 1)
