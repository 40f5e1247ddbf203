"""The release path of Type C (issue 52, item 2): the squeeze-release cycle of Table 1's
Type C at 10 kPa on the 40 cm³ reservoir (and vented), 6 mm at 1 mm/s, with the
snap-throughs followed on the way down and back up, in the wall model and the 3D FEM (quarter
model, default mesh; about 2 min): the jumps (travel, force before and after, energy released)
and the largest loading-minus-unloading force.

    python bench/bench_snap_cycle.py [--no-fem]
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np

from spsc.cad.geometry import preset
from spsc.fem.engine import CloseValve, Cycle, Inflate, solve
from spsc.fem.solid.chamber import build_model, chamber_run
from spsc.fem.wall.cycle import wall_cycle
from spsc.materials import material


def _jumps(jumps) -> str:
    return ", ".join(f"{y:.3g} mm {a:.4g} -> {b:.4g} N ({e:.3g} mJ)" for y, a, b, e in jumps) \
        or "none"


def fem_cycle(pressure_kPa: float, reservoir_mm3: float) -> None:
    t0 = time.perf_counter()
    run = chamber_run(preset("C"), material("tpu60a"), pressure_kPa=pressure_kPa,
                      reservoir_mm3=reservoir_mm3, stroke_mm=6, points=13)
    model = build_model(run)
    s = dataclasses.replace(model.default_settings(), snap_through=True)
    y = np.linspace(0.0, 6.0, 25)
    travels = np.concatenate([y, y[-2::-1]])
    times = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(travels)))])
    steps = [Inflate(pressure_kPa / 1000.0, 4), CloseValve(reservoir_mm3)] \
        if pressure_kPa > 0 else []
    res = solve(model, steps + [Cycle(tuple(times), tuple(travels))], settings=s)
    F = np.array([r.force for r in res.records if r.kind == "press"])
    n = y.size - 1
    # loading at y_0..y_n (F[:n] from y_1), unloading back from y_n (F[n - 1]) to y_0
    gap = np.r_[0.0, F[:n]] - np.r_[F[n:][::-1], F[n - 1]] if F.size == 2 * n else None
    jumps = [(j.y_mm, j.force_before_N, j.force_after_N, j.energy_released_mJ)
             for j in res.jumps]
    print(f"  3D FEM: {res.message[:60]}; jumps: {_jumps(jumps)}; largest gap "
          f"{'incomplete' if gap is None else f'{np.max(gap):.3g} N'} "
          f"({time.perf_counter() - t0:.0f} s)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--no-fem", action="store_true")
    args = ap.parse_args()
    for p, vr in ((10.0, 40000.0), (0.0, 0.0)):
        r = wall_cycle(preset("C"), material("tpu60a"), None, snaps=True, pressure_kPa=p,
                       reservoir_mm3=vr)
        print(f"Type C, {p:g} kPa, V_r {vr:g} mm³: wall model {r.message[:40]}; jumps: "
              f"{_jumps(r.jumps)}; largest gap {r.hysteresis_N:.3g} N ({r.seconds:.0f} s)")
        if not args.no_fem and p > 0:
            fem_cycle(p, vr)


if __name__ == "__main__":
    main()
