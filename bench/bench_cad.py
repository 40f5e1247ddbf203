"""CAD benchmark: build, export and check every preset bladder and the fingertip.

Prints, per part: analytic and mesh cavity volume against Table 1, the measured minimum wall,
the verdict, and the wall-clock seconds of the build (B-rep + mesh), the export and the check.
Run: ``.venv/bin/python bench/bench_cad.py`` (or ``make bench``).
"""

from __future__ import annotations

import os
import platform
import tempfile
import time
from pathlib import Path

from spsc.cad.bladder import BladderSpec, build_bladder
from spsc.cad.check import check_mesh
from spsc.cad.export import export_part, tessellate
from spsc.cad.fingertip import build_fingertip, measure_pockets
from spsc.cad.geometry import TABLE1_VOLUME_CM3, preset
from spsc.cad.meshbuild import bladder_mesh


def main() -> None:
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores")
    print("type | V Table 1 | V analytic | V mesh (capped) | min wall | verdict | "
          "build s | export s | check s")
    out = Path(tempfile.mkdtemp())
    for t in "ABCD":
        t0 = time.perf_counter()
        b = build_bladder(BladderSpec(preset(t)))
        mesh = bladder_mesh(b.spec)
        t_build = time.perf_counter() - t0
        t0 = time.perf_counter()
        w = export_part(b.solid, b.design, out, f"bladder-{t}", mesh=mesh)
        t_export = time.perf_counter() - t0
        t0 = time.perf_counter()
        r = check_mesh(w["paths"]["stl"], design=b.design, process="fdm")
        t_check = time.perf_counter() - t0
        print(f"{t} | {TABLE1_VOLUME_CM3[t]:.2f} cm³ | {b.design['cavity_volume_mm3'] / 1e3:.4f} cm³"
              f" | {r['cavity_volume'].value / 1e3:.4f} cm³ "
              f"({100 * r['cavity_volume'].details['relative_error']:+.3f} %) | "
              f"{r['min_wall'].value:.3f} mm | {'PASS' if r.passed else 'FAIL'} | "
              f"{t_build:.1f} | {t_export:.1f} | {t_check:.1f}")
    t0 = time.perf_counter()
    tip = build_fingertip()
    mesh = tessellate(tip.solid, 0.005, 0.1)
    t_build = time.perf_counter() - t0
    w = export_part(tip.solid, tip.design, out, "fingertip", mesh=mesh)
    t0 = time.perf_counter()
    r = check_mesh(w["paths"]["stl"], design=tip.design, process="sla")
    pk = measure_pockets(mesh, tessellate(tip.cavity, 0.005, 0.1), tip.design)
    t_check = time.perf_counter() - t0
    print(f"fingertip | cavities {r['cavity_count'].value} | pockets {pk['pocket_count']} | "
          f"min wall under pockets {pk['min_wall_under_pockets_mm']:.3f} mm | "
          f"min wall {r['min_wall'].value:.3f} mm | {'PASS' if r.passed else 'FAIL'} | "
          f"build {t_build:.1f} s | check {t_check:.1f} s")


if __name__ == "__main__":
    main()
