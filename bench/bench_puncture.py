"""The paper's puncture probe on a Type B dome (issue 51, sec. 3.2: a cone of half-angle 30°,
tip Ø 0.1 mm, on the chamber at 50 kPa with its 40 cm³ reservoir): the wall model pressed by
``cone:angle=60,r=0.05`` to 11 mm (the chamber is 13 mm tall) on three meshes, the force and
the largest principal stretch under the tip every 2 mm.

What it shows: the force-travel curve converges (the probe's load spreads through the dome),
the stretch under the 0.05 mm tip does not at 0.125 mm elements — it grows with every
refinement, as under a point load — and the force at 11 mm (about 10 N) stays below the
paper's failure forces (27 to > 80 N): those are reached with the membrane pinned between the
probe and the base, a contact of the cavity with its floor that no model here has.

    python bench/bench_puncture.py [--material tpu60a]
"""

from __future__ import annotations

import argparse
import time

from spsc.cad.geometry import preset
from spsc.core.indenter import parse_indenter
from spsc.fem.engine import CloseValve, Inflate, Press, solve
from spsc.fem.wall.fields import nodal, wall_fields
from spsc.fem.wall.model import WallModel, WallSettings
from spsc.materials import material

PROBE = "cone:angle=60,r=0.05"
MESHES = ((0.5, 2), (0.25, 4), (0.125, 8))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--material", default="tpu60a")
    args = ap.parse_args()
    cone = parse_indenter(PROBE)
    print(f"{PROBE} on the Type B dome, {args.material}, 50 kPa, V_r 40 cm³; "
          "force N / largest stretch at y = 2, 4, 6, 8, 10, 11 mm")
    for size, layers in MESHES:
        t0 = time.perf_counter()
        m = WallModel(preset("B", l=0.0), material(args.material),
                      WallSettings(mesh_size_mm=size, layers=layers))
        res = solve(m, [Inflate(0.05, 4), CloseValve(40000.0), Press(11.0, 22, indenter=cone)])
        pressed = [r for r in res.records if r.kind == "press"]
        cells = []
        for r in pressed[3::4] + pressed[-1:]:
            stretch = nodal(m, wall_fields(m, r.x).stretch).max()
            cells.append(f"{r.force:5.2f} / {stretch:5.2f}")
        print(f"  {size:5.3f} mm, {layers} layers ({time.perf_counter() - t0:5.1f} s, "
              f"{'converged' if res.converged else res.message[:40]}): " + "  ".join(cells))


if __name__ == "__main__":
    main()
