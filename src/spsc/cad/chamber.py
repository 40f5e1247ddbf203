"""Exact B-rep bodies of a chamber: the cavity, the outer envelope and the wall between them.

A body is the region under a profile curve above z = 0, revolved for the two ends and extruded
along y for the middle (sec. 2.2: "extruding the profile along k for a length l … revolute
extrusions on both sides"). The wall is outer − cavity, built from two bodies and a boolean cut:
OCCT's ``shell()`` is known to fail or give invalid solids on these profiles.
"""

from __future__ import annotations

import cadquery as cq
import numpy as np

from .geometry import SPSCGeometry

__all__ = ["profile_body", "cavity_solid", "outer_solid", "wall_solid"]

#: Spline points per profile: the B-rep volume then matches the analytic one to ~1e-5.
PROFILE_POINTS = 121


def _section_wire(pts: np.ndarray, mirrored: bool, straight_tail: bool) -> cq.Workplane:
    """Closed section in the x–z plane: base line, the profile as a spline, back to the start.

    ``pts`` runs from the apex (0, z_top) to the base (x_b, 0). ``mirrored`` closes over the full
    width (−x_b … x_b) for the extrusion, otherwise over the half x >= 0 for the revolution.
    ``straight_tail``: the last segment of ``pts`` is a straight prolongation to z = 0 (Type C).
    """
    base = tuple(pts[-1])
    curve = [tuple(p) for p in (pts[:-1] if straight_tail else pts)][::-1]  # up to the apex
    if mirrored:
        curve += [(-x, z) for x, z in curve[-2::-1]]  # over the apex and down the other side
    wp = cq.Workplane("XZ").moveTo(-base[0] if mirrored else 0.0, 0.0).lineTo(*base)
    if straight_tail:
        wp = wp.lineTo(*curve[0])
    for a, b in _smooth_runs(np.asarray(curve)):
        wp = wp.spline(curve[a + 1:b + 1], includeCurrent=True)
    if mirrored and straight_tail:
        wp = wp.lineTo(-base[0], 0.0)
    return wp.close()


def _smooth_runs(pts: np.ndarray, corner_deg: float = 15.0) -> list[tuple[int, int]]:
    """Index ranges [a, b] of ``pts`` between corners (where consecutive segments turn by more
    than ``corner_deg``): one spline per run, since an interpolating spline rings through a
    corner (n2 = 1 with c_y > 0 has one at the widest point: 0.7 % volume error)."""
    d = np.diff(pts, axis=0)
    ang = np.arctan2(d[:, 1], d[:, 0])
    turn = np.abs((np.diff(ang) + np.pi) % (2 * np.pi) - np.pi)
    cuts = [0] + [int(i) + 1 for i in np.nonzero(turn > np.radians(corner_deg))[0]] + [len(pts) - 1]
    return [(a, b) for a, b in zip(cuts[:-1], cuts[1:]) if b > a]


def profile_body(pts: np.ndarray, l: float, *, straight_tail: bool = False) -> cq.Solid:
    """The solid under the profile ``pts`` (x, z; apex first, base last): two revolved half
    ends at y = ±l/2 and, for l > 0, the extruded middle, fused into one solid."""
    section = _section_wire(pts, False, straight_tail)
    if l <= 0:
        return section.revolve(360, (0, 0, 0), (0, 1, 0)).val()
    half = section.revolve(180, (0, 0, 0), (0, 1, 0)).val()
    other = half.mirror("XZ")
    mid = _section_wire(pts, True, straight_tail).extrude(l / 2, both=True).val()
    return half.translate(cq.Vector(0, l / 2, 0)).fuse(
        mid, other.translate(cq.Vector(0, -l / 2, 0))).clean()


def cavity_solid(g: SPSCGeometry) -> cq.Solid:
    """The cavity bounded by the nominal profile and z = 0 (its volume is ``g.cavity_volume()``)."""
    pts, _ = g.profile_points(PROFILE_POINTS)
    return profile_body(pts, g.l)


def outer_solid(g: SPSCGeometry) -> cq.Solid:
    """The outer envelope: the profile offset by t0, cut or prolonged to z = 0."""
    pts = g.outer_profile_points(PROFILE_POINTS)
    # Type C: the offset ends above z = 0 and outer_profile_points appended a straight tail.
    straight_tail = g.t0 * float(g.outward_normal(g.w, 0.0)[1]) > 1e-9
    return profile_body(pts, g.l, straight_tail=straight_tail)


def wall_solid(g: SPSCGeometry) -> cq.Solid:
    """The chamber wall above the base plane: outer envelope minus cavity (the mechanical model
    of docs/design.md, clamped on z = 0)."""
    return outer_solid(g).cut(cavity_solid(g)).clean()
