"""The chamber as a sensor (issue 29) on traces of the time-domain circuit:

* the table P -> (y, F) against the closed form of a linear chamber;
* force from pressure on the wall model's Type B dome, high and low mode, within 5 % or the
  noise floor of the true force; across a high -> low switch under load no jump beyond the
  noise and no release, with the valve column and with the switch inferred from P;
* the rest pressure's drift tracked; contact and release, slip (with the FSRs) and not a
  partial release, stiff and soft objects (in the low mode from the pressure's fitted line);
  no event in quiet noise; the stream's speed;
* bad samples are one-line errors naming the column.
"""

from __future__ import annotations

import json
import math
import time

import numpy as np
import pandas as pd
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.dynamics import Sensor
from spsc.dynamics.chamber_map import ChamberMap
from spsc.sensing import DenseMap, EstimatorParams, SenseParams, SenseStream
from spsc.sensing.chamber import chamber_map
from spsc.sensing.detectors import ComplianceParams, ContactParams
from spsc.sensing.table import PA_KPA
from spsc_support import sense_traces as st

DOME = {"type": "B", "l": 0}
RES = 40000.0


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("sense-cache")


@pytest.fixture(scope="module")
def dome(cache):
    """The wall model's Type B dome at 40 kPa (1 mm mesh: the estimator reads the same map
    the circuit ran on, so the mesh's accuracy is not what is tested; about 3 s)."""
    m = chamber_map(DOME, setup_kPa=40.0, reservoir_mm3=RES, stroke_mm=3.0, mesh_size=1.0,
                    cache_dir=cache)
    return m, DenseMap(m)


def stream(dense, trial, *, model_error=0.0, **kw):
    est = EstimatorParams(40.0, RES, trial.meta["noise_kPa"], model_error,
                          valve_open=trial.meta["valve_open"],
                          **{k: kw.pop(k) for k in list(kw) if k in
                             ("rest_time_s", "smoothing_s")})
    return SenseStream(dense, SenseParams(est, **kw))


def feed(s, trial, *, valve=True):
    log = trial.log
    fsr = [c for c in log if c.startswith("fsr_")]
    F = log[fsr].to_numpy() if fsr else None
    a = log.angle_deg.to_numpy() if "angle_deg" in log else None
    out = [s.push(t, p, v if valve else None, None if F is None else F[i],
                  None if a is None else a[i])[0]
           for i, (t, p, v) in enumerate(zip(log.t_s, log.pressure_kPa, log.valve_open))]
    return np.array([o.force_N for o in out]), np.array([o.force_hi_N - o.force_N for o in out])


def kinds(events):
    return [e["kind"] for e in events]


def test_table_is_the_closed_form_of_a_linear_chamber():
    # V = v0 (1 + P/K) − a y, F = a P y / 1000: the content c = (P + Pa) V gives
    # y = (v0 (1 + P/K) − c/(P + Pa))/a in the high mode, with V + V_r in the low
    v0, a, K = 3000.0, 400.0, 300.0
    y = np.linspace(-1.0, 5.0, 25)
    p = np.linspace(0.0, 120.0, 9)
    Y, P = np.meshgrid(y, p, indexing="ij")
    m = ChamberMap(y, p, v0 * (1 + P / K) - a * Y, a * P * np.clip(Y, 0, None) / 1e3,
                   np.zeros_like(Y), 40.0)
    d = DenseMap(m, ny=601, np_=1201)
    for vr in (0.0, 40000.0):
        c = (40.0 + PA_KPA) * (v0 * (1 + 40.0 / K) + vr)
        table = d.table(c, vr)
        assert_allclose(table.rest_kPa, 40.0, atol=2e-3)
        for pk in np.linspace(41.0, table.p[-1] - 0.5, 7) if vr == 0 else \
                np.linspace(40.2, table.p[-1] - 0.05, 7):
            yk = (v0 * (1 + pk / K) + vr - c / (pk + PA_KPA)) / a
            got_y, got_f, _, inside = table.lookup(pk)
            # the dense grid's bilinear reading: 0.01 mm and 0.1 kPa nodes
            assert inside and abs(got_y - yk) < 2e-3
            # F(y, P) is the map's own (PCHIP along y rounds the contact's kink)
            # (and the dense grid's bilinear reading of it near the kink: 0.2 %)
            assert_allclose(got_f, float(m.at(yk).force(pk)), rtol=5e-3)


