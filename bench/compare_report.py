"""Every curve of a rebuilt validation report against another report's: the largest relative
difference per column over all runs, and whether the points without equilibrium (NaN) are the
same. Used to show a refactor leaves the report unchanged.

    python bench/compare_report.py OLD/reports/validation/data reports/validation/data
                                   [--until-jump]

``--until-jump``: only the points before the first snap-through the new curve records (its
solver block's ``jumps``): the wall model follows a snap since stop 33, so a curve that
stopped there before now goes on, and its points after the jump are new.

(``git archive REV reports/validation | tar -x -C OLD`` gives a committed report.)
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

COLUMNS = ("y_mm", "force_N", "pressure_kPa", "contact_area_mm2", "volume_change_mm3")


def _jump_y(doc: dict) -> float:
    jumps = (doc.get("solver") or {}).get("details", {}).get("jumps") or []
    return min((j["y_mm"] for j in jumps), default=np.inf)


def compare(old: Path, new: Path, until_jump: bool = False) -> dict:
    """``{"compared", "missing", "extra", "nan_differs", "worst": {column: (rel, file)}}``;
    ``until_jump``: over the points before the new curve's first snap-through only."""
    worst = {c: (0.0, "") for c in COLUMNS}
    missing, nan_differs, n = [], [], 0
    for f in sorted(old.glob("*.json")):
        g = new / f.name
        if not g.exists():
            missing.append(f.name)
            continue
        da, db = (json.loads(p.read_text(encoding="utf-8")) for p in (f, g))
        a, b = da["curve"], db["curve"]
        keep = np.array(b["y_mm"], float) < _jump_y(db) if until_jump else slice(None)
        n += 1
        for c in COLUMNS:
            x, y = np.array(a[c], dtype=float), np.array(b[c], dtype=float)
            if x.shape != y.shape:
                worst[c] = (float("inf"), f.name)
                continue
            x, y = x[keep], y[keep]
            if not np.array_equal(np.isnan(x), np.isnan(y)):
                nan_differs.append(f"{f.name}:{c}")
            ok = ~(np.isnan(x) | np.isnan(y))
            d = np.abs(x[ok] - y[ok]) / np.maximum(np.abs(x[ok]), 1e-12)
            if d.size and d.max() > worst[c][0]:
                worst[c] = (float(d.max()), f.name)
    extra = sorted(p.name for p in new.glob("*.json") if not (old / p.name).exists())
    return {"compared": n, "missing": missing, "extra": extra, "nan_differs": nan_differs,
            "worst": worst}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old", type=Path)
    ap.add_argument("new", type=Path)
    ap.add_argument("--until-jump", action="store_true",
                    help="only the points before the new curve's first snap-through")
    args = ap.parse_args()
    r = compare(args.old, args.new, args.until_jump)
    print(f"{r['compared']} curves compared; missing in the new: {r['missing']}; "
          f"only in the new: {r['extra']}; NaN points differ: {r['nan_differs']}")
    for c, (v, name) in r["worst"].items():
        print(f"  {c:20s} max relative difference {v:.3g}" + (f"  ({name})" if v else ""))
    same = not (r["missing"] or r["extra"] or r["nan_differs"]) and \
        all(v == 0 for v, _ in r["worst"].values())
    return 0 if same else 1


if __name__ == "__main__":
    raise SystemExit(main())
