"""The fused fingertip of sec. 4.1 (PneuTact.Q): two Type A chambers, one cavity, five FSR pockets.

Frame: the finger points along +y, the pulp faces +z. A body block (z ∈ [−b, 0]) carries the
pulp chamber on its top face z = 0 and the distal-edge chamber on an inclined front face whose
normal is tilted by ``angle`` from +z towards +y. A channel swept through the body joins the
two cavities into one (the paper's lofted connection; a swept circle is the robust B-rep). Three FSR pockets sit on the pulp, two on the distal chamber, each
recessed into a raised pad whose pocket floor lies above the tangent plane of the wall at the
pocket centre, so the (convex) wall under a pocket keeps at least its thickness t0. The rear of
the body holds the mounting slot for the gripper finger, two cross screw holes and the inlet
port (a barbed nipple along −y whose bore rises into the pulp cavity).

FSR defaults are Ohmite FSR05 (datasheet: active area Ø5.60 mm, sensor head Ø7.62 mm,
thickness 0.325 mm, tail width 6.35 mm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cadquery as cq
import numpy as np

from .bladder import nipple
from .chamber import PROFILE_POINTS, profile_body
from .geometry import SPSCGeometry
from .specs import FingertipSpec, MountSpec, PocketSpec

__all__ = ["PocketSpec", "MountSpec", "FingertipSpec", "Fingertip", "build_fingertip",
           "measure_pockets"]

#: Chord sag (mm) and angle (rad) of the fingertip's export mesh: its many small features would
#: give 600k triangles at the bladder's settings; the SLA gate (0.5 mm) has ample margin.
MESH_TOLERANCE = (0.005, 0.1)



@dataclass(frozen=True)
class Fingertip:
    spec: FingertipSpec
    solid: cq.Solid
    cavity: cq.Solid
    design: dict


def _outer_surface_point(g: SPSCGeometry, r: float) -> tuple[float, np.ndarray]:
    """Height and outward unit normal (radial, z) of the outer wall at radius r from the axis."""
    pts = g.outer_profile_points(PROFILE_POINTS)
    k = int(np.clip(np.searchsorted(pts[:, 0], r), 1, len(pts) - 1))
    a, b = pts[k - 1], pts[k]
    f = (r - a[0]) / (b[0] - a[0]) if b[0] > a[0] else 0.0
    z = a[1] + f * (b[1] - a[1])
    t = (b - a) / np.hypot(*(b - a))
    return float(z), np.array([-t[1], t[0]]) if t[0] >= 0 else np.array([t[1], -t[0]])


def _pocket_frames(g: SPSCGeometry, offsets: list[float]) -> list[tuple[np.ndarray, np.ndarray]]:
    """(point, outward normal) on the outer wall at y = offset along the chamber's axis (x = 0),
    in the chamber's own frame (base z = 0, extrusion along y)."""
    frames = []
    for s in offsets:
        r = max(0.0, abs(s) - g.l / 2)
        z, (nr, nz) = _outer_surface_point(g, r)
        frames.append((np.array([0.0, s, z]), np.array([0.0, math.copysign(nr, s), nz])))
    return frames


def _cylinder(p0: np.ndarray, axis: np.ndarray, radius: float, length: float) -> cq.Solid:
    return cq.Solid.makeCylinder(radius, length, cq.Vector(*p0), cq.Vector(*axis))


def _pad_and_cuts(point, normal, tangent, spec: FingertipSpec, g: SPSCGeometry):
    """The raised pad (to add) and the pocket + lead channel (to cut) at one pocket site."""
    pk = spec.pocket
    r_pad = pk.diameter / 2 + pk.rim
    floor = point + normal * pk.clearance
    sink = g.t0 + r_pad**2 / (2 * min(g.w, g.h))  # reaches the convex wall at the pad's edge
    pad = _cylinder(point - normal * sink, normal, r_pad, sink + pk.clearance + pk.depth)
    pocket = _cylinder(floor, normal, pk.diameter / 2, pk.depth + 1.0)
    tangent = tangent - normal * float(tangent @ normal)  # lead runs in the pocket's plane
    tangent = tangent / np.linalg.norm(tangent)
    lead = cq.Solid.makeBox(r_pad + 4.0, pk.lead_width, pk.depth + 1.0,
                            cq.Vector(0, -pk.lead_width / 2, 0))
    lead = _place(lead, floor, tangent, normal)
    return pad, pocket.fuse(lead), (floor, normal, pk.diameter / 2)


def _place(shape: cq.Shape, origin: np.ndarray, xdir: np.ndarray, zdir: np.ndarray) -> cq.Shape:
    """Move ``shape`` from its own frame into the frame (origin, x → xdir, z → zdir)."""
    plane = cq.Plane(origin=cq.Vector(*origin), xDir=cq.Vector(*xdir), normal=cq.Vector(*zdir))
    return shape.moved(cq.Location(plane))


