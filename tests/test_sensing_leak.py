"""The leak detector (issue 51) on rest logs whose truth is known: a leak's steady loss is
called with its rate; a thermal swing that comes back, a sine of the room's, a step (a valve
switched in contact), and noise alone are not; a steady cooling is (the pressure alone cannot
tell it from a leak: the event says how many kelvin would explain it)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.sensing.leak import LeakDetector, LeakParams

SIGMA = 0.086  # kPa, the paper's ELVH sensor (1 kHz); here at 10 Hz
RATE_HZ = 10.0


def _run(pressure, seconds=2400.0, params=LeakParams(), seed=0):
    t = np.arange(0.0, seconds, 1.0 / RATE_HZ)
    p = pressure(t) + np.random.default_rng(seed).normal(0.0, SIGMA, t.size)
    det = LeakDetector(params)
    return [e for e in (det.push(float(a), float(b)) for a, b in zip(t, p)) if e]


def test_a_steady_leak_is_called_with_its_rate():
    rate = 1.0 / 1800.0  # kPa/s: the paper's FDM worst case, 1 kPa in 30 min
    events = _run(lambda t: 40.0 - rate * t)
    assert len(events) == 1  # re-armed a window later: the 2400 s log holds one
    e = events[0]
    assert e["kind"] == "leak" and 1795.0 <= e["t_s"] <= 1805.0  # one window of rest
    # the issue asks 30 %; 1,800 one-second bins of σ/√10 fit the slope to ~0.1 %
    assert_allclose(e["rate_kPa_per_30min"], 1.0, rtol=0.01)
    assert_allclose(e["rate_kPa_per_min"], rate * 60.0, rtol=0.01)
    assert "2.1 K" in e["trigger"]  # the room's cooling that would explain it


@pytest.mark.parametrize("name, pressure", [
    # 1 kPa down and back over the window (2.07 K of the room at 40 kPa)
    ("swing back", lambda t: 40.0 - np.sin(np.pi * np.minimum(t, 1800.0) / 1800.0)),
    # the room's cycle: ± 0.5 kPa with a 30 min period (fits a 0.95 kPa 'drop' to one window)
    ("room cycle", lambda t: 40.0 + 0.5 * np.sin(2.0 * np.pi * t / 1800.0)),
    # the rest stepping down by 1 kPa (the valve closed on a compressed reservoir)
    ("step", lambda t: 40.0 - 1.0 * (t > 900.0)),
    ("noise alone", lambda t: np.full_like(t, 40.0)),
    # a leak below the bound: 0.1 kPa in 30 min
    ("slow", lambda t: 40.0 - 0.1 * t / 1800.0),
])
def test_what_comes_back_or_steps_is_no_leak(name, pressure):
    assert _run(pressure) == [], name


def test_contact_samples_are_left_out_and_a_short_log_is_not_judged():
    det = LeakDetector(LeakParams(window_s=600.0, bin_s=1.0))
    out = [det.push(t, 40.0 - t / 600.0) for t in np.arange(0.0, 590.0, 0.1)]
    assert not any(out)  # less than a window
    assert LeakParams().min_drop_kPa == 0.2


def test_leak_params_are_checked():
    for kw, name in (({"window_s": 0}, "leak window_s"), ({"parts": 1}, "leak parts"),
                     ({"spread": 1.5}, "leak spread"), ({"bin_s": 500}, "leak bin_s")):
        with pytest.raises(ParameterError, match=name):
            LeakParams(**kw)
    assert math.isfinite(LeakParams(window_s=60, bin_s=1).window_s)
