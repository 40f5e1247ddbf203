"""A mold for a bladder's wall (issue 15): two outer halves, a lost core and, where needed, pins.

The bladder is closed but for its inlet bore, so its cavity is formed by a **core** that stays in
the part until the halves are off and is then dissolved (printed in PVA or BVOH, or cast in wax)
and flushed out through the bore: no rigid core could leave a closed cavity through a 1.4 mm bore.
The core is the cavity, the bore and a stem that leaves the port's tip into a square **core
print**, the seat both halves clamp, so the core is located by the inlet stem alone and the only
opening the part is left with is its own inlet.

The **parting plane** is chosen by an undercut test (:func:`pull_test`: each half moved along its
pull direction must not cut into the part): a horizontal plane through the port axis when the
chamber narrows upward from its base (Types A–C: the flange holes are formed by the halves
themselves), else the vertical plane x = 0 with the halves pulled sideways and the flange holes
formed by **pins** pulled down before the halves (Type D, widest 4.9 mm above its base).

Conical registration keys (drafted, with a clearance in their sockets) stand on the first half
(below / left of the plane), bolt holes run through both halves at the corners. Casting adds a
conical sprue onto the flange, a riser over the dome's apex and vents over the port's barbs (the
high points where air is trapped); compression adds a flash groove around the part in the first
half's parting face, one land width away. The cavity is the part scaled by 1 / (1 − s) for the
silicone's linear shrinkage s.

Every piece is built twice by the same recipe (:mod:`spsc.cad.mold.kernel`): as a mesh (the mold
gate, STL, 3MF) and as an exact B-rep (STEP). Part coordinates, mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import manifold3d as m3
import numpy as np

from ..bladder import flange_hole_centres, widest_outer_radius
from ..meshbuild import bladder_solids
from .kernel import BrepKernel, MeshKernel, frame
from .spec import MoldSpec
from ..specs import BladderSpec

__all__ = ["Piece", "Mold", "build_mold", "pull_test", "pull_length", "bladder_bbox",
           "UNDERCUT_TOL_MM2"]

#: A half whose undercut (interference volume per mm of pull at the first 0.02 mm) is above this
#: area (mm²) cannot be pulled: 0.5 mm² is a few triangles of a 0.004 mm-sag surface, far under
#: Type D's down-facing band (~80 mm²) and above boolean round-off (~1e-6 mm³).
UNDERCUT_TOL_MM2 = 0.5
#: The first pull step (mm) and the later ones, as fractions of the pull length.
FIRST_STEP_MM = 0.02
STEPS = (0.05, 0.2, 0.5, 1.0)


@dataclass(frozen=True)
class Piece:
    """One mold piece: ``role`` ``half`` | ``core`` | ``pin``; ``pull`` its unit pull direction
    (None for the core, which is dissolved); ``order`` when it comes off (0 first)."""

    name: str
    role: str
    solid: object
    pull: tuple | None
    order: int


@dataclass(frozen=True)
class Mold:
    """A built mold. ``part`` is the bladder scaled for shrinkage (the space the closed mold must
    leave), ``void`` its cavity and bore, ``voids`` every intended empty space of the closed mold
    besides the part (feed channels or flash grooves, bolt holes, key gaps), ``keys`` the key
    cones on the first half and ``plane`` (normal axis, origin) the parting plane."""

    bladder: BladderSpec
    spec: MoldSpec
    kernel: str
    parting: str
    plane_origin: tuple
    pieces: tuple
    part: object
    void: object
    block: object
    voids: object
    keys: tuple
    channels: dict = field(default_factory=dict)
    undercut: dict = field(default_factory=dict)

    def piece(self, name: str) -> Piece:
        return next(p for p in self.pieces if p.name == name)


def build_mold(bladder: BladderSpec, spec: MoldSpec = MoldSpec(), *, kernel: str = "mesh",
               parting: str | None = None) -> Mold:
    """Build the mold of ``bladder`` (see the module docstring). ``kernel``: ``mesh``
    (manifold3d) or ``brep`` (cadquery); ``parting`` overrides ``spec.parting``. With ``auto``
    the horizontal split is kept when no half has an undercut, else the vertical one."""
    choice = parting or spec.parting
    if choice != "auto":
        return _build(bladder, spec, kernel, choice)
    z = _build(bladder, spec, "mesh", "z")
    found = {"z": _undercut(z)}
    if max(found["z"].values()) <= UNDERCUT_TOL_MM2:
        best = "z"
    else:
        x = _build(bladder, spec, "mesh", "x")
        found["x"] = _undercut(x)
        best = min(found, key=lambda k: max(found[k].values()))
    mold = z if best == "z" else x
    if kernel != "mesh":
        mold = _build(bladder, spec, kernel, best)
    return replace(mold, undercut=found)


def _undercut(mold: Mold) -> dict:
    """Undercut area (mm²) of each half pulled from the part and core."""
    obstacles = mold.part + mold.piece("core").solid
    return {p.name: pull_test(p.solid, p.pull, obstacles, pull_length(mold))["undercut_mm2"]
            for p in mold.pieces if p.role == "half"}


def pull_length(mold: Mold) -> float:
    """How far a piece is pulled in the pull test (mm): the mold block's diagonal."""
    lo, hi = np.asarray(mold.block.bounding_box()).reshape(2, 3)
    return float(np.linalg.norm(hi - lo))


