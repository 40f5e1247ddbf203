"""A pad's contact with a grasped object (issue 50), computed outside the host simulator's
solver and applied to its bodies as forces every step.

Normal: the pad (its chamber on its map) in series with the object's own local stiffness
``k_o`` (N/mm, the force per mm of the object's indentation at one pad): of the overlap ``s``
of the object's undeformed surface with the pad's face, the pad takes the travel ``y`` where
F_pad(y) = k_o (s − y). The pad's force is linearised about its last state (its force and its
stiffness with the gas following, :meth:`VirtualChambers.read`), so a step costs no solve:

    y = (k_o s + K y₀ − F₀) / (K + k_o),  clipped to [y_lo, s]

(a rigid object, k_o = ∞: y = s). A dashpot on the pad's travel rate settles the grasp (the
wall's viscosity is not in the virtual chamber's map).

Tangential: Coulomb friction with a stuck contact's shear stiffness (an elastoplastic
"bristle": the contact's tangential displacement grows with the relative sliding velocity,
its spring force is capped at μ F_n, and past the cap the anchor slides — a slip). Units: mm,
N, s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import require

__all__ = ["PadContact", "series_travel", "friction"]


@dataclass(frozen=True)
class PadContact:
    """The contact of a pad with an object: the object's local stiffness at one pad
    ``object_N_per_mm`` (N/mm; ``inf``: rigid), the Coulomb coefficient ``mu`` of pad on
    object, the stuck contact's shear stiffness ``shear_N_per_mm`` (N/mm; assumed: the pad's
    skin in shear is not modelled) and the dashpot ``damping_N_s_per_m`` on the pad's travel
    (N s/m)."""

    object_N_per_mm: float = math.inf
    mu: float = 0.8
    shear_N_per_mm: float = 5.0
    damping_N_s_per_m: float = 5.0

    def __post_init__(self):
        if not math.isinf(self.object_N_per_mm) or self.object_N_per_mm < 0:
            require("object stiffness_N_per_mm", self.object_N_per_mm, gt=0, le=1e6,
                    unit="N/mm; \"rigid\" for a rigid object")
        require("object friction", self.mu, ge=0, le=5)
        require("contact shear_N_per_mm", self.shear_N_per_mm, gt=0, le=1e4, unit="N/mm")
        require("contact damping_N_s_per_m", self.damping_N_s_per_m, ge=0, le=1e4,
                unit="N s/m")


def series_travel(s_mm, k_obj, y0_mm, f0_N, k_pad, y_lo_mm):
    """The pad's travel (mm) at the overlap ``s_mm`` with an object of stiffness ``k_obj``
    (N/mm) in series, the pad linearised about its last travel ``y0_mm``, force ``f0_N`` and
    stiffness ``k_pad`` (N/mm); no overlap: the pad's own travel is the overlap (at least its
    map's ``y_lo_mm``)."""
    s = np.asarray(s_mm, float)
    if math.isinf(k_obj):
        y = s
    else:
        k = np.maximum(k_pad, 0.0)
        y = np.where(s > 0, (k_obj * s + k * y0_mm - f0_N) / (k + k_obj), s)
        y = np.minimum(y, s)
    return np.maximum(y, y_lo_mm)


def friction(anchor_mm, v_rel_mm_s, f_n_N, dt_s, contact: PadContact):
    """Tangential force (N, one row per pad, opposing the object's sliding on the pad), the
    new anchor displacements (mm) and which contacts slip: the anchor's displacement grows by
    the relative velocity ``v_rel_mm_s`` (object on pad, in the pad's plane) over ``dt_s``;
    its spring force −k_t d is capped at μ F_n (the anchor then slides with the object).
    Without normal force the anchor resets."""
    d = np.asarray(anchor_mm, float) + np.asarray(v_rel_mm_s, float) * dt_s
    cap = contact.mu * np.maximum(np.asarray(f_n_N, float), 0.0)
    k = contact.shear_N_per_mm
    size = np.linalg.norm(d, axis=-1)
    slipping = (k * size > cap) & (cap > 0)
    scale = np.where(slipping, cap / np.maximum(k * size, 1e-300), 1.0)
    d = np.where((cap > 0)[..., None], d * scale[..., None], 0.0)
    return -k * d, d, slipping
