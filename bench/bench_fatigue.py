"""Fatigue (issue 51), the figures of its closing note from the wall model:

1. each catalogue material's law calibrated on its Table 2 test (Type B, 50 kPa, 40 cm³,
   6 mm: the hot spot's energy amplitude W_a, the one-cycle amplitude W_c with F = 4);
2. peak stretch, peak energy amplitude and where, for Types A–D in TPU 60A at the test's
   setup, and the lives of A, C and D predicted from B's calibration (F = 4, and F = 2);
3. the Type B life in TPU 60A at other strokes (4, 5, 8 mm) and pressures (30, 40 kPa).

    python bench/bench_fatigue.py
"""

from __future__ import annotations

import time

from spsc.cad.geometry import preset
from spsc.fem.wall.durability import paper_fatigue_law, squeeze_cycle
from spsc.materials import material
from spsc.materials.catalogue import FATIGUE_TESTS


def _where(p: dict) -> str:
    return f"{p['face']} face, z {p['height_mm']:.1f} mm, r {p['radius_mm']:.1f} mm"


def main() -> None:
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
    print(f"({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
