"""A leaking chamber (the paper's sec. 3.2 leak test: inflated to 40 kPa, isolated, "leak-free
for at least 30 minutes"; FDM bladders lost < 1 kPa after a latex sealant).

The leak is an orifice from the chamber to the ambient air, its mass flow ISO 6358's
(:class:`~.valve.Valve`, a sonic conductance C: a pinhole, a porous seam, a poorly sealed
port), given by C, by an effective area, or by the loss it causes: ``drop_kPa`` over
``over_s`` at rest at the setup pressure, the way a leak test reports it
(:func:`conductance_for_drop`).

Closed form (:func:`leak_time`), the isothermal gas in a rigid volume V: with u = P_a/P the
pressure ratio across the orifice, C' = C ρ₀ √(T₀/T) and k = R T C'/V,

    dP/dt = −k P φ(u)   ⇒   k t = ∫ du / (u φ(u))   from u₀ to u,

and with ISO 6358's φ (subsonic index m = ½, a = 1 − b) the subsonic part integrates in closed
form, ∫ du/(u φ) = a ∫ du/(u √(a² − (u − b)²)):

    b > ½:  (a/√(2b − 1)) arcsin((b u + 1 − 2b)/(a u))
    b < ½:  −(a/√(1 − 2b)) ln((2(1 − 2b) + 2b u + 2√(1 − 2b) √(a² − (u − b)²))/u)
    b = ½:  −2a √(u − u²)/u,

the choked part (u ≤ b, φ = 1) is ln u and the laminar end (u > r_l) (1 − r_l)/φ(r_l) ·
ln(u/(1 − u)). A compliant chamber's volume grows with its pressure: to first order its
rigid volume is the effective one, V + P ∂V/∂P (the gas leaves it as if it were that much
larger).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.integrate import quad
from scipy.optimize import brentq

from spsc.core.constants import P_AMB
from spsc.core.errors import ParameterError, require

from .gas import R_AIR, T_AMBIENT
from .valve import LAMINAR_RATIO, RHO0, T0, Valve, sonic_conductance

__all__ = ["LeakSpec", "leak_time", "leak_pressure", "conductance_for_drop"]

_C_SI = 1e-3 / 1e5  # dm³/(s·bar) in m³/(s·Pa)
_PA_KPA = P_AMB * 1e3  # ambient, kPa absolute


def _subsonic(u: float, b: float) -> float:
    """∫ du/(u φ(u)) of the subsonic law (m = ½), up to a constant."""
    a = 1.0 - b
    if abs(b - 0.5) < 1e-12:
        return -2.0 * a * math.sqrt(max(u - u * u, 0.0)) / u
    if b > 0.5:
        arg = (b * u + 1.0 - 2.0 * b) / (a * u)
        return a / math.sqrt(2.0 * b - 1.0) * math.asin(min(1.0, max(-1.0, arg)))
    c = 1.0 - 2.0 * b
    q = max(a * a - (u - b) ** 2, 0.0)
    return -a / math.sqrt(c) * math.log((2.0 * c + 2.0 * b * u + 2.0 * math.sqrt(c * q)) / u)


def _primitive(u: float, valve: Valve) -> float:
    """G(u) with dG/du = 1/(u φ(u)), continuous across the choked, subsonic and laminar
    parts (G(b) = ln b)."""
    b, rl = valve.b, LAMINAR_RATIO
    if valve.m != 0.5:  # no closed form: the same integral by quadrature
        return math.log(min(u, b)) + (quad(lambda s: 1.0 / (s * valve.phi(s)), b, u,
                                           limit=200)[0] if u > b else 0.0)
    if u <= b:
        return math.log(u)
    g = math.log(b) + _subsonic(min(u, rl), b) - _subsonic(b, b)
    if u > rl:
        scale = (1.0 - rl) / valve.phi(rl)
        g += scale * (math.log(u / (1.0 - u)) - math.log(rl / (1.0 - rl)))
    return g


def _rate(valve: Valve, volume_mm3: float, temperature_K: float) -> float:
    """k = R T C'/V (1/s)."""
    c = valve.C * _C_SI * RHO0 * math.sqrt(T0 / temperature_K)
    return R_AIR * temperature_K * c / (volume_mm3 * 1e-9)


def leak_time(p_from_kPa: float, p_to_kPa: float, volume_mm3: float, valve: Valve,
              temperature_K: float = T_AMBIENT) -> float:
    """The time (s) an isothermal rigid volume ``volume_mm3`` (mm³) takes to leak from gauge
    ``p_from_kPa`` to ``p_to_kPa`` through the orifice ``valve``."""
    u0, u1 = _PA_KPA / (p_from_kPa + _PA_KPA), _PA_KPA / (p_to_kPa + _PA_KPA)
    return (_primitive(u1, valve) - _primitive(u0, valve)) / _rate(valve, volume_mm3,
                                                                   temperature_K)


