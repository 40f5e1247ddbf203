"""Events from the pressure (and the FSRs and the finger's closure): slip and the object's
compliance (contact and release: :mod:`.contact`, re-exported here), and :data:`DETECTORS`,
the registry of the detectors :class:`~.stream.SenseStream` runs after the contact's. Each
detector takes one sample at a time in O(1) and returns an event (a dict) or None: through
its own ``push`` (the numbers it reads) or the :class:`~.protocol.Detector` protocol's
``detect`` (a :class:`~.protocol.Sample`).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass

from spsc.core.errors import ParameterError, require

from .contact import ContactParams, CusumContact, Slope, ThresholdContact, contact_detector
from .leak import LeakDetector, LeakParams
from .protocol import Context, Detector, Sample

__all__ = ["ContactParams", "ThresholdContact", "CusumContact", "Slope", "contact_detector",
           "SlipParams", "SlipDetector", "ComplianceParams", "ComplianceDetector",
           "LeakParams", "LeakDetector", "DETECTORS",
           "detector_class", "build_detector", "parse_detectors"]


@dataclass(frozen=True)
class SlipParams:
    """Slip (sec. 4.1, Fig. 10b): over ``window_s`` the load fell — the filtered pressure by
    more than ``drop_sigmas`` σ and ``drop_fraction`` of its rise, or the FSRs' sum by more
    than ``fsr_drop_fraction`` of itself (in the low mode a slip's fall of the pressure is
    within its noise: 0.1–0.5 kPa/mm against σ 0.086 kPa) — while the FSRs' centroid moved
    ``shift`` (fraction of the array, toward fsr_N, the tip) with at least ``fsr_min_N`` on
    them. ``fsr_min_N`` is 25 times a typical FSR channel's noise (0.01 N): with less on the
    array, as a hand lets go, the noise alone moves the centroid by a tenth of the array."""

    window_s: float = 0.05
    drop_sigmas: float = 4.0
    drop_fraction: float = 0.05
    shift: float = 0.15
    fsr_min_N: float = 0.25
    fsr_drop_fraction: float = 0.1

    def __post_init__(self):
        require("slip window_s", self.window_s, gt=0, le=10, unit="s")
        require("slip drop_sigmas", self.drop_sigmas, ge=0, le=100)
        require("slip drop_fraction", self.drop_fraction, ge=0, lt=1)
        require("slip shift", self.shift, gt=0, le=1, unit="fraction of the FSR array")
        require("slip fsr_min_N", self.fsr_min_N, ge=0, unit="N")
        require("slip fsr_drop_fraction", self.fsr_drop_fraction, gt=0, lt=1)


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

    name, kinds, Params = "slip", {"slip": "C4"}, SlipParams

    def __init__(self, params: SlipParams, context: Context | None = None):
        self.prm = params
        self.hist = deque()
        self.armed = True

    def detect(self, s: Sample) -> dict | None:
        """:meth:`push` on the sample's filtered pressure, σ, rest and FSRs (none without
        FSRs: the pressure alone cannot tell a slip from an unloading)."""
        if s.fsr is None:
            return None
        return self.push(s.t_s, s.filtered_kPa, s.sigma_kPa, s.rest_kPa, s.fsr, s.in_contact)

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
        unloaded = tot0 - total > prm.fsr_drop_fraction * tot0
        slipping = (in_contact and (drop > need or unloaded) and moved > prm.shift
                    and min(total, tot0) >= prm.fsr_min_N)
        if slipping and self.armed:
            self.armed = False
            by = f"P fell {drop:.3g} kPa" if drop > need else \
                f"the FSRs' sum fell {tot0 - total:.3g} N (P {drop:.3g} kPa)"
            return {"t_s": t, "kind": "slip", "trigger": f"{by} and the FSR centroid moved "
                    f"{moved:+.2f} toward the tip in {t - t0:.3g} s",
                    "drop_kPa": drop, "fsr_drop_N": tot0 - total, "centroid_shift": moved}
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
    samples does not): stiff_object|soft_object, once per contact. With ``depth_of`` (the
    chamber's depth at a pressure) dy/dα is the depth of the fitted pressure line's ends over
    the angle between them: near the contact a sample's depth is clipped at the rest's (the
    noise below it reads no depth, above it some), which biases the depths' own fit low, the
    pressure's fit is not. ``depth_of`` is the estimator's ``depth_at`` (of ``context``)."""

    name, Params = "compliance", ComplianceParams
    kinds = {"stiff_object": "C5", "soft_object": "C6"}

    def __init__(self, params: ComplianceParams, context: Context | None = None):
        self.prm, self.sums = params, None
        self.depth_of = context.estimator.depth_at if context is not None else None
        self.hist = deque(maxlen=2048)  # (t, α, depth, P): back to the onset

    def detect(self, s: Sample) -> dict | None:
        """:meth:`push` on the sample's closure, depth, filtered pressure and the contact
        event this sample raised (none without a closure angle)."""
        if s.angle_deg is None:
            return None
        started = next((e for e in s.events if e["kind"] == "contact"), None)
        return self.push(s.t_s, s.angle_deg, s.depth_mm, s.filtered_kPa, started,
                         s.in_contact)

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
        if self.depth_of is not None and span > 0:
            dy = f.chord(self.depth_of, dp)
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

    def chord(self, depth_of, dp: float) -> float:
        """(depth at the fitted P of the last angle − at the first)/(their angle), mm/deg."""
        n, a_end = self.n, self.a_max - self.a0
        p_mid = self.first[2] + self.sp / n

        def p(a):
            return p_mid + dp * (a - self.sa / n)

        return (depth_of(p(a_end)) - depth_of(p(0.0))) / a_end


