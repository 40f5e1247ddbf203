"""Force and depth from the chamber's pressure: the inverse of the chamber's quasi-static map for
the current mode and gas content, carried across valve switches, with its uncertainty.

The physics (the paper's eq. 2; sec. 2.1's two modes), for the gas at the ambient temperature:

* high mode (valve closed): the chamber's gas is conserved, P_abs V(y, P) = c_c;
* low mode (valve open, equalised): the chamber's and the reservoir's together,
  P_abs (V(y, P) + V_r) = c_c + c_r.

Air pressed in fractions of a second is not at the ambient temperature: with the gas's ratio
of heat capacities n and thermal time τ (``EstimatorParams.gas``, the ``gas`` of ``spsc
simulate``) its energy W = P_abs V_s is followed sample by sample (:mod:`.thermal`, eqs.
T1–T2) and the travel is read at the pressure the same gas would have at the ambient
temperature, P_iso = P_abs c/W − P_a, the force at the measured pressure, F(y, P). The
contact detectors and the rest tracker see P_iso: the cooling after a release is not a
contact, the cooling in a hold not a plate backing off. The isothermal gas (n = 1, the
default: the paper's static tests) has P_iso = P.

So from P and the current content the travel y follows, then F(y, P): one table P -> (y, F)
per content (:class:`~spsc.sensing.table.ForceTable`), rebuilt only when the content changes.
Across a switch the chamber's gas is conserved: opening pools c_c with the reservoir's gas at
its last known pressure (c_r = P_r,abs V_r); closing keeps the chamber's c_c = P_abs V(y, P)
of that instant (and the reservoir keeps P). While the valve equalises after an opening the
chamber is not at the pooled pressure yet: the travel is held (the plate does not move in the
valve's milliseconds) and F = F(y_held, P) follows the chamber's own pressure, until P reaches
the pooled table's pressure at that travel. While nothing touches the chamber its rest pressure
is tracked with its drift (temperature, leaks; :class:`~.rest.RestTracker`) and the content
re-based on it.

The pressure is smoothed by an α-β filter (constant rate: a steady press is followed without
lag). Uncertainty (a 95 % band): the sensor's noise σ_P through the filter and dF/dP of the
table, and the model's stated relative error e_m (a 95 % half-width, explicit: the paper states
no model-versus-bench error; the wall model is within 2.7 % of the 3D FEM, docs/theory/wall.md,
and a material's calibration adds its own),

    ΔF = √((1.96 σ_f dF/dP)² + (e_m F)²),   σ_f² = σ_P² (2α² + 2β − 3αβ)/(α (4 − 2α − β)),

α = 1 − exp(−Δt/τ_s), β = α²/(2 − α).
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from typing import NamedTuple

from spsc.core.errors import require
from spsc.dynamics.gas import Gas

from .rest import RestTracker
from .table import PA_KPA, DenseMap
from .thermal import compress_by, energy, invariant, iso_pressure, relax, relax_invariant

__all__ = ["EstimatorParams", "Estimator", "Estimate", "Z95"]

#: the two-sided 95 % quantile of the normal distribution
Z95 = 1.959964


@dataclass(frozen=True)
class EstimatorParams:
    """``setup_kPa`` the gauge pressure chamber and reservoir were filled to at rest,
    ``reservoir_mm3`` V_r, ``noise_kPa`` the sensor's σ_P, ``model_error`` e_m (relative, 95 %
    half-width of the model's force), ``smoothing_s`` τ_s of the α-β filter on P,
    ``rest_time_s`` the rest filter's time constant τ, ``rest_delay_s`` the age of the samples
