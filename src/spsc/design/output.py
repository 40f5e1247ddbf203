"""What ``spsc design`` writes and prints: ``design.json`` (schema ``spsc.design`` v1), the
trials table (``trials.parquet``, CSV on request), the ``spsc curve`` commands that re-run the
best design, and the summary on stdout.

``design.json``::

    {"schema": "spsc.design", "schema_version": 1,
     "best": {"trial": 7, "params": {type, w, h, l, t0, n1, n2, cy, material, pressure,
              reservoir}, "metrics": {...}, "miss": 0.004, "printability": "..."} or null,
     "pareto": [the same, for every non-dominated feasible design],
     "met": true, "verify": {...} or null, "build": {...} or null,
     "goal": {...}, "space": {...}, "model": "wall", "process": "fdm", "points": 25,
     "stroke_mm": 6, "trials": 12, "states": {"COMPLETE": 11, "FAIL": 1}, "run": {...},
     "rerun": {"high": "spsc curve ...", "low": "spsc curve ..."}, "command": "spsc design ..."}

Parameters are under the CLI's names, metrics under :data:`~.design_goal.METRIC_NAMES` (N/mm,
kPa/mm, mm, mm³); ``miss`` is the largest relative miss of the targets (a fraction).
"""

from __future__ import annotations

import shlex
from collections import Counter
from pathlib import Path

from spsc.core.jsonio import to_jsonable, write_json

from spsc.design.goal import METRIC_NAMES
from spsc.design.space import INPUTS, fmt
from spsc.cad.geometry import PARAMS

__all__ = ["SCHEMA", "SCHEMA_VERSION", "document", "design_entry", "rerun_commands",
           "write_tables", "write_document", "print_summary", "TABLE_COLUMNS"]

SCHEMA, SCHEMA_VERSION = "spsc.design", 1
#: The columns of trials.parquet, in order.
TABLE_COLUMNS = ("trial", "state") + INPUTS + METRIC_NAMES + (
    "miss", "feasible", "printable", "printability", "status", "reason", "seconds", "proposer",
    "life_cycles", "peak_stretch", "energy_amplitude_MPa")
_NUMERIC = PARAMS + ("pressure", "reservoir") + METRIC_NAMES + (
    "miss", "seconds", "life_cycles", "peak_stretch", "energy_amplitude_MPa")


def design_entry(row: dict) -> dict:
    """A trial row as ``{"trial", "params", "metrics", "miss", "printability"}``."""
    return {"trial": row["trial"], "params": {k: row.get(k) for k in INPUTS},
            "metrics": {m: row.get(m) for m in METRIC_NAMES}, "miss": row.get("miss"),
            "printable": row.get("printable"), "printability": row.get("printability")}


def rerun_commands(params: dict, model: str, points: int | None, stroke_mm: float) -> dict:
    """``{"high": cmd, "low": cmd}``: the ``spsc curve`` commands computing the design's two
    modes (closed; with its reservoir) as the study did; every parameter written so it reads
    back to the same float."""
    from spsc.models import get

    n = get(model).points if points is None else points
    head = ["spsc", "curve", "--model", model]
    if params.get("type"):
        head += ["--type", str(params["type"])]
    for k in PARAMS:
        head += [f"--{k}", fmt(params[k])]
    head += ["--material", str(params["material"]), "--pressure", fmt(params["pressure"])]
    tail = ["--stroke", fmt(stroke_mm), "--points", str(n)]
    return {mode: shlex.join(head + ["--reservoir", fmt(v)] + tail)
            for mode, v in (("high", 0.0), ("low", params["reservoir"]))}