def pull_test(solid: m3.Manifold, direction, obstacles: m3.Manifold, length: float) -> dict:
    """Move ``solid`` along ``direction`` and measure its interference with ``obstacles``:
    ``undercut_mm2`` = interference volume / travel after the first 0.02 mm (the projected area of
    the faces that lock the piece), ``collision_mm3`` the largest interference volume over the
    rest of the pull (``length``·0.05 … ``length``): a feature met farther along. A ray or sweep
    test in one: an undercut interferes at once, a distant obstacle later."""
    d = np.asarray(direction, float)
    first = float((solid.translate((d * FIRST_STEP_MM).tolist()) ^ obstacles).volume())
    later = [float((solid.translate((d * f * length).tolist()) ^ obstacles).volume())
             for f in STEPS]
    # round-off gives ±1e-13 on a free pull: report it as 0
    return {"undercut_mm2": max(first / FIRST_STEP_MM, 0.0),
            "collision_mm3": max(max(later), 0.0)}


def bladder_bbox(b: BladderSpec) -> tuple[np.ndarray, np.ndarray]:
    """The bladder's bounding box (mm), from its parameters."""
    g, f, p = b.geometry, b.flange, b.port
    r_flange = widest_outer_radius(g) + f.width
    y_tip = -(g.l / 2 + r_flange) - p.length
    return (np.array([-r_flange, y_tip, -f.thickness]),
            np.array([r_flange, g.l / 2 + r_flange, g.h + g.t0]))


def _build(bladder: BladderSpec, spec: MoldSpec, kernel: str, parting: str) -> Mold:
    K = {"mesh": MeshKernel, "brep": BrepKernel}[kernel]()
    k, p = spec.scale, bladder.port
    raw = K.bladder(bladder)
    body = K.scale(raw["body"], k)
    void = K.scale(K.union([raw["cavity"], raw["bore"]]), k)
    holes = K.scale(raw["holes"], k) if raw["holes"] is not None else None
    part = K.cut(body, [void, holes])
    # what the halves are cut by: the part with its cavity and bore filled (the core's place),
    # never part and core one after the other, whose shared bore surface leaves slivers
    filled = K.cut(body, [holes]) if (holes is not None and parting == "z") else body
    lo, hi = (a * k for a in bladder_bbox(bladder))
    z_axis = bladder.port_axis_z * k
    side, wall = spec.side, spec.wall
    pad_lo = np.array([side, side, wall]) if parting == "z" else np.array([wall, side, side])
    blo, bhi = lo - pad_lo, hi + pad_lo
    block = K.box(blo, bhi)
    R = frame(parting)
    n = R[:, 2]
    origin = np.array([0.0, 0.0, z_axis]) if parting == "z" else np.zeros(3)

    # the core: cavity, bore, the stem out of the port's tip and its square print to the face
    c = spec.core_print
    y_print = lo[1] - spec.stem_length  # the port's tip less the stem
    # built at nominal size and scaled, like the bore it continues, so both share their facets
    stem = K.scale(K.cylinder(p.bore / 2, (spec.stem_length + 1.0) / k,
                              [0.0, (y_print - 0.5) / k, bladder.port_axis_z], [0.0, 1.0, 0.0]), k)
    core_print = K.box([-c / 2, blo[1], z_axis - c / 2], [c / 2, y_print, z_axis + c / 2])
    core = K.union([void, stem, core_print])

    pins = _pins(K, bladder, k, blo) if (parting == "x" and holes is not None) else []

    # the halves are cut by the raw channels (they overlap the part: no shared surface); the
    # channels as voids of the closed mold stop at the part's surface
    raw_channels = _channels(K, bladder, spec, parting, R, origin, blo, bhi)
    channels = {name: K.cut(c, [filled]) for name, c in raw_channels.items()}
    feed = K.union(list(channels.values())) if channels else None

    # keys on the first half (−n side), sockets in the second; bolts through both at the corners
    u_lo, u_hi = R.T @ blo, R.T @ bhi
    spots = _spots(R, u_lo, u_hi, side, lo, hi, [(-c / 2, blo[1], z_axis - c / 2),
                                                   (c / 2, y_print, z_axis + c / 2)])
    keys, sockets = _keys(K, spec, spots["keys"], R, origin)
    bolts = _bolts(K, spec, spots["bolts"], R, origin, blo, bhi)

    space = K.cut(block, [filled, stem, core_print] + list(raw_channels.values()) + pins + bolts)
    half_box = {"lo": K.box(blo - 1.0, np.where(n > 0, origin, bhi + 1.0)),
                "hi": K.box(np.where(n > 0, origin, blo - 1.0), bhi + 1.0)}
    first = K.union([K.intersect(space, half_box["lo"])] + keys)
    second = K.cut(K.intersect(space, half_box["hi"]), sockets)
    names = {"z": ("lower", "upper"), "x": ("left", "right")}[parting]
    pieces = [Piece(names[0], "half", first, tuple(-n), 1),
              Piece(names[1], "half", second, tuple(n), 1),
              Piece("core", "core", core, None, 2)]
    pieces += [Piece(f"pin-{i + 1}", "pin", s, (0.0, 0.0, -1.0), 0) for i, s in enumerate(pins)]
    gaps = [K.cut(K.intersect(s, half_box["hi"]), [kk]) for s, kk in zip(sockets, keys)]
    voids = K.union([feed] + bolts + gaps) if (feed is not None or bolts or gaps) else None
    return Mold(bladder, spec, kernel, parting, tuple(origin), tuple(pieces), part, void, block,
                voids, tuple(keys), channels)


