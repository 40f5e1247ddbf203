"""The report's time-domain section: a press–hold–switch–release trace, the squeeze–release
hysteresis of Types A–D with the viscoelastic wall, and the Bode plot, from the study
``make time-study`` wrote (:mod:`spsc.studies.time`), shown as the haptic study is.

The study takes about 3 min on a 2-core machine (four viscous wall cycles), so the report does
not run it: it shows the study found at ``--time DIR`` (default ``build/time-study``) and says
how to make it when there is none.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from spsc.report.fingertip import read_study

__all__ = ["time_section", "DEFAULT_DIR", "COMMAND"]

DEFAULT_DIR = Path("build/time-study")
COMMAND = ("make time-study   # = spsc simulate examples/press-hold-switch.toml --study "
           "--out build/time-study")

_FIGURES = {"trace": "trace/trace.png", "bode": "bode/bode.png", "hysteresis": "hysteresis.png"}


def time_section(study_dir, out) -> dict | None:
    """The section's data from ``study_dir/summary.json`` (None if there is none), its figures
    copied to ``out/time/``."""
    study_dir = Path(study_dir)
    found = read_study(study_dir, out, "time")
    if found is None:
        return None
    summary, dest = found
    figures = {}
    for name, rel in _FIGURES.items():
        if (study_dir / rel).is_file():
            shutil.copy2(study_dir / rel, dest / f"{name}.png")
            figures[name] = f"time/{name}.png"
    scenario = summary.get("scenario", {})
    return {"figures": figures, "command": COMMAND, "switches": summary.get("switches", []),
            "bode": summary.get("bode", {}), "hysteresis": summary.get("hysteresis", []),
            "prony_source": summary.get("prony_source", ""),
            "material": summary.get("material", ""), "cycle": summary.get("cycle", {}),
            "circuit": scenario.get("circuit", {}), "chamber": scenario.get("chamber", {}),
            "complete": summary.get("complete", False), "seconds": summary.get("seconds", {})}
