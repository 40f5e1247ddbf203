"""Recompute cached report runs with this checkout's code and compare them with the cached
curves, column by column: a refactor's check that is minutes, not a whole report rebuild.

    python bench/recompute_runs.py [--cache build/cache] LABEL_PREFIX ...

e.g. ``wall-B-tpu60a-low-p40-vr40000-y6x25-h1l2 fem-B-tpu60a-low-p40-vr40000-y6x7-h2l1``
(a run's label, the cache folder's name without its key). Prints the largest difference
relative to each column's largest value and whether the points without equilibrium are the
same; exit 1 when a curve differs by more than 1e-9 or its NaN points differ.
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

COLUMNS = ("force_N", "pressure_kPa", "contact_area_mm2", "volume_change_mm3")


def main() -> int:
    from spsc.core.curve import Curve
    from spsc.study.runner import compute
    from spsc.study.runs import Run

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("labels", nargs="+")
    ap.add_argument("--cache", default="build/cache")
    args = ap.parse_args()
    worst, same = 0.0, True
    for label in args.labels:
        dirs = sorted((Path(args.cache) / "runs").glob(f"{label}-*"))
        if not dirs:
            print(f"{label}: not in {args.cache}/runs", file=sys.stderr)
            return 2
        old = json.loads(next(dirs[0].glob("*.json")).read_text(encoding="utf-8"))
        run = Run(**{k: v for k, v in old["inputs"].items()
                     if k not in ("geometry", "material_law")})
        with tempfile.TemporaryDirectory() as tmp:
            new = Curve.from_dict(compute(run, Path(tmp))["curve"])
        cached = Curve.from_dict(old["curve"])
        diff = max(float(np.nanmax(np.abs(getattr(cached, c) - getattr(new, c))))
                   / max(float(np.nanmax(np.abs(getattr(cached, c)))), 1e-300) for c in COLUMNS)
        nan = np.array_equal(np.isnan(cached.force_N), np.isnan(new.force_N))
        worst, same = max(worst, diff), same and nan
        print(f"{label}: largest relative difference {diff:.2e}, NaN points "
              f"{'the same' if nan else 'DIFFER'}")
    print(f"worst {worst:.2e}")
    return 0 if worst <= 1e-9 and same else 1


if __name__ == "__main__":
    sys.exit(main())