def build_fingertip(spec: FingertipSpec = FingertipSpec()) -> Fingertip:
    """Build the monolithic fingertip solid, its cavity and the design facts for the gate."""
    P, D, mt, pt = spec.pulp, spec.distal, spec.mount, spec.port
    a = math.radians(spec.angle)
    W = spec.width
    n_d = np.array([0.0, math.sin(a), math.cos(a)])       # distal chamber axis
    t_d = np.array([0.0, math.cos(a), -math.sin(a)])      # down the inclined face
    Rp, Rd = P.w + P.t0, D.w + D.t0
    y_front = P.l / 2 + Rp                                # front edge of the top face
    A = np.array([0.0, y_front, 0.0])
    C = A + t_d * (Rd + spec.margin)                      # distal base centre
    B = A + t_d * (2 * Rd + 2 * spec.margin)
    b = max(-B[2], mt.slot_depth + pt.barb_diameter + 2 * P.t0 + 1.0)
    y_rear = -(P.l / 2 + Rp) - mt.length

    # body block: side profile in (y, z), extruded across the width
    prof = [(y_rear, -b), (y_rear, 0.0), (A[1], 0.0), (B[1], B[2])]
    if B[2] > -b + 1e-9:
        prof.append((B[1], -b))
    body = (cq.Workplane("YZ").polyline(prof).close().extrude(W / 2, both=True).val())

    # distal chamber frame: its own z -> n_d, its own y (extrusion) -> x, so its own x -> −t_d
    rot_d = np.column_stack([-t_d, [1.0, 0.0, 0.0], n_d])

    def place_distal(shape):
        return _place(shape, C, -t_d, n_d)

    pulp_out = profile_body(P.outer_profile_points(PROFILE_POINTS), P.l)
    pulp_cav = profile_body(P.profile_points(PROFILE_POINTS)[0], P.l)
    dist_out = place_distal(profile_body(D.outer_profile_points(PROFILE_POINTS), D.l))
    dist_cav = place_distal(profile_body(D.profile_points(PROFILE_POINTS)[0], D.l))

    channel = _channel(spec, A, C, n_d)
    adds, cuts, pockets = _pockets(spec, C, rot_d, place_distal)

    # port along −y at the rear face; bore rises into the pulp cavity at the rear cap centre
    z_axis = -b + mt.slot_depth + pt.barb_diameter / 2 + P.t0
    port = nipple(pt, y_rear, z_axis)
    y_riser = -P.l / 2
    y_tip = y_rear - pt.length
    # the horizontal bore ends on the riser's axis, so capping the riser closes the cavity
    bore_h = cq.Solid.makeCylinder(pt.bore / 2, y_riser - y_tip + 0.5,
                                   cq.Vector(0, y_tip - 0.5, z_axis), cq.Vector(0, 1, 0))
    bore_v = cq.Solid.makeCylinder(pt.bore / 2, -z_axis + 0.5, cq.Vector(0, y_riser, z_axis),
                                   cq.Vector(0, 0, 1))

    mount_cuts = _mount_cuts(mt, W, y_rear, b)

    for part in (pulp_cav, dist_cav, channel):
        if part.Volume() <= 0 or not part.isValid():
            raise RuntimeError("fingertip: a cavity part is empty or invalid")
    cavity = pulp_cav.fuse(dist_cav, channel).clean()
    outer = body.fuse(pulp_out, dist_out, port, *adds).clean()
    solid = outer.cut(cavity, bore_h, bore_v, *cuts, *mount_cuts).clean()
    if not solid.isValid():
        raise RuntimeError("OCCT produced an invalid fingertip solid")

    design = _design(spec, cavity, pockets, y_riser, z_axis)
    design["fem"] = _fem_facts(spec, pockets, b, y_rear, n_d)
    return Fingertip(spec, solid, cavity, design)


#: Ohmite FSR05 (datasheet): sensor head Ø7.62 mm, 0.325 mm thick — the rigid insert in each
#: pocket through which a plate presses the pocket floor
FSR05_HEAD_RADIUS_MM = 7.62 / 2
FSR05_THICKNESS_MM = 0.325


