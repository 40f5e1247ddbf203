"""Events from the pressure (and the FSRs and the finger's closure): contact and release, slip,
the object's compliance, a valve switch inferred from the pressure. Each detector takes one
sample at a time in O(1) and returns an event (a dict) or None.

Contact, two detectors against the noise σ_P of the sensor:

* :class:`ThresholdContact`, the paper's (sec. 4.1, Fig. 10a: "threshold values on the pressure
  and its first derivative"): the filtered rise ΔP = P_f − P_rest above ``on`` while dP/dt is
  above ``rate`` (a rising pressure, not a drift), or above 2 ``on`` whatever the rate; release
  below ``off`` < ``on`` (the hysteresis);
* :class:`CusumContact`, Page's CUSUM on z = (P − P_rest)/σ_P: g⁺ = max(0, g⁺ + z − k),
  contact when g⁺ > h; once in contact g⁻ = max(0, g⁻ + k_r − z), release when g⁻ > h_r
  (k_r < k: the hysteresis — a mean between k_r σ and k σ above the rest moves neither). It
  integrates the evidence of every sample (optimal for a shift of 2kσ) instead of waiting for a
  smoothed level to cross a line, and gives the onset's time: the last sample g⁺ was 0. Its
  false-alarm run length at k = 1, h = 12 is of order e^(2k(h + 1.166))/(2k²) ≈ 10¹¹ samples
  (Siegmund's approximation).
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

from spsc.core.errors import require

__all__ = ["ContactParams", "ThresholdContact", "CusumContact", "Slope", "SlipParams",
           "SlipDetector", "ComplianceParams", "ComplianceDetector"]


@dataclass(frozen=True)
class ContactParams:
    """``method`` cusum|threshold. CUSUM: ``k``, ``h`` (σ) of the contact, ``k_release``,
    ``h_release`` of the release. Threshold: ``on_sigmas``,
    ``off_sigmas`` (of the filtered pressure's σ), ``rate_sigmas`` (of the slope's σ over
    ``rate_window_s``)."""

    method: str = "cusum"
    k: float = 1.0
    h: float = 12.0
    k_release: float = 0.5
    h_release: float = 8.0
    on_sigmas: float = 5.0
    off_sigmas: float = 2.0
    rate_sigmas: float = 3.0
    rate_window_s: float = 0.02

    def __post_init__(self):
        if self.method not in ("cusum", "threshold"):
            from spsc.core.errors import ParameterError
            raise ParameterError("contact method", self.method, "cusum or threshold")
        require("contact k", self.k, gt=0, le=20, unit="σ")
        require("contact h", self.h, gt=0, le=1000, unit="σ")
        require("contact k_release", self.k_release, ge=0, le=self.k, unit="σ, <= k")
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

    def __init__(self, params: ContactParams, noise_kPa: float, rate_Hz: float):
        self.prm, self.noise = params, noise_kPa
        n = max(int(round(params.rate_window_s * rate_Hz)), 2)
        self.slope = Slope(n)
        h = self.slope.half
        # the slope's σ: two means of h samples, h samples apart
        self.rate_sigma = noise_kPa * math.sqrt(2.0 / h) * rate_Hz / h
        self.contact = False

    def push(self, t: float, p_raw: float, p_f: float, sigma_f: float,
             rest: float) -> dict | None:
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


class CusumContact:
    """Page's two-sided CUSUM on the raw pressure against the rest, in units of σ_P."""

    def __init__(self, params: ContactParams, noise_kPa: float, rate_Hz: float):
        self.prm, self.noise = params, noise_kPa
        self.g, self.since, self.contact = 0.0, None, False

    def push(self, t: float, p_raw: float, p_f: float, sigma_f: float,
             rest: float) -> dict | None:
        z, k, h = (p_raw - rest) / self.noise, self.prm.k, self.prm.h
        if not self.contact:
            self.g = max(0.0, self.g + z - k)
            if self.g == 0.0:
                self.since = t
            if self.g > h:
                self.contact, self.g = True, 0.0
                return {"t_s": t, "kind": "contact", "detector": "cusum",
                        "onset_s": self.since,
                        "trigger": f"CUSUM of (P − P_rest)/σ above {h:g} (rest "
                        f"{rest:.4g} kPa, P {p_raw:.4g} kPa)"}
            return None
        self.g = max(0.0, self.g + self.prm.k_release - z)
        if self.g > self.prm.h_release:
            self.contact, self.g, self.since = False, 0.0, t
            return {"t_s": t, "kind": "release", "detector": "cusum",
                    "trigger": f"CUSUM of the return to the rest ({rest:.4g} kPa) above "
                    f"{self.prm.h_release:g}"}
        return None


