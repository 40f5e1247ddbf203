"""The mold gate (issue 15), as the printability gate is for parts: a mold passes when every piece
prints, the pieces do not overlap, the closed mold leaves exactly the part, the core fills exactly
the cavity, every piece comes off along its pull direction, and the walls and key gaps are kept.

Each check is a :class:`~spsc.cad.check.Check` (name, passed, measured value, limit, one-line
message). Volumes in mm³, lengths in mm. The mold is the mesh one (:func:`build_mold`,
``kernel="mesh"``): manifold3d's booleans are exact up to round-off, so the volume identities
hold to ~1e-9 on a good mold and any misplaced piece shows at once.
"""

from __future__ import annotations

import itertools
import json
from dataclasses import dataclass, field
from pathlib import Path

import manifold3d as m3
import numpy as np

from ..check import Check, check_mesh
from ..meshbuild import manifold_mesh
from .build import UNDERCUT_TOL_MM2, Mold, bladder_bbox, pull_length, pull_test

__all__ = ["MoldReport", "mold_gate", "VOLUME_RTOL", "OVERLAP_TOL_MM3"]

#: Volume identities (wall, core) within 0.5 % (the issue's bound).
VOLUME_RTOL = 0.005
#: Pieces overlap when they share more than this volume (mm³): boolean round-off is ~1e-9.
OVERLAP_TOL_MM3 = 1e-3
#: A piece collides later in its pull when it cuts more than this volume (mm³).
COLLISION_TOL_MM3 = 1e-3
#: Keys and bolt holes keep at least this much mold material from the part and the core (mm).
KEY_WALL_MM = 2.0
#: Printability checks that gate a mold piece (the rest of the part gate is about bladders; a
#: piece is an open part, supported where needed, so its overhang is not gated: the pull tests
#: and undercuts judge its shape; spsc.cad.printability says why per process).
PIECE_CHECKS = ("watertight", "manifold", "oriented", "self_intersections", "one_part")


@dataclass(frozen=True)
class MoldReport:
    """The gate's checks on one mold; ``passed`` if none failed."""

    checks: tuple
    facts: dict = field(default_factory=dict)
    passed: bool = field(init=False)
    failed: tuple = field(init=False)

    def __post_init__(self):
        failed = tuple(c.name for c in self.checks if c.passed is False)
        object.__setattr__(self, "failed", failed)
        object.__setattr__(self, "passed", not failed)

    def __getitem__(self, name: str) -> Check:
        return next(c for c in self.checks if c.name == name)

    def to_dict(self) -> dict:
        return {"passed": self.passed, "failed": list(self.failed), "facts": self.facts,
                "checks": [c.as_dict() for c in self.checks]}

    def to_json(self, path) -> None:
        Path(path).write_text(json.dumps(self.to_dict(), indent=1) + "\n", encoding="utf-8")

    def summary(self) -> str:
        lines = [c.message for c in self.checks]
        lines.append("MOLD PASSED" if self.passed else "MOLD FAILED: " + ", ".join(self.failed))
        return "\n".join(lines)


def mold_gate(mold: Mold, *, printability: bool = True) -> MoldReport:
    """Run every check of the mold gate on the mesh ``mold`` (see the module docstring);
    ``printability=False`` skips the per-piece mesh checks (the slow part, ~1 s per piece)."""
    if mold.kernel != "mesh":
        raise ValueError("the mold gate measures the mesh mold (build_mold(kernel='mesh'))")
    checks = []
    if printability:
        checks += [_printable(p) for p in mold.pieces]
    checks.append(_overlap(mold))
    checks += _identities(mold)
    checks += [_pull(mold, p) for p in mold.pieces if p.pull is not None]
    checks += [_mold_wall(mold), _key_clearance(mold), _key_wall(mold)]
    facts = {"parting": mold.parting, "undercut_mm2": mold.undercut,
             "scale": mold.spec.scale, "process": mold.spec.process}
    return MoldReport(tuple(checks), facts)


def _printable(p) -> Check:
    mesh = manifold_mesh(p.solid)
    rep = check_mesh((mesh.vertices, mesh.faces), design=None, process="fdm")
    bad = [n for n in PIECE_CHECKS if rep[n].passed is False]
    ok = not bad
    msg = (f"{p.name}: closed 2-manifold, one part, no self-intersections, "
           f"{len(mesh.faces)} triangles" if ok else f"{p.name}: " + "; ".join(
               rep[n].message for n in bad))
    return Check(f"print_{p.name}", ok, len(bad), 0, msg, {"failed": bad})


def _overlap(mold: Mold) -> Check:
    worst, pair = 0.0, None
    for a, b in itertools.combinations(mold.pieces, 2):
        v = float((a.solid ^ b.solid).volume())
        if v > worst:
            worst, pair = v, (a.name, b.name)
    ok = worst <= OVERLAP_TOL_MM3
    msg = (f"pieces do not overlap (largest shared volume {worst:.2g} mm³)" if ok else
           f"pieces {pair[0]} and {pair[1]} overlap by {worst:.3g} mm³ "
           f"(allowed {OVERLAP_TOL_MM3:g})")
    return Check("overlap", ok, worst, OVERLAP_TOL_MM3, msg, {"pair": pair})


