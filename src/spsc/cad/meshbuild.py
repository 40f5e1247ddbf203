"""The bladder as a triangle mesh, built with manifold3d from the same profile as the B-rep.

Why a second construction: OCCT's mesher does not honour an absolute chord tolerance on the
revolved B-spline faces of these chambers (triangles deviated 0.045 mm from the B-rep at a
requested 0.002 mm, thinning the measured wall by 5 %). Here every tolerance is ours: the profile
polyline is dense enough that its chord sag is < 0.002 mm, circles get enough segments for the
same sag, and manifold3d's booleans guarantee a closed 2-manifold. The STEP stays the exact
B-rep of :mod:`spsc.cad.bladder`; a test checks that both agree (volume, genus, extents).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import manifold3d as m3
import numpy as np

from .bladder import BladderSpec, flange_hole_centres, widest_outer_radius
from .export import TriMesh
from .geometry import MESH_PROFILE_POINTS, SPSCGeometry

__all__ = ["bladder_mesh", "bladder_solids", "BladderSolids", "chamber_manifold", "hull_meridian",
           "manifold_mesh", "SAG_MM"]

#: Chord sag (mm) of every circle of the mesh: volume error ~2·sag/R ≈ 0.05 %, far inside the
#: 0.2 % the issue allows, and a wall error far under the gate's 0.01 mm allowance.
SAG_MM = 0.004
#: A meridian point within this fraction of the part's largest coordinate of the chord between
#: its neighbours is left out of the hull (:func:`hull_meridian`): 100x under QuickHull's own
#: coplanarity tolerance (1e-7 of that coordinate), a million times over rounding noise.
COLLINEAR_REL = 1e-9


def _segments(radius: float, degrees: float = 360.0) -> int:
    """Segments for an arc of ``radius`` so the chord sag is <= SAG_MM (a multiple of 4)."""
    per_rad = 1.0 / math.acos(max(-1.0, 1.0 - SAG_MM / max(radius, 1e-9))) / 2.0
    n = int(math.ceil(per_rad * math.radians(degrees)))
    return max(8, 4 * math.ceil(n / 4))


def chamber_manifold(pts: np.ndarray, l: float, *, sink: float = 0.0) -> m3.Manifold:
    """The solid under the profile ``pts`` (x, z; apex first, base last): revolved ends at
    y = ±l/2 and the extruded middle.

    The body {(x, y, z): dist((x, y), segment y ∈ [−l/2, l/2]) <= r(z)} is convex for every
    convex profile (r concave), so it is the convex hull of its horizontal stadium rings: one
    piece, no seams where ends and middle meet. ``sink`` > 0 prolongs the profile's last
    (straight) segment from z = 0 down to z = −sink in place of the base ring, so a union with
    a plate whose top is z = 0 shares no coplanar face or ring (an STL cannot represent the
    coincident vertices such a union leaves); above z = 0 the surface is unchanged. Points on
    the chord of their neighbours go before the hull (:func:`hull_meridian`).
    """
    pts = np.asarray(pts, float)
    if sink > 0:
        d = pts[-1] - pts[-2]
        pts = np.vstack([pts[:-1], pts[-2] + d * ((-sink - pts[-2, 1]) / d[1])])
    pts = hull_meridian(pts, l)
    n = _segments(float(pts[:, 0].max()))
    a = np.linspace(0.0, math.pi, n // 2 + 1)
    rings = []
    for r, z in pts:
        if r <= 1e-9:
            rings.append([[0.0, -l / 2, z], [0.0, l / 2, z]])
            continue
        xs = np.concatenate([r * np.cos(a), -r * np.cos(a)])
        ys = np.concatenate([l / 2 + r * np.sin(a), -l / 2 - r * np.sin(a)])
        rings.append(np.column_stack([xs, ys, np.full_like(xs, z)]))
    return m3.Manifold.hull_points(np.vstack(rings))


def hull_meridian(pts: np.ndarray, l: float = 0.0) -> np.ndarray:
    """The meridian ``pts`` (x, z) without the points that lie on the chord between their
    neighbours (within :data:`COLLINEAR_REL` of the largest coordinate of the body, extruded by
    ``l``); every point left out lies that close to the chord of the points kept around it.

    Why: such a point adds nothing to the convex body, but its ring lies in the planes of the
    facets spanned by the rings on either side, and QuickHull (manifold3d's ``hull_points``)
    then tells on which side of them each of its points lies by the sign of rounding noise: it
    keeps part of the ring, drops the rest, fails to close horizons and can return folded,
    self-intersecting facets. Type C's outer wall has such a point by construction: its offset
    ends above the base plane and is prolonged along its last chord
    (:meth:`SPSCGeometry.outer_profile_points`), and ``sink`` prolongs that same line into the
    plate, so the ring where the offset ends sits exactly on the line (issue 10: self-
    intersecting faces at the wall's root). A cone (n1 = n2 = 1) is nothing but such points.
    """
    pts = np.asarray(pts, float)
    tol = COLLINEAR_REL * (l / 2 + float(np.abs(pts).max()))
    keep, skipped = [0], []
    for i in range(1, len(pts) - 1):
        a, b = pts[keep[-1]], pts[i + 1]
        run = pts[skipped + [i]]
        ab = b - a
        t = np.clip((run - a) @ ab / (ab @ ab), 0.0, 1.0)
        if np.hypot(*(a + t[:, None] * ab - run).T).max() <= tol:
            skipped.append(i)  # on the chord from the last kept point to the next one
        else:
            keep.append(i)
            skipped = []
    keep.append(len(pts) - 1)
    return pts[keep]


def _cylinder(radius, height, start, direction, r_top=None) -> m3.Manifold:
    """Cylinder (or cone) of ``height`` from ``start`` along unit ``direction``."""
    c = m3.Manifold.cylinder(height, radius, radius if r_top is None else r_top,
                             _segments(radius))
    d = np.asarray(direction, float)
    if abs(d[2] - 1.0) > 1e-12:
        if abs(d[2] + 1.0) < 1e-12:
            c = c.rotate([180.0, 0.0, 0.0])
        else:  # rotate +z onto d: about x for d in the y–z plane, about y for the x–z plane
            if abs(d[0]) < 1e-12:
                c = c.rotate([-math.degrees(math.atan2(d[1], d[2])), 0.0, 0.0])
            else:
                c = c.rotate([0.0, math.degrees(math.atan2(d[0], d[2])), 0.0])
    return c.translate(list(map(float, start)))


def _stadium(radius: float, l: float, z0: float, height: float) -> m3.Manifold:
    n = _segments(radius)
    a = np.linspace(0.0, math.pi, n // 2 + 1)
    top = np.column_stack([radius * np.cos(a), l / 2 + radius * np.sin(a)])
    bottom = np.column_stack([-radius * np.cos(a), -l / 2 - radius * np.sin(a)])
    ring = np.vstack([top, bottom]) if l > 0 else top[:-1].tolist() + bottom[:-1].tolist()
    return m3.Manifold.extrude(m3.CrossSection([np.asarray(ring).tolist()]), height).translate(
        [0.0, 0.0, z0])


@dataclass(frozen=True)
class BladderSolids:
    """The bladder's construction in manifold3d (mm, part coordinates): ``body`` (wall envelope,
    plate and port, before any cut), ``cavity`` (the chamber's inner body), ``bore`` (the port's
    horizontal bore and its riser into the cavity), ``holes`` (the flange's screw holes, None
    without holes). The part is ``body − cavity − bore − holes``; molds reuse the pieces."""

    body: m3.Manifold
    cavity: m3.Manifold
    bore: m3.Manifold
    holes: m3.Manifold | None

    @property
    def part(self) -> m3.Manifold:
        cut = self.cavity + self.bore
        if self.holes is not None:
            cut += self.holes
        return self.body - cut


def bladder_solids(spec: BladderSpec) -> BladderSolids:
    """The pieces of :func:`bladder_mesh` (see :class:`BladderSolids`)."""
    g: SPSCGeometry = spec.geometry
    f, p = spec.flange, spec.port
    inner, outer = g.wall_profiles(MESH_PROFILE_POINTS)
    r_wall = widest_outer_radius(g)
    r_flange = r_wall + f.width
    y_edge = -(g.l / 2 + r_flange)
    z_axis = spec.port_axis_z
    solid = chamber_manifold(outer, g.l, sink=f.thickness / 2) + _stadium(
        r_flange, g.l, -f.thickness, f.thickness)
    down = [0.0, -1.0, 0.0]
    solid += _cylinder(p.tube_id / 2, p.length + 1.0, [0.0, y_edge + 1.0, z_axis], down)
    if p.barbs:
        pitch = p.length / (p.barbs + 0.5)
        for k in range(p.barbs):
            solid += _cylinder(p.barb_diameter / 2, pitch * 0.9,
                               [0.0, y_edge - (k + 0.5) * pitch, z_axis], down,
                               r_top=p.tube_id / 2)
    y_riser = -g.l / 2
    y_tip = y_edge - p.length
    bore = _cylinder(p.bore / 2, y_riser - y_tip + 0.5, [0.0, y_tip - 0.5, z_axis],
                     [0.0, 1.0, 0.0])
    bore += _cylinder(p.bore / 2, -z_axis + 0.5, [0.0, y_riser, z_axis], [0.0, 0.0, 1.0])
    holes = None
    for x, y in flange_hole_centres(spec):
        h = _cylinder(f.hole_diameter / 2, f.thickness + 2.0, [x, y, -f.thickness - 1.0],
                      [0.0, 0.0, 1.0])
        holes = h if holes is None else holes + h
    return BladderSolids(solid, chamber_manifold(inner, g.l), bore, holes)


def bladder_mesh(spec: BladderSpec) -> TriMesh:
    """The printable bladder of :func:`spsc.cad.bladder.build_bladder` as a closed mesh."""
    solid = bladder_solids(spec).part
    if solid.status() != m3.Error.NoError or solid.is_empty():
        raise RuntimeError(f"manifold3d could not build the bladder mesh: {solid.status()}")
    return manifold_mesh(solid)


def manifold_mesh(solid: m3.Manifold) -> TriMesh:
    """A manifold's triangles as a :class:`TriMesh` (mm)."""
    mesh = solid.to_mesh()
    return TriMesh(np.asarray(mesh.vert_properties, float)[:, :3],
                   np.asarray(mesh.tri_verts, np.int64))
