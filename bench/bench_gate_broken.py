"""The printability gate on deliberately broken bladders: a hole, a self-intersection, a 0.5 mm
wall and two disjoint parts, each made from a real Type D export and run through ``spsc check``.

Run: ``.venv/bin/python bench/bench_gate_broken.py``; prints each verdict and the failed checks.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import trimesh

from spsc.cad.bladder import BladderSpec, build_bladder
from spsc.cad.geometry import preset
from spsc.cad.meshbuild import bladder_mesh


def check(path: Path, design: dict) -> tuple[int, str]:
    path.with_suffix(".design.json").write_text(json.dumps(design), encoding="utf-8")
    r = subprocess.run([sys.executable, "-m", "spsc.cli.main", "check", str(path)],
                       capture_output=True, text=True)
    return r.returncode, (r.stdout.strip().splitlines() or [""])[-1]


def main() -> None:
    out = Path(tempfile.mkdtemp())
    b = build_bladder(BladderSpec(preset("D")))
    good = bladder_mesh(b.spec).to_trimesh()
    cases = {}
    cases["intact"] = (good, b.design)
    holed = good.copy()
    top = np.argsort(-holed.triangles_center[:, 2])[:20]  # 20 faces at the dome's apex
    holed.update_faces(np.setdiff1d(np.arange(len(holed.faces)), top))
    cases["hole (20 faces removed)"] = (holed, b.design)
    crossing = good.copy()
    v = crossing.vertices.copy()
    apex = np.argsort(-v[:, 2])[:40]
    v[apex, 2] -= 3.0  # push the apex's outer vertices through the inner wall
    crossing.vertices = v
    cases["self-intersection (apex pushed 3 mm in)"] = (crossing, b.design)
    thin = build_bladder(BladderSpec(preset("D", t0=0.5)))
    cases["0.5 mm wall"] = (bladder_mesh(thin.spec).to_trimesh(), thin.design)
    two = trimesh.util.concatenate([good, good.copy().apply_translation([60.0, 0.0, 0.0])])
    cases["two disjoint parts"] = (two, b.design)
    for i, (name, (mesh, design)) in enumerate(cases.items()):
        path = out / f"case{i}.stl"
        mesh.export(path)
        rc, last = check(path, design)
        print(f"{name:42s} exit {rc}: {last}")


if __name__ == "__main__":
    main()