@pytest.mark.parametrize("opened", [False, True])
def test_force_from_pressure_in_both_modes(dome, opened):
    m, d = dome
    trial = st.press(m, depth_mm=2.5, speed_mm_s=10.0, hold_s=0.6, valve_open=opened, seed=3)
    f, band = feed(stream(d, trial), trial)
    true = trial.truth.force_N.to_numpy()
    touching = true > 0.2 * true.max()
    err = np.abs(f - true)[touching]
    # the bound: 5 % or the noise floor (the 95 % band of the sensor's noise alone,
    # model_error = 0 as the trace ran on this map). A 95 % band holds 95 % of the samples,
    # and the filtered noise is correlated over τ_s (a few hundred independent samples here):
    # 90 % is the bound (measured 97 % closed, 93 % open; a 10 % scale error gives < 60 %)
    assert np.mean(err <= np.maximum(0.05 * true[touching], band[touching])) > 0.90
    hold = trial.truth.t_s.between(0.3 + 2.8 / 10 + 0.05, 0.3 + 2.8 / 10 + 0.6).to_numpy()
    # over the hold the noise averages out: what is left is the table (1e-3) and, open, the
    # valve's flow lag (measured 0.1 %)
    assert_allclose(f[hold].mean(), true[hold].mean(), rtol=0.01)


@pytest.mark.parametrize("column", [True, False])
def test_switch_under_load_no_jump_no_release(dome, column):
    m, d = dome
    trial = st.press(m, depth_mm=2.5, speed_mm_s=10.0, hold_s=1.0, switches=[(1.0, True)],
                     seed=5)
    s = stream(d, trial)
    f, band = feed(s, trial, valve=column)
    assert kinds(s.events) == ["contact", "switch", "release"]
    sw = s.events[1]
    t = trial.truth.t_s.to_numpy()
    assert abs(sw["t_s"] - 1.0) <= 0.003 and sw["valve"] == "open"
    assert ("inferred" in sw["trigger"]) != column
    true = trial.truth.force_N.to_numpy()
    # no jump: the error's 10 ms mean stays within the noise band through the switch (from
    # 30 ms after it when inferred: the fall it is inferred from takes the valve's 10–20 ms)
    err = np.convolve(f - true, np.ones(10) / 10, mode="same")
    wide = np.r_[band[:5], np.lib.stride_tricks.sliding_window_view(band, 10).max(axis=1),
                 band[-4:]]  # the widest band the 10 ms mean draws on
    window = (t > 0.9) & (t < 1.3) & ((t > 1.03) | (t < 0.99) | column)
    assert np.all(np.abs(err[window]) <= wide[window])
    before, after = (t > 0.95) & (t < 1.0), (t > 1.05) & (t < 1.1)
    assert_allclose(f[before].mean() - f[after].mean(),
                    true[before].mean() - true[after].mean(), atol=band[after].mean() / 3)


def test_a_switch_under_a_shallow_press_is_not_a_release(dome):
    """High -> low under a press of 0.6–0.8 mm: the low mode's pressure at that travel is a σ
    or less above its rest, so a release measured against the high mode's level comes before
    the true one (measured: in five of six such presses, three of them within 0.2 s of the
    switch; here three of four within 0.2 s); measured against the pooled
    pressure at the held travel it waits for the true release (from 0.05 s before to 0.3 s
    after it)."""
    m, d = dome
    early = 0
    for depth in (0.6, 0.8):
        for seed in (0, 2):
            trial = st.press(m, depth_mm=depth, speed_mm_s=10.0, hold_s=0.8, seed=seed,
                             switches=[(0.7 + depth / 10.0 + 0.03, True)])
            truth = {e["kind"]: e["t_s"] for e in trial.events}
            s = stream(d, trial)
            feed(s, trial)
            assert kinds(s.events) == ["contact", "switch", "release"]
            assert -0.05 <= s.events[2]["t_s"] - truth["release"] <= 0.3
            old = stream(d, trial)
            old.contact.rebase = lambda level: None  # the high mode's level kept
            feed(old, trial)
            released = [e["t_s"] for e in old.events if e["kind"] == "release"]
            early += released[0] < truth["switch"] + 0.2
    assert early >= 2


