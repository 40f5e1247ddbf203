"""The contact detector's two scales and the rest tracker under it, on synthetic pressure
(white noise of σ = 0.086 kPa, the ELVH's, at 1 kHz, around a 40 kPa rest):

* the rest tracker follows a steady drift without lag, and a press that starts within its
  delay is not learnt as drift;
* a shift of 0.6 σ held for a second (the low mode's shallow press) is a contact at the slow
  scale and none without it, and its release is seen within 0.1 s of the pressure's return;
* minutes of noise on a drifting rest raise no event (a warming, a cooling that stops);
* the FSRs' sum falling with the centroid moving is a slip when the pressure cannot show the
  fall, and the centroid moving under a steady load is not.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.sensing.contact import ContactParams, CusumContact
from spsc.sensing.detectors import SlipDetector, SlipParams
from spsc.sensing.rest import RestTracker
from spsc_support import sense_traces as st

SIGMA, REST, DT = 0.086, 40.0, 1e-3


def run(p, params=ContactParams(), *, tracker=True):
    """The contact detector on ``p`` (kPa at 1 kHz) against the tracked rest, as the stream
    runs them: the tracker fed while not in contact and held at a contact."""
    det = CusumContact(params, SIGMA, 1000.0)
    rest = RestTracker(REST, time_s=2.0)
    events = []
    for i, x in enumerate(p):
        t = i * DT
        base = rest.baseline(t) if (tracker and rest.settled) else rest.held
        ev = det.push(t, x, x, SIGMA, base, rest.settled)
        if ev is not None:
            events.append(ev)
            if det.contact:
                rest.hold(t)
        if tracker and not det.contact:
            rest.push(t, x)
    return events


def noise(n, seed):
    return SIGMA * np.random.default_rng(seed).standard_normal(n)


def test_the_rest_tracker_follows_a_drift_without_lag():
    t = np.arange(20000) * DT
    r = RestTracker(REST, time_s=2.0)
    p = REST + 0.02 * t + noise(t.size, 1)  # warming, 0.02 kPa/s
    err = []
    for x, y in zip(t, p):
        r.push(x, y)
        if x > 10.0:
            err.append(r.baseline(x) - (REST + 0.02 * x))
    # a one-pole filter of 2 s lags this drift by 0.04 kPa; the tracker's error is its noise
    # (measured mean 1e-4, largest 0.006 kPa)
    assert abs(np.mean(err)) < 0.002 and np.max(np.abs(err)) < 0.015
    assert_allclose(r.rate, 0.02, atol=0.004)


def test_a_press_inside_the_delay_is_not_learnt_as_drift():
    r = RestTracker(REST, time_s=2.0, delay_s=0.3)
    for i in range(3000):
        r.push(i * DT, REST)
    for i in range(3000, 3250):  # 0.25 s of a 1 kPa press: still in the delay
        r.push(i * DT, REST + 1.0)
    assert_allclose(r.baseline(3.25), REST, atol=1e-9)
    assert_allclose(r.hold(3.25), REST, atol=1e-9)
    assert not r.settled
    for i in range(3250, 3400):  # a new rest after the contact, acquired from scratch
        r.push(i * DT, REST + 0.05)
    for i in range(3400, 3800):
        r.push(i * DT, REST + 0.05)
    assert r.settled
    assert_allclose(r.baseline(3.8), REST + 0.05, atol=1e-9)


def shallow(seed, shift=0.6):
    """1 s of rest, a press of ``shift`` σ for a second (50 ms ramps), 1 s of rest."""
    t = np.arange(3000) * DT
    rise = np.interp(t, [1.0, 1.05, 2.0, 2.05], [0.0, 1.0, 1.0, 0.0])
    return REST + shift * SIGMA * rise + noise(t.size, seed)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_shift_of_half_a_sigma_is_a_contact_at_the_slow_scale(seed):
    p = shallow(seed)
    ev = run(p)
    assert [e["kind"] for e in ev] == ["contact", "release"]
    assert 1.0 <= ev[0]["t_s"] <= 1.5 and "slow scale" in ev[0]["trigger"]
    assert 1.0 <= ev[0]["onset_s"] <= ev[0]["t_s"]
    assert 2.0 <= ev[1]["t_s"] <= 2.3  # k_r = 0.2 σ, h_r = 20 σ: about 100 samples
    assert run(p, ContactParams(k_slow=0.0)) == []  # what the fast scale alone sees


@pytest.mark.parametrize("seed", [4, 5])
def test_minutes_of_drifting_noise_raise_no_event(seed):
    t = np.arange(240000) * DT
    warming = REST + 0.02 * t  # 0.02 kPa/s for 4 min
    cooling = REST - 0.3 * (1.0 - np.exp(-t / 60.0))  # settling by 0.3 kPa, τ 60 s
    stops = REST - np.interp(t, [0.0, 60.0], [0.0, 0.3])  # a ramp that stops at 1 min
    for p in (warming, cooling, stops):
        assert run(p + noise(t.size, seed)) == []


def test_a_slip_unloading_the_fsrs_is_a_slip_when_the_pressure_cannot_show_it():
    t = np.arange(500) * DT
    pos = np.interp(t, [0.1, 0.18], [0.35, 0.85])
    rng = np.random.default_rng(7)

    def events(load):
        F = np.column_stack(list(st.fsr_columns(load, pos, rng).values()))
        det = SlipDetector(SlipParams())
        p = 40.2 + 0.03 * rng.standard_normal(t.size)  # a low-mode press: no visible drop
        return [e for k in range(t.size)
                if (e := det.push(t[k], p[k], 0.03, 40.0, F[k], True))]

    slip = events(np.interp(t, [0.1, 0.18], [2.0, 1.2]))  # 40 % of the load gone
    assert len(slip) == 1 and "FSRs' sum fell" in slip[0]["trigger"]
    assert 0.1 <= slip[0]["t_s"] <= 0.18
    assert events(np.full(t.size, 2.0)) == []  # the contact rolls under a steady load


def test_the_release_reference_follows_the_contact_level():
    from spsc.sensing.contact import release_reference

    prm = ContactParams()
    assert release_reference(40.0, prm) == (0.5, 8.0)  # a high-mode press: as the paper's
    assert_allclose(release_reference(2.4, prm), (0.3, 8.0 * 0.5 / 0.3))  # an eighth
    assert_allclose(release_reference(0.6, prm), (0.2, 20.0))  # the floor
    k, h = release_reference(0.3, prm)  # below 0.4 σ: half the level, h for 10⁶ samples
    assert k == 0.15 and h > 4.0 / 0.15
    # Siegmund's run length of a false release in the hold (drift k − mean a sample)
    d = 0.3 - k
    assert (np.exp(2 * d * (h + 1.166)) - 2 * d * (h + 1.166) - 1) / (2 * d * d) >= 0.99e6


def test_a_log_that_starts_in_contact_has_its_start_as_onset():
    p = REST + 3.0 * SIGMA + noise(200, 9)
    ev = run(p)
    assert [e["kind"] for e in ev] == ["contact"] and ev[0]["onset_s"] == 0.0