def _pins(K, bladder: BladderSpec, k: float, blo) -> list:
    """The flange holes' pins of a mold parted in x: a shaft through each hole (built at nominal
    size and scaled, like the holes) with a head below the block."""
    f = bladder.flange
    pins = []
    z0 = blo[2] - 3.0
    for x, y in flange_hole_centres(bladder):
        shaft = K.scale(K.cylinder(f.hole_diameter / 2, (1.0 - z0) / k, [x, y, z0 / k],
                                   [0.0, 0.0, 1.0]), k)
        head = K.cylinder(f.hole_diameter / 2 * k + 2.0, 3.0 - 1e-3, [x * k, y * k, z0],
                          [0.0, 0.0, 1.0])
        pins.append(K.union([shaft, head]))
    return pins


def _keys(K, spec: MoldSpec, spots, R, origin) -> tuple[list, list]:
    """Drafted keys on the first half and their sockets (with the clearance) in the second, at
    the ``spots`` (u, v) of the parting plane. Each cone starts 0.5 mm inside the first half,
    so key and half share no face."""
    n = R[:, 2]
    tan = math.tan(math.radians(spec.key_draft_deg))
    r_top = spec.key_radius - spec.key_height * tan
    r_base, h = spec.key_radius + 0.5 * tan, spec.key_height + 0.5
    keys, sockets = [], []
    for u, v in spots:
        at = origin + R[:, 0] * u + R[:, 1] * v - n * 0.5
        keys.append(K.cylinder(r_base, h, at, n, r_top=r_top))
        sockets.append(K.cylinder(r_base + spec.clearance, h + spec.clearance, at, n,
                                  r_top=r_top + spec.clearance))
    return keys, sockets


def _bolts(K, spec: MoldSpec, spots, R, origin, blo, bhi) -> list:
    """Bolt holes through both halves at the ``spots`` (u, v), 1 mm beyond the block."""
    n = R[:, 2]
    depth = float(n @ (bhi - blo))
    bolts = []
    for u, v in spots:
        at = origin + R[:, 0] * u + R[:, 1] * v
        at = at - n * (n @ (at - blo)) - n * 1.0
        bolts.append(K.cylinder(spec.bolt_diameter / 2, depth + 2.0, at, n))
    return bolts


