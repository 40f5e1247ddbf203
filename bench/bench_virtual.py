"""Chambers stepped for a host simulator (issue 50): the time of one 1 ms step for 1, 100 and
1000 chambers of the Type B dome (its surrogate map), isothermal and air (n = 1.4, thermal
time 0.5 s), the valve to 40 cm³ closed and open (pressed slowly, so its two sides stay
within 0.05 kPa and the substeps rarely run), and the valve opened with every chamber held at
3 mm (its first 100 ms: the substeps run until the sides meet). Time it on a quiet machine.

    python bench/bench_virtual.py
"""

from __future__ import annotations

import time

import numpy as np


def main() -> None:
    from spsc.cad.geometry import preset
    from spsc.dynamics.circuit import Circuit
    from spsc.dynamics.gas import Gas
    from spsc.dynamics.surrogate_map import surrogate_map
    from spsc.dynamics.valve import Valve
    from spsc.materials import material
    from spsc.virtual.chambers import MapTable, VirtualChambers

    t = time.perf_counter()
    m = surrogate_map(preset("B", l=0), material("tpu60a"), setup_kPa=40, top_kPa=80,
                      y_max_mm=5.0)
    table = MapTable(m)
    print(f"the map (surrogate) and its table: {time.perf_counter() - t:.2f} s")
    for n in (1, 100, 1000):
        for gas, name in ((Gas(1.0), "isothermal"), (Gas(1.4, 0.5), "air")):
            for valve, substep in ((False, 1e-4), (True, 1e-4), (True, 1e-3)):
                v = VirtualChambers(m, Circuit(40.0, 40_000.0, Valve(0.06), gas), count=n,
                                    table=table, y0_mm=0.0, substep_s=substep)
                y = np.linspace(0.0, 3.0, n)
                times = []
                for k in range(300):
                    t = time.perf_counter()
                    v.step(y * k / 300, valve, 1e-3)
                    times.append(time.perf_counter() - t)
                step = float(np.median(times))
                what = (f"open, {1e3 * substep:g} ms substeps" if valve else "closed")
                print(f"{n:5d} chambers, {name:10s}, valve {what:22s}: "
                      f"{1e3 * step:.3f} ms a 1 ms step (median of 300, slowest "
                      f"{1e3 * max(times):.3f}; real time x {1e-3 / step:.2f}; "
                      f"{n / step:,.0f} chamber-steps/s)")
            # the valve opened under load: its sides apart, the substeps run until they meet
            v = VirtualChambers(m, Circuit(40.0, 40_000.0, Valve(0.06), gas), count=n,
                                table=table, y0_mm=0.0)
            for k in range(300):
                v.step(3.0 * k / 299, False, 1e-3)
            times = []
            for k in range(100):
                t = time.perf_counter()
                v.step(3.0, True, 1e-3)
                times.append(time.perf_counter() - t)
            settled = next((k for k in range(100) if times[k] < 3 * min(times)), 100)
            print(f"{n:5d} chambers, {name:10s}, valve opened at 3 mm : the first 100 ms "
                  f"{1e3 * np.mean(times):.3f} ms a step on average, the slowest "
                  f"{1e3 * max(times):.3f} ms (substeps for about {settled} ms)")


if __name__ == "__main__":
    main()
