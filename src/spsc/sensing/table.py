"""The chamber's map resampled for sensing: V and F on a dense (travel y, gauge pressure P) grid,
and from it, for one gas content, the monotone table P -> (y, F) the estimator reads each
sample in O(1).

The gas content is c = P_abs (V + V_e) (kPa·mm³), with V_e the volume that shares the chamber's
gas: 0 with the valve closed (high mode), the reservoir's V_r with it open and equalised (low
mode). At the ambient temperature c is the gas mass times R T (eq. 2 with n = 1, the paper's
static tests): conserving the mass conserves c. For each travel y the table's pressure is the
root of (P + P_a)(V(y, P) + V_e) = c; pressing lowers V, so P rises with y and the table can be
read backwards, from the measured P to y and F(y, P).
"""

from __future__ import annotations

from bisect import bisect_right
from dataclasses import dataclass

import numpy as np

from spsc.core.constants import P_AMB_KPA
from spsc.core.errors import ParameterError

__all__ = ["DenseMap", "ForceTable", "PA_KPA"]

#: the ambient pressure (kPa absolute) the gauge pressures are measured against
PA_KPA = P_AMB_KPA
#: the force (N) below which the map's interpolation is taken for no contact
RINGING_N = 5e-3


class DenseMap:
    """V (mm³) and F (N) of ``chamber_map`` (:class:`~spsc.dynamics.chamber_map.ChamberMap`) on
    ``ny`` travels × ``np_`` pressures spanning the map, through the map's own interpolation
    (``map.at(y)``); bilinear between the nodes."""

    def __init__(self, chamber_map, ny: int = 301, np_: int = 401):
        y0, y1 = chamber_map.y_range
        p0, p1 = chamber_map.pressure_range
        self.map = chamber_map
        self.y = np.linspace(y0, y1, ny)
        self.p = np.linspace(p0, p1, np_)
        self.volume = np.empty((ny, np_))
        self.force = np.empty((ny, np_))
        for i, y in enumerate(self.y):
            s = chamber_map.at(y)
            self.volume[i] = s.volume(self.p)
            # the spline along P rings by a few mN where some levels touch and others not
            # yet (as in the circuit's output): the plate only pushes
            self.force[i] = np.maximum(s.force(self.p), 0.0)
        self._y, self._p = self.y.tolist(), self.p.tolist()

    @property
    def pressure_range(self) -> tuple[float, float]:
        return float(self.p[0]), float(self.p[-1])

    def free_volume(self, p_kPa: float) -> float:
        """The cavity volume (mm³) of the chamber at ``p_kPa`` touching nothing: at the map's
        lowest travel, the first contact of its highest level."""
        return float(np.interp(p_kPa, self.p, self.volume[0]))

    def content(self, p_kPa: float, y_mm: float, extra_mm3: float = 0.0) -> float:
        """c = (P + P_a)(V(y, P) + V_e) (kPa·mm³)."""
        return (p_kPa + PA_KPA) * (self.at(self.volume, y_mm, p_kPa) + extra_mm3)

    def rest_content(self, p_kPa: float, extra_mm3: float = 0.0) -> float:
        """The content of the chamber (and V_e) at rest at the gauge pressure ``p_kPa``."""
        return (p_kPa + PA_KPA) * (self.free_volume(p_kPa) + extra_mm3)

    def at(self, grid: np.ndarray, y_mm: float, p_kPa: float) -> float:
        """``grid`` (volume or force) at (y, P), bilinear, clamped to the map."""
        i = min(max(bisect_right(self._y, y_mm) - 1, 0), len(self._y) - 2)
        j = min(max(bisect_right(self._p, p_kPa) - 1, 0), len(self._p) - 2)
        u = min(max((y_mm - self._y[i]) / (self._y[i + 1] - self._y[i]), 0.0), 1.0)
        v = min(max((p_kPa - self._p[j]) / (self._p[j + 1] - self._p[j]), 0.0), 1.0)
        g = grid
        return float((1 - u) * ((1 - v) * g[i, j] + v * g[i, j + 1])
                     + u * ((1 - v) * g[i + 1, j] + v * g[i + 1, j + 1]))

    def compliance(self, y_mm: float, p_kPa: float) -> float:
        """∂V/∂P (mm³/kPa) at (y, P): the slope of the bilinear volume along P."""
        i = min(max(bisect_right(self._y, y_mm) - 1, 0), len(self._y) - 2)
        j = min(max(bisect_right(self._p, p_kPa) - 1, 0), len(self._p) - 2)
        u = min(max((y_mm - self._y[i]) / (self._y[i + 1] - self._y[i]), 0.0), 1.0)
        g = self.volume
        dv = (1 - u) * (g[i, j + 1] - g[i, j]) + u * (g[i + 1, j + 1] - g[i + 1, j])
        return float(dv / (self._p[j + 1] - self._p[j]))

    def travel(self, volume_mm3: float, p_kPa: float) -> tuple[float, bool]:
        """(y mm, within the map) where the cavity at ``p_kPa`` holds ``volume_mm3``: the
        inverse of V(·, P), which pressing lowers (bilinear, as :meth:`at`); the map's
        first travel when the cavity is not pressed that far (no contact), its last when
        pressed beyond it (not within)."""
        j = min(max(bisect_right(self._p, p_kPa) - 1, 0), len(self._p) - 2)
        v = min(max((p_kPa - self._p[j]) / (self._p[j + 1] - self._p[j]), 0.0), 1.0)
        col = (1.0 - v) * self.volume[:, j] + v * self.volume[:, j + 1]
        inside = self._p[0] <= p_kPa <= self._p[-1]
        if volume_mm3 >= col[0]:
            return float(self.y[0]), inside
        if volume_mm3 <= col[-1]:
            return float(self.y[-1]), False
        # V falls along y (flat before contact): the first node at or below the volume
        i = int(np.searchsorted(-col, -volume_mm3, side="left"))
        v0, v1 = col[i - 1], col[i]
        u = (v0 - volume_mm3) / (v0 - v1) if v0 > v1 else 1.0
        return float(self.y[i - 1] + u * (self.y[i] - self.y[i - 1])), inside

    def table(self, content: float, extra_mm3: float = 0.0) -> "ForceTable":
        """The table P -> (y, F) of the gas content ``content`` (kPa·mm³) shared with
        ``extra_mm3``. Raises ParameterError when no pressure of the map holds it."""
        g = (self.p[None, :] + PA_KPA) * (self.volume + extra_mm3)  # rises with P at each y
        below = g < content
        k = below.sum(axis=1) - 1  # the last node below the content, per travel
        ok = (k >= 0) & (k < self.p.size - 1)
        if not ok.any():
            lo, hi = g[:, 0].min(), g[:, -1].max()
            raise ParameterError("gas content", f"{content:.6g} kPa·mm³",
                                 f"within the chamber map's [{lo:.6g}, {hi:.6g}] (a rest or "
                                 "setup pressure inside the map's pressures)")
        rows = np.flatnonzero(ok)
        kk = k[rows]
        g0, g1 = g[rows, kk], g[rows, kk + 1]
        w = (content - g0) / (g1 - g0)
        p = self.p[kk] + w * (self.p[kk + 1] - self.p[kk])
        f = self.force[rows, kk] + w * (self.force[rows, kk + 1] - self.force[rows, kk])
        return ForceTable.of(p, self.y[rows], f)