def test_rest_drift_is_tracked(dome):
    m, d = dome
    trial = st.press(m, depth_mm=2.0, speed_mm_s=10.0, hold_s=0.5, lead_s=11.0, seed=7)
    # warming at rest: +0.2 kPa in 10 s (0.4 K of the gas at 140 kPa absolute; a one-pole
    # filter of 2 s would lag it by 0.04 kPa, half the noise's σ: the tracker follows the rate)
    drift = np.interp(trial.log.t_s, [0.0, 10.0], [0.0, 0.2])
    trial.log["pressure_kPa"] += drift
    trial.truth["pressure_kPa"] += drift
    tracked = stream(d, trial)
    f, _ = feed(tracked, trial)
    assert kinds(tracked.events) == ["contact", "release"]
    true = trial.truth.force_N.to_numpy()
    hold = true > 0.9 * true.max()
    # the warmer gas is a larger content: re-based at rest, the press reads true (1 %)
    assert_allclose(f[hold].mean(), true[hold].mean(), rtol=0.01)
    stale = stream(d, trial)
    stale.est.track_rest = lambda p: False  # the same stream, its rest never tracked
    f_stale, _ = feed(stale, trial)
    # what tracking avoids (measured 5.9 %, and a contact that never ends)
    assert abs(f_stale[hold].mean() / true[hold].mean() - 1) > 0.04
    assert stale.events and stale.events[0]["t_s"] < 10.0  # the drift read as a contact


@pytest.mark.parametrize("method", ["cusum", "threshold"])
def test_contact_and_release_and_no_event_in_quiet_noise(dome, method):
    m, d = dome
    trial = st.press(m, depth_mm=2.0, speed_mm_s=20.0, hold_s=0.3, seed=11)
    s = stream(d, trial, contact=ContactParams(method=method))
    feed(s, trial)
    truth = {e["kind"]: e["t_s"] for e in trial.events}
    got = {e["kind"]: e["t_s"] for e in s.events}
    assert sorted(got) == ["contact", "release"]
    assert 0 <= got["contact"] - truth["contact"] <= 0.05  # high mode, 20 mm/s
    assert abs(got["release"] - truth["release"]) <= 0.05
    # a minute of the chamber at rest read by the sensor: the circuit would add nothing
    t = np.arange(60000) * 1e-3
    quiet = st.Trial(pd.DataFrame({"t_s": t, "valve_open": 0, "pressure_kPa": Sensor.preset(
        "elvh", seed=13).read(np.full(t.size, 40.0))}), None, [], dict(trial.meta))
    q = stream(d, quiet, contact=ContactParams(method=method))
    feed(q, quiet)
    assert q.events == []


def test_slip_needs_the_fsr_centroid_moving_to_the_tip(dome):
    m, d = dome
    slip = st.slip_press(m, depth_mm=2.5, slip=True, seed=17)
    s = stream(d, slip)
    feed(s, slip)
    assert kinds(s.events) == ["contact", "slip", "release"]
    assert 0 <= s.events[1]["t_s"] - slip.meta["t_slip_s"] <= 0.08
    partial = st.slip_press(m, depth_mm=2.5, slip=False, seed=17)
    s = stream(d, partial)
    feed(s, partial)
    assert kinds(s.events) == ["contact", "release"]


def _slide(detector, *, total_N, drop_kPa, seconds=0.3, flicker=0.0):
    """A slide of the contact from 0.2 to 0.8 of the FSR array over ``seconds`` at 1 kHz, the
    pressure falling by ``drop_kPa`` (σ_f 0.02 kPa, rest 40) with a ``flicker`` on it."""
    from spsc.sensing.detectors import SlipDetector

    t = np.arange(int(seconds * 1000) + 200) * 1e-3
    pos = np.clip((t - 0.1) / seconds, 0.0, 1.0) * 0.6 + 0.2
    p = 41.0 - drop_kPa * np.clip((t - 0.1) / seconds, 0.0, 1.0) \
        + flicker * np.sign(np.sin(2 * np.pi * 40 * t))
    fsr = st.fsr_columns(np.full(t.size, total_N), pos, np.random.default_rng(3))
    F = np.column_stack(list(fsr.values()))
    det = SlipDetector(detector)
    return [e for k in range(t.size) if (e := det.push(t[k], p[k], 0.02, 40.0, F[k], True))]


