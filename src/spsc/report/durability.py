"""The report's "Durability" section: the paper's fatigue test (sec. 3.2, Table 2) in the
wall model — the calibration of each material on its Table 2 test, the lives it predicts for
Types A–D and for other strokes and pressures, what agrees and what the data cannot tell —
from the study ``spsc fatigue --study`` writes (``build/durability``)."""

from __future__ import annotations

from pathlib import Path

from spsc.report.fingertip import copy_figure, read_study

__all__ = ["durability_section", "DEFAULT_DIR", "COMMAND"]

DEFAULT_DIR = Path("build/durability")
COMMAND = "make durability-study   # = spsc fatigue --study --out build/durability"


def durability_section(study_dir, out) -> dict | None:
    """The section's data from ``study_dir/summary.json`` (None if there is none), its two
    figures copied to ``out/durability/``."""
    study_dir = Path(study_dir)
    found = read_study(study_dir, out, "durability")
    if found is None:
        return None
    s, dest = found
    types = s["types"]
    order = sorted(types, key=lambda t: types[t]["life_cycles"])
    return {"summary": s, "order": order, "command": COMMAND,
            "lives": copy_figure(study_dir, dest, "lives.png"),
            "fields": copy_figure(study_dir, dest, "fields-C.png")}
