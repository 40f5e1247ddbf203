"""The report's first screen in words: what was validated and how well, against what, and the
biggest open gap, each a sentence computed from the sections' numbers (never typed in).

The gap to the bench compares the headline means of every model with the paper's printed bench
means (:mod:`.paper`): a model without bending is taken with the FEM's F_el added when the
study has it (as the paper added its measured F_el), on its own (p·A) only when it has not.
"""

from __future__ import annotations

import math

__all__ = ["bench_gap", "gap_sentences", "gap_summary", "softer_everywhere", "fem_agreement",
           "model_name", "overview_section", "WHY_SOFTER"]

QUANTITIES = {"stiffness": "Stiffness", "sensitivity": "Pressure sensitivity"}
MODES = ("high", "low")

#: Why the models may be softer than the bench, and where the report measures it.
WHY_SOFTER = ("The headline's setup is not the bench's: its plate is frictionless, its material "
              "is the catalogue's TPU 60A (the datasheet's modulus, not a test of printed TPU), "
              "its wall is the nominal 1 mm and its means are taken over 0–6 mm, where the "
              "paper averages over a stroke it does not print. The section “Against the bench, "
              "factor by factor” measures how much of the gap each accounts for.")


def compared_variants(by_variant: dict) -> list[str]:
    """The variants compared with the bench: every one but a model's p·A alone when the
    same model is there with F_el added."""
    return [v for v in by_variant
            if not (v.endswith(" p·A") and f"{v[:-4]}+F_el" in by_variant)]


def bench_gap(by_variant: dict, paper, compare_pressure_kPa: float | None = None) -> dict:
    """``{quantity: {mode: {"bench", "printed", "unit", "models": {variant: (model −
    bench) / bench}, "names": {variant: its name in words}}}}`` of the headline means
    ``by_variant`` ({variant: {mode: {"stiffness", "sensitivity"}}}) against the paper's bench
    figures; NaN means are left out. ``compare_pressure_kPa``: the FEM's only pressure."""
    out: dict = {}
    for q in QUANTITIES:
        for mode in MODES:
            f = paper.get(f"{q}_{mode}")
            if f is None:
                continue
            models = {}
            for v in compared_variants(by_variant):
                x = by_variant[v].get(mode, {}).get(q, math.nan)
                if x is not None and math.isfinite(x):
                    models[v] = x / f.value - 1.0
            out.setdefault(q, {})[mode] = {
                "bench": f.value, "printed": f.printed, "unit": f.unit, "models": models,
                "names": {v: model_name(v, compare_pressure_kPa) for v in models}}
    return out


def model_name(variant: str, compare_pressure_kPa: float | None = None) -> str:
    """A variant as the sentences name it."""
    if variant == "fem":
        p = compare_pressure_kPa
        return "the 3D FEM" + (f" ({p:g} kPa only)" if p is not None else "")
    if variant.endswith("+F_el"):
        return f"{variant[:-5]} + F_el"
    return f"the {variant} model" if " " not in variant else variant


def _pct(x: float) -> str:
    """A relative difference as words before "the bench's …": "27 % below", "within 0.5 % of"."""
    p = round(abs(100 * x))
    return "within 0.5 % of" if p == 0 else f"{p} % {'below' if x < 0 else 'above'}"


def _span(xs) -> str:
    lo, hi = sorted(round(abs(100 * x)) for x in (min(xs, key=abs), max(xs, key=abs)))
    return f"{lo} %" if lo == hi else f"{lo}–{hi} %"


def _mode_phrase(mode: str, d: dict) -> str:
    """How the models stand against the bench in one mode: one span when they all fall on
    one side, else each model by name."""
    diffs, names, bench = d["models"], d["names"], f"{d['printed']} {d['unit']}"
    if not diffs:
        return f"no model has a {mode}-mode value (bench {bench})"
    for side, test in (("below", lambda x: round(100 * x) < 0),
                       ("above", lambda x: round(100 * x) > 0)):
        if all(test(x) for x in diffs.values()):
            every = "every model is" if len(diffs) > 1 else f"{names[next(iter(diffs))]} is"
            return f"{every} {_span(diffs.values())} {side} the bench's {bench} in the {mode} mode"
    if len(diffs) == 1:
        (v, x), = diffs.items()
        return f"{names[v]} is {_pct(x)} the bench's {bench} in the {mode} mode"
    each = ", ".join(f"{names[v]} {_pct(x).removesuffix(' of')}" for v, x in diffs.items())
    return f"in the {mode} mode (bench {bench}): {each}"


def gap_sentences(gap: dict, only: str | None = None) -> list[str]:
    """One sentence per quantity of :func:`bench_gap` (``only``: that variant's numbers)."""
    out = []
    for q, label in QUANTITIES.items():
        modes = gap.get(q, {})
        if not modes:
            continue
        if only is not None:
            modes = {m: {**d, "models": {k: v for k, v in d["models"].items() if k == only}}
                     for m, d in modes.items()}
        out.append(f"{label}: " + "; ".join(_mode_phrase(m, d) for m, d in modes.items()) + ".")
    return out


