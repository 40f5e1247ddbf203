"""The haptic loop of sec. 4.2 on a generated squeeze: the threshold is rest + 2 % of the
calibration's maximum, and the loop's valve/vibrate commands come where the circuit's own valve,
triggered at that threshold, switched. The chamber is the linear one of test_dynamics (the
loop reads pressures only; 10 kPa setup, 40 cm³ reservoir)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.dynamics.chamber_map import ChamberMap
from spsc.dynamics.circuit import Trigger
from spsc.sensing.haptic import HapticCalibration, HapticLoop, calibrate
from spsc_support import sense_traces as st


def linear_map(v0=3000.0, a=400.0, K=300.0, setup=10.0):
    y = np.linspace(-1.0, 5.0, 25)
    p = np.linspace(0.0, 200.0, 9)
    Y, P = np.meshgrid(y, p, indexing="ij")
    return ChamberMap(y, p, v0 * (1 + P / K) - a * Y, a * P * np.clip(Y, 0, None) / 1e3,
                      np.zeros_like(Y), setup)


SQUEEZE = [[0, -0.3], [0.3, -0.3], [0.8, 4.0], [1.0, 4.0], [1.5, -0.3], [1.8, -0.3]]


def test_threshold_is_rest_plus_two_percent_of_the_squeeze_maximum():
    m = linear_map()
    trial = st.run(m, SQUEEZE, setup_kPa=10.0, valve_open=True, seed=31)
    cal = calibrate(trial.log.t_s, trial.log.pressure_kPa)
    true_max = trial.truth.pressure_kPa.max()
    # the rest: a median of 200 samples (σ/√200 ≈ 0.006 kPa); the maximum: the noisiest
    # sample's, up to ~3.5 σ above the true one (0.3 kPa), which 2 % makes 6 Pa
    assert_allclose(cal.rest_kPa, 10.0, atol=0.02)
    assert 0 <= cal.max_kPa - true_max < 4 * trial.meta["noise_kPa"]
    assert_allclose(cal.threshold_kPa, 10.0 + 0.02 * true_max, atol=0.03)
    assert_allclose(calibrate(trial.log.t_s, trial.log.pressure_kPa,
                              fraction=0.05).threshold_kPa, 10.0 + 0.05 * true_max, atol=0.03)
    with pytest.raises(ParameterError, match="squeeze"):
        calibrate(trial.log.t_s[:250], trial.log.pressure_kPa[:250])  # no squeeze yet


def test_the_loop_closes_the_valve_where_the_threshold_is_crossed(tmp_path):
    m = linear_map()
    cal = calibrate(*(lambda t: (t.log.t_s, t.log.pressure_kPa))(
        st.run(m, SQUEEZE, setup_kPa=10.0, valve_open=True, seed=31)))
    cal.to_json(tmp_path / "haptic.json")
    cal = HapticCalibration.from_json(tmp_path / "haptic.json")
    # the user squeezes again; the circuit's valve closes at the threshold (the device's
    # digital valve), opens again below it less the hysteresis
    trig = (Trigger(cal.threshold_kPa, True, False),
            Trigger(cal.threshold_kPa - cal.hysteresis_kPa, False, True, after_s=1.0))
    from spsc.dynamics import Gas, Valve, sonic_conductance
    from spsc.dynamics.circuit import Circuit, integrate
    from spsc.dynamics.profile import PressProfile

    tr = integrate(m, Circuit(10.0, 40000.0, Valve(sonic_conductance(0.3)), Gas(1.0)),
                   PressProfile.of(SQUEEZE), valve_open=True, dt=1e-3, triggers=trig)
    loop = HapticLoop(cal, smoothing_s=0.0)
    joints, cmds = [], []
    for t, p in zip(tr.t_s, tr.pressure_kPa):
        theta, c = loop.push(t, p)
        joints.append(theta)
        cmds += c
    assert [(c["command"], c.get("state")) for c in cmds] == [
        ("valve", "closed"), ("vibrate", None), ("valve", "open")]
    (t_close, _, _), (t_open, _, _) = tr.switches
    # the loop reads 1 ms samples: it closes at the first sample past the crossing
    assert 0 <= cmds[0]["t_s"] - t_close <= 1e-3 + 1e-9
    # and opens at the first sample below the threshold less the hysteresis: the circuit's
    # valve opened there first, the reservoir's gas lifted the chamber back over it for a few
    # ms, the release took it under again
    p, t = tr.pressure_kPa, tr.t_s
    under = np.flatnonzero((t > t_close) & (p < cal.threshold_kPa - cal.hysteresis_kPa))
    assert cmds[2]["t_s"] == t[under[0]] and t_open <= t[under[0]] < t_open + 0.02
    joints = np.array(joints)
    assert joints.min() == 0.0 and joints.max() == cal.joint_max_deg  # saturates once closed
    rise = (tr.pressure_kPa - cal.rest_kPa) / (cal.max_kPa - cal.rest_kPa)
    early = tr.t_s < t_close
    assert_allclose(joints[early], 90 * np.clip(rise[early], 0, 1), atol=1e-9)
    assert json.loads((tmp_path / "haptic.json").read_text())["haptic_calibration"][
        "fraction"] == 0.02


def test_spsc_sense_haptic_calibrate_writes_the_threshold(tmp_path, capsys):
    from spsc.cli.main import main

    trial = st.run(linear_map(), SQUEEZE, setup_kPa=10.0, valve_open=True, seed=37)
    squeeze = tmp_path / "squeeze.csv"
    trial.log.to_csv(squeeze, index=False)
    out = tmp_path / "cal"
    assert main(["sense", "--haptic-calibrate", str(squeeze), "--out", str(out),
                 "--haptic-fraction", "0.03"]) == 0
    cal = HapticCalibration.from_json(out / "haptic.json")
    assert_allclose(cal.threshold_kPa, cal.rest_kPa + 0.03 * cal.max_kPa, rtol=1e-12)
    assert main(["sense", "--haptic-calibrate", str(squeeze), "--out", str(out),
                 "--haptic-fraction", "1.5"]) == 2
    assert "haptic fraction" in capsys.readouterr().err


@pytest.mark.parametrize("change, needle", [
    ({"threshold_kPa": float("nan")}, "threshold_kPa"),
    ({"threshold_kPa": "abc"}, "threshold_kPa"),
    ({"max_kPa": 9.0}, "max_kPa"),
    ({"threshold_kPa": 12.0}, "threshold_kPa"),
])
def test_an_edited_calibration_is_refused_naming_its_field(tmp_path, change, needle):
    """Issue 53: a calibration with a NaN threshold, a maximum below the rest or a threshold
    of "abc" was accepted (or failed later)."""
    import json

    from spsc.core.errors import ParameterError
    from spsc.sensing.haptic import HapticCalibration

    good = {"rest_kPa": 10.0, "max_kPa": 11.3, "fraction": 0.02, "threshold_kPa": 10.22,
            "noise_kPa": 0.08, "hysteresis_kPa": 0.24, "joint_max_deg": 90.0}
    f = tmp_path / "haptic.json"
    f.write_text(json.dumps({"haptic_calibration": {**good, **change}}))
    with pytest.raises(ParameterError, match=f"haptic calibration {needle}"):
        HapticCalibration.from_json(f)