def leak_pressure(p0_kPa: float, t_s: float, volume_mm3: float, valve: Valve,
                  temperature_K: float = T_AMBIENT) -> float:
    """The gauge pressure (kPa) after ``t_s`` of the leak from ``p0_kPa``
    (:func:`leak_time` inverted)."""
    if t_s <= 0 or p0_kPa <= 0:
        return p0_kPa
    lo = 1e-12 * max(p0_kPa, 1.0)
    if leak_time(p0_kPa, lo, volume_mm3, valve, temperature_K) <= t_s:
        return lo
    return brentq(lambda p: leak_time(p0_kPa, p, volume_mm3, valve, temperature_K) - t_s,
                  lo, p0_kPa, xtol=1e-14, rtol=1e-14)


def conductance_for_drop(drop_kPa: float, over_s: float, setup_kPa: float,
                         volume_mm3: float, temperature_K: float = T_AMBIENT) -> float:
    """The sonic conductance C (dm³/(s·bar), b = 0.528, m = ½) of the orifice through which
    ``volume_mm3`` at ``setup_kPa`` loses ``drop_kPa`` in ``over_s`` (k t is linear in C)."""
    unit = Valve(1.0)
    return leak_time(setup_kPa, setup_kPa - drop_kPa, volume_mm3, unit, temperature_K) / over_s


@dataclass(frozen=True)
class LeakSpec:
    """A scenario's ``[circuit] leak``: an orifice's ``C`` (dm³/(s·bar)), or its
    ``area_mm2``, or the loss ``drop_kPa`` over ``over_s`` at rest at the setup pressure
    (resolved on the chamber's map, :meth:`valve`)."""

    C: float | None = None
    area_mm2: float | None = None
    drop_kPa: float | None = None
    over_s: float | None = None

    @classmethod
    def parse(cls, table, setup_kPa: float) -> "LeakSpec":
        if not isinstance(table, dict):
            raise ParameterError("circuit.leak", table, "an inline table {C = ...}, "
                                 "{area_mm2 = ...} or {drop_kPa = ..., over_s = ...}")
        extra = sorted(set(table) - {"C", "area_mm2", "drop_kPa", "over_s"})
        if extra:
            raise ParameterError(f"circuit.leak.{extra[0]}", table[extra[0]],
                                 "one of the keys C, area_mm2, drop_kPa, over_s")
        given = [k for k in ("C", "area_mm2", "drop_kPa") if k in table]
        if len(given) != 1 or ("over_s" in table) != ("drop_kPa" in table):
            raise ParameterError("circuit.leak", table, "one of C, area_mm2, or drop_kPa "
                                 "with over_s")
        if "C" in table:
            return cls(C=require("circuit.leak.C", table["C"], gt=0, le=1,
                                 unit="dm³/(s·bar)"))
        if "area_mm2" in table:
            return cls(area_mm2=require("circuit.leak.area_mm2", table["area_mm2"], gt=0,
                                        le=1, unit="mm²"))
        drop = require("circuit.leak.drop_kPa", table["drop_kPa"], gt=0, unit="kPa")
        if drop >= setup_kPa:
            raise ParameterError("circuit.leak.drop_kPa", drop, f"< the setup pressure "
                                 f"{setup_kPa:g} kPa (a leak only loses the gauge pressure)")
        return cls(drop_kPa=drop, over_s=require("circuit.leak.over_s", table["over_s"],
                                                 gt=0, le=1e7, unit="s"))

    def valve(self, setup_kPa: float, effective_mm3: float,
              temperature_K: float = T_AMBIENT) -> Valve:
        """The orifice; for a loss, the one that gives it to the volume ``effective_mm3``
        (mm³: the chamber's, and the reservoir's if the valve is open, with its
        compliance) at ``setup_kPa``."""
        if self.C is not None:
            return Valve(self.C)
        if self.area_mm2 is not None:
            return Valve(sonic_conductance(self.area_mm2))
        return Valve(conductance_for_drop(self.drop_kPa, self.over_s, setup_kPa,
                                          effective_mm3, temperature_K))

    def describe(self) -> str:
        if self.C is not None:
            return f"an orifice of C = {self.C:.3g} dm³/(s·bar)"
        if self.area_mm2 is not None:
            return f"an orifice of {self.area_mm2:.3g} mm²"
        return f"{self.drop_kPa:g} kPa lost in {self.over_s:g} s at rest"
