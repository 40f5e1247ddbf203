"""The haptic loop of the paper's PAL-HAND.Q (sec. 4.2, Fig. 12), per finger.

Calibration (sec. 4.2: "the user is instructed to compress each bladder with maximum effort
while in the low-stiffness configuration; the activation threshold is defined as the sum of the
pressure at rest and a fixed increment of 2% of the maximum pressure recorded during
calibration"):

    P_th = P_rest + f P_max,   f = 0.02,

P_rest the median of the squeeze log's first ``rest_s`` (the finger not yet pressing), P_max its
largest gauge pressure (the text's "maximum pressure", taken literally: gauge, not the rise).

The loop (sec. 4.2, steps 1–4):

1. "The pressure change is first calculated, then normalized against the maximum pressure
   change recorded during the calibration phase, and finally linearly mapped into rotation
   angles of the virtual fingers joints": θ = θ_max · clip((P − P_rest)/(P_max − P_rest), 0, 1);
2. "when the pressure within a specific SPSC exceeds the user-calibrated threshold, the
   corresponding digital valve is activated to increase the SPSC's stiffness [...] further
   reinforced by a vibration": commands ``valve closed`` and ``vibrate``;
4. "the digital valves are switched back to the low-stiffness configuration" on release: the
   command ``valve open`` when P falls below P_th − the hysteresis (ours, not the paper's: 3 σ
   of the calibration's rest, so the sensor's noise at the threshold does not chatter the
   valve).

P is the pressure through a one-pole filter of time constant ``smoothing_s`` (a threshold
crossing is late by about that much, and chatters less).
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError, require

__all__ = ["HapticCalibration", "calibrate", "HapticLoop"]


@dataclass(frozen=True)
class HapticCalibration:
    """``rest_kPa``, ``max_kPa`` of the squeeze, ``fraction`` f, ``threshold_kPa`` P_th,
    ``noise_kPa`` σ at rest, ``hysteresis_kPa``, ``joint_max_deg`` θ_max."""

    rest_kPa: float
    max_kPa: float
    fraction: float
    threshold_kPa: float
    noise_kPa: float
    hysteresis_kPa: float
    joint_max_deg: float = 90.0

    def __post_init__(self):
        """A calibration file edited by hand is checked as its fields are read: numbers,
        finite, the squeeze's maximum above its rest and the threshold between them."""
        for name in ("rest_kPa", "max_kPa", "threshold_kPa"):
            require(f"haptic calibration {name}", getattr(self, name), ge=-100, le=1000,
                    unit="kPa gauge")
        require("haptic calibration fraction", self.fraction, gt=0, lt=1)
        require("haptic calibration noise_kPa", self.noise_kPa, ge=0, le=100, unit="kPa")
        require("haptic calibration hysteresis_kPa", self.hysteresis_kPa, ge=0, le=100,
                unit="kPa")
        require("haptic calibration joint_max_deg", self.joint_max_deg, gt=0, le=360,
                unit="deg")
        if not self.max_kPa > self.rest_kPa:
            raise ParameterError("haptic calibration max_kPa", self.max_kPa,
                                 f"above the rest {self.rest_kPa:g} kPa (a squeeze)")
        if not self.rest_kPa < self.threshold_kPa < self.max_kPa:
            raise ParameterError("haptic calibration threshold_kPa", self.threshold_kPa,
                                 f"between the rest {self.rest_kPa:g} and the maximum "
                                 f"{self.max_kPa:g} kPa")

    def to_json(self, path) -> None:
        Path(path).write_text(json.dumps({"haptic_calibration": asdict(self),
                                          "source": "spsc sense --haptic-calibrate (paper "
                                          "sec. 4.2: threshold = rest + fraction × max)"},
                                         indent=2) + "\n", encoding="utf-8")

    @classmethod
    def from_json(cls, path) -> "HapticCalibration":
        try:
            d = json.loads(Path(path).read_text(encoding="utf-8"))["haptic_calibration"]
            if not isinstance(d, dict):
                raise TypeError("not an object")
            bad = next((k for k, v in d.items() if isinstance(v, (str, bool))), None)
            if bad is not None:  # a number written as text (or true) names its field
                raise ParameterError(f"haptic calibration {bad}", d[bad], "a number")
            return cls(**d)
        except ParameterError:
            raise
        except (OSError, ValueError, KeyError, TypeError) as exc:
            raise ParameterError("haptic calibration", str(path), "a file written by spsc "
                                 f"sense --haptic-calibrate ({type(exc).__name__})") from None


def calibrate(t_s, pressure_kPa, *, fraction: float = 0.02, rest_s: float = 0.2,
              joint_max_deg: float = 90.0) -> HapticCalibration:
    """The calibration of one finger from its squeeze log (low-stiffness mode)."""
    require("haptic fraction", fraction, gt=0, lt=1)
    require("rest_s", rest_s, gt=0, unit="s")
    require("joint_max_deg", joint_max_deg, gt=0, le=360, unit="deg")
    t, p = np.asarray(t_s, float), np.asarray(pressure_kPa, float)
    rest = t < t[0] + rest_s
    if rest.sum() < 5:
        raise ParameterError("rest_s", rest_s, f"a span with at least 5 samples at the start "
                             f"of the squeeze ({rest.sum()} here)")
    p_rest, p_max = float(np.median(p[rest])), float(p.max())
    noise = 1.4826 * float(np.median(np.abs(p[rest] - p_rest)))
    threshold = p_rest + fraction * p_max
    if not p_max > threshold:
        raise ParameterError("squeeze", f"max {p_max:.4g} kPa", f"above the threshold "
                             f"{threshold:.4g} kPa (rest {p_rest:.4g} + {fraction:g} × max): a "
                             "harder squeeze, or a smaller fraction")
    return HapticCalibration(p_rest, p_max, fraction, threshold, noise, 3.0 * noise,
                             joint_max_deg)


class HapticLoop:
    """:meth:`push` one sample: (joint angle θ in degrees, commands raised)."""

    def __init__(self, cal: HapticCalibration, *, smoothing_s: float = 0.005,
                 vibrate_s: float = 0.2):
        self.cal, self.tau, self.vibrate_s = cal, smoothing_s, vibrate_s
        self.p = self.t = None
        self.closed = False

    def push(self, t_s: float, p_kPa: float) -> tuple[float, list]:
        if self.p is None:
            self.p = p_kPa
        else:
            a = 1.0 - math.exp(-(t_s - self.t) / self.tau) if self.tau > 0 else 1.0
            self.p += a * (p_kPa - self.p)
        self.t = t_s
        cal, cmds = self.cal, []
        span = cal.max_kPa - cal.rest_kPa
        theta = cal.joint_max_deg * min(max((self.p - cal.rest_kPa) / span, 0.0), 1.0)
        if not self.closed and self.p > cal.threshold_kPa:
            self.closed = True
            cmds = [{"t_s": t_s, "command": "valve", "state": "closed",
                     "why": f"P {self.p:.4g} kPa above the threshold {cal.threshold_kPa:.4g} kPa"},
                    {"t_s": t_s, "command": "vibrate", "duration_s": self.vibrate_s}]
        elif self.closed and self.p < cal.threshold_kPa - cal.hysteresis_kPa:
            self.closed = False
            cmds = [{"t_s": t_s, "command": "valve", "state": "open",
                     "why": f"P {self.p:.4g} kPa below the threshold less "
                     f"{cal.hysteresis_kPa:.3g} kPa"}]
        return theta, cmds
