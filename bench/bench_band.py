"""A chamber's band under print and material scatter (issue 49), from the surrogate and from
the wall model on Dask, and the Sobol indices of the Table 1 metrics for Types A–D.

    python bench/bench_band.py [--wall-samples N]      (default 64: 384 wall setups a mode)

The tolerance (``TOL`` below): the wall t0 normal, sd 0.05 mm (an FDM wall's scatter); the
footprint w uniform 10.9–11.1 mm; the setup pressure normal, sd 0.5 kPa (a regulator); the
material's stiffness lognormal, cv 10 %. Prints (1) the Type B profile as a dome (l = 0: the
surrogate's domain), 40 kPa, both modes: the P5, P50, P95 of the mean stiffness and
sensitivity from the surrogate (N = 1024: 6144 setups) and from the wall model (N =
--wall-samples), their differences and times; (2) per type A–D (domes, 40 kPa, closed), the
Sobol total and first-order indices of the two metrics with their 95 % intervals and sums.
"""

from __future__ import annotations

import sys
import time

TOL = {"t0": {"dist": "normal", "sd": 0.05}, "w": {"dist": "uniform", "low": 10.9, "high": 11.1},
       "pressure": {"dist": "normal", "sd": 0.5}, "material": {"dist": "lognormal", "cv": 0.1}}
KEYS = (("stiffness_N_per_mm", "mean stiffness", "N/mm"),
        ("sensitivity_kPa_per_mm", "mean sensitivity", "kPa/mm"))


def _setup(kind: str, reservoir: float):
    from spsc.cad.geometry import preset
    from spsc.core.setup import Setup
    from spsc.materials import material

    return Setup.of(preset(kind, l=0), material("tpu60a"), pressure_kPa=40.0,
                    reservoir_mm3=reservoir, stroke_mm=6.0, points=25, polytropic_n=1.0)


def agreement(wall_n: int) -> None:
    from spsc.models import get
    from spsc.study.band import band
    from spsc.study.tolerance import parse_tolerance

    tol = parse_tolerance(TOL)
    for mode, reservoir in (("high", 0.0), ("low", 40_000.0)):
        setup = _setup("B", reservoir)
        t = time.perf_counter()
        s = band(setup, get("surrogate").Options(), "surrogate", tol, n=1024, seed=0)
        ts = time.perf_counter() - t
        t = time.perf_counter()
        w = band(setup, get("wall").Options(), "wall", tol, n=wall_n, seed=0, workers=2)
        tw = time.perf_counter() - t
        print(f"Type B dome, {mode} mode: surrogate {s['samples']} setups in {ts:.1f} s, wall "
              f"{w['samples']} setups on 2 workers in {tw:.0f} s ({w['refused']} refused)")
        for key, label, unit in KEYS:
            row = ", ".join(f"{q} {s[key][q]:.4g} / {w[key][q]:.4g} "
                            f"({100 * (s[key][q] / w[key][q] - 1):+.2f} %)"
                            for q in ("p5", "p50", "p95"))
            print(f"  {label} ({unit}), surrogate / wall: {row}")


def indices() -> None:
    from spsc.models import get
    from spsc.study.band import band
    from spsc.study.tolerance import parse_tolerance

    tol = parse_tolerance(TOL)
    for kind in "ABCD":
        r = band(_setup(kind, 0.0), get("surrogate").Options(), "surrogate", tol, n=2048,
                 seed=1)
        for metric in ("stiffness", "sensitivity"):
            si = r["sobol"][metric]
            if "not_computed" in si:
                print(f"Type {kind} {metric}: {si['not_computed']}")
                continue
            order = sorted(si["ST"], key=lambda k: -si["ST"][k])
            print(f"Type {kind} {metric} (high mode, {r['samples']} setups): ST " + ", ".join(
                f"{k} {si['ST'][k]:.3f}±{si['ST_conf'][k]:.3f}" for k in order)
                + "; S1 " + ", ".join(f"{k} {si['S1'][k]:.3f}" for k in order)
                + f"; sums S1 {sum(si['S1'].values()):.3f}, ST {sum(si['ST'].values()):.3f}")


if __name__ == "__main__":
    n = int(sys.argv[sys.argv.index("--wall-samples") + 1]) if "--wall-samples" in sys.argv \
        else 64
    agreement(n)
    indices()
