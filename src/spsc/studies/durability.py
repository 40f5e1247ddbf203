"""The report's durability study (issue 51): the paper's fatigue test (sec. 3.2, Table 2) in
the wall model — each catalogue material's fatigue law calibrated on its Type B test, the
lives of Types A–D in TPU 60A predicted from Type B's, the Type B life at other strokes and
pressures — and the puncture test (the probe through the Type B dome onto its base, each
material on the coarse mesh and TPU 60A on three meshes, :mod:`spsc.fem.wall.puncture`),
written where ``spsc report`` finds it (``build/durability``: ``summary.json``, ``lives.png``,
``fields-C.png``, ``puncture.png``). 15–20 minutes on one core, most of it the puncture's
finest mesh.

    spsc fatigue --study [--out build/durability]
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from spsc.cad.geometry import preset
from spsc.core.jsonio import write_json
from spsc.core.provenance import code_provenance
from spsc.fem.wall.durability import PAPER_TEST, paper_fatigue_law, squeeze_cycle
from spsc.fem.wall.puncture import MESHES, PAPER_PUNCTURE, puncture
from spsc.materials import material
from spsc.materials.catalogue import CATALOGUE, FATIGUE_TESTS, failure

__all__ = ["run_study", "run_puncture", "DEFAULT_DIR", "STROKES", "PRESSURES",
           "PUNCTURE_MESHES", "TABLE2_PUNCTURE"]

DEFAULT_DIR = Path("build/durability")
#: the other strokes (mm, at 50 kPa) and pressures (kPa, at 6 mm) of Type B in TPU 60A
STROKES = (4.0, 5.0, 8.0)
PRESSURES = (30.0, 40.0)
#: the meshes TPU 60A's puncture is walked on (the convergence); the others take the first
PUNCTURE_MESHES = MESHES
#: Table 2's puncture forces (N; ``above``: the probe did not puncture it up to that force)
TABLE2_PUNCTURE = {"as40": {"force_N": 27.0, "above": False},
                   "elastic50a": {"force_N": 40.0, "above": False},
                   "tpu60a": {"force_N": 45.0, "above": False},
                   "silicone40a": {"force_N": 80.0, "above": True}}


def _cycle_row(cycle, law, other) -> dict:
    w = cycle.energy_amplitude_MPa
    hot = cycle.fields.peak("energy_amplitude")
    return {"energy_amplitude_MPa": w, "life_cycles": law.life(w),
            "life_other_exponent": law.with_exponent(other).life(w),
            "stretch_max": cycle.fields.peak("stretch_max")["value"],
            "hot_spot": {k: hot[k] for k in ("face", "height_mm", "radius_mm")},
            "converged": cycle.converged, "seconds": cycle.seconds}


def run_study(out=DEFAULT_DIR, progress=print) -> dict:
    """Run the study into ``out``; returns its summary."""
    t0 = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    calibration = {}
    for name, test in FATIGUE_TESTS.items():
        law = paper_fatigue_law(name)
        calibration[name] = {"cycles": test["cycles"], "runout": test["runout"],
                             "exponent": law.exponent, "amplitude_MPa": law.amplitude_MPa,
                             "energy_MPa": law.energy_MPa, "source": test["source"]}
        progress(f"durability: {name} calibrated (W_a {law.amplitude_MPa:.4g} MPa)")
    law = paper_fatigue_law("tpu60a")
    other = 2.0 if law.exponent != 2.0 else 4.0
    types, cycles = {}, {}
    for t in "ABCD":
        cycles[t] = squeeze_cycle(preset(t), material("tpu60a"))
        types[t] = _cycle_row(cycles[t], law, other)
        progress(f"durability: Type {t} {types[t]['life_cycles']:.3g} cycles")
    strokes = {f"{s:g}": _cycle_row(squeeze_cycle(preset("B"), material("tpu60a"),
                                                   stroke_mm=s), law, other)
               for s in STROKES}
    pressures = {f"{p:g}": _cycle_row(squeeze_cycle(preset("B"), material("tpu60a"),
                                                    pressure_kPa=p), law, other)
                 for p in PRESSURES}
    punctured = run_puncture(out, progress)
    summary = {"schema": "spsc.durability", "schema_version": 2, "test": dict(PAPER_TEST),
               "exponent": law.exponent, "other_exponent": other,
               "calibration": calibration, "types": types, "strokes": strokes,
               "pressures": pressures, "puncture": punctured,
               "seconds": time.perf_counter() - t0,
               "provenance": {"commit": code_provenance().commit}}
    write_json(out / "summary.json", summary)
    _figures(out, summary, cycles["C"], law)
    return summary


def _puncture_row(run, criterion) -> dict:
    row = {"mesh": run.mesh.label, "apex_mm": run.mesh.apex_mm, "layers": run.mesh.layers,
           "clearance_mm": run.clearance_mm, "converged": run.converged,
           "message": run.message, "seconds": run.seconds,
           "reached_mm": float(run.travel_mm[-1]) if len(run.travel_mm) else 0.0,
           "force_end_N": float(run.force_N[-1]) if len(run.force_N) else 0.0,
           "stretch_end": float(run.stretch[-1]) if len(run.stretch) else 0.0,
           "at": {}}
    for y in (2.0, 6.0, 10.0) if len(run.travel_mm) else ():  # before the pinch
        k = int(np.argmin(np.abs(run.travel_mm - y)))
        if abs(run.travel_mm[k] - y) < 1e-6:
            row["at"][f"{y:g}"] = {"force_N": float(run.force_N[k]),
                                   "stretch": float(run.stretch[k])}
    row["failure"] = None if criterion is None else run.failure(criterion)
    return row


def run_puncture(out, progress=print, meshes=None) -> dict:
    """The puncture test (Table 2) of every catalogue material on the first of ``meshes``
    (default :data:`PUNCTURE_MESHES`), TPU 60A on each of them; draws ``puncture.png``."""
    meshes = tuple(PUNCTURE_MESHES if meshes is None else meshes)
    dome = preset("B", l=0.0)
    rows, tpu_runs = {}, []
    for name in CATALOGUE:
        criterion, source = failure(name)
        runs = []
        for mesh in meshes if name == "tpu60a" else meshes[:1]:
            runs.append(puncture(dome, material(name), mesh))
            progress(f"durability: puncture {name}, {mesh.label}: {runs[-1].seconds:.0f} s")
        rows[name] = {"criterion": None if criterion is None else {
                          "elongation_pct": criterion.elongation_pct,
                          "stretch": criterion.stretch,
                          "strength_MPa": criterion.strength_MPa},
                      "source": source, "table2": TABLE2_PUNCTURE.get(name),
                      "runs": [_puncture_row(r, criterion) for r in runs]}
        if name == "tpu60a":
            tpu_runs = runs
    from .puncture_figure import draw

    if tpu_runs:
        draw(tpu_runs, failure("tpu60a")[0], Path(out) / "puncture.png",
             title="TPU 60A: the paper's probe through the Type B dome onto its base, three "
                   "meshes (×: the stretch at break reached)")
    return {"test": dict(PAPER_PUNCTURE), "materials": rows}


def _figures(out: Path, s: dict, cycle_c, law) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .fatigue_figure import draw

    fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
    names = list(s["types"])
    for k, (key, label, marker) in enumerate((("life_cycles", f"F = {s['exponent']:g}", "o"),
                                             ("life_other_exponent",
                                              f"F = {s['other_exponent']:g}", "s"))):
        ax.semilogy([i + 0.1 * (k - 0.5) for i in range(len(names))],
                    [s["types"][t][key] for t in names], marker, ms=8, label=label)
    ax.semilogy([names.index("B")], [s["calibration"]["tpu60a"]["cycles"]], "k*", ms=14,
                label="Table 2 (TPU 60A, the calibration)")
    ax.set_xticks(range(len(names)), [f"Type {t}" for t in names])
    ax.set_ylabel("cycles to failure (predicted)")
    ax.set_title("TPU 60A at the paper's fatigue test: 50 kPa, 40 cm³, 0 → 6 mm", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.savefig(out / "lives.png", dpi=120)
    plt.close(fig)
    draw(cycle_c, preset("C"), law, law.life(cycle_c.energy_amplitude_MPa),
         out / "fields-C.png")
