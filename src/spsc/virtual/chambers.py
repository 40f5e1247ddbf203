"""Chambers stepped in time for a host simulator (issue 50): given each chamber's plate travel
and valve command every step, the contact force, the pressure as its sensor reads it and its
current stiffness — many chambers at once, no solve inside a step.

The physics is :mod:`spsc.dynamics.circuit`'s (the paper's Fig. 1): the chamber's gas on its
quasi-static map V(y, P), F(y, P) (:class:`~spsc.dynamics.chamber_map.ChamberMap`, from the
wall model or the surrogate), a valve to a rigid reservoir (ISO 6358,
:class:`~spsc.dynamics.valve.Valve`), the gas in each volume with its energy balance
(:class:`~spsc.dynamics.gas.Gas`: isothermal, adiabatic, or relaxing to ambient with a thermal
time constant), a sensor (:class:`~spsc.dynamics.sensor.Sensor`: noise, quantisation, full
scale, sample rate). Where ``spsc simulate`` integrates one chamber's ODE adaptively, this steps
N chambers together with fixed substeps while a valve is open (:data:`SUBSTEP_S`), the valve's
flow linearly implicit and the gas's energy and pressure solved together, the pressure of each chamber from the gas law on the map at every substep
(P V(y, P) = m R T, a few Newton steps from the last pressure on a dense table of the map,
bilinear between its nodes). The map's table is built once (:class:`MapTable`).

Units: mm, N, kPa gauge at the edges; SI inside.
"""

from __future__ import annotations

import math

import numpy as np

from spsc.core.constants import P_AMB

__all__ = ["MapTable", "VirtualChambers", "SUBSTEP_S"]

_PA = P_AMB * 1e6  # ambient pressure (Pa)
_MM3 = 1e-9
#: the substep of the gas's integration while a valve is open (s): the valve's laminar end is a
#: millisecond time constant; its flow is linearly implicit (stable at any step) and first
#: order, 0.02 kPa off the integrator at the valve's opening with 0.1 ms, 0.19 kPa with 1 ms
SUBSTEP_S = 1e-4
#: the valve's two sides this close (kPa) take one implicit step per host step, not substeps
SETTLED_KPA = 0.05
#: the map's table: travel step (mm) and pressure levels
TABLE_DY_MM, TABLE_LEVELS = 0.01, 129


class MapTable:
    """V(y, P) (mm³) and F(y, P) (N) of a :class:`ChamberMap` on a dense regular grid (travel
    step :data:`TABLE_DY_MM`, :data:`TABLE_LEVELS` pressures over the map's range), looked up
    bilinearly for arrays of (y, P); values beyond the grid are the edge's (clamped)."""

    def __init__(self, chamber_map, dy_mm: float = TABLE_DY_MM, levels: int = TABLE_LEVELS):
        from scipy.interpolate import CubicSpline

        y_lo, y_hi = chamber_map.y_range
        p_lo, p_hi = chamber_map.pressure_range
        self.y = np.arange(y_lo, y_hi + 0.5 * dy_mm, dy_mm)
        self.p = np.linspace(p_lo, p_hi, levels)
        coarse_p = chamber_map.pressure_kPa
        # the map's own PCHIP along y at each level, then its cubic spline along P
        self.V, self.F = (CubicSpline(coarse_p, along_y, axis=1)(self.p)
                          for along_y in chamber_map.levels_at(self.y))
        self.F = np.maximum(self.F, 0.0)
        self.dy, self.dp = self.y[1] - self.y[0], self.p[1] - self.p[0]
        self.y_range, self.p_range = (float(self.y[0]), float(self.y[-1])), (p_lo, p_hi)

    def _cell(self, y, p):
        fy = np.clip((y - self.y[0]) / self.dy, 0.0, self.y.size - 1 - 1e-9)
        fp = np.clip((p - self.p[0]) / self.dp, 0.0, self.p.size - 1 - 1e-9)
        i, j = fy.astype(int), fp.astype(int)
        return i, j, fy - i, fp - j

    def lookup(self, table, y, p):
        """(value, ∂/∂P) of ``table`` (``self.V`` or ``self.F``) at (y mm, p kPa)."""
        i, j, a, b = self._cell(y, p)
        t00, t01 = table[i, j], table[i, j + 1]
        t10, t11 = table[i + 1, j], table[i + 1, j + 1]
        lo, hi = t00 + a * (t10 - t00), t01 + a * (t11 - t01)
        return lo + b * (hi - lo), (hi - lo) / self.dp