it is fed (:class:`~.rest.RestTracker`), ``drift_step_kPa`` how far the tracked
    rest moves before the content is re-based, ``settle_max_s`` the longest wait for the
    valve to equalise after an opening, ``settle_still_s`` the window over which a pressure
    that has stopped moving ends that wait, ``valve_open`` the valve at the start, ``gas`` the
    air's n and thermal time (:class:`~spsc.dynamics.gas.Gas`; isothermal by default)."""

    setup_kPa: float
    reservoir_mm3: float
    noise_kPa: float
    model_error: float
    smoothing_s: float = 0.005
    rest_time_s: float = 2.0
    rest_delay_s: float = 0.3
    drift_step_kPa: float = 0.01
    settle_max_s: float = 0.5
    settle_still_s: float = 0.005
    valve_open: bool = False
    gas: Gas = Gas()

    def __post_init__(self):
        require("setup_kPa", self.setup_kPa, ge=0, le=1000, unit="kPa gauge")
        require("reservoir_mm3", self.reservoir_mm3, ge=0, le=1e8, unit="mm³")
        require("noise_kPa", self.noise_kPa, gt=0, le=100, unit="kPa, the sensor's σ")
        require("model_error", self.model_error, ge=0, lt=1, unit="relative, 95 %")
        require("smoothing_s", self.smoothing_s, ge=0, le=10, unit="s")
        require("rest_time_s", self.rest_time_s, gt=0, le=1e4, unit="s")
        require("rest_delay_s", self.rest_delay_s, ge=0, le=100, unit="s")
        require("drift_step_kPa", self.drift_step_kPa, gt=0, le=100, unit="kPa")
        require("settle_max_s", self.settle_max_s, gt=0, le=100, unit="s")
        require("settle_still_s", self.settle_still_s, gt=0, le=10, unit="s")
        if not isinstance(self.gas, Gas):
            from spsc.core.errors import ParameterError
            raise ParameterError("gas", self.gas, "a spsc.dynamics.Gas (n, thermal_time_s)")
        if self.valve_open and self.reservoir_mm3 <= 0:
            from spsc.core.errors import ParameterError
            raise ParameterError("valve_open", True, "False without a reservoir "
                                 "(reservoir_mm3 = 0)")


class Estimate(NamedTuple):
    """One sample's estimate: force (N) with its 95 % band, depth y (mm), the filtered
    pressure (kPa), whether P was inside the table, whether the valve is still settling, the
    filtered pressure at the ambient temperature (kPa, :mod:`.thermal`; the filtered pressure
    for the isothermal gas)."""

    force_N: float
    force_lo_N: float
    force_hi_N: float
    depth_mm: float
    pressure_kPa: float
    in_map: bool
    settling: bool
    iso_kPa: float


