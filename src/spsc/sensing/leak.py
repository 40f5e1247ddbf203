"""A leak at rest (the paper's sec. 3.2 leak test: inflated, isolated, watched for 30 minutes):
a slow loss of the rest pressure at a steady rate, told from the thermal drift the rest
tracker follows (:mod:`.rest`) and from a contact's release.

An orifice leak from a chamber at 40 kPa loses its gas at a rate that changes by 0.7 % per kPa
lost (:mod:`spsc.dynamics.leak`): over a leak test the loss is a straight line. The room's
temperature moves the pressure too (1 K is 0.48 kPa at 40 kPa gauge), but it swings and comes
back. So the detector fits the rest pressure over ``window_s`` (the test's 30 minutes by
default; samples in contact are left out) and calls a leak when

* the line lost at least ``min_drop_kPa`` over the window, ``sigmas`` standard errors beyond
  zero (the residuals' scatter), and
* the loss was steady: each of ``parts`` equal sub-windows lost at a rate within ``spread``
  of the whole window's (a swing that turns back, a step from a valve switched in contact,
  do not).

The rest samples are averaged over ``bin_s`` (the fit's points: 1,800 over a 30-minute
window whatever the sampling rate), and the event gives the loss rate (kPa/min, and the leak
test's kPa per 30 minutes) and the temperature fall that would explain the same loss if the
room cooled steadily all along (a steady cooling cannot be told from a leak by the pressure
alone). Once a leak is called the next is armed a window later.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

import numpy as np

from spsc.core.constants import P_AMB_KPA
from spsc.core.errors import require

from .protocol import Context, Sample

__all__ = ["LeakParams", "LeakDetector"]

_T_ROOM = 293.15  # K: the temperature a loss is converted at (ISO 8778)


@dataclass(frozen=True)
class LeakParams:
    """A leak: ``min_drop_kPa`` lost over ``window_s`` at a steady rate (see the module)."""

    window_s: float = 1800.0
    min_drop_kPa: float = 0.2
    sigmas: float = 5.0
    parts: int = 3
    spread: float = 0.5
    bin_s: float = 1.0
    min_rest: float = 0.8  # the share of the window that must be at rest

    def __post_init__(self):
        require("leak window_s", self.window_s, gt=0, le=1e6, unit="s")
        require("leak min_drop_kPa", self.min_drop_kPa, gt=0, le=1e3, unit="kPa")
        require("leak sigmas", self.sigmas, ge=0, le=100)
        require("leak parts", self.parts, ge=2, le=20)
        require("leak spread", self.spread, gt=0, lt=1)
        require("leak bin_s", self.bin_s, gt=0, le=self.window_s / 10,
                unit="s, at most a tenth of the window")
        require("leak min_rest", self.min_rest, gt=0, le=1)


class LeakDetector:
    """The rest pressure's bins over the last window, fitted at each new bin (1,800 points
    once a second at the defaults: a few tens of microseconds a sample on average)."""

    name, Params = "leak", LeakParams
    kinds = {"leak": "C9"}

    def __init__(self, params: LeakParams, context: Context | None = None):
        self.prm = params
        self.bins: deque = deque()  # (t mid, mean P) of the rest samples
        self.acc = None  # the open bin: [start, sum t, sum P, n]
        self.armed_at = -math.inf

    def detect(self, s: Sample) -> dict | None:
        """The rest samples (not in contact, the rest tracker settled) binned and fitted."""
        if s.in_contact or not s.settled or not math.isfinite(s.pressure_kPa):
            return None
        return self.push(s.t_s, s.pressure_kPa)

    def push(self, t: float, p: float) -> dict | None:
        acc, prm = self.acc, self.prm
        if acc is not None and t - acc[0] >= prm.bin_s:
            self.bins.append((acc[1] / acc[3], acc[2] / acc[3]))
            self.acc = acc = None
            while self.bins and t - self.bins[0][0] > prm.window_s:
                self.bins.popleft()
            event = self._judge(t)
            if event is not None:
                self.acc = [t, t, p, 1]
                return event
        if acc is None:
            self.acc = [t, t, p, 1]
        else:
            acc[1] += t
            acc[2] += p
            acc[3] += 1
        return None

    def _judge(self, t: float) -> dict | None:
        prm, bins = self.prm, self.bins
        if t < self.armed_at or len(bins) < prm.min_rest * prm.window_s / prm.bin_s \
                or bins[-1][0] - bins[0][0] < (1.0 - 2.0 * prm.bin_s / prm.window_s) \
                * prm.window_s:
            return None
        tb, pb = np.array(bins).T
        rate, se = _slope(tb, pb)
        drop = -rate * prm.window_s
        if drop < prm.min_drop_kPa or -rate < prm.sigmas * se:
            return None
        edges = np.linspace(tb[0], tb[-1], prm.parts + 1)
        for a, b in zip(edges[:-1], edges[1:]):
            part = (tb >= a) & (tb <= b)
            if part.sum() < 3:
                return None
            r, _ = _slope(tb[part], pb[part])
            if not (1.0 - prm.spread) * rate >= r >= (1.0 + prm.spread) * rate:
                return None
        self.armed_at = t + prm.window_s
        p_abs = float(pb.mean()) + P_AMB_KPA
        cooling = drop / p_abs * _T_ROOM
        per_min = -rate * 60.0
        return {"t_s": t, "kind": "leak", "rate_kPa_per_min": per_min,
                "rate_kPa_per_30min": -rate * 1800.0, "drop_kPa": drop,
                "window_s": float(tb[-1] - tb[0]),
                "trigger": f"the rest pressure fell {drop:.3g} kPa over {tb[-1] - tb[0]:.0f} s "
                f"at a steady {per_min:.3g} kPa/min ({-rate * 1800:.3g} kPa per 30 min; "
                f"as much as a room cooling {cooling:.2g} K all along)"}


def _slope(t: np.ndarray, p: np.ndarray) -> tuple[float, float]:
    """(the least-squares slope of p(t), its standard error)."""
    tc = t - t.mean()
    sxx = float(tc @ tc)
    rate = float(tc @ (p - p.mean())) / sxx
    resid = p - p.mean() - rate * tc
    dof = max(len(t) - 2, 1)
    return rate, math.sqrt(float(resid @ resid) / dof / sxx)