class VirtualChambers:
    """``count`` chambers of one design on ``chamber_map`` in the circuit ``circuit``
    (:class:`~spsc.dynamics.circuit.Circuit`: setup pressure, reservoir, valve, gas), each
    with ``sensor`` (None: a perfect one) seeded apart, the circuit's leak to the air if it has
    one, at rest at the setup pressure with the
    plate at ``y0_mm`` (default: the map's first travel, above the chamber) and the valve
    ``valve_open``; ``substep_s`` the gas's step while a valve is open (:data:`SUBSTEP_S`:
    accuracy against speed).

    :meth:`step` advances every chamber by ``dt`` to its new travel and valve command and
    returns what a host simulator reads."""

    def __init__(self, chamber_map, circuit, *, count: int = 1, sensor=None,
                 y0_mm: float | None = None, valve_open: bool = False, table=None,
                 substep_s: float = SUBSTEP_S):
        self.table = table or MapTable(chamber_map)
        self.leak = circuit.leak  # an orifice to the air (:mod:`spsc.dynamics.leak`) or None
        self.circuit, self.gas, self.count = circuit, circuit.gas, int(count)
        self.sensor, self.substep_s = sensor, float(substep_s)
        n = self.count
        y0 = self.table.y_range[0] if y0_mm is None else float(y0_mm)
        gas, ta = circuit.gas, circuit.gas.ambient_K
        p0 = np.full(n, float(circuit.setup_kPa))
        self.y = np.full(n, y0)
        v0, _ = self.table.lookup(self.table.V, self.y, p0)
        pa0 = p0 * 1e3 + _PA
        self.p = p0
        self.tc = np.full(n, ta)
        self.mc = pa0 * v0 * _MM3 / (gas.R * ta)
        self.vr = circuit.reservoir_mm3 * _MM3
        self.tr = np.full(n, ta)
        self.mr = pa0 * self.vr / (gas.R * ta)
        self.valve = np.full(n, bool(valve_open))
        self.t = 0.0
        self._rng = np.random.default_rng(None if sensor is None else sensor.seed)
        self._next_sample = 0.0
        self._reading = self.p.copy()

    # -- the gas ---------------------------------------------------------------------------
    def _pressure(self, y, m, t, p):
        """Gauge P (kPa) with (P + Pₐ) V(y, P) = m R T, Newton from ``p``."""
        target = m * self.gas.R * t / _MM3  # Pa·mm³
        for _ in range(6):
            v, dv = self.table.lookup(self.table.V, y, p)
            g = (p * 1e3 + _PA) * v - target
            step = g / (1e3 * v + (p * 1e3 + _PA) * dv)
            p = p - step
            if np.abs(step).max() < 1e-9:  # kPa: converged (quadratically, from the last P)
                break
        return p

    def _leak(self, pc_pa):
        """ISO 6358 mass flow (kg/s) from the ambient air into each chamber through its leak
        (negative: out; zero when sealed), explicit: a leak empties a chamber in minutes."""
        if self.leak is None:
            return np.zeros(self.count)
        return self.leak.mass_flows(np.full(self.count, _PA), pc_pa,
                                    np.full(self.count, self.gas.ambient_K), self.tc)

    def _flow(self, pc_pa, pr_pa):
        """ISO 6358 mass flow (kg/s) reservoir → chamber, per chamber (0 where shut)."""
        if self.vr <= 0 or self.circuit.valve is None:
            return np.zeros(self.count)
        q = self.circuit.valve.mass_flows(pr_pa, pc_pa, self.tr, self.tc)
        return np.where(self.valve, q, 0.0)

    def _substep(self, y_new, h):
        """One substep of ``h`` (s) to the travels ``y_new``: the valve's flow explicit, the
        chamber's gas energy and pressure solved together (the work P dV over the step,
        dV from the travel and from the wall's compliance, by a fixed point of three
        passes)."""
        gas = self.gas
        pc_pa = self.p * 1e3 + _PA
        pr_pa = self.mr * gas.R * self.tr / self.vr if self.vr > 0 else np.full(self.count,
                                                                                  _PA)
        q = self._flow(pc_pa, pr_pa)  # kg/s into the chamber
        if self.vr > 0 and self.valve.any():
            # linearly implicit in the flow (backward Euler on its pressure difference): the
            # valve's conductance G = ∂q/∂(P_r − P_c) against how fast each side's pressure
            # answers a mass (R T_r / V_r; R T_c / (V + P ∂V/∂P) for the chamber)
            d = 1.0  # Pa
            G = (self._flow(pc_pa - d, pr_pa) - q) / d
            v, dv = self.table.lookup(self.table.V, self.y, self.p)
            dpc_dm = gas.R * self.tc / ((v + pc_pa * dv * 1e-3) * _MM3)
            dpr_dm = gas.R * self.tr / self.vr
            q = q / (1.0 + h * G * (dpc_dm + dpr_dm))
        q_leak = self._leak(pc_pa)  # kg/s into the chamber from the air (< 0: out)
        mc = self.mc + h * (q + q_leak)
        if gas.isothermal:
            tc = self.tc
            p = self._pressure(y_new, mc, tc, self.p)
        else:
            cv, cp = gas.cv, gas.n * gas.cv
            v_old, _ = self.table.lookup(self.table.V, self.y, self.p)
            inflow = np.where(q >= 0, q * (cp * self.tr - cv * self.tc), q * gas.R * self.tc)
            inflow = inflow + np.where(q_leak >= 0, q_leak * (cp * gas.ambient_K - cv * self.tc),
                                       q_leak * gas.R * self.tc)
            heat = 0.0 if math.isinf(gas.thermal_time_s) else \
                self.mc * cv * (gas.ambient_K - self.tc) / gas.thermal_time_s
            p = self.p
            for _ in range(3):
                v_new, _ = self.table.lookup(self.table.V, y_new, p)
                work = (0.5 * (self.p + p) * 1e3 + _PA) * (v_new - v_old) * _MM3 / h
                tc = self.tc + h * (inflow - work + heat) / (self.mc * cv)
                p = self._pressure(y_new, mc, tc, p)
            if self.vr > 0:
                out = np.where(q >= 0, -q * gas.R * self.tr, -q * (cp * self.tc - cv * self.tr))
                heat_r = 0.0 if math.isinf(gas.thermal_time_s) else \
                    self.mr * cv * (gas.ambient_K - self.tr) / gas.thermal_time_s
                self.tr = self.tr + h * (out + heat_r) / (self.mr * cv)
        self.mc, self.tc, self.y, self.p = mc, tc, y_new, p
        self.mr = self.mr - h * q

    # -- the step --------------------------------------------------------------------------
    def step(self, y_mm, valve_open, dt: float) -> dict:
        """Advance by ``dt`` (s) to the travels ``y_mm`` (mm from first contact at the setup
        pressure; one value or one per chamber; the plate moves linearly over the step) and
        the valve commands ``valve_open`` (held over the step). Returns ``force_N``,
        ``pressure_kPa`` (true), ``measured_kPa`` (the sensor's last reading),
        ``reservoir_kPa``, ``stiffness_N_per_mm`` (dF/dy with the gas following, at fixed
        mass and temperature), ``temperature_K`` (n each)."""
        y1 = np.broadcast_to(np.asarray(y_mm, float), (self.count,)).copy()
        lo, hi = self.table.y_range
        if np.any(y1 < lo - 1e-9) or np.any(y1 > hi + 1e-9):
            raise ValueError(f"plate travel outside the map's {lo:.3g} to {hi:.3g} mm")
        self.valve = np.broadcast_to(np.asarray(valve_open, bool), (self.count,)).copy()
        # substeps only while a valve is open with the two sides apart (its flow is the
        # stiff part; once they have met, the implicit step follows the slow flow a plate's
        # motion drives as well as the substeps do)
        k = max(1, int(math.ceil(dt / self.substep_s - 1e-9))) if self._flowing() else 1
        y0 = self.y.copy()
        for s in range(1, k + 1):
            self._substep(y0 + (y1 - y0) * s / k, dt / k)
        self.t += dt
        return self.read()

    def _flowing(self) -> bool:
        if self.vr <= 0 or not self.valve.any():
            return False
        pr = (self.mr * self.gas.R * self.tr / self.vr - _PA) / 1e3
        return bool(np.abs(np.where(self.valve, pr - self.p, 0.0)).max() > SETTLED_KPA)

    def force_at(self, y_mm):
        """(force N, stiffness N/mm) each chamber would have at the travels ``y_mm`` now,
        its gas's mass and temperature held (no step taken): for a host that solves its
        contact against the chambers."""
        y = np.clip(np.broadcast_to(np.asarray(y_mm, float), (self.count,)),
                    *self.table.y_range)
        p = self._pressure(y, self.mc, self.tc, self.p)
        f, _ = self.table.lookup(self.table.F, y, p)
        y2 = np.minimum(y + 0.02, self.table.y_range[1])
        f2, _ = self.table.lookup(self.table.F, y2, self._pressure(y2, self.mc, self.tc, p))
        return f, np.where(y2 > y, (f2 - f) / np.maximum(y2 - y, 1e-12), 0.0)

    def read(self) -> dict:
        """What the chambers show now (see :meth:`step`)."""
        f, _ = self.table.lookup(self.table.F, self.y, self.p)
        _, stiff = self.force_at(self.y)
        pr = (self.mr * self.gas.R * self.tr / self.vr - _PA) / 1e3 if self.vr > 0 else \
            np.zeros(self.count)
        return {"force_N": f, "pressure_kPa": self.p.copy(), "measured_kPa": self._sense(),
                "reservoir_kPa": pr, "stiffness_N_per_mm": stiff,
                "temperature_K": self.tc.copy(), "t_s": self.t}

    def _sense(self):
        s = self.sensor
        if s is None:
            return self.p.copy()
        if self.t + 1e-12 >= self._next_sample:  # a new sample at the sensor's rate
            p = self.p + s.noise_kPa * self._rng.standard_normal(self.count)
            if s.resolution_kPa > 0:
                p = np.round(p / s.resolution_kPa) * s.resolution_kPa
            if s.full_scale_kPa > 0:
                p = np.clip(p, 0.0, s.full_scale_kPa)
            self._reading = p
            self._next_sample += 1.0 / s.rate_Hz
        return self._reading.copy()