@dataclass(frozen=True)
class ForceTable:
    """P (kPa, strictly increasing), y (mm) and F (N) along one gas content: the chamber's
    rest at ``p[0]`` (F = 0), its deepest press in the map at ``p[-1]``."""

    p: tuple
    y: tuple
    f: tuple

    @classmethod
    def of(cls, p, y, f) -> "ForceTable":
        """The monotone table of the (P, y, F) rows along increasing y: the rows before first
        contact (P constant, F = 0) collapse to the last of them, the rest keep P rising."""
        p, y, f = (np.asarray(a, float) for a in (p, y, f))
        # the map's spline along P rings by a few mN before contact (spsc.dynamics.circuit):
        # contact is a force above 5 mN
        touching = np.flatnonzero(f > RINGING_N)
        start = max(int(touching[0]) - 1, 0) if touching.size else max(p.size - 1, 0)
        p, y, f = p[start:], y[start:], f[start:]
        keep = np.r_[True, np.diff(p) > 1e-9 * (1.0 + np.abs(p[1:]))]
        keep &= np.r_[True, p[1:] > np.maximum.accumulate(p)[:-1]]
        p, y, f = p[keep], y[keep], f[keep]
        f[0] = 0.0
        return cls(tuple(p.tolist()), tuple(y.tolist()), tuple(f.tolist()))

    @property
    def rest_kPa(self) -> float:
        """The pressure of this content with nothing touching the chamber."""
        return self.p[0]

    def lookup(self, p_kPa: float) -> tuple[float, float, float, bool]:
        """(y mm, F N, dF/dP N/kPa, within the table) at the gauge pressure ``p_kPa``;
        clamped to the table's ends (below the rest: no contact)."""
        p = self.p
        if len(p) < 2:
            return self.y[0], 0.0, 0.0, p_kPa <= p[0]
        if p_kPa <= p[0]:
            return self.y[0], 0.0, (self.f[1] - self.f[0]) / (p[1] - p[0]), True
        i = bisect_right(p, p_kPa) - 1
        inside = i < len(p) - 1
        if not inside:
            i = len(p) - 2
            p_kPa = p[-1]
        u = (p_kPa - p[i]) / (p[i + 1] - p[i])
        slope = (self.f[i + 1] - self.f[i]) / (p[i + 1] - p[i])
        return (self.y[i] + u * (self.y[i + 1] - self.y[i]),
                self.f[i] + u * (self.f[i + 1] - self.f[i]), slope, inside)

    def pressure_at(self, y_mm: float) -> float:
        """The table's pressure at the travel ``y_mm`` (kPa; the rest below first contact)."""
        y, p = self.y, self.p
        if y_mm <= y[0] or len(y) < 2:
            return p[0]
        i = min(bisect_right(y, y_mm) - 1, len(y) - 2)
        u = min((y_mm - y[i]) / (y[i + 1] - y[i]), 1.0)
        return p[i] + u * (p[i + 1] - p[i])
