"""The report's "The surrogate against the wall model" section: the check of the shipped
surrogate on fresh designs it never saw (``spsc surrogate check --out DIR``, about a minute on
two cores), shown as the other studies are: the error table, where in the domain it grows, the
worst curves drawn and what made the surrogate.
"""

from __future__ import annotations

from pathlib import Path

from spsc.report.fingertip import copy_figure, read_study

__all__ = ["surrogate_section", "DEFAULT_DIR", "COMMAND", "ROWS"]

DEFAULT_DIR = Path("build/surrogate-check")
COMMAND = "make surrogate-check   # = spsc surrogate check --samples 200 --out build/surrogate-check"
#: the error table's rows: (summary key, label, the issue's target)
ROWS = (("force", "force, per point", "1 %, 3 %, 8 %"),
        ("pressure", "pressure rise, per point", "1 %, 3 %, 8 %"),
        ("stiffness", "mean stiffness, per curve", "2 % at p95"),
        ("sensitivity", "mean sensitivity, per curve", "2 % at p95"))


def surrogate_section(study_dir, out) -> dict | None:
    """The section's data from ``study_dir/summary.json`` (None if there is none), its two
    figures copied to ``out/surrogate/``."""
    study_dir = Path(study_dir)
    found = read_study(study_dir, out, "surrogate")
    if found is None:
        return None
    s, dest = found
    meta = s.get("surrogate") or {}
    hours = meta.get("worker_seconds")
    return {"summary": s, "rows": [(label, s[key], target) for key, label, target in ROWS],
            "unflagged": s.get("unflagged"), "worst": s.get("worst") or [],
            "meta": meta, "worker_hours": None if hours is None else hours / 3600.0,
            "check": copy_figure(study_dir, dest, "check.png"),
            "worst_figure": copy_figure(study_dir, dest, "worst.png"), "command": COMMAND}
