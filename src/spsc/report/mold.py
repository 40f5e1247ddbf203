"""The report's mold section: the mold of every type's bladder (``spsc mold``), its gate, its
volume identities and pull tests, an exploded render; and the gate failing on three broken molds
(a half moved by 1 mm, a core 2 % too small, Type D split horizontally where its flank locks the
upper half). Cheap (seconds per type), so the report builds them itself."""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

import numpy as np

__all__ = ["mold_section", "broken_molds"]


def mold_section(out, types=("A", "B", "C", "D"), *, render: bool = True) -> dict:
    """Build, gate and render the casting mold of each type's Table 1 bladder; figures under
    ``out/mold/``."""
    from spsc.cad.geometry import preset
    from spsc.cad.mold.build import build_mold
    from spsc.cad.mold.gate import mold_gate
    from spsc.cad.mold.spec import MoldSpec
    from spsc.cad.specs import BladderSpec

    dest = Path(out) / "mold"
    dest.mkdir(parents=True, exist_ok=True)
    rows, figures = [], {}
    for t in types:
        t0 = time.perf_counter()
        mold = build_mold(BladderSpec(preset(t)), MoldSpec())
        gate = mold_gate(mold)
        seconds = time.perf_counter() - t0
        pulls = {c.name.removeprefix("pull_"): c.value for c in gate.checks
                 if c.name.startswith("pull_")}
        rows.append({"type": t, "parting": mold.parting, "passed": gate.passed,
                     "failed": list(gate.failed), "seconds": seconds,
                     "pieces": [{"name": p.name, "role": p.role, "volume_mm3": p.solid.volume(),
                                 "pull": None if p.pull is None else [float(x) + 0.0
                                                                      for x in p.pull]}
                                for p in mold.pieces],
                     "wall_error": gate["wall_volume"].value,
                     "symmetric_difference": gate["wall_volume"].details["symmetric_difference"],
                     "core_error": gate["core_volume"].value,
                     "undercut_mm2": pulls, "undercut_z": mold.undercut.get("z", {}),
                     "key_gap_mm": gate["key_clearance"].value,
                     "mold_wall_mm": gate["mold_wall"].value})
        if render:
            from spsc.report.mold_figures import render_mold

            render_mold(mold, dest / f"mold-{t}.png")
            figures[t] = f"mold/mold-{t}.png"
    return {"rows": rows, "figures": figures, "broken": broken_molds(),
            "command": "make mold TYPE=B   # = spsc mold --type B -> build/mold-B/"}


def broken_molds() -> list[dict]:
    """The gate on three broken molds: what fails and its one-line reason."""
    from spsc.cad.geometry import preset
    from spsc.cad.mold.build import build_mold
    from spsc.cad.mold.gate import mold_gate
    from spsc.cad.mold.spec import MoldSpec
    from spsc.cad.specs import BladderSpec

    b = build_mold(BladderSpec(preset("B")), MoldSpec())
    moved = tuple(replace(p, solid=p.solid.translate([0.0, 1.0, 0.0])) if p.name == "upper"
                  else p for p in b.pieces)
    core = b.piece("core").solid
    c = np.asarray(core.bounding_box()).reshape(2, 3).mean(axis=0)
    small = core.translate((-c).tolist()).scale([0.98] * 3).translate(c.tolist())
    shrunk = tuple(replace(p, solid=small) if p.role == "core" else p for p in b.pieces)
    cases = [("Type B, upper half moved 1 mm along y", replace(b, pieces=moved)),
             ("Type B, core scaled by 0.98", replace(b, pieces=shrunk)),
             ("Type D split horizontally (--parting z)",
              build_mold(BladderSpec(preset("D")), MoldSpec(), parting="z"))]
    out = []
    for what, mold in cases:
        gate = mold_gate(mold, printability=False)
        out.append({"case": what, "passed": gate.passed, "failed": list(gate.failed),
                    "reasons": [gate[n].message for n in gate.failed]})
    return out
