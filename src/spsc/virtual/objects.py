"""Objects a gripper's pads grasp (issue 50): a box, an upright cylinder or a sphere, with its
mass, its local stiffness at a pad and its friction on the pads. Its extent along any direction
is its support function (how far its surface reaches from its centre), which gives each pad's
overlap with it. Units: mm, g, N/mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError, require

from .contact import PadContact

__all__ = ["GraspObject", "SHAPES"]

#: the shapes and the sizes each takes (mm, full lengths)
SHAPES = {"box": ("x", "y", "z"), "cylinder": ("diameter", "height"),
          "sphere": ("diameter",)}


@dataclass(frozen=True)
class GraspObject:
    """A rigid body of ``shape`` (:data:`SHAPES`) and ``size_mm`` (full lengths: a box's
    x, y, z; a cylinder's diameter and height, its axis vertical; a sphere's diameter), of
    ``mass_g`` (g), resting on the table at the start, with its ``contact`` on the pads (its
    local stiffness, friction)."""

    shape: str = "box"
    size_mm: tuple = (30.0, 30.0, 40.0)
    mass_g: float = 50.0
    contact: PadContact = PadContact()

    def __post_init__(self):
        if self.shape not in SHAPES:
            raise ParameterError("object.shape", self.shape, " | ".join(SHAPES))
        names = SHAPES[self.shape]
        size = tuple(self.size_mm) if isinstance(self.size_mm, (list, tuple)) else ()
        if len(size) != len(names):
            raise ParameterError("object.size_mm", self.size_mm, f"[{', '.join(names)}] in "
                                 f"mm for a {self.shape}")
        object.__setattr__(self, "size_mm", tuple(
            require(f"object.size_mm ({n})", v, ge=2, le=500, unit="mm")
            for n, v in zip(names, size)))
        require("object.mass_g", self.mass_g, gt=0, le=5000, unit="g")

    @property
    def half_height_mm(self) -> float:
        """Its centre's height above the table at rest (mm)."""
        return 0.5 * self.size_mm[-1] if self.shape != "sphere" else 0.5 * self.size_mm[0]

    def support_mm(self, rotation, direction) -> float:
        """How far its surface reaches from its centre along the unit ``direction`` (world),
        turned by ``rotation`` (3 × 3, body to world)."""
        n = np.asarray(rotation, float).T @ np.asarray(direction, float)
        if self.shape == "box":
            return float(0.5 * np.abs(n) @ np.asarray(self.size_mm))
        if self.shape == "sphere":
            return 0.5 * self.size_mm[0]
        axial = abs(float(n[2]))
        return 0.5 * self.size_mm[0] * math.sqrt(max(1.0 - axial * axial, 0.0)) + \
            0.5 * self.size_mm[1] * axial

    def mjcf_geom(self) -> str:
        """Its MuJoCo geom (SI: half sizes in m, mass in kg)."""
        size = " ".join(f"{0.5e-3 * v:g}" for v in self.size_mm)  # MuJoCo's half sizes
        return (f'<geom name="object" type="{self.shape}" size="{size}" '
                f'mass="{self.mass_g * 1e-3:g}" rgba="0.85 0.55 0.2 1" friction="0.6"/>')
