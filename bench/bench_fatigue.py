"""Fatigue (issue 51), the figures of its closing note from the wall model:

1. each catalogue material's law calibrated on its Table 2 test (Type B, 50 kPa, 40 cm³,
   6 mm: the hot spot's energy amplitude W_a, the one-cycle amplitude W_c with F = 4);
2. peak stretch, peak energy amplitude and where, for Types A–D in TPU 60A at the test's
   setup, and the lives of A, C and D predicted from B's calibration (F = 4, and F = 2);
3. the Type B life in TPU 60A at other strokes (4, 5, 8 mm) and pressures (30, 40 kPa);
4. with ``--fem``: the peaks of Types A-D by the 3D FEM (quarter model, default mesh) against
   the wall model's, and where (about 25 s a type).

    python bench/bench_fatigue.py [--fem]
"""

from __future__ import annotations

import argparse
import time

from spsc.cad.geometry import preset
from spsc.fem.wall.durability import paper_fatigue_law, squeeze_cycle
from spsc.materials import material
from spsc.materials.catalogue import FATIGUE_TESTS


def _where(p: dict) -> str:
    return f"{p['face']} face, z {p['height_mm']:.1f} mm, r {p['radius_mm']:.1f} mm"


def fem_against_wall() -> None:
    from spsc.fem.solid.chamber import chamber_run, run_chamber
    from spsc.fem.solid.fields import cycle_fields

    print("4. the 3D FEM (default mesh) against the wall model, TPU 60A at the test's setup")
    for t in "ABCD":
        g = preset(t)
        run = chamber_run(g, material("tpu60a"), pressure_kPa=50, reservoir_mm3=40000,
                          stroke_mm=6, points=13)
        _, res, model = run_chamber(run)
        rest = [r for r in res.records if r.kind != "press"][-1]
        fem = cycle_fields(model, [rest.x] + [r.x for r in res.records if r.kind == "press"],
                           g)
        wall = squeeze_cycle(g, material("tpu60a")).fields
        for name in ("stretch_max", "energy_amplitude"):
            a, b = fem.peak(name), wall.peak(name)
            print(f"   {t} {name:17s} FEM {a['value']:.4f} ({_where(a)}), wall "
                  f"{b['value']:.4f} ({_where(b)}): {100 * (a['value'] / b['value'] - 1):+.1f} %")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fem", action="store_true")
    args = ap.parse_args()
    t0 = time.perf_counter()
    print("1. calibration on Table 2 (Type B, 50 kPa, V_r 40 cm³, 0 -> 6 mm, F = 4)")
    for name, test in FATIGUE_TESTS.items():
        law = paper_fatigue_law(name)
        print(f"   {name:12s} {'>' if test['runout'] else ' '}{test['cycles']:6.0f} cycles  "
              f"W_a {law.amplitude_MPa:.4f} MPa  W_c {law.energy_MPa:.4f} MPa")
    law = paper_fatigue_law("tpu60a")
    print("2. Types A-D in TPU 60A at the test's setup (peaks away from the clamped base)")
    for t in "ABCD":
        c = squeeze_cycle(preset(t), material("tpu60a"))
        p = c.peaks()
        w = c.energy_amplitude_MPa
        print(f"   {t}: stretch max {p['stretch_max']['value']:.4f} ({_where(p['stretch_max'])});"
              f" energy amplitude {w:.4f} MPa ({_where(p['energy_amplitude'])}); "
              f"life {law.life(w):.3g} (F = 2: {law.with_exponent(2).life(w):.3g}); "
              f"{c.seconds:.1f} s")
    print("3. Type B, TPU 60A: other strokes and pressures")
    for stroke, pressure in ((4, 50), (5, 50), (8, 50), (6, 30), (6, 40)):
        c = squeeze_cycle(preset("B"), material("tpu60a"), stroke_mm=stroke,
                          pressure_kPa=pressure)
        w = c.energy_amplitude_MPa
        print(f"   {stroke} mm at {pressure} kPa: W_a {w:.4f} MPa, life {law.life(w):.3g} "
              f"(F = 2: {law.with_exponent(2).life(w):.3g})")
    if args.fem:
        fem_against_wall()
    print(f"({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
