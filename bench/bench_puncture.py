"""The paper's puncture test (issue 51, sec. 3.2, Table 2) in the wall model: the probe
``cone:angle=60,r=0.05`` (half-angle 30°, tip Ø 0.1 mm, sticking) pressed on the Type B dome
at 50 kPa with its 40 cm³ reservoir, through the chamber's height onto its base
(:mod:`spsc.fem.wall.puncture`), on the three meshes graded to the tip
(:data:`~spsc.fem.wall.puncture.MESHES`): the probe's force, the base's push and the largest
principal stretch under the tip at y = 2, 6, 10, 14 mm and where the walk ended, then the
force at which the stretch reaches each material's stretch at break.

    python bench/bench_puncture.py [--material tpu60a,elastic50a] [--meshes 0,1,2]
                                   [--stick-increment MM]

``--stick-increment``: the longest travel of one increment on the sticking probe (default
the engine's 0.05 mm): the stretch under the tip depends on it (a node is anchored at the end
of the increment it touched in).
"""

from __future__ import annotations

import argparse
import dataclasses

from spsc.cad.geometry import preset
from spsc.fem.wall import puncture as P
from spsc.materials import material
from spsc.materials.catalogue import failure

SHOWN = (2.0, 6.0, 10.0, 14.0)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--material", default="tpu60a,elastic50a")
    ap.add_argument("--meshes", default="0,1,2")
    ap.add_argument("--stick-increment", type=float, default=None)
    args = ap.parse_args()
    if args.stick_increment is not None:  # the engine's default for the sticking probe
        from spsc.fem.wall.model import WallModel

        base = WallModel.default_settings
        WallModel.default_settings = lambda self: dataclasses.replace(
            base(self), stick_increment=args.stick_increment)
    dome = preset("B", l=0.0)
    for name in args.material.split(","):
        criterion, source = failure(name)
        print(f"{name}: force N / base's push N / λ1 under the tip at y = "
              f"{', '.join(f'{y:g}' for y in SHOWN)} mm and at the walk's end")
        for k in (int(v) for v in args.meshes.split(",")):
            r = P.puncture(dome, material(name), P.MESHES[k])
            rows = {round(row["travel_mm"], 6): row for row in r.rows()}
            cells = []
            for y in SHOWN:
                row = rows.get(y)
                cells.append("—" if row is None else f"{row['force_N']:.3f} / "
                             f"{row['floor_N']:.2f} / {row['stretch']:.2f}")
            end = r.rows()[-1]
            cells.append(f"end {r.clearance_mm - end['travel_mm']:.4f} mm above the base: "
                         f"{end['force_N']:.2f} / {end['floor_N']:.2f} / {end['stretch']:.2f}")
            verdict = ""
            if criterion is not None:
                f = r.failure(criterion)
                verdict = (f"; failure (λ {criterion.stretch:g}) at {f['force_N']:.3g} N, "
                           f"{f['travel_mm']:.3g} mm" if f["reached"] else
                           f"; λ {criterion.stretch:g} not reached: > {f['force_N']:.3g} N")
            print(f"  {r.mesh.label} ({r.seconds:.0f} s, "
                  f"{'reached the base' if r.converged else 'stopped: ' + r.message[:70]})"
                  f": " + "  ".join(cells) + verdict)
        print(f"  criterion: {source}")


if __name__ == "__main__":
    main()