class Estimator:
    """The streaming estimator on ``dense`` (:class:`~.table.DenseMap`): :meth:`update` per
    sample, :meth:`switch` at a valve switch, :meth:`track_rest` while not in contact."""

    def __init__(self, dense: DenseMap, params: EstimatorParams):
        self.dense, self.params = dense, params
        self.open = bool(params.valve_open)
        self.p_res = params.setup_kPa  # the reservoir's last known pressure (at T_a)
        self.c_ch = dense.rest_content(params.setup_kPa)
        self.gas = params.gas
        self.c = self.w = None  # the shared gas's content at T_a and its W (kPa·mm³)
        self.s = None  # W's adiabatic invariant (eq. T2; None: to be taken from W and P)
        self.theta_r = 1.0  # the closed-off reservoir's T/T_a
        self._rebuild()
        self.p_s = self.t = self._raw = None
        self.a, self.b, self.v = 1.0, 0.0, 0.0
        self.noise_half = 0.0  # the last sample's band from the noise alone (N)
        self.y = self.table.y[0]
        self.settle = None  # (t of the opening, held travel, pooled pressure, tolerance)
        self.rest = RestTracker(self.table.rest_kPa, time_s=params.rest_time_s,
                                delay_s=params.rest_delay_s)
        self.offset = 0.0  # the held baseline less the table's rest, through a contact
        self.resting = True

    # -- the content ---------------------------------------------------------------------
    def _rebuild(self, w: float | None = None) -> None:
        """The tables of the current content; the shared gas's W is ``w``, or keeps its
        temperature (W/c) when the content is re-based."""
        vr = self.params.reservoir_mm3
        c_pool = self.c_ch + (self.p_res + PA_KPA) * vr
        pooled = self.dense.table(c_pool, vr) if vr > 0 else None
        # closed, the pooled table is what an opening would give (the switch inferred from P)
        self.table, self.pooled = (pooled, None) if self.open else \
            (self.dense.table(self.c_ch), pooled)
        c = c_pool if self.open else self.c_ch
        if w is not None:  # a switch: the invariant is taken again at the next sample
            self.w, self.s = w, None
        elif self.c is None:  # at rest at the setup pressure, at the ambient temperature
            self.w = c
            self.s = None if self.isothermal else invariant(
                c, self.params.setup_kPa + PA_KPA, self.gas.n)
        else:  # re-based: the same temperature, W and its invariant scaled with the content
            if self.s is not None:
                self.s += self.gas.n * math.log(c / self.c)
            self.w *= c / self.c
        self.c = c

    @property
    def isothermal(self) -> bool:
        return self.gas.isothermal

    def iso(self, p_kPa: float) -> float:
        """The gauge pressure (kPa) the shared gas would have at the ambient temperature at
        the present travel (:mod:`.thermal`, eq. T3); ``p_kPa`` itself for the isothermal
        gas."""
        if self.isothermal:
            return p_kPa
        return iso_pressure(p_kPa, self.w, self.c, PA_KPA, self.dense.compliance(self.y, p_kPa))

    def _heat(self, dt: float, p0: float, p1: float) -> None:
        """The shared gas's W over a sample: through its adiabatic invariant (eq. T2), or,
        while the valve equalises (the chamber's pressure not the pooled gas's), by eq. T1
        with the chamber's own volume change at the held travel; the closed-off reservoir's
        temperature relaxed."""
        if self.isothermal or dt <= 0.0:
            return
        n, tau = self.gas.n, self.gas.thermal_time_s
        if self.settle is not None:  # the chamber's wall moves with its own pressure
            y, vol = self.settle[1], self.dense.volume
            dv = self.dense.at(vol, y, p1) - self.dense.at(vol, y, p0)
            self.w = compress_by(self.w, self.c, dt, 0.5 * (p0 + p1) + PA_KPA, dv, n, tau)
            self.s = None
        else:
            if self.s is None:
                self.s = invariant(self.w, p0 + PA_KPA, n)
            self.s = relax_invariant(self.s, self.c, dt, p0 + PA_KPA, p1 + PA_KPA, n, tau)
            self.w = energy(self.s, p1 + PA_KPA, n)
        if not self.open:
            self.theta_r = relax(self.theta_r, 1.0, dt, tau)

    @property
    def rest_kPa(self) -> float:
        """The pressure of the current content with nothing touching."""
        return self.table.rest_kPa

    def pooled_pressure(self, y_mm: float) -> float | None:
        """The pressure the closed chamber would equalise to at ``y_mm`` if the valve opened
        now (None when open or without a reservoir)."""
        return None if self.pooled is None else self.pooled.pressure_at(y_mm)

    def switch(self, t_s: float, opened: bool, p_kPa: float, y_mm: float | None = None) -> dict:
        """The valve switched at ``t_s`` with the chamber at ``p_kPa`` (and the travel
        ``y_mm``, default the last estimate): the content carried over (the chamber's gas
        conserved). What it did, for the event."""
        if opened == self.open:
            return {}
        if opened and self.params.reservoir_mm3 <= 0:
            from spsc.core.errors import ParameterError
            raise ParameterError(f"valve_open (at t = {t_s:g} s)", 1, "0 without a reservoir "
                                 "(reservoir_mm3 = 0)")
        y = self.y if y_mm is None else y_mm
        if opened:
            before = self.table.rest_kPa
            self.open = True
            # the valve's throttling keeps the gases' energy: W adds up
            w_res = self.theta_r * (self.p_res + PA_KPA) * self.params.reservoir_mm3
            self._rebuild(w=self.w + w_res)
            p_eq = self.table.pressure_at(y)
            # within a σ of the pooled pressure the table's reading differs from the held
            # travel's by no more than its own noise: no jump at the hand-over
            tol = max(self.sigma_kPa, 0.005 * abs(p_kPa - p_eq))
            self.settle = (t_s, y, p_eq, tol, self.noise_half)
            # the samples since the opening, the last two windows of them (``_still``)
            self._opened_at, self._since_open = (t_s, p_kPa), deque([(t_s, p_kPa)])
            self.v = 0.0  # the valve's step is not the press's rate
            return {"valve": "open", "held_depth_mm": y, "pooled_kPa": float(p_eq),
                    "rest_before_kPa": before, "rest_after_kPa": self.table.rest_kPa}
        p = p_kPa if self.p_s is None else self.p_s
        # the pooled gas splits at one temperature θ = W/c: the chamber keeps W_c = P V(y, P)
        theta = self.w / self.c
        w_ch = self.dense.content(p, y)
        self.c_ch = w_ch / theta
        self.p_res = (p + PA_KPA) / theta - PA_KPA
        self.theta_r = theta
        self.open, self.settle = False, None
        self._rebuild(w=w_ch)
        return {"valve": "closed", "depth_mm": y, "reservoir_kPa": p,
                "rest_after_kPa": self.table.rest_kPa}

    @property
    def baseline_kPa(self) -> float:
        """The contact detectors' reference: the tracked rest while nothing touches (and it
        is settled), else the content's rest with the offset it had when contact began (a
        switch under load moves it with the content)."""
        if self.resting and self.rest.settled and self.t is not None:
            return self.rest.baseline(self.t)
        return self.table.rest_kPa + self.offset

    def track_rest(self, p_kPa: float) -> bool:
        """A sample with nothing touching: the rest tracker, and the content re-based when
        the rest has drifted ``drift_step_kPa``; True if it was."""
        if self.settle is not None or self.t is None:
            return False
        self.resting = True
        self.rest.push(self.t, p_kPa)
        if not self.rest.settled:
            return False
        rest = self.rest.baseline(self.t)
        rebased = abs(rest - self.table.rest_kPa) >= self.params.drift_step_kPa
        if rebased:
            self.c_ch = self.dense.rest_content(rest)
            if self.open:
                self.p_res = rest
            self._rebuild()
        self.offset = rest - self.table.rest_kPa
        return rebased

    def leave_rest(self) -> None:
        """Contact began: the baseline held (:meth:`~.rest.RestTracker.hold`)."""
        if self.t is not None:
            self.offset = self.rest.hold(self.t) - self.table.rest_kPa
        self.resting = False

    def depth_at(self, p_kPa: float) -> float:
        """The travel (mm) at the gauge pressure ``p_kPa`` for the current content."""
        return self.table.lookup(p_kPa)[0]

    # -- one sample ----------------------------------------------------------------------
    @property
    def sigma_kPa(self) -> float:
        """σ of the filtered pressure (kPa): the α-β filter's steady state,
        σ_f² = σ_P² (2α² + 2β − 3αβ)/(α (4 − 2α − β))."""
        a, b = self.a, self.b
        return self.params.noise_kPa * math.sqrt((2 * a * a + 2 * b - 3 * a * b)
                                                 / (a * (4 - 2 * a - b)))

    def _filter(self, dt: float, z: float) -> None:
        """The α-β (constant-rate) filter on P: no lag on a steady press, unlike a one-pole
        filter; α = 1 − exp(−Δt/τ_s), β = α²/(2 − α) (critically damped)."""
        tau = self.params.smoothing_s
        self._dt = dt
        a = 1.0 - math.exp(-dt / tau) if tau > 0 else 1.0
        self.a, self.b = a, a * a / (2.0 - a)
        if self.settle is not None:  # the valve's exponential fall: no rate to follow
            self.b = self.v = 0.0
        pred = self.p_s + self.v * dt
        r = z - pred
        self.p_s = pred + a * r
        self.v += self.b * r / dt

    def update(self, t_s: float, p_kPa: float) -> Estimate:
        """The estimate at the sample (``t_s`` s, ``p_kPa`` gauge)."""
        p0, raw0 = self.p_s, self._raw
        self._raw = p_kPa
        dt = 0.0
        if self.p_s is None:
            self.p_s, self.v, self._dt = p_kPa, 0.0, 0.0
        else:
            dt = t_s - self.t
            self._filter(dt, p_kPa)
        self.t = t_s
        p = self.p_s
        if self.settle is not None:
            # the valve's fall outruns the filter: the gas's work from the raw samples
            if p0 is not None:
                self._heat(dt, raw0, p_kPa)
            t0, y, p_eq, tol, _ = self.settle
            h = self._since_open
            h.append((t_s, p_kPa))
            while h[0][0] <= t_s - 2.0 * self.params.settle_still_s:
                h.popleft()
            still = self._still()
            if abs(self.iso(p) - p_eq) <= tol or t_s - t0 > self.params.settle_max_s or still:
                self.settle = None
                # the filter starts again from the equalised pressure, not from its lag
                last = [x for s, x in self._since_open
                        if s > t_s - self.params.settle_still_s]
                self.p_s = p = sum(last) / len(last)
                self.v, p0 = 0.0, None
        elif p0 is not None:
            self._heat(dt, p0, p)
        q = self.iso(p)
        sigma = self.sigma_kPa
        if self.settle is not None:
            # at the held travel F barely depends on P (0.1 N/kPa on the Type B dome): the raw
            # sample, not the filter lagging the valve's fall
            y, sigma = self.settle[1], self.params.noise_kPa
            f = self.dense.at(self.dense.force, y, p_kPa)
            dp = 0.05
            slope = (self.dense.at(self.dense.force, y, p_kPa + dp) - f) / dp
            inside = True
            # and the held travel is as uncertain as it was read at the switch
            noise = math.hypot(Z95 * sigma * slope, self.settle[4])
        elif self.isothermal:
            y, f, slope, inside = self.table.lookup(p)
            noise = self.noise_half = Z95 * sigma * slope
        else:
            y, f, inside = self._read(p, self.w)
            # dF/dP along an adiabatic step of the pressure (it moves W too)
            dp = 0.05
            pd = p + dp
            wd = self.w if self.s is None else energy(self.s, pd + PA_KPA, self.gas.n)
            slope = (self._read(pd, wd)[1] - f) / dp
            noise = self.noise_half = Z95 * sigma * abs(slope)
        self.y = y
        half = math.hypot(noise, self.params.model_error * f)
        return Estimate(f, max(f - half, 0.0), f + half, y, p, inside, self.settle is not None,
                        q)

    def _still(self) -> bool:
        """The valve has equalised although the pressure is not the pooled one at the held
        travel (a force-controlled press moves the plate as the chamber softens): over the
        last two windows of ``settle_still_s`` the mean pressure moved less than 3 σ of its
        noise and 2 % of its fall since the opening."""
        w, h = self.params.settle_still_s, self._since_open
        t = h[-1][0]
        t0, p0 = self._opened_at
        if t - t0 < 2.0 * w:
            return False
        last = [p for s, p in h if s > t - w]
        before = [p for s, p in h if t - 2.0 * w < s <= t - w]
        if len(last) < 3 or len(before) < 3:
            return False
        a, b = sum(last) / len(last), sum(before) / len(before)
        need = max(3.0 * self.params.noise_kPa * math.sqrt(2.0 / len(last)),
                   0.02 * abs(p0 - a))
        return abs(a - b) < need

    def _read(self, p: float, w: float) -> tuple[float, float, bool]:
        """(y, F, within the map) at the measured ``p`` (kPa) with the shared gas's energy
        ``w``: the cavity holds V = W/(P + P_a) − V_e at P (the chamber's compliance at the
        measured pressure, not at the isothermal one), the travel is where the map's V(y, P)
        is that, the force F(y, P)."""
        ve = self.params.reservoir_mm3 if self.open else 0.0
        y, inside = self.dense.travel(w / (p + PA_KPA) - ve, p)
        if y <= self.table.y[0]:
            return self.table.y[0], 0.0, inside
        return y, max(self.dense.at(self.dense.force, y, p), 0.0), inside