def document(problem, run, *, verify=None, build=None, command: str = "",
             confirmed=None, robust=None) -> dict:
    """The ``design.json`` document of a finished run (module docstring); with
    ``confirmed`` (:func:`~spsc.design.confirm.confirm`), the goal is met when the confirming
    model meets it and the re-run commands are that model's for the confirmed design."""
    best = design_entry(run.best) if run.best else None
    doc = {"schema": SCHEMA, "schema_version": SCHEMA_VERSION, "best": best,
           "pareto": [design_entry(r) for r in run.pareto], "met": bool(run.met),
           "verify": _public(verify), "build": build, "goal": problem.goal.to_dict(),
           "space": problem.space.to_dict(), "model": problem.model,
           "process": problem.process, "points": problem.points,
           "stroke_mm": problem.stroke_mm, "trials": len(run.rows),
           "states": dict(Counter(r["state"] for r in run.rows)), "run": run.facts,
           "rerun": (rerun_commands(best["params"], problem.model, problem.points,
                                    problem.stroke_mm) if best else None),
           "command": command}
    if problem.life is not None:  # the life asked, and the best's (its trial's wall cycle)
        doc["life"] = dict(problem.life)
        if run.best is not None:
            doc["life"]["best"] = {k: run.best.get(k) for k in ("life_cycles", "peak_stretch",
                                                                "energy_amplitude_MPa")}
    if robust is not None:  # met when the wall model's prints meet it at the confidence
        doc["robust"] = robust
        doc["met"] = bool(robust["wall"]["p_met"] >= robust["confidence"] - 1e-12)
    if confirmed is not None:
        doc["confirmed"] = confirmed
        doc["met"] = bool(confirmed["met"])
        if confirmed["chosen"] is not None:
            doc["rerun"] = rerun_commands(confirmed["candidates"][confirmed["chosen"]]["params"],
                                          confirmed["model"], None, problem.stroke_mm)
    if best is None:
        closest = [r for r in run.rows if r["state"] == "COMPLETE"]
        if closest:
            doc["closest"] = design_entry(min(closest, key=lambda r: (r["miss"], r["trial"])))
    return doc


def _public(verify):
    return None if verify is None else {k: v for k, v in verify.items() if not k.startswith("_")}


def write_document(doc: dict, out: Path, json_path=None) -> Path:
    path = write_json(Path(out) / "design.json", doc)
    if json_path:
        write_json(json_path, doc)
    return path


def write_tables(rows: list[dict], out: Path, csv_path=None) -> Path:
    """``out/trials.parquet`` (and ``csv_path``): one row per trial, :data:`TABLE_COLUMNS`."""
    import pandas as pd

    df = pd.DataFrame([{k: r.get(k) for k in TABLE_COLUMNS} for r in rows],
                      columns=list(TABLE_COLUMNS))
    for k in _NUMERIC:
        df[k] = pd.to_numeric(df[k], errors="coerce").astype("float64")
    df["trial"] = df["trial"].astype("int64")
    df["printable"] = df["printable"].astype("boolean")
    df["feasible"] = df["feasible"].astype(bool)
    for k in ("type", "material", "state", "printability", "status", "reason"):
        df[k] = df[k].astype("string")
    path = Path(out) / "trials.parquet"
    df.to_parquet(path, index=False)
    if csv_path:
        df.to_csv(csv_path, index=False)
    return path


def _line(entry: dict) -> str:
    p, m = entry["params"], entry["metrics"]
    geom = " ".join(f"{k}={fmt(p[k])}" for k in PARAMS)
    mets = ", ".join(f"{k} {to_jsonable(m[k]) if m[k] is None else format(m[k], '.4g')}"
                     for k in METRIC_NAMES)
    return (f"type {p.get('type') or '-'} {geom} mm, {p['material']}, {fmt(p['pressure'])} kPa, "
            f"reservoir {fmt(p['reservoir'])} mm³\n    {mets}")


def print_summary(doc: dict, out: Path) -> None:
    """The result on stdout: trials, the best (or the closest), its verification and part,
    the re-run commands and what was written."""
    run, states = doc["run"], doc["states"]
    print(f"{doc['trials']} trials ({', '.join(f'{n} {s.lower()}' for s, n in states.items())}); "
          f"{run['evaluated']} evaluated in this run on {run['workers']} worker(s) in "
          f"{run['loop_seconds']:.1f} s ({run['sampler']}, seed {run['seed']})")
    best = doc["best"]
    if best is None:
        life = doc.get("life")
        print("no feasible design: none was printable"
              + (f" and lasted {life['cycles']:g} cycles" if life else "")
              + (" and met the targets" if doc["goal"]["multi_objective"] else ""))
        if doc.get("closest"):
            print(f"closest (trial {doc['closest']['trial']}, not printable): "
                  + _line(doc["closest"]))
        return
    miss = "" if best["miss"] is None else f", miss {100 * best['miss']:.2f} %"
    state = (f"screened by the {doc['model']} model" if doc.get("confirmed")
             or doc.get("robust") else "goal met" if doc["met"] else "goal NOT met")
    print(f"best: trial {best['trial']}{miss} ({state}): " + _line(best))
    life = doc.get("life")
    if life and life.get("best") and life["best"].get("life_cycles") is not None:
        b = life["best"]
        print(f"  its life: {b['life_cycles']:.3g} cycles squeezed to {life['stroke_mm']:g} mm "
              f"at its setup (asked {life['cycles']:g}; hot spot's energy amplitude "
              f"{b['energy_amplitude_MPa']:.3g} MPa, largest stretch {b['peak_stretch']:.4f})")
    if doc["goal"]["multi_objective"]:
        print(f"Pareto front: {len(doc['pareto'])} feasible non-dominated designs")
    if doc.get("confirmed"):
        _print_confirmed(doc["confirmed"], doc["model"], doc["goal"]["tol"])
    if doc.get("robust"):
        _print_robust(doc["robust"], doc["goal"]["tol"])
    v = doc.get("verify")
    if v:
        _print_verify(v)
    b = doc.get("build")
    if b:
        gate = "PASSED" if b["gate"]["passed"] else "FAILED: " + ", ".join(b["gate"]["failed"])
        print(f"part: {out / 'part' / b['files']['stl']} ({b['triangles']} triangles); gate "
              f"({b['process']}): {gate}")
    print("re-run the best design (high, low mode):")
    for mode in ("high", "low"):
        print("  " + doc["rerun"][mode])


