"""The report's fingertip section: the FEM study ``spsc fingertip --fem`` wrote (its
``summary.json`` and figures) shown in the validation report, figures copied beside it.

The study takes hours on a 2-core machine (eight FEM curves of the whole part), so the report
does not run it: it shows the study found at ``--fingertip DIR`` (default
``build/fingertip/fem``, where ``make fingertip-fem`` writes), and says how to make it when
there is none.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

__all__ = ["fingertip_section", "read_study", "DEFAULT_DIR", "COMMAND"]

DEFAULT_DIR = Path("build/fingertip/fem")
COMMAND = "make fingertip-fem   # = spsc fingertip --fem --out build/fingertip"


def read_study(study_dir, out, name: str):
    """(summary, figure folder) of a study a section shows: ``study_dir/summary.json`` read,
    ``out/name/`` made empty for its figures; None when there is no summary."""
    path = Path(study_dir) / "summary.json"
    if not path.is_file():
        return None
    dest = Path(out) / name
    if dest.exists():
        shutil.rmtree(dest)
    dest.mkdir(parents=True)
    return json.loads(path.read_text(encoding="utf-8")), dest


def copy_figure(study_dir, dest, name: str) -> str | None:
    """``study_dir/name`` copied into a section's figure folder ``dest`` (``out/SECTION``);
    its path relative to the report (``SECTION/name``), None if the study has no such
    figure."""
    src = Path(study_dir) / name
    if not src.is_file():
        return None
    shutil.copy2(src, Path(dest) / Path(name).name)
    return f"{Path(dest).name}/{Path(name).name}"


def fingertip_section(study_dir, out) -> dict | None:
    """The section's data from the study in ``study_dir`` (None if it has no summary.json),
    its figures copied to ``out/fingertip/``."""
    study_dir = Path(study_dir)
    found = read_study(study_dir, out, "fingertip")
    if found is None:
        return None
    summary, dest = found
    figures = {}
    for png in sorted((study_dir / "figures").glob("*.png")):
        shutil.copy2(png, dest / png.name)
        figures[png.stem] = f"fingertip/{png.name}"
    rows = []
    for name, row in summary["cases"].items():
        fem, fast = row["fem"], row.get("fast_error") or {}
        end = {k: v[-1] for k, v in fem["pockets_N"].items()} if fem["pockets_N"] else {}
        rows.append({"name": name, "site": row["site"], "mode": row["mode"],
                     "pressure": row["pressure_kPa"],
                     "sensitivity": fem["mean_sensitivity_kPa_per_mm"],
                     "stiffness": fem["mean_stiffness_N_per_mm"],
                     "force_end": fem["force_N"][-1], "pockets_end": end,
                     "ratio": row.get("sensitivity_ratio_fused_to_single"),
                     "fast_force": fast.get("force_max"),
                     "fast_pressure": fast.get("pressure_rise_max"),
                     "converged": fem["converged"], "message": fem["message"],
                     "seconds": fem["seconds"], "dofs": fem["dofs"]})
    return {"summary": {k: v for k, v in summary.items() if k != "cases"}, "rows": rows,
            "figures": figures, "command": COMMAND, "pockets": sorted(
                {p for r in rows for p in r["pockets_end"]})}
