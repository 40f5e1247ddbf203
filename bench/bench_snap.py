"""The wall model through a snap-through (issue 26): Type C at 10 kPa over 6 mm, the jump it
follows and records, against the 3D FEM of the same chamber, which has no stability check and
passes the point on its own (1 mm, 2 layers; ~4 min on 2 cores, cached in build/reference/).

    python bench/bench_snap.py [--pressure 10] [--png build/bench/snap-C.png]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from spsc.cad.geometry import preset
from spsc.cli.figure import _mark_jumps, title
from spsc.core.curve import Curve
from spsc.fem.solid.chamber import chamber_run, run_chamber
from spsc.fem.wall import wall_curve
from spsc.materials import material


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pressure", type=float, default=10.0)
    ap.add_argument("--png", default="build/bench/snap-C.png")
    args = ap.parse_args(argv)
    kw = dict(pressure_kPa=args.pressure, stroke_mm=6.0, points=25)
    t = time.perf_counter()
    wall = wall_curve(preset("C"), material("tpu60a"), **kw)
    seconds = time.perf_counter() - t
    ref = Path("build/reference") / f"snap-C-fem-p{args.pressure:g}.json"
    if ref.exists():
        fem = Curve.from_json(ref)
    else:
        ref.parent.mkdir(parents=True, exist_ok=True)
        fem, _, _ = run_chamber(chamber_run(preset("C"), material("tpu60a"), mesh_size_mm=1.0,
                                            layers=2, **kw), cache_dir=ref.parent / "cache")
        fem.to_json(ref)
    print(f"wall: {wall.solver.message}, {seconds:.1f} s, {wall.solver.iterations} iterations")
    for j in wall.solver.details["jumps"]:
        print("jump:", {k: round(v, 6) if isinstance(v, float) else v for k, v in j.items()})
    after = wall.y_mm > max(j["y_mm"] for j in wall.solver.details["jumps"]) + 0.2 \
        if wall.solver.details["jumps"] else wall.y_mm > 0
    before = wall.y_mm < min((j["y_mm"] for j in wall.solver.details["jumps"]), default=9e9)
    before[0] = False
    dp = lambda c: c.pressure_kPa - args.pressure  # noqa: E731
    for name, mask in (("before the jump", before), ("after the jump (+0.2 mm)", after)):
        ef = np.max(np.abs(wall.force_N[mask] / fem.force_N[mask] - 1))
        ep = np.max(np.abs(dp(wall)[mask] / dp(fem)[mask] - 1))
        print(f"{name}: wall vs 3D FEM max |ΔF/F| {ef:.2%}, max |Δ(p−p_i)/(p−p_i)| {ep:.2%} "
              f"over {mask.sum()} points")
    Path(args.png).parent.mkdir(parents=True, exist_ok=True)
    _figure(wall, fem, args.png)
    print(f"figure: {args.png}")
    return 0


def _figure(wall, fem, path) -> None:
    """Force and pressure against travel: the wall model with the jump it followed, the 3D
    FEM (no stability check: it passes the point on its own branch)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for a, key, label in ((ax[0], "force_N", "plate force (N)"),
                          (ax[1], "pressure_kPa", "gauge pressure (kPa)")):
        a.plot(fem.y_mm, getattr(fem, key), "s", mfc="none", color="0.4", ms=5,
               label="3D FEM (1 mm, 2 layers)")
        a.plot(wall.y_mm, getattr(wall, key), "o-", ms=3, label="wall model")
        a.set_xlabel("plate travel y (mm)")
        a.set_ylabel(label)
        a.grid(alpha=0.3)
    _mark_jumps(wall, ax[0], ax[1])
    ax[1].legend(fontsize=8, loc="upper left")
    fig.suptitle(title(wall), fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    raise SystemExit(main())
