"""Manufacturing processes and the limits the printability gate applies (cad/check.py).

Lengths in mm, angles in degrees. ``max_overhang_deg`` is the largest angle from the vertical a
downward-facing surface may make without support, for the part standing on its base (build
direction +z, print plane i–k of the paper = x–y here, Table 2 note 3). The rule that applies
these limits, and why the overhang of the chamber's outer wall gates while other overhangs are
only reported, is :mod:`spsc.cad.printability` (one rule for the gate, sweeps, the design
search and the report).
"""

from __future__ import annotations

from dataclasses import dataclass

from spsc.core.errors import ParameterError

__all__ = ["Process", "PROCESSES", "process", "WALL_TOL_MM", "MESH_THINNING_MM"]

#: Tessellation allowance on the wall (mm): a 0.8 mm wall exported with a 0.005 mm chord
#: tolerance measures ~0.795 mm; 0.01 mm is far below what FDM resolves (0.1–0.2 mm layers).
WALL_TOL_MM = 0.01
#: How much thinner the export mesh's wall can measure than the design's profile polylines (mm):
#: the circles' chord sag (``meshbuild.SAG_MM``, 0.004 mm) plus what the gate's sampling of the
#: cavity misses (< 0.001 mm; the slow agreement test in tests/test_printability.py). Where the
#: rule judges the design's wall, the gate's mesh wall gets this on top of ``WALL_TOL_MM``, so
#: a design the rule passes is never failed by its own mesh.
MESH_THINNING_MM = 0.005


@dataclass(frozen=True)
class Process:
    """A manufacturing process: its minimum wall (mm) and unsupported overhang limit (deg)."""

    name: str
    min_wall_mm: float
    max_overhang_deg: float
    notes: str


#: The catalogue. Only the FDM wall is from the paper; the rest are stated assumptions.
PROCESSES: dict[str, Process] = {
    p.name: p
    for p in (
        Process("fdm", 0.8, 45.0,
                "FDM (TPU): minimum wall 0.8 mm from the paper, sec. 2.2 (thinner bladders are "
                "impractical and not air-tight); 45 deg overhang is the usual FDM rule of thumb"),
        Process("sla", 0.5, 60.0,
                "SLA/DLP elastomer resin: 0.5 mm wall and 60 deg from vertical (30 deg from the "
                "plate) are assumptions from vendor design guidelines, not from the paper"),
        Process("molding", 1.0, 90.0,
                "cast silicone in a printed mould: 1.0 mm wall is an assumption (thin walls tear "
                "on demoulding); no layer-wise build, so no overhang limit"),
    )
}


def process(name: str) -> Process:
    """The :class:`Process` called ``name`` (case-insensitive); ParameterError if unknown."""
    key = str(name).strip().lower()
    if key not in PROCESSES:
        raise ParameterError("process", name, "one of " + ", ".join(PROCESSES))
    return PROCESSES[key]
