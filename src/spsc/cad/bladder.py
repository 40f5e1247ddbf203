"""The printable bladder: chamber wall + floor/clamping flange + barbed inlet port.

Layout (part coordinates, docs/design.md): the wall rises from the base plane z = 0; a stadium-shaped
plate below it (z ∈ [−floor, 0]) closes the cavity and extends outward as the clamping flange with
screw holes. The inlet port is a barbed nipple lying horizontally along −y with its barbs resting
on the build plane, so the part prints standing on its base (print plane i–k, Table 2 note 3)
without supports; its bore runs through the plate and rises into the cavity at the centre of the
−y end cap.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cadquery as cq
import numpy as np

from .chamber import PROFILE_POINTS, cavity_solid, outer_solid
from .specs import BladderSpec, FlangeSpec, PortSpec
from .geometry import SPSCGeometry

__all__ = ["PortSpec", "FlangeSpec", "BladderSpec", "Bladder", "build_bladder", "nipple",
           "widest_outer_radius", "flange_hole_centres", "bladder_breps",
           "bladder_design"]


@dataclass(frozen=True)
class Bladder:
    """A built bladder: the B-rep solid and the design facts the printability gate checks."""

    spec: BladderSpec
    solid: cq.Solid
    design: dict


def widest_outer_radius(g: SPSCGeometry) -> float:
    """Largest half-width of the outer wall (mm): where the flange starts, for both the B-rep
    (here) and the export mesh (:mod:`spsc.cad.meshbuild`)."""
    return float(g.outer_profile_points(PROFILE_POINTS)[:, 0].max())


def _stadium(radius: float, l: float, z0: float, height: float) -> cq.Solid:
    wp = cq.Workplane("XY").workplane(offset=z0)
    wp = wp.slot2D(l + 2 * radius, 2 * radius, angle=90) if l > 0 else wp.circle(radius)
    return wp.extrude(height).val()


def flange_hole_centres(spec: BladderSpec) -> list[tuple[float, float]]:
    """(x, y) centres (mm) of the flange's M3 holes: on the stadium midway across the flange
    (half a flange width beyond :func:`widest_outer_radius`), 2 on the x axis or 4 at 45°.
    Shared by the B-rep and the export mesh so both drill the same holes."""
    r_mid = widest_outer_radius(spec.geometry) + spec.flange.width / 2
    n, l = spec.flange.holes, spec.geometry.l
    angles = {0: [], 2: [0.0, 180.0], 4: [45.0, 135.0, 225.0, 315.0]}[n]
    out = []
    for a in np.radians(angles):
        s = math.sin(a)
        out.append((r_mid * math.cos(a), r_mid * s + math.copysign(l / 2, s) if abs(s) > 1e-9
                    else r_mid * s))
    return out


def nipple(p: PortSpec, y_start: float, z: float) -> cq.Solid:
    """Shaft + saw-tooth barbs along −y from the face at ``y_start``, axis at height ``z``; the
    sharp step of each barb faces the part so a pushed-on tube is held."""
    d = cq.Vector(0, -1, 0)
    shaft = cq.Solid.makeCylinder(p.tube_id / 2, p.length + 1.0,
                                  cq.Vector(0, y_start + 1.0, z), d)
    if p.barbs == 0:
        return shaft
    pitch = p.length / (p.barbs + 0.5)
    parts = []
    for k in range(p.barbs):
        a = y_start - (k + 0.5) * pitch
        parts.append(cq.Solid.makeCone(p.barb_diameter / 2, p.tube_id / 2, pitch * 0.9,
                                       cq.Vector(0, a, z), d))
    return shaft.fuse(*parts).clean()


def bladder_breps(spec: BladderSpec) -> dict[str, cq.Solid | None]:
    """The B-rep pieces the bladder is cut from (mm, part coordinates): ``body`` (wall envelope,
    plate and port), ``cavity``, ``bore`` (horizontal bore and riser), ``holes`` (None without
    flange holes); the same construction as :func:`spsc.cad.meshbuild.bladder_solids`."""
    g, f, p = spec.geometry, spec.flange, spec.port
    r_flange = widest_outer_radius(g) + f.width
    plate = _stadium(r_flange, g.l, -f.thickness, f.thickness)
    y_edge = -(g.l / 2 + r_flange)
    body = outer_solid(g).fuse(plate, nipple(p, y_edge, spec.port_axis_z)).clean()
    z_axis = spec.port_axis_z
    y_riser = -g.l / 2  # centre of the −y end cap: inside the cavity footprint for any type
    y_tip = y_edge - p.length
    # the horizontal bore ends on the riser's axis, so capping the riser closes the cavity
    bore_h = cq.Solid.makeCylinder(p.bore / 2, y_riser - y_tip + 0.5,
                                   cq.Vector(0, y_tip - 0.5, z_axis), cq.Vector(0, 1, 0))
    bore_v = cq.Solid.makeCylinder(p.bore / 2, -z_axis + 0.5, cq.Vector(0, y_riser, z_axis),
                                   cq.Vector(0, 0, 1))
    holes = [cq.Solid.makeCylinder(f.hole_diameter / 2, f.thickness + 2.0,
                                   cq.Vector(x, y, -f.thickness - 1.0))
             for x, y in flange_hole_centres(spec)]
    return {"body": body, "cavity": cavity_solid(g), "bore": bore_h.fuse(bore_v).clean(),
            "holes": holes[0].fuse(*holes[1:]).clean() if holes else None}


def build_bladder(spec: BladderSpec) -> Bladder:
    """Build the printable bladder solid and its design facts (for ``spsc check``)."""
    g = spec.geometry
    b = bladder_breps(spec)
    cutters = [b["cavity"], b["bore"]] + ([b["holes"]] if b["holes"] is not None else [])
    solid = b["body"].cut(*cutters).clean()
    if not solid.isValid():
        raise RuntimeError(f"OCCT produced an invalid bladder solid for {g}")
    return Bladder(spec, solid, bladder_design(spec))


def bladder_design(spec: BladderSpec) -> dict:
    """The design facts of the bladder ``spec`` (what ``spsc check`` and ``spsc fem --part``
    read beside its STL)."""
    g, f, p = spec.geometry, spec.flange, spec.port
    r_flange = widest_outer_radius(g) + f.width
    y_edge = -(g.l / 2 + r_flange)
    z_axis = spec.port_axis_z
    y_riser = -g.l / 2
    y_tip = y_edge - p.length
    return {
        "kind": "bladder",
        "geometry": g.as_dict(),
        "cavity_volume_mm3": g.cavity_volume(),
        "volume_rtol": 0.002,
        "cavities": 1,
        "genus": f.holes,
        "min_wall_design_mm": g.t0,
        "port": {"axis_point": [0.0, y_riser, 0.0], "axis_dir": [0.0, 0.0, 1.0],
                 "radius": p.bore / 2 + 0.02, "z_range": [z_axis - p.bore / 2 - 0.05, 0.0]},
        # the wall's root meets the floor, flange and bore (feature edges): judge the wall from
        # one thickness above the base plane
        "wall_region": {"z_min": g.t0},
        "exclude": [{"center": [0.0, y_riser, 0.0], "radius": p.bore / 2 + 0.5}],
        "bbox_mm": [[-r_flange, y_tip, -f.thickness], [r_flange, g.l / 2 + r_flange, g.h + g.t0]],
        "print": {"build_direction": [0.0, 0.0, 1.0], "plane": "i-k (x-y), base down"},
        # spsc fem --part: the wall is clamped on its base plane (docs/design.md), floor and flange
        # below it held by the mount; a plate first touches the outer apex
        "fem": {"mount": "z<=0",
                "sites": {"apex": {"at": [0.0, 0.0, g.h + g.t0], "normal": [0.0, 0.0, -1.0]}}},
    }