def _fem_facts(spec, pockets, b, y_rear, n_d) -> dict:
    """What ``spsc fem --part`` needs: the mount (the underside on the gripper finger and the
    slot that holds it), plate sites (``pulp``: straight down on the pulp; ``distal``: along
    the distal chamber's axis), and the five pocket floors as contact patches pressed through
    an FSR05 (named pulp1..3 from the rear, distal1..2 from −x)."""
    mt, pk = spec.mount, spec.pocket
    slot = (f" | y<={y_rear + mt.length:.6g} & z<={-b + mt.slot_depth:.6g} & "
            f"x>={-mt.slot_width / 2:.6g} & x<={mt.slot_width / 2:.6g}"
            if mt.slot_width > 0 and mt.slot_depth > 0 else "")
    names = ["pulp1", "pulp2", "pulp3", "distal1", "distal2"]
    contacts, tops = [], {}
    for name, (site, floor, normal, _) in zip(names, pockets):
        contacts.append({"name": name, "center": [float(v) for v in floor],
                         "normal": [float(v) for v in normal],
                         "radius": FSR05_HEAD_RADIUS_MM, "insert_mm": FSR05_THICKNESS_MM})
        # a point on the pad's rim, beside the pocket, opposite its lead channel
        side = np.cross(normal, [1.0, 0.0, 0.0] if site == "pulp" else [0.0, 1.0, 0.0])
        side = side / np.linalg.norm(side)
        tops.setdefault(site, []).append(floor + normal * pk.depth
                                         + side * (pk.diameter / 2 + pk.rim / 2))
    pulp_at = tops["pulp"][1]
    distal_at = tops["distal"][0]
    return {"mount": f"z<={-b:.6g}{slot}",
            "sites": {"pulp": {"at": [float(v) for v in pulp_at], "normal": [0.0, 0.0, -1.0]},
                      "distal": {"at": [float(v) for v in distal_at],
                                 "normal": [float(-v) for v in n_d]}},
            "contacts": contacts}


def _channel(spec, A, C, n_d):
    """The channel: a circle swept along a spline from inside the pulp cavity's front cap,
    under the valley between the chambers (A, the front edge of the top face), into the distal
    cavity (base centre C, axis n_d): one connected cavity."""
    P, D = spec.pulp, spec.distal
    rc = spec.channel_width / 2
    dip = max(P.t0, D.t0) + rc + 1.0
    p1 = np.array([0.0, P.l / 2, 0.5])
    p2 = A + np.array([0.0, 0.0, -dip])
    p3 = C + n_d * 0.5
    t1 = np.array([0.0, 0.6, -1.0]) / math.hypot(0.6, 1.0)
    path = cq.Workplane().spline([tuple(p1), tuple(p2), tuple(p3)],
                                 tangents=[tuple(t1), tuple(n_d)], includeCurrent=False)
    start = cq.Plane(origin=cq.Vector(*p1), xDir=cq.Vector(1, 0, 0), normal=cq.Vector(*t1))
    return cq.Workplane(start).circle(rc).sweep(path, transition="round").val()


def _pockets(spec, C, rot_d, place_distal):
    """The FSR pockets: three along the pulp's axis, two across the distal chamber. (pads to
    add, cuts, [(site, floor centre, normal, radius)])."""
    P, D = spec.pulp, spec.distal
    adds, cuts, pockets = [], [], []
    for p, n in _pocket_frames(P, [-spec.pocket_pitch, 0.0, spec.pocket_pitch]):
        pad, cut, info = _pad_and_cuts(p, n, np.array([1.0, 0.0, 0.0]), spec, P)
        adds.append(pad), cuts.append(cut), pockets.append(("pulp",) + info)
    half = spec.pocket_pitch / 2
    for p, n in _pocket_frames(D, [-half, half]):
        # distal leads run sideways (local ±y = global ±x), away from the valley
        pad, cut, info = _pad_and_cuts(p, n, np.array([0.0, math.copysign(1.0, p[1]), 0.0]),
                                       spec, D)
        adds.append(place_distal(pad)), cuts.append(place_distal(cut))
        floor, normal, r = info
        pockets.append(("distal", rot_d @ floor + C, rot_d @ normal, r))
    return adds, cuts, pockets


def _mount_cuts(mt, W, y_rear, b):
    """The mount: a slot under the rear block for the gripper finger, screw holes across it
    (x)."""
    mount_cuts = []
    if mt.slot_width > 0 and mt.slot_depth > 0:
        mount_cuts.append(cq.Solid.makeBox(mt.slot_width, mt.length + 1.0, mt.slot_depth + 1.0,
                                           cq.Vector(-mt.slot_width / 2, y_rear - 1.0, -b - 1.0)))
    ys = {0: [], 1: [0.5], 2: [0.3, 0.75]}[mt.screws]
    for f in ys:
        mount_cuts.append(cq.Solid.makeCylinder(
            mt.screw_diameter / 2, W + 2.0,
            cq.Vector(-W / 2 - 1.0, y_rear + f * mt.length, -b + mt.slot_depth / 2),
            cq.Vector(1, 0, 0)))
    return mount_cuts


