"""Contact and release from the pressure against the noise σ_P of the sensor, two detectors,
one sample at a time in O(1):

* :class:`ThresholdContact`, the paper's (sec. 4.1, Fig. 10a: "threshold values on the pressure
  and its first derivative"): the filtered rise ΔP = P_f − P_rest above ``on`` while dP/dt is
  above ``rate`` (a rising pressure, not a drift), or above 2 ``on`` whatever the rate; release
  below ``off`` < ``on`` (the hysteresis);
* :class:`CusumContact`, Page's CUSUM on z = (P − P_rest)/σ_P: g⁺ = max(0, g⁺ + z − k),
  contact when g⁺ > h; once in contact g⁻ = max(0, g⁻ + k_r − z), release when g⁻ > h_r
  (k_r < k: the hysteresis — a mean between k_r σ and k σ above the rest moves neither). It
  integrates the evidence of every sample (optimal for a shift of 2kσ) instead of waiting for a
  smoothed level to cross a line, and gives the onset's time: the last sample g⁺ was 0. Its
  false-alarm run length is of order e^(2k(h + 1.166))/(2k²) samples (Siegmund's
  approximation): about 10¹¹ at k = 1, h = 12, and 7·10⁹ (80 days at 1 kHz) at the slow
  scale's k = 0.25, h = 40, which sees a shift of half a σ within 160 samples where the first
  never does.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

from spsc.core.errors import ParameterError, require

__all__ = ["ContactParams", "ThresholdContact", "CusumContact", "Slope", "CONTACT_DETECTORS",
           "CONTACT_KINDS", "contact_detector", "release_reference"]

#: the events of a contact detector and their colours in ``sense.png``
CONTACT_KINDS = {"contact": "C2", "release": "C3"}


@dataclass(frozen=True)
class ContactParams:
    """``method`` cusum|threshold. CUSUM: ``k``, ``h`` (σ) of the contact, ``k_slow``,
    ``h_slow`` of its second, slow scale (``k_slow`` 0: none), ``k_release``, ``h_release``
    of the release (the largest k_r; :class:`CusumContact`). Threshold: ``on_sigmas``,
    ``off_sigmas`` (of the filtered pressure's σ), ``rate_sigmas`` (of the slope's σ over
    ``rate_window_s``)."""

    method: str = "cusum"
    k: float = 1.0
    h: float = 12.0
    k_slow: float = 0.25
    h_slow: float = 40.0
    k_release: float = 0.5
    h_release: float = 8.0
    on_sigmas: float = 5.0
    off_sigmas: float = 2.0
    rate_sigmas: float = 3.0
    rate_window_s: float = 0.02

    def __post_init__(self):
        if self.method not in CONTACT_DETECTORS:
            raise ParameterError("contact method", self.method, " or ".join(CONTACT_DETECTORS))
        require("contact k", self.k, gt=0, le=20, unit="σ")
        require("contact h", self.h, gt=0, le=1000, unit="σ")
        require("contact k_slow", self.k_slow, ge=0, lt=self.k, unit="σ, below k (0: none)")
        require("contact h_slow", self.h_slow, gt=0, le=1000, unit="σ")
        require("contact k_release", self.k_release, gt=0, le=self.k, unit="σ, <= k")
        require("contact h_release", self.h_release, gt=0, le=1000, unit="σ")
        require("contact on_sigmas", self.on_sigmas, gt=0, le=100)
        require("contact off_sigmas", self.off_sigmas, ge=0, lt=self.on_sigmas,
                unit="below on_sigmas")
        require("contact rate_sigmas", self.rate_sigmas, ge=0, le=100)
        require("contact rate_window_s", self.rate_window_s, gt=0, le=10, unit="s")


class Slope:
    """dP/dt (kPa/s) over the last ``n`` samples: the mean of the newer half less the mean of
    the older, over the time between the halves' centres (running sums: O(1))."""

    def __init__(self, n: int):
        self.half = max(n // 2, 1)
        self.buf = deque(maxlen=2 * self.half)
        self.new = self.old = 0.0

    def push(self, t: float, p: float) -> float | None:
        b, h = self.buf, self.half
        if len(b) == 2 * h:
            mid = b[h][1]  # moves from the newer half to the older
            self.old += mid - b[0][1]
            self.new += p - mid
            b.append((t, p))
        else:
            b.append((t, p))
            if len(b) < 2 * h:
                return None
            values = [x for _, x in b]
            self.old, self.new = sum(values[:h]), sum(values[h:])
        dt = (b[-1][0] + b[h][0] - b[h - 1][0] - b[0][0]) / 2.0
        return (self.new - self.old) / h / dt if dt > 0 else None


class ThresholdContact:
    """The paper's contact detector (sec. 4.1): levels and rate on the filtered pressure."""

    name, kinds = "threshold", CONTACT_KINDS

    def __init__(self, params: ContactParams, noise_kPa: float, rate_Hz: float):
        self.prm, self.noise = params, noise_kPa
        n = max(int(round(params.rate_window_s * rate_Hz)), 2)
        self.slope = Slope(n)
        h = self.slope.half
        # the slope's σ: two means of h samples, h samples apart
        self.rate_sigma = noise_kPa * math.sqrt(2.0 / h) * rate_Hz / h
        self.contact = False

    def push(self, t: float, p_raw: float, p_f: float, sigma_f: float, rest: float,
             settled: bool = True) -> dict | None:
        rate = self.slope.push(t, p_f)
        rise, prm = p_f - rest, self.prm
        if not self.contact:
            on = prm.on_sigmas * sigma_f
            rising = rate is not None and rate > prm.rate_sigmas * self.rate_sigma
            if (rise > on and rising) or rise > 2.0 * on:
                self.contact = True
                return {"t_s": t, "kind": "contact", "detector": "threshold",
                        "trigger": f"ΔP {rise:.4g} kPa > {on:.3g} kPa"
                        + (f" and dP/dt {rate:.3g} kPa/s" if rising else " (2× the level)")}
            return None
        if rise < prm.off_sigmas * sigma_f:
            self.contact = False
            return {"t_s": t, "kind": "release", "detector": "threshold",
                    "trigger": f"ΔP {rise:.4g} kPa < {prm.off_sigmas * sigma_f:.3g} kPa"}
        return None

    def rebase(self, level: float) -> None:
        """The paper's detector keeps its levels across a valve switch."""


class _Page:
    """One scale of the CUSUM: g = max(0, g + z − k), the samples since g was last 0 and
    the time of that sample (the onset's estimate)."""

    def __init__(self, k: float, h: float):
        self.k, self.h = k, h
        self.g, self.n, self.since = 0.0, 0, None

    def push(self, t: float, z: float) -> bool:
        if self.since is None:  # a log that starts in contact: the onset is its start
            self.since = t
        g = self.g + z - self.k
        if g <= 0.0:
            self.g, self.n, self.since = 0.0, 0, t
            return False
        self.g, self.n = g, self.n + 1
        return g > self.h

    def level(self) -> float:
        """The mean z since the onset (σ): g = Σ (z − k) over those samples."""
        return self.g / self.n + self.k if self.n else self.k

    def reset(self, t: float) -> None:
        self.g, self.n, self.since = 0.0, 0, t


class CusumContact:
    """Page's CUSUM on z = (P − P_rest)/σ_P at two scales, for the press that moves the
    pressure by many σ (``k``, ``h``: a few samples) and for the one that moves it by a
    fraction of σ (``k_slow``, ``h_slow``: the low mode's first millimetre, a soft object),
    each with its false-alarm run length of order 10¹⁰ samples or more. The slow scale runs
    only while the rest is known to a small fraction of σ (``settled``, see
    :class:`~.rest.RestTracker`). The release's k_r is an eighth of the contact's mean
    level since its onset (in σ), at most ``k_release`` and at least 0.2, with
    h_r = h_release k_release / k_r: a press many σ high is released at ``k_release`` as
    before, a low-mode contact of one to three σ when it is back near the rest, not when it
    has fallen below a fixed half σ it never rose far above (a finger opening slowly unloads
    the chamber over half a second, and its last millimetre moves the pressure by less than
    half a σ: the release is where the load is gone, not where it halved). In the hold the
    release's drift is −k_r a sample or less (a contact of 0.4 σ at the floor; 0.6 σ: −2 k_r),
    a false release rarer than one in 10⁶ samples."""

    name, kinds = "cusum", CONTACT_KINDS

    def __init__(self, params: ContactParams, noise_kPa: float, rate_Hz: float):
        self.prm, self.noise = params, noise_kPa
        self.scales = [_Page(params.k, params.h)]
        if params.k_slow > 0:
            self.scales.append(_Page(params.k_slow, params.h_slow))
        self.g, self.contact, self.n, self.sum = 0.0, False, 0, 0.0
        self.rate = rate_Hz

    def push(self, t: float, p_raw: float, p_f: float, sigma_f: float, rest: float,
             settled: bool = True) -> dict | None:
        z = (p_raw - rest) / self.noise
        if not self.contact:
            fired = None
            for i, s in enumerate(self.scales):
                if i and not settled:
                    s.reset(t)
                elif s.push(t, z) and fired is None:
                    fired = s
            if fired is None:
                return None
            self.contact, self.g = True, 0.0
            self.n, self.sum = max(fired.n, 1), fired.level() * max(fired.n, 1)
            onset = fired.since
            for s in self.scales:
                s.reset(t)
            slow = " (the slow scale)" if fired is not self.scales[0] else ""
            return {"t_s": t, "kind": "contact", "detector": "cusum", "onset_s": onset,
                    "trigger": f"CUSUM of (P − P_rest)/σ above {fired.h:g} at k = {fired.k:g}"
                    f"{slow}, a mean {self.sum / self.n:.3g} σ since "
                    f"{onset:.4g} s (rest {rest:.4g} kPa, P {p_raw:.4g} kPa)"}
        self.n, self.sum = self.n + 1, self.sum + z
        k_r, h_r = release_reference(self.sum / self.n, self.prm)
        self.g = max(0.0, self.g + k_r - z)
        if self.g > h_r:
            self.contact, self.g = False, 0.0
            for s in self.scales:
                s.reset(t)
            return {"t_s": t, "kind": "release", "detector": "cusum",
                    "trigger": f"CUSUM of the return to the rest ({rest:.4g} kPa) above "
                    f"{h_r:.3g} at k = {k_r:.3g} (the contact's mean level "
                    f"{self.sum / self.n:.3g} σ)"}
        return None

    def rebase(self, level: float) -> None:
        """A valve switch in contact: the pressure's level is now ``level`` σ above the rest
        (an opening: the pooled pressure at the held travel), and the release's statistics
        start again from it, as if 0.2 s of samples had shown it — the high mode's level is
        not what the low mode's pressure will be measured against."""
        if self.contact:
            self.n = max(int(0.2 * self.rate), 1)
            self.sum, self.g = self.n * max(level, 0.0), 0.0


def release_reference(mean: float, prm: ContactParams) -> tuple[float, float]:
    """The release's (k_r, h_r) for a contact whose mean level is ``mean`` σ: k_r an eighth
    of it, between 0.2 (or half the level, below 0.4 σ) and ``k_release``; h_r =
    h_release k_release / k_r, or more where a false release in the hold (a drift of
    k_r − mean a sample) would come sooner than once in 10⁶ samples."""
    k_r = max(min(prm.k_release, max(mean / 8.0, min(0.2, mean / 2.0))), 0.05)
    h_r = prm.h_release * prm.k_release / k_r
    d = mean - k_r
    if d > 0.0:
        h_r = max(h_r, math.log(2.0 * d * d * 1e6) / (2.0 * d) - 1.166)
    return k_r, h_r


#: ``ContactParams.method`` -> the contact detector's class, built as ``cls(params,
#: noise_kPa, rate_Hz)``
CONTACT_DETECTORS = {"cusum": CusumContact, "threshold": ThresholdContact}


def contact_detector(params: ContactParams, noise_kPa: float, rate_Hz: float):
    """The contact detector ``params.method`` names (a
    :class:`~.protocol.ContactDetector`)."""
    return CONTACT_DETECTORS[params.method](params, noise_kPa, rate_Hz)