def contact_detector(params: ContactParams, noise_kPa: float, rate_Hz: float):
    """The contact detector ``params.method`` names."""
    cls = CusumContact if params.method == "cusum" else ThresholdContact
    return cls(params, noise_kPa, rate_Hz)


@dataclass(frozen=True)
class SlipParams:
    """Slip (sec. 4.1, Fig. 10b): over ``window_s`` the filtered pressure fell by more than
    ``drop_sigmas`` σ and ``drop_fraction`` of its rise, while the FSRs' centroid moved
    ``shift`` (fraction of the array, toward fsr_N, the tip) with at least ``fsr_min_N`` on
    them. ``fsr_min_N`` is 25 times a typical FSR channel's noise (0.01 N): with less on the
    array, as a hand lets go, the noise alone moves the centroid by a tenth of the array."""

    window_s: float = 0.05
    drop_sigmas: float = 4.0
    drop_fraction: float = 0.05
    shift: float = 0.15
    fsr_min_N: float = 0.25

    def __post_init__(self):
        require("slip window_s", self.window_s, gt=0, le=10, unit="s")
        require("slip drop_sigmas", self.drop_sigmas, ge=0, le=100)
        require("slip drop_fraction", self.drop_fraction, ge=0, lt=1)
        require("slip shift", self.shift, gt=0, le=1, unit="fraction of the FSR array")
        require("slip fsr_min_N", self.fsr_min_N, ge=0, unit="N")


def centroid(fsr) -> tuple[float, float]:
    """(position 0 (fsr_1, the base) … 1 (fsr_N, the tip), total N) of the FSR readings."""
    total = sum(fsr)
    n = len(fsr)
    if total <= 0 or n < 2:
        return math.nan, total
    return sum(i * f for i, f in enumerate(fsr)) / total / (n - 1), total


class SlipDetector:
    """A pressure drop with the contact moving toward the tip, once per episode: the next
    slip is armed when the pressure has stopped falling and the centroid has stopped moving
    (in the low mode the drop is within a few σ and flickers across its bound mid-slide)."""

    def __init__(self, params: SlipParams):
        self.prm = params
        self.hist = deque()
        self.armed = True

    def push(self, t, p_f, sigma_f, rest, fsr, in_contact) -> dict | None:
        h, prm = self.hist, self.prm
        c, total = centroid(fsr)
        h.append((t, p_f, c, total))
        while h and t - h[0][0] > prm.window_s:
            h.popleft()
        t0, p0, c0, tot0 = h[0]
        drop = p0 - p_f
        need = max(prm.drop_sigmas * sigma_f, prm.drop_fraction * (p0 - rest))
        moved = c - c0 if not (math.isnan(c) or math.isnan(c0)) else math.nan
        slipping = (in_contact and drop > need and moved > prm.shift
                    and min(total, tot0) >= prm.fsr_min_N)
        if slipping and self.armed:
            self.armed = False
            return {"t_s": t, "kind": "slip", "trigger": f"P fell {drop:.3g} kPa and the FSR "
                    f"centroid moved {moved:+.2f} toward the tip in {t - t0:.3g} s",
                    "drop_kPa": drop, "centroid_shift": moved}
        still = not (moved > 0.5 * prm.shift)  # a NaN centroid (nothing on it) is still
        if not slipping and drop <= 0.5 * need and still:
            self.armed = True
        return None


