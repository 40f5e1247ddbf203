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
    for rows in (s["types"], s["strokes"], s["pressures"]):
        for r in rows.values():  # three significant figures, in full: 27,700 cycles
            r["life_text"] = _cycles(r["life_cycles"])
            r["life_other_text"] = _cycles(r["life_other_exponent"])
    types = s["types"]
    order = sorted(types, key=lambda t: types[t]["life_cycles"])
    return {"summary": s, "order": order, "command": COMMAND,
            "lives": copy_figure(study_dir, dest, "lives.png"),
            "fields": copy_figure(study_dir, dest, "fields-C.png")}


def _cycles(n) -> str:
    """A life to three significant figures, written out (27,700; 227; 96.5)."""
    if n is None:
        return "–"
    v = float(f"{float(n):.3g}")
    return f"{v:,.0f}" if v >= 100 else f"{v:.3g}"
