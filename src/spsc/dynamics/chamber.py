"""The chamber's gas on its quasi-static map: the pressure of a gas mass at a plate travel, and
the plate travel at which a plate force is carried (the force-controlled press).

At a travel y the gauge pressure P is the root of (P + Pₐ) V(y, P) = m R T (the ideal gas in
the chamber's cavity, :mod:`.chamber_map`). Under a prescribed plate force F the travel is
the root of F(y, P(y)) = F with P(y) that root: g(y) = F(y, P(y)) − F increases with y where
the plate touches, with

    g'(y) = ∂F/∂y + ∂F/∂P dP/dy,    dP/dy = −(P + Pₐ) ∂V/∂y / (V + (P + Pₐ) ∂V/∂P)

(the gas law differentiated at fixed m R T), so a Newton iteration safeguarded by bisection
finds it. A force of zero leaves the plate anywhere above the chamber: the force-controlled
press carries at least :data:`FORCE_FLOOR_N`, the plate resting on the chamber. On a spring of
stiffness k whose far end is at x the travel is the root of g(y) = F(y, P(y)) − k (x − y) in
[y_lo, x] (g' = the above + k > 0; g(x) = F(x, P(x)) ≥ 0), or y = x off the chamber.
"""

from __future__ import annotations

from spsc.core.constants import P_AMB, P_AMB_KPA

__all__ = ["Chamber", "FORCE_FLOOR_N"]

_PA_KPA = P_AMB_KPA  # ambient pressure (kPa)
_PA = P_AMB * 1e6  # (Pa)
_MM3 = 1e-9  # m³ per mm³
_KPA = 1e3  # Pa per kPa

#: the least plate force of a force-controlled press (N): the plate resting on the chamber
FORCE_FLOOR_N = 1e-3