def _spots(R, u_lo, u_hi, side, lo, hi, print_box) -> dict:
    """Key and bolt positions (u, v) in the parting plane: bolts in the four corners, keys on
    the edges' midpoints clear of the part and the core print (three of them, so the halves go
    together one way only)."""
    lo2, hi2 = np.sort(np.vstack([R.T @ lo, R.T @ hi])[:, :2], axis=0)
    p2 = np.sort(np.vstack([R.T @ np.asarray(print_box[0]), R.T @ np.asarray(print_box[1])])
                 [:, :2], axis=0)
    a = side / 2
    (u0, v0), (u1, v1) = u_lo[:2], u_hi[:2]
    um, vm = (lo2[0] + hi2[0]) / 2, (lo2[1] + hi2[1]) / 2
    bolts = [(u0 + a, v0 + a), (u1 - a, v0 + a), (u0 + a, v1 - a), (u1 - a, v1 - a)]
    keys = []
    for u, v in [(u0 + a, vm), (u1 - a, vm), (um, v1 - a), (um, v0 + a)]:
        if all(_clear((u, v), box, a - 1.0) for box in (np.vstack([lo2, hi2]), p2)):
            keys.append((u, v))
    return {"bolts": bolts, "keys": keys[:3]}


def _clear(pt, box, r) -> bool:
    d = np.maximum(np.maximum(box[0] - pt, np.asarray(pt) - box[1]), 0.0)
    return float(np.hypot(*d)) >= r


def _channels(K, bladder, spec, parting, R, origin, blo, bhi) -> dict:
    """The feed system (casting) or the flash groove (compression), reaching into the part."""
    g, f, p = bladder.geometry, bladder.flange, bladder.port
    k = spec.scale
    up = [0.0, 0.0, 1.0]
    top = bhi[2]
    out = {}
    if spec.process == "casting":
        y_s = (g.l / 2 + widest_outer_radius(g) + f.width / 2) * k
        r_top, r_bottom = spec.sprue_radius
        out["sprue"] = K.cylinder(r_bottom, top + 0.3 + 1.0, [0.0, y_s, -0.3], up, r_top=r_top)
        z_apex = (g.h + g.t0) * k
        riser = [K.cylinder(spec.vent_radius, top - z_apex + 0.3 + 1.0,
                            [0.0, 0.0, z_apex - 0.3], up),
                 K.cylinder(spec.vent_radius, 4.0 + 1.0, [0.0, 0.0, top - 4.0], up,
                            r_top=3.0)]
        out["riser"] = K.union(riser)
        if p.barbs:
            pitch = p.length / (p.barbs + 0.5)
            y_edge = -(g.l / 2 + widest_outer_radius(g) + f.width)
            vents = []
            for i in range(p.barbs):
                y_b = (y_edge - (i + 0.5) * pitch) * k
                # a square vent over the barb's crest, just off its step, from inside the port's
                # wall above the bore: flat sides cut the barb's cone facets cleanly (the halves
                # are cut by it whole)
                z_a = (bladder.port_axis_z + p.tube_id / 2) * k - 0.2
                a = spec.vent_radius
                vents.append(K.box([-a, y_b - 2 * a - 0.1, z_a], [a, y_b - 0.1, top + 1.0]))
            out["vents"] = K.union(vents)
    else:
        outline = _outline(bladder, spec, parting, origin)
        rings = [_offset(outline, spec.groove_land + spec.groove_width),
                 _offset(outline, spec.groove_land)]
        groove = K.cut(K.prism(rings[0], spec.groove_depth, R, origin),
                       [K.prism(rings[1], spec.groove_depth + 1.0, R, origin)])
        c = spec.core_print
        corridor = K.box([-c / 2 - 1.0, blo[1] - 1.0, bladder.port_axis_z * k - c / 2 - 1.0],
                         [c / 2 + 1.0, bladder_bbox(bladder)[0][1] * k + 1.0,
                          bladder.port_axis_z * k + c / 2 + 1.0])
        out["flash_groove"] = K.cut(groove, [corridor])
    return out


def _outline(bladder, spec, parting, origin) -> np.ndarray:
    """The part's outer outline in the parting plane ((u, v), mm): the largest polygon of the
    section of the scaled part (its holes and cavity are inside it)."""
    solid = bladder_solids(bladder).body.scale([spec.scale] * 3)
    if parting == "x":
        solid = solid.transform(np.hstack([frame("x").T, np.zeros((3, 1))]).tolist())
        section = solid.slice(0.0)
    else:
        section = solid.slice(float(origin[2]))
    polys = [np.asarray(q, float) for q in section.to_polygons()]
    return max(polys, key=lambda q: abs(_area(q)))


def _area(q) -> float:
    x, y = q[:, 0], q[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def _offset(poly: np.ndarray, d: float) -> np.ndarray:
    """``poly`` grown by ``d`` (mm) with round corners, simplified to 0.01 mm."""
    cs = m3.CrossSection([poly.tolist()]).offset(d, m3.JoinType.Round, 2.0, 64).simplify(0.01)
    return max((np.asarray(q, float) for q in cs.to_polygons()), key=lambda q: abs(_area(q)))
