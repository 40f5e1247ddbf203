"""The haptic chamber's cost: what the motor and its support film cost the plain Type D in
force and pressure sensitivity.

    make haptic-fem   (= spsc haptic [--mesh-size 1.2] [--out build/haptic-fem] [--parts build])

Three part-FEM curves, Table 1's Type D in TPU 60A, high mode (no reservoir), 40 kPa, the plate
pressed 4 mm at the apex in 0.5 mm steps: the plain Type D (``spsc bladder --type D``), the
haptic chamber without its motor (``spsc bladder --type D --haptic``: the film and pocket only)
and with it (``spsc fem --part … --motor``: the FIT0774 as a rigid insert, met by the dome once
the press closes the printed gap over it). Each curve is the ``spsc fem --part`` JSON, kept
with a key of what computed it (the command, the part file's bytes and the code version of the
part FEM): it is reused only while all three are the same. The figure and ``summary.json`` are
written beside them, where ``spsc report`` finds them (:mod:`spsc.report.haptic`). Times are
the curves' own (meshing + solve, 2-core machine).
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

from spsc.core.curve import Curve

__all__ = ["CASES", "LABELS", "changes", "summary", "figure", "run_study"]

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
            raise RuntimeError(f"spsc bladder {stem} failed")
    return stl


def _case(out: Path, parts: Path, name: str, stem: str, extra, mesh: float) -> Curve:
    from spsc.study.keyed import KeyedFile, input_key

    path = out / f"{name}.json"
    stl = _part(parts, stem)
    argv = ["fem", "--part", str(stl), "--pressure", "40", "--stroke", "4", "--points", "9",
            "--plate-at", "apex", "--mesh-size", f"{mesh:g}", "--material", "tpu60a", "--force",
            "--json", str(path), *extra]
    kept = KeyedFile(path, input_key({"argv": [a for a in argv if a != str(path)],
                                      "part": hashlib.sha256(stl.read_bytes()).hexdigest()},
                                     ("spsc.cli.fem",)))
    if not kept.valid:
        code = _spsc(*argv)
        if code not in (0, 1):
            raise RuntimeError(f"spsc fem --part {stem} {' '.join(extra)} failed ({code})")
        kept.mark()
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


_KEYS = ("stiffness_N_per_mm", "sensitivity_kPa_per_mm", "kPa_per_N",
         "start_stiffness_N_per_mm", "start_sensitivity_kPa_per_mm")


def run_study(out, parts, mesh_size: float = 1.2) -> tuple[dict, dict]:
    """The three curves (``{case: Curve}``) and the summary rows (``{case: row}`` plus the
    changes against the plain chamber and of the motor alone, %), written to
    ``out/summary.json`` with the figure ``out/haptic-cost.png``. ``parts``: where the
    bladders are (made when missing); ``mesh_size`` in mm."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    curves = {name: _case(out, Path(parts), name, stem, extra, mesh_size)
              for name, stem, extra in CASES}
    rows = {name: summary(c) for name, c in curves.items()}
    base = rows["plain"]
    for name, row in rows.items():
        row["vs_plain_pct"] = {k: 100 * (row[k] / base[k] - 1) for k in _KEYS}
    m, f = rows["motor"], rows["film"]
    rows["motor_alone_pct"] = {k: 100 * (m[k] / f[k] - 1) for k in _KEYS}
    rows["mesh_size_mm"] = mesh_size
    (out / "summary.json").write_text(json.dumps(rows, indent=2))
    figure(curves, out / "haptic-cost.png")
    return curves, rows


def changes(rows: dict, name: str, ref: str) -> dict:
    """Relative change (%) of case ``name`` against ``ref`` in the slopes of the summary."""
    return {k: 100 * (rows[name][k] / rows[ref][k] - 1) for k in _KEYS}
