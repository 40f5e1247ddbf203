"""The report's headline band (issue 49): the wall model's P5–P95 of the Table 1 means under
the declared tolerance set (:mod:`spsc.study.headline_band`), whether each of the paper's bench
means falls inside it, which input moves it most (Sobol total index), and how well the
interpolant behind it reproduces the wall model off its grid.

Units: N/mm (stiffness), kPa/mm (sensitivity).
"""

from __future__ import annotations

__all__ = ["band_section", "band_sentence"]


def _verdict(bench: float, q: dict) -> tuple[str, float]:
    """("inside" | "above" | "below", how far outside as a fraction of the nearer bound)."""
    if bench > q["p95"]:
        return "above", bench / q["p95"] - 1.0
    if bench < q["p5"]:
        return "below", bench / q["p5"] - 1.0
    return "inside", 0.0


def band_section(record: dict, paper, sources: dict | None = None, name: str = "") -> dict:
    """The section's data: rows (quantity, mode, bench, P5, P50, P95, verdict, the input
    with the largest total index), the declared inputs in words, the interpolant's check, the
    sentence for the summary; ``{"not_computed": why}`` when the band has none."""
    from spsc.report.overview import QUANTITIES
    from spsc.study.tolerance import parse_tolerance

    if "not_computed" in record or not record.get("quantiles"):
        return {"not_computed": record.get("not_computed", "no quantiles")}
    tol = parse_tolerance(record["tolerance"]["inputs"], record["tolerance"]["source"])
    inputs = [{"name": s.name, "spread": s.describe(),
               "source": (sources or {}).get(s.name, name)}
              for s in tol.spreads]
    rows = []
    for q, label in QUANTITIES.items():
        for mode in ("high", "low"):
            key = f"{q}_{mode}"
            if key not in record["quantiles"]:
                continue
            b = paper.get(key)
            qs = record["quantiles"][key]
            st = record["sobol"][key]["ST"]
            top = max(st, key=st.get)
            verdict, off = _verdict(b.value, qs) if b else ("", 0.0)
            checks = [abs(c[key]["interpolated"] / c[key]["wall"] - 1.0)
                      for c in record["checks"] if c[key]["wall"]]
            rows.append({"quantity": label, "key": key, "mode": mode,
                         "check_error": max(checks) if checks else float("nan"),
                         "unit": b.unit if b else "", "bench": b.value if b else None,
                         "printed": b.printed if b else "", **qs, "verdict": verdict,
                         "outside": off, "dominant": top, "dominant_ST": st[top],
                         "ST": st, "ST_conf": record["sobol"][key]["ST_conf"]})
    return {"rows": rows, "inputs": inputs, "tolerance": name, "method": record["method"],
            "samples": record["samples"], "clipped_share": record["clipped_share"],
            "curves": record["curves"], "compute_seconds": record["compute_seconds"],
            "check_error_max": record["check_error_max"], "checks": len(record["checks"]),
            "stopped_short": _stopped_short_words(record), "sentence": band_sentence(rows)}


def _stopped_short_words(record: dict) -> str:
    """Which of the band's wall curves stopped short of the stroke, in words ("" when none;
    a record cached before the count says so)."""
    rows = record.get("stopped_short")
    if rows is None:
        return "This band's record predates the count of the curves that stopped short."
    if not rows:
        return f"All {record['curves']} wall curves reached the stroke."
    n = sum(len(r["draws"]) for r in rows)
    each = "; ".join(f"Type {r['type']} at {r['pressure_kPa']:g} kPa, {r['mode']} mode, in "
                     f"{len(r['draws'])} draw{'s' if len(r['draws']) > 1 else ''} (from "
                     f"{r['reached_mm']:.2g} mm)" for r in rows)
    return (f"{n} of the {record['curves']} wall curves stopped short of the stroke: {each}; "
            "their means are over the stroke they reached.")


def band_sentence(rows: list[dict]) -> str:
    """What the band concludes against the bench, in words, from its own rows."""
    inside = [r for r in rows if r["verdict"] == "inside"]
    outside = [r for r in rows if r["verdict"] in ("above", "below")]

    def name(r):
        return f"{r['quantity'].lower()} ({r['mode']} mode, {r['printed']} {r['unit']})"

    parts = []
    if inside:
        parts.append("the bench's " + ", ".join(name(r) for r in inside)
                     + (" lies" if len(inside) == 1 else " lie") + " inside the wall model's "
                     "P5–P95 band")
    for r in outside:
        parts.append(f"the bench's {name(r)} lies {100 * abs(r['outside']):.0f} % "
                     f"{r['verdict']} the band's {'P95' if r['verdict'] == 'above' else 'P5'} "
                     f"({r['p95' if r['verdict'] == 'above' else 'p5']:.3g} {r['unit']})")
    if not parts:
        return ""
    text = "Under the declared tolerances, " + "; ".join(parts) + "."
    return text[0].upper() + text[1:]