#: The detectors :class:`~.stream.SenseStream` can run after the contact's: name -> class
#: (a :class:`~.protocol.Detector` with its ``Params``, built as ``cls(params, context)``).
#: A new detector is its class and one line here.
DETECTORS: dict[str, type] = {"slip": SlipDetector, "compliance": ComplianceDetector,
                              "leak": LeakDetector}


def detector_class(params) -> type:
    """The registered detector whose ``Params`` ``params`` is."""
    for cls in DETECTORS.values():
        if type(params) is cls.Params:
            return cls
    raise ParameterError("detector parameters", type(params).__name__, "the Params of a "
                         "registered detector (" + ", ".join(DETECTORS) + ")")


def build_detector(params, context: Context) -> Detector:
    """The detector of ``params`` (:func:`detector_class`), built with ``context``."""
    return detector_class(params)(params, context)


def parse_detectors(text: str | None, option: str = "detectors",
                    built_in: Mapping[str, str] | None = None) -> tuple:
    """The parameters (each its ``Params``'s defaults) of the registered detectors the comma
    list ``text`` names (None: none); ``built_in`` the names that run without being named,
    each with when it runs, refused. Any mistake is one :class:`ParameterError` naming
    ``option``."""
    if text is None:
        return ()
    built_in = built_in or {}
    extra = [n for n in DETECTORS if n not in built_in]
    beyond = ", ".join(f"{k} (runs {v})" for k, v in built_in.items())
    allowed = (f"a comma list of the registered detectors{' beyond ' if beyond else ''}"
               f"{beyond}: {', '.join(extra) or 'none is registered'}")
    names, out = [n.strip() for n in str(text).split(",")], []
    for i, name in enumerate(names):
        if name in built_in:
            raise ParameterError(option, name, f"a detector not already on ({name} runs "
                                 f"{built_in[name]})")
        if name not in extra:
            raise ParameterError(option, name or text, allowed)
        if name in names[:i]:
            raise ParameterError(option, text, f"each name once ({name} twice)")
        try:
            out.append(DETECTORS[name].Params())
        except TypeError:
            raise ParameterError(option, name, "a detector whose parameters all have "
                                 "defaults (set them in Python)") from None
    return tuple(out)
