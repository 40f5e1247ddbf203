"""The haptic chamber's cost (issue 15, figure 3): what the motor and its support film cost the
plain Type D in force and pressure sensitivity.

    make haptic-fem   (= python -m spsc.studies.haptic [--mesh-size 1.2]
                       [--out build/haptic-fem] [--parts build])

Three part-FEM curves, Table 1's Type D in TPU 60A, high mode (no reservoir), 40 kPa, the plate
pressed 4 mm at the apex in 0.5 mm steps: the plain Type D (``spsc bladder --type D``), the
haptic chamber without its motor (``spsc bladder --type D --haptic``: the film and pocket only)
and with it (``spsc fem --part … --motor``: the FIT0774 as a rigid insert, met by the dome once
the press closes the printed gap over it). Each curve is the ``spsc fem --part`` JSON, reused
when it exists (delete the folder to measure again); the figure and ``summary.json`` are
written beside them, where ``spsc report`` finds them (:mod:`.report_haptic`). Times are the
curves' own (meshing + solve, 2-core machine).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

from spsc.core.curve import Curve


__all__ = ["CASES", "LABELS", "summary", "figure", "main"]

LABELS = {"plain": "Type D", "film": "haptic chamber, no motor",
          "motor": "haptic chamber with its motor"}

CASES = (("plain", "bladder-D", ()), ("film", "bladder-D-haptic", ()),
         ("motor", "bladder-D-haptic", ("--motor",)))


def _spsc(*argv) -> int:
    return subprocess.run([sys.executable, "-m", "spsc.cli.main", *argv]).returncode


def _part(parts: Path, stem: str) -> Path:
    stl = parts / stem / f"{stem}.stl"
    if not stl.exists():
        extra = ("--haptic",) if "haptic" in stem else ()
        if _spsc("bladder", "--type", "D", *extra, "--out", str(stl.parent)) != 0:
            raise SystemExit(f"spsc bladder {stem} failed")
    return stl


def _case(out: Path, parts: Path, name: str, stem: str, extra, mesh: float) -> Curve:
    path = out / f"{name}.json"
    if not path.exists():
        code = _spsc("fem", "--part", str(_part(parts, stem)), "--pressure", "40", "--stroke",
                     "4", "--points", "9", "--plate-at", "apex", "--mesh-size", f"{mesh:g}",
                     "--material", "tpu60a", "--force", "--json", str(path), *extra)
        if code not in (0, 1):
            raise SystemExit(f"spsc fem --part {stem} {' '.join(extra)} failed ({code})")
    return Curve.from_json(path)


def summary(curve: Curve) -> dict:
    """End values and slopes (mm, N, kPa): mean over the stroke, over its first and over its
    last mm."""
    y, F = curve.y_mm, curve.force_N
    dP = curve.pressure_kPa - curve.pressure_kPa[0]
    last = y >= y[-1] - 1.0 - 1e-9
    first = y <= 1.0 + 1e-9
    out = {"converged": bool(curve.all_converged), "y_mm": float(y[-1]),
           "force_N": float(F[-1]), "dp_kPa": float(dP[-1]),
           "stiffness_N_per_mm": float(F[-1] / y[-1]),
           "sensitivity_kPa_per_mm": float(dP[-1] / y[-1]),
           "kPa_per_N": float(dP[-1] / F[-1]),
           "start_stiffness_N_per_mm": float(np.ptp(F[first]) / np.ptp(y[first])),
           "start_sensitivity_kPa_per_mm": float(np.ptp(dP[first]) / np.ptp(y[first])),
           "end_stiffness_N_per_mm": float(np.ptp(F[last]) / np.ptp(y[last])),
           "end_sensitivity_kPa_per_mm": float(np.ptp(dP[last]) / np.ptp(y[last])),
           "dofs": int(curve.setup["dofs"]), "seconds": float(curve.solver.seconds)}
    motor = curve.series.get("force_motor_N")
    if motor is not None:
        out["motor_force_N"] = float(motor[-1])
        out["motor_peak_N"] = float(np.nanmax(motor))
        touch = np.flatnonzero(motor > 0)
        out["motor_met_at_mm"] = float(y[touch[0]]) if touch.size else None
    return out


def figure(curves: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    for name, c in curves.items():
        dP = c.pressure_kPa - c.pressure_kPa[0]
        ax[0].plot(c.y_mm, c.force_N, "o-", label=LABELS[name])
        ax[1].plot(c.y_mm, dP, "o-", label=LABELS[name])
        ax[2].plot(c.force_N, dP, "o-", label=LABELS[name])
        if "force_motor_N" in c.series:
            ax[0].plot(c.y_mm, c.series["force_motor_N"], "k--", label="through the motor")
    ax[0].set(xlabel="plate stroke y (mm)", ylabel="plate force F (N)")
    ax[1].set(xlabel="plate stroke y (mm)", ylabel="pressure rise ΔP (kPa)")
    ax[2].set(xlabel="plate force F (N)", ylabel="pressure rise ΔP (kPa)")
    for a in ax:
        a.grid(alpha=0.3)
    ax[0].legend()
    fig.suptitle("Type D, TPU 60A, 40 kPa high mode, apex press: the motor's cost (part FEM)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mesh-size", type=float, default=1.2)
    ap.add_argument("--out", default="build/haptic-fem")
    ap.add_argument("--parts", default="build", help="where the parts are (make bladder's "
                    "build/bladder-D and build/bladder-D-haptic; made when missing)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    curves = {name: _case(out, Path(args.parts), name, stem, extra, args.mesh_size)
              for name, stem, extra in CASES}
    rows = {name: summary(c) for name, c in curves.items()}
    base = rows["plain"]
    keys = ("stiffness_N_per_mm", "sensitivity_kPa_per_mm", "kPa_per_N",
            "start_stiffness_N_per_mm", "start_sensitivity_kPa_per_mm")
    for name, row in rows.items():
        row["vs_plain_pct"] = {k: 100 * (row[k] / base[k] - 1) for k in keys}
    m, f = rows["motor"], rows["film"]
    rows["motor_alone_pct"] = {k: 100 * (m[k] / f[k] - 1) for k in keys}
    rows["mesh_size_mm"] = args.mesh_size
    (out / "summary.json").write_text(json.dumps(rows, indent=2))
    figure(curves, out / "haptic-cost.png")
    print(f"{'case':30s} {'F(4) N':>7s} {'ΔP kPa':>7s} {'N/mm':>6s} {'kPa/mm':>6s} "
          f"{'kPa/N':>6s} {'0-1 mm: N/mm':>12s} {'kPa/mm':>6s} {'3-4 mm: N/mm':>12s} "
          f"{'kPa/mm':>6s} {'motor N':>7s} {'s':>5s}")
    for name in curves:
        r = rows[name]
        print(f"{LABELS[name]:30s} {r['force_N']:7.2f} {r['dp_kPa']:7.2f} "
              f"{r['stiffness_N_per_mm']:6.2f} {r['sensitivity_kPa_per_mm']:6.2f} "
              f"{r['kPa_per_N']:6.3f} {r['start_stiffness_N_per_mm']:12.2f} "
              f"{r['start_sensitivity_kPa_per_mm']:6.2f} {r['end_stiffness_N_per_mm']:12.2f} "
              f"{r['end_sensitivity_kPa_per_mm']:6.2f} {r.get('motor_force_N', float('nan')):7.2f} "
              f"{r['seconds']:5.0f}")
    for name, ref in (("film", "plain"), ("motor", "plain"), ("motor", "film")):
        v = {k: 100 * (rows[name][k] / rows[ref][k] - 1) for k in keys}
        print(f"{LABELS[name]} vs {LABELS[ref]}: stiffness {v['stiffness_N_per_mm']:+.1f} % "
              f"(first mm {v['start_stiffness_N_per_mm']:+.1f} %), sensitivity "
              f"{v['sensitivity_kPa_per_mm']:+.1f} % (first mm "
              f"{v['start_sensitivity_kPa_per_mm']:+.1f} %), kPa per N {v['kPa_per_N']:+.1f} %")
    print(f"the motor is met at y = {m.get('motor_met_at_mm')} mm and carries "
          f"{m.get('motor_force_N', float('nan')):.2f} N of the plate's {m['force_N']:.2f} N at "
          f"the end (peak {m.get('motor_peak_N', float('nan')):.2f} N)")
    print(f"written: {out / 'summary.json'}, {out / 'haptic-cost.png'}")
    return 0 if all(rows[name]["converged"] for name in curves) else 1


if __name__ == "__main__":
    raise SystemExit(main())
