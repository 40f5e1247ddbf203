"""The printability rule: one verdict, from the design facts, for the gate, sweeps, the design
search and the report (issues 13, 30).

``printability(geometry, "fdm")`` judges a chamber in milliseconds, without building the solid.
It is the only place a chamber's printability is decided: the gate (:mod:`spsc.cad.check`)
runs it on the design's geometry (its ``printability`` check) beside its mesh checks of the
construction, ``spsc sweep`` writes it in the ``printable`` column, ``spsc design`` makes it the
constraint, and the report counts and draws that column. Each check computes, from the meridian
(eqs. 10–16), the quantity the gate can also measure on the exported mesh, against the limits
of :mod:`spsc.cad.process`:

wall       gates. The closest distance from the cavity surface above z = t0 to the outer
           surface. Bodies of revolution and extrusion have their nearest points in the
           meridian plane, so it is the distance between the two profile polylines the export
           mesh is built from (:meth:`SPSCGeometry.wall_profiles` at ``MESH_PROFILE_POINTS``),
           exact for polylines: t0 (less a chord's sagitta) on a smooth profile and round a
           profile corner (n2 = 1 with c_y > 0, whose offset is an arc of t0). Passes at
           >= the process minimum less ``WALL_TOL_MM``. The mesh's circles add at most
           ``meshbuild.SAG_MM`` (0.004 mm) of thinning, which the gate's own ``min_wall`` sees
           and allows for (``MESH_THINNING_MM``): a design this rule passes, its mesh passes.
overhang   gates, for every process. The steepest downward-facing outer wall of the chamber, in
           degrees from the vertical, for the part standing on its base (build +z, the paper's
           print plane, Table 2 note 3), against ``max_overhang_deg``. Only the bulge below the
           widest section of a c_y > 0 chamber faces down; it is steepest where the outer wall
           meets the base plane: the point of the offset curve at z = 0, whose normal is the
           profile's normal there (analytic, one root find). The mesh's facets are chords: the
           steepest lies within one profile segment's turn (~1°) of this angle.
ceiling    reported only: the cavity's ceiling faces down up to the apex (90° for n1 > 1), a
           bridge closing a closed bladder, which no support can reach.

Why the outer overhang gates, per process. FDM (TPU 60A) and SLA (Elastic 50A, Silicone 40A)
print the bladder as one closed part, base down, without support, as the paper's were. Inside,
a support could never be removed from the sealed cavity; outside, under the bulge, it would
stand in the notch between the wall and the flange and be fused to the air-tight skin of a
0.5–2 mm wall that holds 40 kPa, and tearing it off scars that skin (the paper's FDM bladders
already leaked < 1 kPa and needed a latex sealant, sec. 3.2). A layer-wise wall leaning out
beyond the limit sags and opens gaps between layers: a leak. So beyond the limit the chamber
is not printable as designed, for the gate as for a sweep. The paper's printed Types stay
within it: Types A–C have no downward outer wall, Type D (c_y = 0.6) leans 43.1° (under FDM's
45°, SLA's 60°). Molding casts the part in a mould: it has no build direction and its limit is
90°, so the check never fails (the mould's pieces have their own gate, spsc.cad.mold.gate, with
pull directions and undercuts). The ceiling and the port's short horizontal cylinders (the
nipple lying on its barbs, the bore's roof) are short bridges every bladder has and the paper
printed: the gate reports their area (its ``overhang`` check) and gates none of them. So does
it for a mould piece (an open part, supported and cleaned where needed) and for a mesh without a
design geometry (``spsc check`` on any STL, the fingertip): no chamber to judge, only the
report.

With ``port`` or ``flange`` (the other then takes its default), the mounting hardware's thin
walls are judged against the process minimum as well, which the gate does not (it judges the
chamber wall only, docs/design.md): the nipple's wall (:attr:`PortSpec.wall`), the roof of the
bore under the flange top (:attr:`BladderSpec.bore_roof`) and the flange around its screw holes
(:attr:`FlangeSpec.ligament`).

What the gate checks about the construction (watertight, one part, genus, cavity volume, box)
is the CAD's business, not the design's: the property test of the gate covers it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq
from scipy.spatial import cKDTree

from spsc.core.errors import ParameterError

from .geometry import MESH_PROFILE_POINTS, SPSCGeometry
from .process import WALL_TOL_MM, Process, process as get_process
from .specs import BladderSpec, FlangeSpec, PortSpec

__all__ = ["GATES", "Verdict", "printability"]


@dataclass(frozen=True)
class Verdict:
    """A printability verdict: ``ok`` (also ``printable``), one sentence per failed check
    (``reasons``), one line naming every check with its value and limit (``summary``), the
    process, the measured values: ``wall_mm`` (None without a wall region), ``wall_at_mm``
    (x, z of the thinnest point on the cavity profile), ``overhang_deg``, ``ceiling_deg`` and,
    with a port or flange, ``port_wall_mm``, ``bore_roof_mm``, ``flange_ligament_mm`` (None
    without holes); and the ``limits`` applied: ``min_wall_mm``, ``wall_tolerance_mm``,
    ``max_overhang_deg`` and ``gates`` (which checks gate; the rest are reported)."""

    ok: bool
    reasons: tuple[str, ...]
    summary: str
    process: str = ""
    measures: dict = field(default_factory=dict, hash=False)
    limits: dict = field(default_factory=dict, hash=False)

    @property
    def printable(self) -> bool:
        return self.ok


#: The checks of the rule that gate (module docstring); ``ceiling`` is reported only.
GATES = ("wall", "overhang", "port wall", "bore roof", "flange ligament")


def printability(geometry: SPSCGeometry, process: str | Process = "fdm", *,
                 flange: FlangeSpec | None = None, port: PortSpec | None = None) -> Verdict:
    """The printability verdict of a chamber for ``process`` (``fdm``, ``sla``, ``molding`` or
    a :class:`Process`), from its parameters alone (mm, degrees); see the module docstring.

    ``port``, ``flange``: judge the bladder's mounting hardware too; the port's exclusion zone
    of the gate's wall region (around the bore's mouth) is the default port's when not given.
    ParameterError for an unknown process or a port that does not fit the flange.
    """
    if not isinstance(geometry, SPSCGeometry):
        raise ParameterError("geometry", type(geometry).__name__, "an SPSCGeometry")
    proc = process if isinstance(process, Process) else get_process(process)
    hardware = flange is not None or port is not None
    spec = BladderSpec(geometry, flange or FlangeSpec(), port or PortSpec()) if hardware else None
    lim_w, lim_a, name = proc.min_wall_mm, proc.max_overhang_deg, proc.name
    lines, reasons = [], []

    def judge(ok: bool, line: str, reason: str) -> None:
        lines.append(line)
        if not ok:
            reasons.append(reason)

    wall, where = _wall(geometry, (port or PortSpec()).bore)
    if wall is None:
        judge(False, f"wall: {where}", f"no chamber wall to judge: {where}")
    else:
        ok = wall >= lim_w - WALL_TOL_MM
        judge(ok, f"wall {wall:.3f} {'≥' if ok else '<'} {lim_w:g} mm",
              f"wall {wall:.3f} mm at (x {where[0]:.2f}, z {where[1]:.2f}) mm < {name} minimum "
              f"{lim_w:g} mm")
    angle = _outer_overhang(geometry)
    ok = not angle > lim_a
    judge(ok, f"overhang {_deg(angle, lim_a)} {'≤' if ok else '>'} {lim_a:g}°",
          f"overhang {_deg(angle, lim_a)}° > {name} limit {lim_a:g}° (outer wall of the bulge "
          f"below the widest section, where it meets the base plane)")
    ceiling = _ceiling(geometry)
    lines.append(f"cavity ceiling {ceiling:.1f}° (a bridge, reported only)")
    measures = {"wall_mm": wall, "wall_at_mm": None if wall is None else where,
                "overhang_deg": angle, "ceiling_deg": ceiling}
    if spec is not None:
        lig = spec.flange.ligament if spec.flange.holes else None
        for key, label, value in (("port_wall_mm", "port wall", spec.port.wall),
                                  ("bore_roof_mm", "bore roof", spec.bore_roof),
                                  ("flange_ligament_mm", "flange ligament", lig)):
            measures[key] = value
            if value is None:
                continue
            ok = value >= lim_w - WALL_TOL_MM
            judge(ok, f"{label} {value:.3f} {'≥' if ok else '<'} {lim_w:g} mm",
                  f"{label} {value:.3f} mm < {name} minimum {lim_w:g} mm")
    summary = f"{name}: " + ", ".join(lines)
    limits = {"min_wall_mm": lim_w, "wall_tolerance_mm": WALL_TOL_MM, "max_overhang_deg": lim_a,
              "gates": list(GATES)}
    return Verdict(not reasons, tuple(reasons), summary, name, measures, limits)


def _deg(angle: float, limit: float) -> str:
    """An angle to 0.1°, or finer when that would print the limit itself."""
    for digits in (1, 2, 3, 4):
        if round(angle, digits) != limit:
            break
    return f"{angle:.{digits}f}"


def _wall(g: SPSCGeometry, bore: float):
    """(thinnest wall in mm, its (x, z) on the cavity profile) over the gate's wall region, or
    (None, why) when the gate would find no cavity point to judge."""
    inner, outer = g.wall_profiles(MESH_PROFILE_POINTS)
    z_min = g.t0  # the bladder's design "wall_region" (spsc.cad.bladder)
    if inner[0, 1] < z_min:
        return None, (f"the cavity (h = {g.h:g} mm) lies below the gate's wall region, "
                      f"z >= t0 = {g.t0:g} mm")
    k = int(np.count_nonzero(inner[:, 1] >= z_min))  # z falls monotonically from the apex
    cav = inner[:k]
    if k < len(inner) and inner[k - 1, 1] > z_min:
        a, b = inner[k - 1], inner[k]
        cav = np.vstack([cav, a + (b - a) * (a[1] - z_min) / (a[1] - b[1])])
    # the gate leaves out the cavity within a ball around the bore's mouth at (0, -l/2, 0); the
    # cavity point farthest from it is on the far end cap, at distance hypot(l + x, z)
    radius = bore / 2 + 0.5
    if np.hypot(g.l + cav[:, 0], cav[:, 1]).max() <= radius:
        return None, (f"every cavity point above z = t0 lies within {radius:g} mm of the bore's "
                      "mouth, which the gate leaves out")
    # polyline to polyline, exact: the nearest pair has a vertex of one or the other; the far
    # half of the outer meridian (the same surface in 3D) only for points nearer the axis
    d, _ = _point_polyline(cav, outer)
    d2, at2 = _point_polyline(outer, cav)
    best = min(d.min(), d2.min())
    # the far half only matters for points within ``best`` of the axis, and only its segments
    # with an end within ``best`` of it (it lies at x <= 0): those, every one, exactly
    mirror = outer * [-1.0, 1.0]
    near_axis = cav[:, 0] < best
    if near_axis.any():
        d3, _ = _point_segments_near_axis(cav[near_axis], mirror, best)
        d[near_axis] = np.minimum(d[near_axis], d3)
    near_axis = outer[:, 0] < best
    if near_axis.any():
        d4, at4 = _point_segments_near_axis(mirror[near_axis], cav, best)
        closer = d4 < d2[near_axis]
        d2[np.flatnonzero(near_axis)[closer]] = d4[closer]
        at2[np.flatnonzero(near_axis)[closer]] = at4[closer]
    if d.min() <= d2.min():
        return float(d.min()), tuple(map(float, cav[np.argmin(d)]))
    j = int(np.argmin(d2))
    return float(d2[j]), (float(at2[j].real), float(at2[j].imag))


def _point_polyline(p: np.ndarray, line: np.ndarray, k: int = 10):
    """Distance of each point ``p`` (x, z) to the polyline ``line`` and the nearest point on it
    (complex x + iz), exact: measured to the segments next to the ``k`` nearest vertices, and to
    every segment long enough to be nearer than that from beyond the k-th nearest vertex (its
    ends lie farther, so it is at least that far less half its length)."""
    k = min(k, len(line))
    dv, iv = cKDTree(line).query(p, k=k)
    dv, iv = dv.reshape(len(p), k), iv.reshape(len(p), k)
    P, L = p[:, 0] + 1j * p[:, 1], line[:, 0] + 1j * line[:, 1]
    d, near = _point_segments(P, L, np.clip(np.concatenate([iv - 1, iv], axis=1), 0, len(L) - 2))
    if k < len(L):
        long = np.flatnonzero(0.5 * np.abs(np.diff(L)) > (dv[:, -1] - d).min())
        if long.size:
            d2, near2 = _point_segments(P, L, np.broadcast_to(long, (len(P), long.size)))
            closer = d2 < d
            d[closer], near[closer] = d2[closer], near2[closer]
    return d, near


def _point_segments_near_axis(p: np.ndarray, line: np.ndarray, reach: float):
    """:func:`_point_polyline` of points ``p`` near the axis (x < ``reach``) to the ``line``
    on the other side of it (x <= 0, or x >= 0 for the points on the far side), measured to
    every segment with an end within ``reach`` of the axis: a segment farther from the axis
    than ``reach`` is farther than that from the point, and cannot make the wall's minimum,
    which is at most ``reach``. Points with no such segment are at infinity."""
    L = line[:, 0] + 1j * line[:, 1]
    near = np.abs(line[:, 0]) < reach
    seg = np.flatnonzero(near[:-1] | near[1:])
    P = p[:, 0] + 1j * p[:, 1]
    if seg.size == 0:
        return np.full(len(p), np.inf), P.copy()
    return _point_segments(P, L, np.broadcast_to(seg, (len(P), seg.size)))


def _point_segments(P: np.ndarray, L: np.ndarray, seg: np.ndarray):
    """Nearest of the segments [L[s], L[s + 1]] (indices ``seg``, one row per point) to each
    point ``P`` (complex x + iz): distances and nearest points."""
    a = L[seg]
    ab = L[np.minimum(seg + 1, len(L) - 1)] - a
    ap = P[:, None] - a
    t = (ap * ab.conj()).real / np.maximum(ab.real ** 2 + ab.imag ** 2, 1e-300)
    r = ap - np.clip(t, 0.0, 1.0) * ab
    dist = np.abs(r)
    j = np.argmin(dist, axis=1)
    rows = np.arange(len(P))
    return dist[rows, j], P - r[rows, j]


def _outer_overhang(g: SPSCGeometry) -> float:
    """Steepest downward outer wall (deg from vertical): its normal where the offset of the
    lower branch (c_y > 0, u > π/2) meets z = 0; 0 when no outer face looks down."""
    if g.cy <= 0.0:
        return 0.0  # the upper branch's normals all look up or sideways

    def z_out(u: float) -> float:  # height of the offset point, falling with u
        x, z = g.profile(u)
        return float(z + g.t0 * g.outward_normal(x, z)[1])

    def down(u: float) -> float:
        x, z = g.profile(u)
        return -float(g.outward_normal(x, z)[1])

    u0, u1 = math.pi / 2 + 1e-9, math.pi - g.delta_u
    if z_out(u0) <= 0.0:
        # n2 = 1: a corner at the widest section; its offset is an arc of radius t0 around it,
        # which meets z = 0 where sin(angle) = z_widest / t0
        return math.degrees(math.asin(min(1.0, g.z_widest / g.t0)))
    if z_out(u1) >= 0.0:
        # a bulge so slight (c_y → 0) that the offset of its whole lower branch stays above
        # the base: the outer wall goes on along its end tangent, its normal that at the edge
        return math.degrees(math.asin(min(1.0, max(0.0, down(u1)))))
    u = brentq(z_out, u0, u1, xtol=1e-12)
    return math.degrees(math.asin(min(1.0, down(u))))


def _ceiling(g: SPSCGeometry) -> float:
    """Steepest downward face of the cavity (deg from vertical): at the apex, whose outward
    normal is vertical unless n1 = 1 (a cone's tip)."""
    nx, nz = g.outward_normal(0.0, g.h)
    return math.degrees(math.atan2(float(nz), abs(float(nx))))
