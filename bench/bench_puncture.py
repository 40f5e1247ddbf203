"""The paper's puncture probe on a Type B dome (issue 51, sec. 3.2: a cone of half-angle 30°,
tip Ø 0.1 mm, on the chamber at 50 kPa with its 40 cm³ reservoir): the wall model pressed by
``cone:angle=60,r=0.05`` through the chamber's height onto its base (the dome's cavity meets
the base, :class:`spsc.fem.engine.bodies.Floor`) on three meshes: the probe's force, the
base's push and the largest principal stretch under the tip at y = 2, 6, 10, 14, 14.3 and
14.38 mm (the inflated outer apex is 14.40 mm above the base).

What it shows: the force-travel curve converges while the probe's load spreads through the
dome; the stretch under the 0.05 mm tip does not at 0.125 mm elements — it grows with every
refinement, as under a point load; once the membrane is pinched on the base the force rises
steeply (the base's push) toward the paper's failure forces (27 to > 80 N).

    python bench/bench_puncture.py [--material tpu60a]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from spsc.cad.geometry import preset
from spsc.core.indenter import parse_indenter
from spsc.fem.engine import CloseValve, Inflate, Press, solve
from spsc.fem.wall.fields import nodal, wall_fields
from spsc.fem.wall.model import WallModel, WallSettings
from spsc.materials import material

PROBE = "cone:angle=60,r=0.05"
MESHES = ((0.5, 2), (0.25, 4), (0.125, 8))
SHOWN = (2.0, 6.0, 10.0, 14.0, 14.3, 14.38)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--material", default="tpu60a")
    args = ap.parse_args()
    cone = parse_indenter(PROBE)
    print(f"{PROBE} on the Type B dome, {args.material}, 50 kPa, V_r 40 cm³; force N / base's "
          f"push N / largest stretch at y = {', '.join(f'{y:g}' for y in SHOWN)} mm")
    for size, layers in MESHES:
        t0 = time.perf_counter()
        m = WallModel(preset("B", l=0.0), material(args.material),
                      WallSettings(mesh_size_mm=size, layers=layers), floor=True)
        travel = sorted(set(np.arange(0.5, 14.01, 0.5).round(6)) | set(SHOWN))
        res = solve(m, [Inflate(0.05, 4), CloseValve(40000.0),
                        Press.through(travel, indenter=cone)])
        # the press's records, one per travel until the walk stopped
        pressed = dict(zip(travel, (r for r in res.records if r.kind == "press")))
        cells = []
        for y in SHOWN:
            r = pressed.get(y)
            if r is None:
                cells.append("  —")
                continue
            stretch = nodal(m, wall_fields(m, r.x).stretch).max()
            cells.append(f"{r.force:5.2f} / {r.bodies['floor']:4.2f} / {stretch:5.2f}")
        print(f"  {size:5.3f} mm, {layers} layers ({time.perf_counter() - t0:5.1f} s, "
              f"{'converged' if res.converged else res.message[:60]}): " + "  ".join(cells))


if __name__ == "__main__":
    main()
