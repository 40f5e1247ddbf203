"""The haptic loop of sec. 4.2 (issue 29, figure 4) on a real chamber: the Table 1 Type D
chamber at a 10 kPa setup with the paper's 40 cm³ reservoir (the device squeezes in the low
mode), its wall-model map, the ELVH's noise at 1 kHz.

1. A calibration squeeze "with maximum effort" (the plate 3 mm into the chamber in 0.5 s,
   held, released) gives the threshold P_th = P_rest + 2 % of the maximum (``spsc sense
   --haptic-calibrate``'s code).
2. A second, lighter squeeze (2 mm) runs through the circuit, whose valve closes where the
   loop says (the device's digital valve) and opens again below the threshold less the
   hysteresis; the loop's valve and vibrate commands are printed in time with the pressure
   and the joint angle, and against the circuit's own switches.

    python bench/bench_haptic.py [--cache build/cache]
"""

from __future__ import annotations

import argparse

import numpy as np

from spsc.dynamics import Gas, Sensor, Valve, sonic_conductance
from spsc.dynamics.circuit import Circuit, Trigger, integrate
from spsc.dynamics.profile import PressProfile
from spsc.sensing.chamber import chamber_map
from spsc.sensing.haptic import HapticLoop, calibrate
from spsc_support import sense_traces as st

SETUP, RES = 10.0, 40000.0
CALIBRATION = [[0, -0.3], [0.3, -0.3], [0.8, 3.0], [1.2, 3.0], [1.7, -0.3], [2.0, -0.3]]
USE = [[0, -0.3], [0.3, -0.3], [0.9, 2.0], [1.5, 2.0], [2.1, -0.3], [2.5, -0.3]]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cache", default="build/cache")
    args = ap.parse_args(argv)
    m = chamber_map({"type": "D"}, setup_kPa=SETUP, reservoir_mm3=RES, stroke_mm=3.5,
                    mesh_size=1.0, cache_dir=args.cache)
    squeeze = st.run(m, CALIBRATION, setup_kPa=SETUP, reservoir_mm3=RES, valve_open=True,
                     seed=41)
    cal = calibrate(squeeze.log.t_s, squeeze.log.pressure_kPa)
    print(f"calibration squeeze (Type D, {SETUP:g} kPa, low mode, 3 mm): rest "
          f"{cal.rest_kPa:.4f} kPa, maximum {cal.max_kPa:.4f} kPa (true "
          f"{squeeze.truth.pressure_kPa.max():.4f}), threshold {cal.threshold_kPa:.4f} kPa, "
          f"hysteresis {cal.hysteresis_kPa:.4f} kPa")
    trig = (Trigger(cal.threshold_kPa, True, False),
            Trigger(cal.threshold_kPa - cal.hysteresis_kPa, False, True, after_s=1.0))
    circuit = Circuit(SETUP, RES, Valve(sonic_conductance(0.3)), Gas(1.0))
    tr = integrate(m, circuit, PressProfile.of(USE), valve_open=True, dt=1e-3, triggers=trig)
    read = Sensor.preset("elvh", seed=43).read(tr.pressure_kPa)
    loop = HapticLoop(cal)
    print("\nsecond squeeze (2 mm), the loop on the sensor's samples:")
    print(f"{'t (s)':>7s} {'P (kPa)':>9s} {'joint (deg)':>11s}  command")
    for t, p in zip(tr.t_s, read):
        theta, cmds = loop.push(float(t), float(p))
        for c in cmds:
            what = c["command"] + (f" {c['state']}" if "state" in c else
                                   f" {c['duration_s']:g} s")
            print(f"{t:7.3f} {p:9.4f} {theta:11.1f}  {what}")
    k = np.searchsorted(tr.t_s, [0.3, 0.6, 0.9, 1.5, 2.1])
    angle = [HapticLoop(cal, smoothing_s=0.0).push(0.0, tr.pressure_kPa[i])[0] for i in k]
    print("\nthe joint angle of the noise-free pressure: " + ", ".join(
        f"{tr.t_s[i]:.1f} s {a:.1f}°" for i, a in zip(k, angle)))
    print("the circuit's own valve switches (triggered at the same levels): " + ", ".join(
        f"{t:.3f} s {'open' if o else 'closed'} ({why})" for t, o, why in tr.switches))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
