"""The report's haptic-chamber section: what the motor and its support cost the plain Type D in
force and pressure sensitivity, from the study ``make haptic-fem`` wrote (its ``summary.json``
and figure), shown as the fingertip study is.

Three part-FEM curves take 10–15 min on a 2-core machine, so the report does not run them:
it shows the study found at ``--haptic DIR`` (default ``build/haptic-fem``) and says how to make
it when there is none.
"""

from __future__ import annotations

from pathlib import Path

from spsc.report.fingertip import copy_figure, read_study
from spsc.studies.haptic import LABELS

__all__ = ["haptic_section", "DEFAULT_DIR", "COMMAND", "LABELS"]

DEFAULT_DIR = Path("build/haptic-fem")
COMMAND = "make haptic-fem   # = spsc haptic --out build/haptic-fem"


def haptic_section(study_dir, out) -> dict | None:
    """The section's data from ``study_dir/summary.json`` (None if there is none), its figure
    copied to ``out/haptic/``."""
    study_dir = Path(study_dir)
    found = read_study(study_dir, out, "haptic")
    if found is None:
        return None
    summary, dest = found
    figure = copy_figure(study_dir, dest, "haptic-cost.png")
    rows = [dict(summary[name], name=LABELS[name]) for name in LABELS if name in summary]
    return {"rows": rows, "mesh_size_mm": summary.get("mesh_size_mm"), "figure": figure,
            "command": COMMAND, "alone": summary.get("motor_alone_pct")}
