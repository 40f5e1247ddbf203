"""What the wall model and the 3D FEM share to read strain and energy where the wall carries
them (issue 51): the largest principal stretch of a deformation gradient, and a cycle's
fields per node — the largest value and the amplitude of each — with the hot spot found
away from the clamped base (:mod:`spsc.fem.wall.fields`, :mod:`spsc.fem.solid.fields`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["principal_stretch", "CycleFields", "over_cycle"]


def principal_stretch(F: np.ndarray) -> np.ndarray:
    """λ₁ (...) of the deformation gradients F (..., 3, 3): √ of C = FᵀF's largest eigenvalue."""
    C = np.einsum("...ki,...kj->...ij", F, F)
    return np.sqrt(np.linalg.eigvalsh(C)[..., -1])


@dataclass(frozen=True)
class CycleFields:
    """Over the records of a cycle, per node (NaN where a node has no recovered value): the
    largest stretch ``stretch_max`` and energy ``energy_max`` (MPa), their amplitudes
    ``stretch_amplitude`` and ``energy_amplitude`` (largest − smallest), and each node's
    ``places``: ``height``, ``radius`` (mm), ``face`` ("inner", "outer", "inside") and
    ``base`` (near the clamped base's corner)."""

    stretch_max: np.ndarray
    stretch_amplitude: np.ndarray
    energy_max: np.ndarray
    energy_amplitude: np.ndarray
    places: dict

    def peak(self, name: str, *, away_from_base: bool = True) -> dict:
        """The largest value of the field ``name`` (one of the four) over the wall, or over
        the nodes away from the clamped base: its value and its node's place."""
        values = getattr(self, name)
        keep = np.isfinite(values)
        if away_from_base:
            keep &= ~self.places["base"]
        k = int(np.flatnonzero(keep)[np.argmax(values[keep])])
        return {"value": float(values[k]), "node": k,
                "height_mm": float(self.places["height"][k]),
                "radius_mm": float(self.places["radius"][k]),
                "face": str(self.places["face"][k]), "base": bool(self.places["base"][k])}


def over_cycle(stretches, energies, places: dict) -> CycleFields:
    """The cycle's fields from the nodal stretch and energy of each of its states."""
    s, w = np.stack(stretches), np.stack(energies)
    return CycleFields(s.max(0), s.max(0) - s.min(0), w.max(0), w.max(0) - w.min(0), places)