def test_a_long_slide_is_one_slip_and_a_light_touch_none():
    """A slide over 0.15 s whose pressure drop flickers across the detector's bound (as in the
    low mode) is one episode, not one event per flicker; with 0.1 N on the array (a hand
    letting go: the FSRs' noise moves the centroid) nothing is a slip."""
    from spsc.sensing.detectors import SlipParams

    assert len(_slide(SlipParams(), total_N=3.0, drop_kPa=0.6, seconds=0.15, flicker=0.1)) == 1
    assert _slide(SlipParams(), total_N=0.1, drop_kPa=0.6, seconds=0.15) == []
    assert len(_slide(SlipParams(fsr_min_N=0.05), total_N=0.1, drop_kPa=0.6, seconds=0.15)) >= 1


@pytest.mark.parametrize("share, kind", [(0.9, "stiff_object"), (0.3, "soft_object")])
def test_object_compliance_after_ten_degrees(dome, share, kind):
    m, d = dome
    trial = st.grasp(m, share=share, omega_deg_s=80.0, seed=19)  # valve closed: high mode
    s = stream(d, trial, compliance=ComplianceParams(stiff_mm_per_deg=0.5 * 0.12))
    feed(s, trial)
    assert kinds(s.events) == ["contact", kind, "release"]
    judged = next(e for e in s.events if e["kind"] == kind)
    # the fitted slope: the chamber's share of the 0.12 mm/deg lever, within 25 % (measured
    # 3 % stiff, 18 % soft: the depth read back from the pressure is least sure near the
    # contact, where the chamber's dP/dy is smallest, and a soft press stays near it)
    assert_allclose(judged["depth_per_deg_mm"], share * 0.12, rtol=0.25)


def test_low_mode_compliance_reads_the_fitted_pressure_not_the_clipped_depths(dome):
    """Low mode (0.1–0.5 kPa/mm against σ 0.086 kPa): near the contact a sample's depth is
    clipped at the rest's, so a fit of the depths is biased low and a stiff object can read
    soft; the pressure's line, its ends read as depths, is not (measured: mean slope 0.94 of
    the true one against the depths' 0.78, one of three grasps read soft by the latter)."""
    m, d = dome
    ratio = {True: [], False: []}
    for share in (0.6,):
        for seed in range(3):
            trial = st.grasp(m, share=share, valve_open=True, seed=seed)
            for chord in (True, False):
                s = stream(d, trial, compliance=ComplianceParams(stiff_mm_per_deg=0.06))
                if not chord:
                    s.compliance.depth_of = None
                feed(s, trial)
                judged = [e for e in s.events if e["kind"].endswith("_object")]
                assert len(judged) == 1
                if chord:
                    assert judged[0]["kind"] == "stiff_object", (share, seed)
                ratio[chord].append(judged[0]["depth_per_deg_mm"] / (share * 0.12))
    assert abs(np.mean(ratio[True]) - 1) < 0.8 * abs(np.mean(ratio[False]) - 1)


@pytest.mark.parametrize("share, kind", [(0.9, "stiff_object"), (0.3, "soft_object")])
def test_a_finger_that_stops_early_is_judged_on_what_it_closed(dome, share, kind):
    """The finger closes 10° past the true contact and holds: the detector's onset is
    later (1.9° stiff, 6.6° soft), so it sees 8.1° and 3.4°, short of the paper's 10°; judged
    when the finger has not closed further for 0.1 s, within 0.2 s of stopping."""
    m, d = dome
    trial = st.grasp(m, share=share, alpha_end=30.0, omega_deg_s=40.0, seed=19)
    s = stream(d, trial, compliance=ComplianceParams(stiff_mm_per_deg=0.5 * 0.12))
    feed(s, trial)
    assert kinds(s.events) == ["contact", kind, "release"]
    judged = next(e for e in s.events if e["kind"] == kind)
    assert 0.1 <= judged["t_s"] - 30.0 / 40.0 <= 0.2 and "stopped after" in judged["trigger"]
    never = stream(d, trial, compliance=ComplianceParams(0.5 * 0.12, stop_s=10.0))
    feed(never, trial)
    assert kinds(never.events) == ["contact", "release"]  # what stopping early used to give