def _identities(mold: Mold) -> list[Check]:
    pieces = m3.Manifold.batch_boolean([p.solid for p in mold.pieces], m3.OpType.Add)
    space = mold.block - pieces
    if mold.voids is not None:
        space = space - mold.voids
    v_part = float(mold.part.volume())
    v_space = float(space.volume())
    dv = (v_space - v_part) / v_part
    sym = float((space - mold.part).volume() + (mold.part - space).volume()) / v_part
    k3 = mold.spec.scale ** 3
    wall = Check("wall_volume", abs(dv) <= VOLUME_RTOL and sym <= VOLUME_RTOL, dv, VOLUME_RTOL,
                 f"the closed mold leaves {v_space / k3:.1f} mm³ at nominal size for the "
                 f"bladder's {v_part / k3:.1f} mm³ ({100 * dv:+.3f} %), symmetric difference "
                 f"{100 * sym:.3f} % (allowed {100 * VOLUME_RTOL:g} %)",
                 {"space_mm3": v_space, "part_mm3": v_part, "symmetric_difference": sym})
    g, p, b = mold.bladder.geometry, mold.bladder.port, mold.bladder
    core = mold.piece("core").solid
    inside = float((core ^ (mold.part + mold.void)).volume()) / k3
    # analytic: the cavity (eq. 16) and the two bore cylinders inside the part; the bores'
    # overlap at the riser (< 0.4 mm³, 0.01 %) is left out
    y_tip = float(bladder_bbox(b)[0][1])
    bore = np.pi * (p.bore / 2) ** 2 * ((-g.l / 2 - y_tip) - b.port_axis_z)
    expected = g.cavity_volume() + bore
    dc = (inside - expected) / expected
    core_check = Check("core_volume", abs(dc) <= VOLUME_RTOL, dc, VOLUME_RTOL,
                       f"core inside the part {inside:.1f} mm³ at nominal size, cavity + bore "
                       f"{expected:.1f} mm³ ({100 * dc:+.3f} %, allowed "
                       f"{100 * VOLUME_RTOL:g} %)",
                       {"core_in_part_mm3": inside, "cavity_and_bore_mm3": expected})
    return [wall, core_check]


def _pull(mold: Mold, piece) -> Check:
    later = [q.solid for q in mold.pieces if q.order > piece.order]
    obstacles = m3.Manifold.batch_boolean([mold.part] + later, m3.OpType.Add)
    r = pull_test(piece.solid, piece.pull, obstacles, pull_length(mold))
    ok = r["undercut_mm2"] <= UNDERCUT_TOL_MM2 and r["collision_mm3"] <= COLLISION_TOL_MM3
    d = np.round(np.asarray(piece.pull, float), 3) + 0.0
    msg = (f"{piece.name} pulls along ({d[0]:g}, {d[1]:g}, {d[2]:g}): undercut "
           f"{r['undercut_mm2']:.3g} mm² (allowed {UNDERCUT_TOL_MM2:g}), later collision "
           f"{r['collision_mm3']:.3g} mm³")
    return Check(f"pull_{piece.name}", ok, r["undercut_mm2"], UNDERCUT_TOL_MM2, msg, r)


def _mold_wall(mold: Mold) -> Check:
    """Least mold material between the part and the mold's outside (the block's faces)."""
    lo, hi = np.asarray(mold.block.bounding_box()).reshape(2, 3)
    outside = m3.Manifold.cube((hi - lo + 2.0).tolist()).translate((lo - 1.0).tolist()) \
        - mold.block
    limit = mold.spec.wall
    gap = float(mold.part.min_gap(outside, 2 * limit))
    ok = gap >= limit - 1e-6
    return Check("mold_wall", ok, gap, limit,
                 f"mold wall {gap:.2f} mm between the part and the outside "
                 f"({'>=' if ok else '<'} {limit:g} mm)")


def _key_clearance(mold: Mold) -> Check:
    c = mold.spec.clearance
    second = next(p for p in mold.pieces if p.role == "half" and p.order == 1
                  and np.dot(p.pull, _normal(mold)) > 0).solid
    gaps = [float(k.min_gap(second, 2 * c + 1.0)) for k in mold.keys]
    if not gaps:
        return Check("key_clearance", False, None, c, "no registration key found room")
    g = min(gaps)
    # a cone offset radially by c stands c·cos(draft) off its socket
    lo = c * np.cos(np.radians(mold.spec.key_draft_deg)) - 1e-3
    ok = lo <= g <= c + 1e-3
    return Check("key_clearance", ok, g, c,
                 f"{len(gaps)} keys, gap to their sockets {g:.3f} mm (design {c:g} mm, "
                 f"{lo:.3f}–{c:g} allowed)")


def _key_wall(mold: Mold) -> Check:
    core = mold.piece("core").solid
    keep = m3.Manifold.batch_boolean([mold.part, core], m3.OpType.Add)
    gaps = [float(k.min_gap(keep, 2 * KEY_WALL_MM)) for k in mold.keys]
    g = min(gaps) if gaps else 0.0
    ok = bool(gaps) and g >= KEY_WALL_MM
    return Check("key_wall", ok, g, KEY_WALL_MM,
                 f"keys stand {g:.2f} mm from the part and the core (>= {KEY_WALL_MM:g} mm)")


def _normal(mold: Mold) -> np.ndarray:
    return np.array([0.0, 0.0, 1.0]) if mold.parting == "z" else np.array([1.0, 0.0, 0.0])
