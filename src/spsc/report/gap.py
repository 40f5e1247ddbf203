"""The report's "Against the bench, factor by factor" section: the wall model's Table 1 means
with one thing changed at a time (friction, wall thickness, the stroke the means are taken
over), from the study ``spsc bench-gap`` wrote (:mod:`spsc.studies.bench_gap`), shown as the
time-domain study is: the report does not run it (about 14 min on two cores).
"""

from __future__ import annotations

from pathlib import Path

from spsc.report.fingertip import copy_figure, read_study

__all__ = ["gap_section", "DEFAULT_DIR", "COMMAND", "QUANTITIES"]

DEFAULT_DIR = Path("build/bench-gap")
COMMAND = "make bench-gap   # = spsc bench-gap --out build/bench-gap"
#: the headline's quantities, in the table's order
QUANTITIES = ("stiffness_high", "stiffness_low", "sensitivity_high", "sensitivity_low")


def gap_section(study_dir, out) -> dict | None:
    """The section's data from ``study_dir/summary.json`` (None if there is none), its figure
    copied to ``out/gap/``; the sentences under the table computed from the rows."""
    study_dir = Path(study_dir)
    found = read_study(study_dir, out, "gap")
    if found is None:
        return None
    summary, dest = found
    figure = copy_figure(study_dir, dest, "bench-gap.png")
    rows = summary["rows"]
    return {"rows": rows, "bench": summary["bench"], "figure": figure, "command": COMMAND,
            "material": summary.get("material", ""), "quantities": QUANTITIES,
            "seconds": summary.get("seconds"), "curves": summary.get("curves"),
            "findings": findings(rows, summary["bench"])}


def findings(rows, bench) -> list[str]:
    """What the rows say, in words: the gap of the baseline, each factor's share of it, and
    whether all stiffening factors at once close it."""
    base = next((r for r in rows if r["factor"] == "baseline"), None)
    if base is None:
        return []
    out = []
    for q in ("stiffness_high", "stiffness_low"):
        gap = bench[q] - base[q]
        if gap <= 0:
            continue
        shares = sorted(((100 * (r[q] - base[q]) / gap, r["label"]) for r in rows
                         if r is not base and r["factor"] != "stiffest"), reverse=True)
        best = shares[0] if shares else (0.0, "")
        mode = q.split("_")[1]
        text = (f"{mode.capitalize()} mode: the model is {base[q]:.2f} N/mm against the bench's "
                f"{bench[q]:.2f} N/mm. The factor that closes most of the gap is "
                f"“{best[1]}” ({best[0]:.0f} % of it).")
        stiff = next((r for r in rows if r["factor"] == "stiffest"), None)
        if stiff is not None:
            text += (f" All stiffening factors at once give {stiff[q]:.2f} N/mm: "
                     f"{100 * (stiff[q] - base[q]) / gap:.0f} % of the gap.")
        out.append(text)
    return out