def _design(spec, cavity, pockets, y_riser, z_axis) -> dict:
    """The design facts the printability gate checks the fingertip against."""
    P, D, pk, mt, pt = spec.pulp, spec.distal, spec.pocket, spec.mount, spec.port
    return {
        "kind": "fingertip",
        "cavity_volume_mm3": float(cavity.Volume()),
        "cavity_volume_source": "exact B-rep of the fused cavity (chambers + channel)",
        "volume_rtol": 0.002,
        "cavities": 1,
        "genus": mt.screws * (2 if mt.slot_width > 0 and mt.slot_depth > 0 else 1),
        "min_wall_design_mm": min(P.t0, D.t0),
        "port": {"axis_point": [0.0, y_riser, 0.0], "axis_dir": [0.0, 0.0, 1.0],
                 "radius": pt.bore / 2 + 0.02, "z_range": [z_axis - pt.bore / 2 - 0.05, 0.0]},
        "wall_region": {"z_min": -1e9},
        "exclude": [{"center": [0.0, y_riser, 0.0], "radius": pt.bore / 2 + 0.5}],
        "pockets": [{"site": site, "floor_center": [float(v) for v in fl],
                     "normal": [float(v) for v in nv], "radius": float(r),
                     "depth": pk.depth} for site, fl, nv, r in pockets],
        "print": {"build_direction": [0.0, 0.0, 1.0], "plane": "i-k (x-y), base down"},
    }


def _first_hit(tri: np.ndarray, origin: np.ndarray, direction: np.ndarray) -> float:
    """Distance along the unit ``direction`` to the nearest triangle of ``tri`` (m, 3, 3) hit
    from ``origin`` (Möller–Trumbore over all triangles at once); inf if none."""
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    p = np.cross(direction, e2)
    det = np.einsum("ij,ij->i", e1, p)
    ok = np.abs(det) > 1e-14
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - tri[:, 0]
    u = np.einsum("ij,ij->i", s, p) * inv
    q = np.cross(s, e1)
    v = (q @ direction) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    hit = ok & (u >= -1e-12) & (v >= -1e-12) & (u + v <= 1 + 1e-12) & (t > 0)
    return float(t[hit].min()) if hit.any() else math.inf


def measure_pockets(solid_mesh, cavity_mesh, design: dict, *, samples: int = 200) -> dict:
    """Measure the FSR pockets on an exported fingertip mesh.

    A pocket counts when a ray cast along −normal at its centre first meets the mesh at the
    design floor (±0.02 mm) and a ray just outside its rim (in one of 8 directions) meets the
    pad top one ``depth`` higher, i.e. the recess is really there. The wall under each pocket is the closest-point
    distance (mm) from points of its floor disc to the cavity surface ``cavity_mesh``.
    Both meshes are :class:`~spsc.cad.export.TriMesh`; returns count, per-pocket minimum wall
    and the overall minimum.
    """
    import pyvista as pv

    def poly(m):
        faces = np.hstack([np.full((len(m.faces), 1), 3), m.faces]).ravel()
        return pv.PolyData(m.vertices, faces)

    cavity = poly(cavity_mesh)
    tri = solid_mesh.vertices[solid_mesh.faces]
    lift, tol = 1.5, 0.02
    found, walls = 0, []
    for pk in design["pockets"]:
        c, n, r, depth = (np.asarray(pk["floor_center"]), np.asarray(pk["normal"]),
                          pk["radius"], pk["depth"])
        u = np.cross(n, [1.0, 0.0, 0.0] if abs(n[0]) < 0.9 else [0.0, 1.0, 0.0])
        u /= np.linalg.norm(u)

        def first_hit(p0):
            return _first_hit(tri, p0 + n * (depth + lift), -n)

        floor_ok = abs(first_hit(c) - (depth + lift)) < tol
        v = np.cross(n, u)
        # the pad top is one depth above the floor somewhere around the rim (neighbouring pads
        # overlap and the lead channel opens one side, so not in every direction)
        rim_ok = any(abs(first_hit(c + (r + 0.4) * (math.cos(a) * u + math.sin(a) * v)) - lift)
                     < tol for a in np.linspace(0.0, 2 * math.pi, 8, endpoint=False))
        found += bool(floor_ok and rim_ok)
        rr = (r - 0.1) * np.sqrt(np.linspace(0.0, 1.0, samples))
        ang = np.linspace(0.0, 2 * math.pi * 21, samples)  # a spiral covering the disc
        pts = c + rr[:, None] * (np.cos(ang)[:, None] * u + np.sin(ang)[:, None] * v)
        d = np.abs(pv.PolyData(pts).compute_implicit_distance(cavity)["implicit_distance"])
        walls.append(float(d.min()))
    return {"pocket_count": found, "pockets_designed": len(design["pockets"]),
            "min_wall_under_pockets_mm": min(walls) if walls else None,
            "wall_under_each_pocket_mm": walls}