def softer_everywhere(gap: dict, quantity: str = "stiffness") -> bool:
    """Every compared model below the bench in ``quantity`` in every mode."""
    modes = gap.get(quantity, {})
    return bool(modes) and all(d["models"] and all(round(100 * x) < 0
                                                   for x in d["models"].values())
                               for d in modes.values())


def fem_agreement(comparison_summary: dict) -> dict:
    """Per model variant, the worst RMS error against the FEM over the types and modes (% of
    the FEM's largest value): ``{variant: {"force_N": %, "pressure_kPa": %}}``."""
    out: dict = {}
    for per in comparison_summary.values():
        for variant, errors in per.items():
            worst = out.setdefault(variant, {"force_N": math.nan, "pressure_kPa": math.nan})
            for col in worst:
                x = errors.get(col, {}).get("rms_pct", math.nan)
                if x is not None and math.isfinite(x):
                    worst[col] = x if not math.isfinite(worst[col]) else max(worst[col], x)
    return out


def _validated(study, comparison: dict) -> str:
    worst = fem_agreement(comparison["summary"])
    if not study.fem or not worst:
        return ("No 3D FEM in this study: the fast models were not checked against it; the "
                "paper's bench means are the only comparison.")
    each = "; ".join(f"{model_name(v)} {w['force_N']:.2g} % in force and "
                     f"{w['pressure_kPa']:.2g} % in pressure" for v, w in worst.items())
    return (f"The fast models against the 3D FEM (Types {', '.join(study.types)}, "
            f"{' and '.join(study.mode_names)} mode, p_i = {study.compare_pressure_kPa:g} kPa; "
            f"RMS difference over the stroke as % of the FEM's largest value, worst type and "
            f"mode): "
            f"{each}.")


def _against(study, convergence: dict | None) -> str:
    rows = [r for r in (convergence or {}).get("rows", []) if "error" not in r]
    mesh = ""
    if len(rows) > 1:
        diffs = ", ".join(f"{r['mesh_mm']:g} mm × {r['layers']} layer(s) "
                          f"{100 * r['max_rel_force_diff']:.2g} %" for r in rows[:-1])
        mesh = (f" (mesh convergence on Type {convergence['type']}: in force, coarser meshes differ "
                f"from the finest, {rows[-1]['mesh_mm']:g} mm × {rows[-1]['layers']} layer(s), "
                f"by {diffs})")
    fem = f"The 3D FEM of this code{mesh}, and the" if study.fem else "The"
    return (f"{fem} only measurements at hand: the paper's bench means, five numbers "
            "printed in its text (stiffness and pressure sensitivity in both modes, the JND "
            "depth); no plotted data is used.")


def gap_summary(gap: dict, ref: str | None) -> str:
    """The summary's sentence on the bench: stiffness over every model, sensitivity of the
    reference model ``ref`` (the FEM; None: every model)."""
    stiff = "; ".join(_mode_phrase(m, d) for m, d in gap.get("stiffness", {}).items())
    sens = gap_sentences({"sensitivity": gap.get("sensitivity", {})}, only=ref)
    if ref is not None and sens:
        per = [f"{_pct(d['models'][ref])} the bench's {d['printed']} {d['unit']} in the {m} mode"
               for m, d in gap["sensitivity"].items() if ref in d["models"]]
        name = next(d["names"][ref] for d in gap["sensitivity"].values() if ref in d["names"])
        sens = [f"In pressure sensitivity {name} is {', and '.join(per)}."]
    lead = "Against the paper's bench, in stiffness"
    if softer_everywhere(gap):
        names = {n for d in gap["stiffness"].values() for n in d["names"].values()}
        who = "every model" if len(names) > 1 else names.pop()
        stiff = stiff.replace(f"{who} is ", "")
        lead = f"{who[0].upper()}{who[1:]} is softer than the paper's bench in stiffness"
    return f"{lead}: {stiff}. " + " ".join(sens)


def overview_section(study, headline: dict, comparison: dict, convergence, paper) -> dict:
    """The summary's sentences (``validated``, ``against``, ``gap``, ``why``) and the gap's
    numbers; ``gap`` is empty when the study's materials do not include the paper's."""
    h = headline.get(paper.material)
    gap = bench_gap(h["summary"], paper, study.compare_pressure_kPa if study.fem else None) \
        if h else {}
    ref = "fem" if "fem" in (h or {}).get("summary", {}) else None
    return {"validated": _validated(study, comparison), "against": _against(study, convergence),
            "gap": gap_summary(gap, ref) if gap else "",
            "gap_sentences": gap_sentences(gap), "why": WHY_SOFTER if gap else "",
            "bench_gap": gap}
