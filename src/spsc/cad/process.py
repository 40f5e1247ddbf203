"""Manufacturing processes and the limits the printability gate applies (cad/check.py).

Lengths in mm, angles in degrees. ``max_overhang_deg`` is the largest angle from the vertical a
downward-facing surface may make without support, for the part standing on its base (build
direction +z, print plane i–k of the paper = x–y here, Table 2 note 3).
"""

from __future__ import annotations

from dataclasses import dataclass

from spsc.core.errors import ParameterError

__all__ = ["Process", "PROCESSES", "process"]


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