class Chamber:
    """The chamber's gas on ``chamber_map``: its pressure from mass, temperature and travel;
    the travel that carries a plate force."""

    def __init__(self, chamber_map, gas):
        self.map, self.gas = chamber_map, gas
        self.p_lo, self.p_hi = chamber_map.pressure_range
        self.y_lo, self.y_hi = chamber_map.y_range
        self._y, self._slice, self._p = None, None, chamber_map.setup_kPa
        self._y_force = None  # the last travel found for a force (the next one's start)
        self._spring = None  # the last (x, y, dy/dx) on a spring

    def slice(self, y: float):
        if y != self._y:
            if not (self.y_lo - 1e-9 <= y <= self.y_hi + 1e-9):
                raise ValueError(f"plate travel {y:.4g} mm outside the map's "
                                 f"[{self.y_lo:.3g}, {self.y_hi:.3g}] mm")
            self._y, self._slice = y, self.map.at(min(max(y, self.y_lo), self.y_hi))
        return self._slice

    def pressure(self, m: float, t: float, y: float, check: bool = True) -> float:
        """The gauge pressure (kPa) with P V(y, P) = m R T (m kg, t K, y mm), by Newton from
        the last one; ``check``: refuse a pressure outside the map's (the integrator's trial
        states are not checked: its splines extend past them, and the circuit locates where
        an accepted state leaves, :mod:`.circuit`)."""
        s, target = self.slice(y), m * self.gas.R * t
        p = self._p
        for _ in range(50):
            v = float(s.volume(p)) * _MM3
            f = (p * _KPA + _PA) * v - target
            df = v * _KPA + (p * _KPA + _PA) * float(s.volume(p, 1)) * _MM3
            step = f / df
            p -= step
            if abs(step) < 1e-12 * (abs(p) + 1.0):
                break
        else:
            raise ValueError(f"no chamber pressure with P V(y, P) = m R T at y = {y:.4g} mm "
                             f"(Newton at {p:.4g} kPa after 50 steps)")
        if check and not (self.p_lo - 1e-6 <= p <= self.p_hi + 1e-6):
            raise ValueError(f"chamber pressure {p:.4g} kPa outside the map's "
                             f"[{self.p_lo:.3g}, {self.p_hi:.3g}] kPa")
        self._p = p
        return p

    def spring_at_pressure(self, p: float, x: float, k: float) -> float:
        """The plate travel (mm) at which the chamber held at ``p`` (kPa gauge) carries a
        spring of ``k`` (N/mm) whose far end is at ``x`` (mm): bisection (the start of a
        trace, the gas at its setup)."""
        hi = min(x, self.y_hi)
        if float(self.map.at(hi).force(p)) <= 0.0:
            return x
        return self._bisect(p, self.y_lo, hi, lambda y: k * (x - y))

    def travel_on_spring(self, m: float, t: float, x: float, k: float) -> float:
        """The plate travel (mm) at which the gas mass ``m`` (kg) at ``t`` (K) carries a
        spring of ``k`` (N/mm) whose far end is at ``x`` (mm): safeguarded Newton on
        g(y) = F(y, P(y)) − k (x − y) in [y_lo, x]; x itself where the plate there is off
        the chamber (F ≤ 0: the map's spline rings by a few mN about first contact)."""
        hi = min(x, self.y_hi)
        g, dg = self._gap(m, t, hi, k * (x - hi))
        if g <= 0.0:
            if x > self.y_hi:
                raise ValueError(f"the spring's end at {x:.4g} mm drives the plate beyond the "
                                 f"map's {self.y_hi:.3g} mm")
            return x
        lo = self.y_lo
        # the last root moved along dy/dx = k/(g' + k) (consecutive calls are close)
        y = hi if self._spring is None else \
            self._spring[1] + self._spring[2] * (x - self._spring[0])
        y = min(max(y, lo), hi)
        tol = 1e-10 * max(k * (x - lo), FORCE_FLOOR_N)
        for _ in range(200):
            g, dg = self._gap(m, t, y, k * (x - y))
            dg += k
            if abs(g) <= tol or hi - lo < 1e-12:
                self._spring = (x, y, k / dg)
                return y
            lo, hi = (y, hi) if g < 0 else (lo, y)
            nxt = y - g / dg if dg > 0 else None
            y = nxt if nxt is not None and lo < nxt < hi else 0.5 * (lo + hi)
        raise ValueError(f"no plate travel carries the spring at x = {x:.4g} mm (at {y:.4g} "
                         f"mm the force is off by {g:.3g} N)")

    def _gap(self, m: float, t: float, y: float, force: float) -> tuple[float, float]:
        """g(y) = F(y, P(y)) − force (N) and g'(y) (N/mm), the module's equations."""
        p = self.pressure(m, t, y, check=False)
        s = self._slice
        pa = p + _PA_KPA
        dp_dy = -pa * float(s.dvolume_dy(p)) / (float(s.volume(p)) + pa * float(s.volume(p, 1)))
        g = float(s.force(p)) - force
        return g, float(s.dforce_dy(p)) + float(s.force(p, 1)) * dp_dy

    def travel_at_pressure(self, p: float, force: float) -> float:
        """The plate travel (mm) at which the chamber held at ``p`` (kPa gauge) carries
        ``force`` (N, at least :data:`FORCE_FLOOR_N`): bisection on F(y, p), increasing in y
        where the plate touches."""
        force = max(force, FORCE_FLOOR_N)
        if float(self.map.at(self.y_hi).force(p)) < force:
            raise ValueError(f"a plate force of {force:.4g} N needs a travel beyond the map's "
                             f"{self.y_hi:.3g} mm; raise press.max_travel_mm")
        return self._bisect(p, self.y_lo, self.y_hi, lambda y: force)

    def _bisect(self, p: float, lo: float, hi: float, need) -> float:
        """The travel in [lo, hi] (mm) where the chamber held at ``p`` (kPa) carries
        ``need(y)`` (N): bisection, F(y, p) − need(y) increasing in y."""
        while hi - lo > 1e-12 * max(1.0, abs(hi)):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if float(self.map.at(mid).force(p)) < need(mid) else (lo, mid)
        return 0.5 * (lo + hi)

    def travel(self, m: float, t: float, force: float) -> float:
        """The plate travel (mm) at which the gas mass ``m`` (kg) at ``t`` (K) carries the
        plate force ``force`` (N, at least :data:`FORCE_FLOOR_N`): safeguarded Newton."""
        force = max(force, FORCE_FLOOR_N)
        lo, hi = self.y_lo, self.y_hi
        y = min(max(self._y_force if self._y_force is not None else 0.0, lo), hi)
        tol = 1e-10 * force
        for _ in range(200):
            g, dg = self._gap(m, t, y, force)
            if abs(g) <= tol:
                self._y_force = y
                return y
            lo, hi = (y, hi) if g < 0 else (lo, y)
            nxt = y - g / dg if dg > 0 else None
            if nxt is None or not (lo < nxt < hi):
                nxt = 0.5 * (lo + hi)
            if hi - lo < 1e-12:
                break
            y = nxt
        if g < 0 and y >= self.y_hi - 1e-9:
            raise ValueError(f"a plate force of {force:.4g} N needs a travel beyond the map's "
                             f"{self.y_hi:.3g} mm (it carries {g + force:.4g} N there); raise "
                             "press.max_travel_mm")
        raise ValueError(f"no plate travel carries {force:.4g} N (at {y:.4g} mm the force is "
                         f"off by {g:.3g} N)")
