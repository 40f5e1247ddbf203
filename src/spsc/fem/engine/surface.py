"""What a rigid body meets on a discretisation: its :class:`ContactSurface`.

A discretisation names the unknowns a body may prescribe and where they sit, and measures what
touches; the body (the plate's active set, :mod:`.active_set`; a sticking plate's anchors,
:mod:`.friction`; a curved indenter's leaning heights, :mod:`.leaning`) does the rest. So the
discretisation's side of contact is this one record, not arrays spread over its interface.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = ["ContactSurface"]


def _no_groups(r, active) -> dict:
    return {}


@dataclass(frozen=True, eq=False)
class ContactSurface:
    """The outer surface a rigid body presses, over the Newton system's unknowns.

    ``dofs``: the sorted vertical displacement unknowns the body may prescribe (unsupported);
    ``lateral`` (k, len(dofs)): each one's lateral unknowns (k = 1, the radius, on an
    axisymmetric section; 2, x and y, in 3D; −1 where a node has none), which a sticking plate
    holds and a curved body's height leans on; ``height``: per unknown its node's reference
    coordinate (mm; z on a vertical unknown, x or y on a lateral one); ``gap``: per unknown
    how far above its node the body meets it (mm, a rigid insert's thickness);
    ``area(x, plate, indenter)``: the outer surface on the body whose tip is at ``plate``
    (mm², whole part; None: not measured); ``groups(r, active)``: the force (N, whole part) through each named
    part of the surface from the residual's reactions of the ``active`` unknowns."""

    dofs: np.ndarray
    lateral: np.ndarray
    height: np.ndarray
    gap: np.ndarray
    area: Callable | None = None
    groups: Callable = _no_groups

    def lateral_of(self, dofs) -> np.ndarray:
        """The lateral unknowns (k, len(dofs)) of the contact unknowns ``dofs``."""
        return self.lateral[:, np.searchsorted(self.dofs, dofs)]

    def top(self, x) -> float:
        """The highest point the body can meet at the state x (mm): reference height plus
        displacement plus gap over the contact unknowns."""
        d = self.dofs
        return float(np.max(self.height[d] + x[d] + self.gap[d]))
