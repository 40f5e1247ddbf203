"""The undeformed meridian of the revolved part, parametrised by its arc length s (mm).

s runs from the apex (s = 0, x = 0) to the clamped edge (s = L, x = w). In s the slope g of
eq. 16 never appears: the membrane only needs the radius x(s) and the metric ds, so the
infinite slopes at x = w (Types A, B) and at x = w̄ (Type D, sec. 2.3.2) are ordinary points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline

from spsc.cad.geometry import SPSCGeometry

__all__ = ["Meridian"]


def _dense_u(g: SPSCGeometry, n: int = 4000) -> np.ndarray:
    """Parameter grid on [0, π − Δu], clustered where X(u), Y(u) have power-law ends."""
    umax = math.pi - g.delta_u
    parts = [np.linspace(0.0, umax, n), np.geomspace(1e-9, 0.3, 400), umax - np.geomspace(1e-9, 0.3, 400)]
    if umax > math.pi / 2 + 1e-9:
        d = np.geomspace(1e-9, 0.3, 400)
        parts += [math.pi / 2 - d, math.pi / 2 + d]
    u = np.unique(np.clip(np.concatenate(parts), 0.0, umax))
    return u


@dataclass(frozen=True)
class Meridian:
    """x(s), y(s) of the nominal profile (eqs. 10–11) by arc length, from a dense polyline."""

    geometry: SPSCGeometry
    length: float = field(init=False)
    _x: CubicSpline = field(init=False, repr=False)
    _y: CubicSpline = field(init=False, repr=False)

    def __post_init__(self):
        g = self.geometry
        u = _dense_u(g)
        X, Y = g.profile(u)
        X[0], Y[0], X[-1], Y[-1] = 0.0, g.h, g.w, 0.0
        ds = np.hypot(np.diff(X), np.diff(Y))
        keep = np.concatenate([[True], ds > 1e-12])
        s = np.concatenate([[0.0], np.cumsum(ds)])[keep]
        X, Y = X[keep], Y[keep]
        # not-a-knot splines on a dense polyline: x(s) ~ s at the apex, smooth elsewhere
        object.__setattr__(self, "length", float(s[-1]))
        object.__setattr__(self, "_x", CubicSpline(s, X))
        object.__setattr__(self, "_y", CubicSpline(s, Y))

    def x(self, s):
        """Undeformed radius x(s), mm (exactly 0 at the apex)."""
        return np.maximum(self._x(s), 0.0)

    def y(self, s):
        """Undeformed height y(s), mm."""
        return self._y(s)

    def angle(self, s):
        """Tangent angle φ of the meridian below the horizontal, rad (0 at the apex)."""
        return np.unwrap(np.arctan2(-self._y(s, 1), self._x(s, 1)))

    def s_of_x_widest(self) -> float:
        """Arc length of the widest section x = w̄ (Type D's split point), mm."""
        s = np.linspace(0.0, self.length, 20001)
        return float(s[np.argmax(self._x(s))])
