"""The rest pressure while nothing touches the chamber: its level and its drift (temperature,
a slow leak), for the contact detectors' baseline and the estimator's gas content.

A one-pole filter lags a drift of r kPa/s by r τ: the paper's ELVH at 1 kHz (σ 0.086 kPa)
warming by 0.02 kPa/s under a 2 s filter reads 0.04 kPa (half a σ) above its rest, which is a
contact to a detector tuned for shifts of a quarter σ. So the rest is a critically damped α-β
(level and rate) filter, which follows a steady drift without lag,

    α = 1 − exp(−Δt/τ),  β = α²/(2 − α),

fed with samples ``delay_s`` old: a press's first, slow rise (a soft object, the low mode)
is not learnt as drift before the detector has seen it. The baseline now is the level
extrapolated over the delay at the filtered rate. Until the filter's memory is the shorter,
the gains are those of the least-squares line through every sample so far (the expanding
memory filter, α_n = 2(2n − 1)/(n(n + 1)), β_n = 6/(n(n + 1))), the setup pressure counting
as ``prior_s`` of samples on a flat line. After a contact the level is acquired again from
the samples that follow it (their running mean along the rate learnt before, α_n = 1/n); until
``acquire_s`` of them have been seen the baseline is the one held through the contact
(:attr:`RestTracker.settled` is False).
"""

from __future__ import annotations

import math
from collections import deque

__all__ = ["RestTracker"]


class RestTracker:
    """``push`` the samples taken at rest; :attr:`baseline` the rest pressure now (kPa).
    ``level_kPa`` the rest at the start (the setup pressure), trusted as ``prior_s`` of
    samples; ``time_s`` τ; ``delay_s``; ``acquire_s``."""

    def __init__(self, level_kPa: float, *, time_s: float, delay_s: float = 0.3,
                 acquire_s: float = 0.1, prior_s: float = 0.5):
        self.tau, self.delay, self.acquire = time_s, delay_s, acquire_s
        self.level, self.rate = float(level_kPa), 0.0
        self.t_level = None  # the time of the last sample the level has seen
        self.prior, self.n, self.fit_rate = prior_s, None, True
        self.seen = prior_s  # s of samples behind the level
        self.buf = deque()
        self.held = self.level

    @property
    def settled(self) -> bool:
        return self.seen >= self.acquire

    def baseline(self, t: float) -> float:
        """The rest at ``t``: the level carried to ``t`` at its rate (at most over the delay
        and the filter's time: a rate is not extrapolated into the unknown), or the held
        value until settled."""
        if not self.settled or self.t_level is None:
            return self.held
        return self.level + self.rate * min(t - self.t_level, self.delay + self.tau)

    def push(self, t: float, p: float) -> None:
        buf = self.buf
        buf.append((t, p))
        while buf and buf[0][0] <= t - self.delay:
            self._update(*buf.popleft())

    def _update(self, t: float, p: float) -> None:
        if self.t_level is None:
            self.t_level = t
            if self.n == 0:  # after a contact: the level from the samples that follow
                self.level, self.n = p, 1
            return
        dt = t - self.t_level
        if dt <= 0.0:
            return
        if self.n is None:  # the prior's weight in samples, now that Δt is known
            self.n = max(round(self.prior / dt), 1)
        self.n += 1
        a_ss = 1.0 - math.exp(-dt / self.tau)
        n = self.n
        a, b = (2.0 * (2 * n - 1) / (n * (n + 1)), 6.0 / (n * (n + 1))) if self.fit_rate \
            else (1.0 / n, 0.0)
        if a <= a_ss:
            a, b = a_ss, a_ss * a_ss / (2.0 - a_ss)
        pred = self.level + self.rate * dt
        self.level = pred + a * (p - pred)
        self.rate += b * (p - pred) / dt
        self.t_level = t
        self.seen += dt

    def hold(self, t: float) -> float:
        """Contact began at ``t``: the baseline is held, the samples not yet used are
        dropped (they may hold the press's first rise), the next rest is acquired anew."""
        self.held = self.baseline(t)
        self.buf.clear()
        self.level, self.t_level, self.seen = self.held, None, 0.0
        self.n, self.fit_rate = 0, False
        return self.held
