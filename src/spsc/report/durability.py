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
            "puncture": _puncture(s.get("puncture")),
            "puncture_told": _told(s.get("puncture")),
            "lives": copy_figure(study_dir, dest, "lives.png"),
            "fields": copy_figure(study_dir, dest, "fields-C.png"),
            "puncture_figure": copy_figure(study_dir, dest, "puncture.png")}


def _puncture(p: dict | None) -> list[dict] | None:
    """One row per material and mesh of the study's puncture block (None without one, a
    study written before it): the predicted failure force (or its lower bound), Table 2's."""
    if not p:
        return None
    rows = []
    for name, m in p["materials"].items():
        t2 = m.get("table2")
        for k, r in enumerate(m["runs"]):
            f = r.get("failure")
            if f is None:
                predicted = "no criterion"
            elif f["reached"]:
                predicted = f"{f['force_N']:.3g} N at {f['travel_mm']:.3g} mm"
            else:
                predicted = f"> {f['force_N']:.3g} N (λ₁ {f['stretch']:.3g})"
            rows.append({"material": name if k == 0 else "", "mesh": r["mesh"],
                         "criterion": "–" if m["criterion"] is None else
                         f"{m['criterion']['elongation_pct']:g} % (λ {m['criterion']['stretch']:g})",
                         "table2": "–" if t2 is None else
                         ("> " if t2["above"] else "") + f"{t2['force_N']:g} N",
                         "at6": r["at"].get("6"), "predicted": predicted,
                         "end": f"{r['force_end_N']:.3g} N, λ₁ {r['stretch_end']:.3g} at "
                                f"{r['clearance_mm'] - r['reached_mm']:.3g} mm above the base"
                                + ("" if r["converged"] else " (stopped)")})
    return rows


def _cycles(n) -> str:
    """A life to three significant figures, written out (27,700; 227; 96.5)."""
    if n is None:
        return "–"
    v = float(f"{float(n):.3g}")
    return f"{v:,.0f}" if v >= 100 else f"{v:.3g}"


def _told(p: dict | None) -> dict | None:
    """What the puncture study tells across its meshes, per material with a criterion: the
    failure forces (or bounds) over the meshes, whether every mesh reached the criterion;
    and TPU 60A's force at 6 mm over its meshes (its spread, %)."""
    if not p:
        return None
    out = {}
    for name, m in p["materials"].items():
        fails = [r["failure"] for r in m["runs"] if r.get("failure")]
        if not fails:
            continue
        forces = [f["force_N"] for f in fails]
        out[name] = {"low": min(forces), "high": max(forces), "meshes": len(fails),
                     "all_reached": all(f["reached"] for f in fails),
                     "none_reached": not any(f["reached"] for f in fails),
                     "travel_high": max(f["travel_mm"] for f in fails),
                     "table2": m.get("table2")}
    tpu = p["materials"].get("tpu60a", {}).get("runs", [])
    at6 = [r["at"]["6"]["force_N"] for r in tpu if "6" in r["at"]]
    if at6:
        out["force6"] = {"low": min(at6), "high": max(at6),
                         "spread_pct": 100.0 * (max(at6) - min(at6)) / max(at6),
                         "meshes": len(at6)}
    return out