def test_the_stream_is_fast_and_refuses_bad_samples(dome):
    m, d = dome
    trial = st.press(m, depth_mm=2.0, speed_mm_s=10.0, hold_s=0.5, seed=23)
    s = stream(d, trial)
    rows = list(zip(trial.log.t_s, trial.log.pressure_kPa, trial.log.valve_open))
    t0 = time.perf_counter()
    for t, p, v in rows:
        s.push(t, p, v)
    rate = len(rows) / (time.perf_counter() - t0)
    assert rate > 10000, f"{rate:.0f} samples/s"  # measured ~3e5 on the 2-core machine
    with pytest.raises(ParameterError, match="t_s"):
        s.push(rows[-1][0], 40.0)
    with pytest.raises(ParameterError, match="pressure_kPa"):
        s.push(rows[-1][0] + 1.0, math.nan)


# -- spsc sense ---------------------------------------------------------------------------------
CHAMBER = ["--type", "B", "--l", "0", "--pressure", "40", "--reservoir", "40000", "--stroke",
           "3", "--mesh-size", "1.0", "--quiet"]


@pytest.fixture(scope="module")
def slip_log(dome, tmp_path_factory):
    m, _ = dome
    trial = st.slip_press(m, depth_mm=2.5, slip=True, seed=29)
    path = tmp_path_factory.mktemp("logs") / "slip.csv"
    trial.log.to_csv(path, index=False)
    return trial, path


def test_sense_writes_the_estimate_the_events_and_the_figure(dome, cache, slip_log, tmp_path):
    from spsc.cli.main import main

    trial, path = slip_log
    out = tmp_path / "out"
    assert main(["sense", str(path), "--out", str(out), "--cache", str(cache)] + CHAMBER) == 0
    est = pd.read_parquet(out / "estimate.parquet")
    for c in ("t_s", "force_N", "force_lo_N", "force_hi_N", "depth_mm", "mode", "in_contact"):
        assert c in est
    assert len(est) == len(trial.log) and set(est["mode"]) == {"high"}
    events = json.loads((out / "events.json").read_text())["events"]
    assert kinds(events) == ["contact", "slip", "release"]
    assert all(e["trigger"] for e in events)
    assert (out / "sense.png").stat().st_size > 10000


def test_sense_warns_when_the_log_does_not_start_at_the_setup(dome, cache, slip_log, tmp_path,
                                                              capsys):
    from spsc.cli.main import main

    trial, path = slip_log
    off = tmp_path / "offset.csv"
    log = trial.log.copy()
    log["pressure_kPa"] += 0.5  # a sensor's offset: 6 σ
    log.to_csv(off, index=False)
    assert main(["sense", str(off), "--out", str(tmp_path / "a"), "--cache", str(cache)]
                + CHAMBER) == 0
    err = capsys.readouterr().err
    assert "warning: the log starts at 40.5" in err and "--pressure 40.5" in err
    assert main(["sense", str(path), "--out", str(tmp_path / "b"), "--cache", str(cache)]
                + CHAMBER) == 0
    assert "warning" not in capsys.readouterr().err


def test_sense_follow_prints_the_same_events(dome, cache, slip_log, tmp_path, monkeypatch,
                                             capsys):
    import io

    from spsc.cli.main import main

    trial, path = slip_log
    monkeypatch.setattr("sys.stdin", io.StringIO(path.read_text()))
    assert main(["sense", "--follow", "--noise", f"{trial.meta['noise_kPa']}",
                 "--cache", str(cache)] + CHAMBER) == 0
    lines = [json.loads(x) for x in capsys.readouterr().out.splitlines()]
    assert kinds(lines) == ["contact", "slip", "release"]


@pytest.mark.parametrize("edit, needle", [
    (lambda d: d.drop(columns=["pressure_kPa"]), "log columns"),
    (lambda d: d.assign(t_s=d.t_s.where(d.index != 5, 0.0)), "t_s (row 6)"),
    (lambda d: d.assign(pressure_kPa=d.pressure_kPa.where(d.index != 7, np.nan)),
     "pressure_kPa (row 8)"),
    (lambda d: d.assign(valve_open=d.valve_open.where(d.index != 3, 2)), "valve_open (row 4)"),
    (lambda d: d.drop(columns=["fsr_2"]), "fsr columns"),
])
def test_a_bad_log_is_one_line_naming_the_column(slip_log, tmp_path, capsys, edit, needle):
    from spsc.cli.main import main

    trial, _ = slip_log
    bad = tmp_path / "bad.csv"
    edit(trial.log.copy()).to_csv(bad, index=False)
    assert main(["sense", str(bad), "--out", str(tmp_path / "o")] + CHAMBER) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("spsc sense: error:") and needle in err
