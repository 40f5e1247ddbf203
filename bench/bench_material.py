"""Issue 12's figures: material fitting and calibration, measured.

    python bench/bench_material.py            # every figure (about 6 min on 2 cores)
    python bench/bench_material.py --quick    # without the Table 1 calibrations (about 1 min)

1. synthetic recovery: Yeoh (3 terms) and Ogden (2 and 3 pairs) from uniaxial + equibiaxial data
   with 1 % noise: the fitted stress against the truth, and how often the 95 % intervals hold the
   true constants (all three tests, 15 points each, seeded repetitions);
2. Treloar (1944): R² per test of every law, and the fitting time;
3. a material file end to end: tpu60a written as a file and read back gives the catalogue's forces;
4. calibration: a bench curve made by the wall model at μ × 1.6 with 1 % noise, the factor
   recovered and the time, for the open and the closed (40 kPa) chamber, dome and Table 1 Type B.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path

import numpy as np

from spsc.cad.geometry import preset
from spsc.fem.wall.calibrate import calibrate, scaled
from spsc.fem.wall import wall_curve
from spsc.materials.fit.fitting import fit_law, fit_laws
from spsc.materials.fit.laws import TESTS, OgdenLaw, law
from spsc.core.bench import BenchData
from spsc.materials.data import TestData, read_tests
from spsc.materials.file import material_record
from spsc.materials import material

DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
#: Known constants (MPa; Ogden's exponents dimensionless), stable, every term significant.
TRUE = {"neo-hookean": (law("neo-hookean"), [0.8]),
        "mooney-rivlin": (law("mooney-rivlin"), [0.4, 0.1]),
        "yeoh": (law("yeoh"), [0.5, -0.02, 0.002]),
        "ogden-2": (OgdenLaw(2), [0.6, 1.8, -0.05, -2.5]),
        "ogden-3": (OgdenLaw(3), [0.5, 1.6, 0.003, 4.5, -0.02, -1.5])}


def synthetic(fl, params, tests, points, noise, seed):
    rng = np.random.default_rng(seed)
    out = []
    for t in tests:
        lam = np.linspace(1.05, 2.0 if t == "equibiaxial" else 3.0, points)
        P = fl.stress(t, lam, params)
        out.append(TestData(t, lam, P * (1.0 + noise * rng.standard_normal(P.shape))))
    return out


def recovery(repeats: int) -> None:
    print("1. synthetic recovery, 1 % noise")
    print(f"{'law':14s} {'stress err uni+equi: max / RMS':>32s} {'95 % CI coverage':>18s}")
    for name, (fl, params) in TRUE.items():
        p = np.asarray(params)
        worst, rms, inside = 0.0, 0.0, []
        for seed in range(repeats):
            tests = synthetic(fl, params, ("uniaxial", "equibiaxial"), 20, 0.01, seed)
            f = fit_law(fl, tests)
            e = np.concatenate([f.stress(d.test, d.stretch) / fl.stress(d.test, d.stretch, p) - 1
                                for d in tests])
            worst, rms = max(worst, np.abs(e).max()), max(rms, np.sqrt(np.mean(e ** 2)))
            g = fit_law(fl, synthetic(fl, params, TESTS, 15, 0.01, 1000 + seed))
            inside.append((g.ci95[:, 0] <= p) & (p <= g.ci95[:, 1]))
        print(f"{name:14s} {100 * worst:14.2f} % / {100 * rms:.2f} % {100 * np.mean(inside):15.1f} %"
              f"  ({repeats} fits)")


def treloar() -> None:
    tests, _ = read_tests(sorted(DATA.glob("treloar_*.csv")))
    t0 = time.perf_counter()
    fits = fit_laws(("neo-hookean", "mooney-rivlin", "yeoh", "ogden"), tests, ogden_terms=3)
    seconds = time.perf_counter() - t0
    print(f"\n2. Treloar (1944), {sum(d.stretch.size for d in tests)} points, four laws fitted in "
          f"{seconds:.2f} s")
    for name, f in fits.items():
        r2 = " / ".join(f"{f.r2[t]:.3f}" for t in ("uniaxial", "equibiaxial", "planar"))
        print(f"   {name:14s} R² uniaxial / equibiaxial / planar {r2}")


def material_file_end_to_end() -> None:
    cat = material("tpu60a")
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "tpu60a-file.json"
        record = material_record("tpu60a-file", "neo-hookean", {"C10": cat.shear_modulus / 2},
                                 source="bench: the catalogue's tpu60a as a file")
        path.write_text(json.dumps(record), encoding="utf-8")
        g = preset("D", l=0.0)
        a = wall_curve(g, cat, pressure_kPa=40.0, stroke_mm=2.0, points=3)
        b = wall_curve(g, material(str(path)), pressure_kPa=40.0, stroke_mm=2.0, points=3)
    diff = np.max(np.abs(a.force_N - b.force_N))
    print(f"\n3. tpu60a as a file vs catalogue (Type D dome, wall, 40 kPa): forces "
          f"{np.round(a.force_N, 4).tolist()} vs {np.round(b.force_N, 4).tolist()} N, "
          f"max difference {diff:.1e} N")


def calibration(quick: bool) -> None:
    print("\n4. calibration: bench = wall model at μ × 1.6 + 1 % noise (21 points, 2.5 mm)")
    mat = material("tpu60a")
    cases = [("B dome", preset("B", l=0.0))] + ([] if quick else [("B Table 1", preset("B"))])
    rng = np.random.default_rng(7)
    for label, g in cases:
        for p in (0.0, 40.0):
            c = wall_curve(g, scaled(mat, 1.6), pressure_kPa=p, stroke_mm=2.5, points=21)
            noisy = lambda v: v * (1 + 0.01 * rng.standard_normal(v.shape))  # noqa: E731
            bench = BenchData(c.y_mm, noisy(c.force_N),
                              None if p == 0 else p + noisy(c.pressure_kPa - p), source="bench")
            t0 = time.perf_counter()
            cal = calibrate(bench, g, mat, pressure_kPa=p, points=13)
            dt = time.perf_counter() - t0
            mode = "open" if p == 0 else f"closed {p:g} kPa"
            print(f"   {label:10s} {mode:16s} factor {cal.scale:.4f} ({100 * (cal.scale / 1.6 - 1):+.2f} %),"
                  f" {cal.evaluations} wall solves, {dt:.1f} s")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="skip the Table 1 calibrations")
    ap.add_argument("--repeats", type=int, default=100)
    a = ap.parse_args()
    recovery(a.repeats)
    treloar()
    material_file_end_to_end()
    calibration(a.quick)


if __name__ == "__main__":
    main()
