"""The gate's verdict and the sweep's ``printable`` column on the same random designs (issue 30):
shared by tests/test_printability.py (a few designs) and bench/bench_printability.py (200).

:func:`random_chamber` draws a bladder over the sweep's parameter ranges (types A–D, the
verified design space of sec. 2.2), a quarter of them with a wall under the material's process
minimum, so both verdicts are exercised both ways. :func:`compare` judges one design the two
ways a user meets: ``spsc bladder`` (the bladder mesh written to STL, the gate on it with the
design facts, for the material's process) and ``spsc sweep`` (:func:`spsc.sweep.evaluate.evaluate`,
its ``printable`` column, for the same process).
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from spsc.cad.process import PROCESSES
from spsc.cli.bladder import MATERIAL_PROCESS
from spsc.core.errors import ParameterError

__all__ = ["random_chamber", "compare"]

#: The sweep's setup for the comparison (its defaults): pressure kPa gauge, reservoir mm³.
SETUP = {"pressure": 40.0, "reservoir": 40000.0}
#: The cheapest model: ``printable`` does not depend on the model (it is judged first).
MODEL = "simplified"


def random_chamber(rng) -> dict:
    """A random design (numpy Generator ``rng``) as ``spsc bladder`` and ``spsc sweep`` take it:
    type, the seven parameters (mm; 4 significant digits, as typed), material, flange holes and
    tube (mm). w 5–15 mm, h/w 0.5–2, l/w 0–3 (0 for a quarter), n1, n2 and c_y in the type's
    family (c_y 0.05–0.9 for Type D); t0 up to 0.2 w and at least the material's process
    minimum, or (one in four) 60–100 % of that minimum."""
    kind = str(rng.choice(list("ABCD")))
    material = str(rng.choice(list(MATERIAL_PROCESS)))
    minimum = PROCESSES[MATERIAL_PROCESS[material]].min_wall_mm
    w = rng.uniform(5.0, 15.0)
    h = w * rng.uniform(0.5, 2.0)
    l = 0.0 if rng.random() < 0.25 else w * rng.uniform(0.0, 3.0)
    if rng.random() < 0.25:
        t0 = rng.uniform(0.6, 1.0) * minimum
    else:
        lo = max(minimum, 0.02 * w)
        t0 = rng.uniform(lo, max(lo, 0.2 * w))
    n1 = {"A": rng.uniform(3, 8), "B": 2.0, "C": rng.uniform(2, 8), "D": 2.0}[kind]
    n2 = {"A": rng.uniform(2, 8), "B": rng.uniform(2, 8), "C": 1.0, "D": rng.uniform(2, 8)}[kind]
    cy = rng.uniform(0.05, 0.9) if kind == "D" else 0.0
    r4 = lambda v: float(f"{v:.4g}")  # noqa: E731
    return {"type": kind, "w": r4(w), "h": r4(h), "l": r4(l), "t0": r4(t0), "n1": r4(n1),
            "n2": r4(n2), "cy": r4(cy), "material": material,
            "flange_holes": int(rng.choice([0, 2, 4])),
            "tube_id": float(f"{rng.uniform(1.6, 4.4):.3g}")}


def compare(d: dict) -> dict:
    """Both verdicts of the design ``d`` (:func:`random_chamber`): ``gate`` (passed), ``failed``
    (the gate's failed checks), ``sweep`` (the printable column), ``reason`` (the column's
    text), ``overhang_deg`` and ``wall_mm`` (the rule's measures), ``seconds``; ``invalid``
    with the one-line error when the bladder refuses the design (then neither judges it)."""
    from spsc.cad.bladder import bladder_design
    from spsc.cad.check import check_mesh
    from spsc.cad.export import write_stl
    from spsc.cad.geometry import PARAMS, preset
    from spsc.cad.meshbuild import bladder_mesh
    from spsc.cad.specs import bladder_spec
    from spsc.sweep.evaluate import evaluate

    t0 = time.perf_counter()
    process = MATERIAL_PROCESS[d["material"]]
    try:  # what spsc bladder checks before it builds anything
        spec = bladder_spec(preset(d["type"], **{k: d[k] for k in PARAMS}), d["flange_holes"],
                            d["tube_id"])
    except ParameterError as exc:
        return {"invalid": str(exc), "process": process}
    with tempfile.TemporaryDirectory() as tmp:
        stl = write_stl(bladder_mesh(spec), Path(tmp) / "bladder.stl")
        report = check_mesh(stl, design=bladder_design(spec), process=process)
    row = evaluate({k: d[k] for k in ("type", *PARAMS, "material")} | SETUP, MODEL, process)
    rule = report["printability"]
    return {"process": process, "gate": bool(report.passed), "failed": list(report.failed),
            "sweep": None if row["printable"] is None else bool(row["printable"]),
            "reason": row["printability"], "overhang_deg": rule.value["overhang_deg"],
            "wall_mm": rule.value["wall_mm"], "mesh_wall_mm": report["min_wall"].value,
            "seconds": time.perf_counter() - t0}
