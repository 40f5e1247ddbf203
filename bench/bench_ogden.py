"""An Ogden law fitted to tension tests and solved by the wall model and the 3D FEM, beside the
neo-Hookean fit of the same data (issue 47's closing figure 3).

    python bench/bench_ogden.py [--out build/bench/ogden]

Fits both laws to Treloar's three tests (tests/data, spsc fit-material: Ogden with three
terms), runs a Type B dome (l = 0) pressed 6 mm with each: the wall model at 10 and 30 kPa,
the 3D FEM at 10 kPa (its default mesh), both closed; prints the end force, the mean stiffness
and sensitivity and the solve times, and draws the curves (OUT/ogden.png).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
CASES = (("wall", 10.0), ("wall", 30.0), ("fem", 10.0))


def _spsc(*argv) -> None:
    subprocess.run([sys.executable, "-m", "spsc.cli.main", *map(str, argv)], check=True,
                   capture_output=True, text=True)


def main(out: Path) -> None:
    from spsc.core.curve import Curve

    out.mkdir(parents=True, exist_ok=True)
    tests = [DATA / f"treloar_{t}.csv" for t in ("uniaxial", "equibiaxial", "planar")]
    laws = {"neo-Hookean": out / "nh.json", "Ogden (3 terms)": out / "ogden.json"}
    _spsc("fit-material", *tests, "--law", "neo-hookean", "--out", laws["neo-Hookean"])
    _spsc("fit-material", *tests, "--law", "ogden", "--ogden-terms", "3", "--out",
          laws["Ogden (3 terms)"])
    curves = {}
    for model, p in CASES:
        for name, path in laws.items():
            j = out / f"{model}-{p:g}-{path.stem}.json"
            _spsc("curve", "--model", model, "--type", "B", "--l", "0", "--pressure", p,
                  "--stroke", 6, "--material", path, "--json", j, "--quiet")
            curves[model, p, name] = Curve.from_json(j)
    print(f"{'model':6s} {'kPa':>4s} {'law':16s} {'F(6 mm) N':>10s} {'k N/mm':>8s} "
          f"{'s kPa/mm':>9s} {'solve s':>8s}")
    for (model, p, name), c in curves.items():
        print(f"{model:6s} {p:4g} {name:16s} {c.force_N[-1]:10.3f} "
              f"{c.mean_stiffness(reached=True):8.4f} {c.mean_sensitivity(reached=True):9.4f} "
              f"{c.solver.seconds:8.1f}")
    for model, p in CASES:
        a, b = (curves[model, p, n] for n in laws)
        print(f"{model} at {p:g} kPa: Ogden - neo-Hookean force at 6 mm "
              f"{100 * (b.force_N[-1] / a.force_N[-1] - 1):+.2f} %, mean stiffness "
              f"{100 * (b.mean_stiffness(reached=True) / a.mean_stiffness(reached=True) - 1):+.2f} %")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for (model, p, name), c in curves.items():
        style = "-" if name.startswith("neo") else "--"
        color = {("wall", 10.0): "C0", ("wall", 30.0): "C1", ("fem", 10.0): "C2"}[model, p]
        label = f"{model} {p:g} kPa, {name}"
        axes[0].plot(c.y_mm, c.force_N, style, color=color, label=label)
        axes[1].plot(c.y_mm, c.pressure_kPa - c.pressure_kPa[0], style, color=color)
    axes[0].set(xlabel="plate travel (mm)", ylabel="force (N)",
                title="Type B dome, Treloar's rubber: two fits of the same tests")
    axes[1].set(xlabel="plate travel (mm)", ylabel="pressure rise (kPa)")
    axes[0].legend(frameon=False, fontsize=8)
    fig.savefig(out / "ogden.png", dpi=110)
    print(f"figure: {out / 'ogden.png'}")


if __name__ == "__main__":
    main(Path(sys.argv[sys.argv.index("--out") + 1]) if "--out" in sys.argv
         else Path("build/bench/ogden"))
