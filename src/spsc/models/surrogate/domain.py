"""Where the wall model's surrogate is trained and may be trusted: the dimensionless design
space, the pressure levels and travels of the maps it learns, and the exact similarities
that carry one trained chamber to every size and every neo-Hookean material.

Two similarities of the wall model are exact and are applied, not learnt:

* **size**: the wall model has no length of its own, so a chamber scaled by k (w, h, l, t0
  all × k) at the same pressure has forces × k², volumes × k³, areas × k², travels × k;
* **stiffness**: the law's constants and the bulk modulus (κ = bulk_ratio · μ0) scale
  together, so a neo-Hookean material of shear modulus μ at pressure P is the reference
  material (μ_ref) at P μ_ref/μ with forces × μ/μ_ref.

What is learnt is then a function of the six ratios h/w, l/w, t0/w, n1, n2, c_y (the hull of
Table 1's Types A–D, the design verb's default space) and of the dimensionless pressure
q = P w/(μ t0) — the membrane's own scale of pressure (eq. 29's tension over radius).

Units: mm, MPa inside; kPa at the edges.
"""

from __future__ import annotations

import numpy as np

__all__ = ["RATIOS", "BOUNDS", "W_REF_MM", "MU_REF_MPA", "Q_LEVELS", "Q_UNIFORM_16", "TRAVELS",
           "ratios_of", "pressure_unit_kPa"]

#: The six dimensionless inputs, in the order the surrogate reads them.
RATIOS = ("h/w", "l/w", "t0/w", "n1", "n2", "cy")
#: Their trained ranges: the hull of Table 1's four types (n1 2–3, n2 1–4, c_y 0–0.6) over the
#: design verb's default footprint (w 8–14, h 8–16, l 0–6 mm, t0 up to 2 mm).
BOUNDS = {"h/w": (0.55, 2.0), "l/w": (0.0, 0.8), "t0/w": (0.04, 0.2),
          "n1": (2.0, 3.0), "n2": (1.0, 4.0), "cy": (0.0, 0.6)}
#: The trained chamber's semi-width (mm) and the reference shear modulus μ_ref (MPa: the
#: catalogue's TPU 60A, E/3 with E = 5 MPa) every answer is scaled from.
W_REF_MM = 11.0
MU_REF_MPA = 5.0 / 3.0
#: The dimensionless pressure levels q = P w/(μ t0) of each learnt map: 0 is the vented
#: chamber. Sixteen evenly spaced (:data:`Q_UNIFORM_16`), and five more at low q where the maps
#: change fastest (a thin wall's bending gives way to its membrane tension there): the quarter,
#: half and three quarters of the first step and the middles of the next two. With six levels
#: (denser at low q, 0.1 … 0.82) the training designs' own maps, interpolated, missed the wall's
#: pressure rise by 2.2 % of its largest value (median; 9 % at the 95th percentile); the
#: sixteen even ones left 0.2–0.6 %, but on five check designs at q_i < 0.12 the exact maps
#: missed the low mode's pressure rise by 3.6–22 %, which the five low levels brought to
#: 0.15–1.4 % for three of them (12.7 % and 5.3 % for the others: a branch and the travels)
#: (design decisions, "The surrogate").
Q_UNIFORM_16 = np.linspace(0.0, 0.82, 16)
Q_LEVELS = np.unique(np.concatenate([Q_UNIFORM_16, (0.82 / 15) * np.array(
    [0.25, 0.5, 0.75, 1.5, 2.5])]))
#: Travels from each level's first contact, as fractions of the cavity height h: denser near
#: contact, where the force grows fastest.
TRAVELS = 0.55 * np.linspace(0.0, 1.0, 12) ** 1.3


def ratios_of(geometry) -> np.ndarray:
    """The six ratios (:data:`RATIOS`) of an :class:`~spsc.cad.geometry.SPSCGeometry`."""
    g = geometry
    return np.array([g.h / g.w, g.l / g.w, g.t0 / g.w, g.n1, g.n2, g.cy])


def pressure_unit_kPa(w_mm, t0_mm, mu_MPa) -> float:
    """The pressure of q = 1 (kPa): μ t0 / w."""
    return 1000.0 * mu_MPa * t0_mm / w_mm