def _print_confirmed(c: dict, screened_by: str, tol: float) -> None:
    print(f"confirmed with the {c['model']} model ({len(c['candidates'])} best designs, "
          f"{c['seconds']:.1f} s): miss {screened_by} -> {c['model']}")
    for i, d in enumerate(c["candidates"]):
        miss = "—" if d["miss"] is None else f"{100 * d['miss']:.2f} %"
        note = "" if d["status"] == "ok" else f" ({d['status']}: {d['message']})"
        mark = "  <- confirmed" if i == c["chosen"] else ""
        print(f"  trial {d['trial']:>4}  {_g(100 * d['screened_miss'])} % -> {miss}"
              f"{note}{mark}")
    if c["chosen"] is None:
        print(f"  the {c['model']} model computed none of them: nothing confirmed")
    else:
        d = c["candidates"][c["chosen"]]
        met = "met" if c["met"] else "NOT met"
        print(f"  goal {met} by the {c['model']} model (tolerance {100 * tol:g} %): " + ", ".join(
            f"{k} {_g(d['metrics'][k])}" for k in METRIC_NAMES))


def _print_robust(r: dict, tol: float) -> None:
    c, w = r["chosen"], r["wall"]
    need = 100 * r["confidence"]
    print(f"robust: {100 * c['p_met']:.0f} % of the chosen design's prints meet the targets "
          f"within {100 * tol:g} % by the surrogate ({need:g} % asked; the {need:g} % quantile "
          f"of their misses {100 * c['quantile_miss']:.2f} %)")
    print(f"  by the {w['model']} model's {w['samples']} fresh samples ({w['seconds']:.0f} s): "
          f"{100 * w['p_met']:.0f} % meet them (quantile miss {100 * w['quantile_miss']:.2f} %)"
          f" — {'confirmed' if w['p_met'] >= r['confidence'] - 1e-12 else 'NOT confirmed'}")
    n = r.get("nominal_best")
    if n:
        print(f"  the nominal best (trial {n['trial']}, nominal miss "
              f"{100 * n['nominal_miss']:.2f} %): {100 * n['p_met']:.0f} % of its prints meet "
              "them")
    for metric, order in (r.get("band") or {}).get("tighten", {}).items():
        print(f"  which tolerance to tighten first for {metric}: " + ", then ".join(
            f"{k} (total Sobol index {v:.2f})" for k, v in order[:2]))


def _print_verify(v: dict) -> None:
    if v["metrics"]["fem"] is None:
        print(f"FEM verification failed: {v['message']}")
        return
    print(f"FEM check ({v['points']['fem']} positions over {v['stroke_mm']:g} mm, mesh "
          f"{v['mesh_size_mm']:g} mm, {v['seconds']:.0f} s): {v['fast_model']} vs FEM")
    for k in METRIC_NAMES:
        a, b, d = v["metrics"]["fast"][k], v["metrics"]["fem"][k], v["difference_pct"][k]
        print(f"  {k:17s} {_g(a):>10} {_g(b):>10}  {'' if d != d else f'{d:+.2f} %'}")
    worst = v["max_abs_difference_pct"]
    print(f"  largest difference on the goal's metrics {_g(worst)} % "
          f"({'within' if v['agrees'] else 'NOT within'} {v['tolerance_pct']:g} %)")
    if v.get("fem_miss") is not None:
        print(f"  the FEM's own miss of the goal {_g(100 * v['fem_miss'])} % "
              f"({'met' if v['fem_met'] else 'not met'} by the FEM)")


def _g(x) -> str:
    return "—" if x is None or x != x else f"{x:.4g}"