@dataclass(frozen=True)
class ComplianceParams:
    """Object compliance (sec. 4.1, Fig. 10a): ``after_deg`` of closure past the contact
    (the paper: "at least 10 deg"), stiff when the chamber took more than
    ``stiff_mm_per_deg`` of depth per degree (a stiff object passes the finger's closure to the
    chamber, a soft one takes it itself). A finger that stops closing (no new angle for
    ``stop_s``) before ``after_deg`` is judged on what it closed, from ``min_deg``."""

    stiff_mm_per_deg: float
    after_deg: float = 10.0
    min_deg: float = 3.0
    stop_s: float = 0.1

    def __post_init__(self):
        require("stiff_mm_per_deg", self.stiff_mm_per_deg, gt=0, le=100, unit="mm/deg")
        require("compliance after_deg", self.after_deg, gt=0, le=180, unit="deg")
        require("compliance min_deg", self.min_deg, gt=0, le=self.after_deg,
                unit="deg, <= after_deg")
        require("compliance stop_s", self.stop_s, gt=0, le=10, unit="s")


class ComplianceDetector:
    """dy/dα and dP/dα from the contact's onset (the CUSUM's estimate of it, else the
    detection) to ``after_deg`` further, or to where the finger stopped: the least-squares
    slopes over every sample between (running sums, O(1) a sample; in the low mode a sample's
    depth from the pressure scatters by a tenth of a millimetre, the fit over hundreds of
    samples does not): stiff_object|soft_object, once per contact."""

    def __init__(self, params: ComplianceParams):
        self.prm, self.sums = params, None
        self.hist = deque(maxlen=2048)  # (t, α, depth, P): back to the onset

    def push(self, t, angle, depth, p_f, contact_event: dict | None, in_contact: bool):
        if angle is None or math.isnan(angle):
            return None
        self.hist.append((t, angle, depth, p_f))
        if contact_event is not None:
            onset = contact_event.get("onset_s", t)
            self.sums = _Fit()
            for h in self.hist:
                if h[0] >= onset:
                    self.sums.add(*h)
        elif self.sums is not None:
            self.sums.add(t, angle, depth, p_f)
        if not in_contact:
            self.sums = None
            return None
        f, prm = self.sums, self.prm
        if f is None:
            return None
        span = f.a_max - f.a0
        stopped = t - f.t_max >= prm.stop_s and span >= prm.min_deg
        if span < prm.after_deg and not stopped:
            return None
        self.sums = None
        dy, dp = f.slopes()
        stiff = dy > prm.stiff_mm_per_deg
        why = "stopped after" if span < prm.after_deg else "over"
        return {"t_s": t, "kind": "stiff_object" if stiff else "soft_object",
                "depth_per_deg_mm": dy, "dP_dalpha_kPa_per_deg": dp,
                "trigger": f"{dy:.3g} mm/deg fitted {why} {span:.3g}° after contact "
                f"({'>' if stiff else '<='} {prm.stiff_mm_per_deg:g})"}


class _Fit:
    """Running sums of (α, depth, P) about the first sample for the least-squares slopes
    d(depth)/dα and dP/dα (about the first sample: P is near 40 kPa, its rise a few)."""

    def __init__(self):
        self.n = self.sa = self.saa = self.sy = self.say = self.sp = self.sap = 0.0
        self.first = None  # (α, depth, P) of the first sample
        self.a0 = self.a_max = self.t_max = None

    def add(self, t, a, y, p):
        if self.first is None:
            self.first, self.a0, self.a_max, self.t_max = (a, y, p), a, a, t
        elif a > self.a_max:
            self.a_max, self.t_max = a, t
        a, y, p = a - self.first[0], y - self.first[1], p - self.first[2]
        self.n += 1
        self.sa += a
        self.saa += a * a
        self.sy += y
        self.say += a * y
        self.sp += p
        self.sap += a * p

    def slopes(self) -> tuple[float, float]:
        var = self.saa - self.sa * self.sa / self.n
        if var <= 0:
            return 0.0, 0.0
        return ((self.say - self.sa * self.sy / self.n) / var,
                (self.sap - self.sa * self.sp / self.n) / var)
