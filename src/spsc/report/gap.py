"""The report's "Against the bench, factor by factor" section: the wall model's Table 1 means
with one thing changed at a time (friction, wall thickness, the stroke the means are taken
over), from the study ``spsc bench-gap`` wrote (:mod:`spsc.studies.bench_gap`), shown as the
time-domain study is: the report does not run it (about 90 min on two cores).
"""

from __future__ import annotations

from pathlib import Path

from spsc.report.fingertip import copy_figure, read_study

__all__ = ["gap_section", "findings", "advice", "DEFAULT_DIR", "COMMAND", "QUANTITIES"]

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
            "findings": findings(rows, summary["bench"]),
            "advice": advice(rows, summary["bench"])}


def findings(rows, bench) -> list[str]:
    """What the rows say, in words: per mode, the baseline's gap in stiffness, the factor that
    closes most of it, what all stiffening factors at once close (with the catalogue's
    material and with each material file); then what friction accounts for."""
    base = _baseline(rows)
    if base is None:
        return []
    out = []
    for q in ("stiffness_high", "stiffness_low"):
        gap = bench[q] - base[q]
        if gap <= 0:
            continue
        share = {r["factor"]: 100 * (r[q] - base[q]) / gap for r in rows}
        single = sorted(((share[r["factor"]], r["label"]) for r in rows if r is not base
                         and not r["factor"].startswith("stiffest")), reverse=True)
        mode = q.split("_")[1]
        text = (f"{mode.capitalize()} mode: the model is {base[q]:.2f} N/mm against the bench's "
                f"{bench[q]:.2f} N/mm.")
        if single:
            text += (f" The factor that closes most of the gap is “{single[0][1]}” "
                     f"({single[0][0]:.0f} % of it).")
        for r in rows:
            if r["factor"].startswith("stiffest"):
                past = (f", {100 * (r[q] / bench[q] - 1):.0f} % past the bench"
                        if r[q] > bench[q] else "")
                text += (f" “{r['label'].capitalize()}” give {r[q]:.2f} N/mm: "
                         f"{share[r['factor']]:.0f} % of the gap{past}.")
        out.append(text)
    out += _friction(rows, base, bench)
    return out


def _baseline(rows) -> dict | None:
    return next((r for r in rows if r["factor"] == "baseline"), None)


def _friction(rows, base, bench) -> list[str]:
    fric = [r for r in rows if r["factor"].startswith("mu_") or r["factor"] == "stick"]
    gaps = {q: bench[q] - base[q] for q in ("stiffness_high", "stiffness_low")}
    if not fric or min(gaps.values()) <= 0:
        return []
    parts = [f"{r['label'].split(' on the')[0]}: {_pct(r, base, 'stiffness_high')}, "
             f"{_pct(r, base, 'stiffness_low')}" for r in fric]
    most = {q: max(100 * (r[q] - base[q]) / g for r in fric) for q, g in gaps.items()}
    return ["What friction on the plate changes in stiffness (high, low mode): "
            + "; ".join(parts) + f". That is at most {most['stiffness_high']:.0f} % of the "
            f"high mode's gap and {most['stiffness_low']:.0f} % of the low mode's."]


def _pct(row, base, q) -> str:
    return f"{100 * (row[q] / base[q] - 1):+.1f} %"


def advice(rows, bench) -> list[str]:
    """Which model to trust for what, with the baseline's distance to the bench."""
    base = _baseline(rows)
    if base is None:
        return []
    below = [100 * (1 - base[q] / bench[q]) for q in ("stiffness_high", "stiffness_low")]
    return [
        "For shapes, trends and comparisons between designs (which type, wall or mode is "
        "stiffer, and by how much relative to another), trust the wall model: it agrees with "
        "the 3D FEM within 2 % and takes seconds a curve.",
        "For absolute forces against a real bench, trust no model uncalibrated: in the "
        f"report's setup they are {min(below):.0f}–{max(below):.0f} % below the paper's bench "
        "in stiffness, and the rows above say how much of that the material, the wall, the "
        "plate's friction and the averaged stroke each account for. Calibrate the material on "
        "one bench test of your own chamber (spsc calibrate), and average over the stroke "
        "your bench uses.",
        "For contact areas, pocket (FSR) forces, bodies other than a plate and friction "
        "beyond a sticking plate, use the 3D FEM; the membrane and simplified models are for "
        "quick exploration only (their errors against the 3D FEM are in “Models vs FEM”).",
    ]
