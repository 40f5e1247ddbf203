"""Against the bench: how much of the gap between the models and the paper's bench each factor
accounts for.

The paper's bench (sec. 3.1; TPU 60A printed by FDM, Table 1) gives stiffness 8.0 / 5.0 N/mm
and sensitivity 6.1 / 0.5 kPa/mm (high / low mode). The models give less stiffness. Every row
below is the wall model's Table 1 means (types A–D, p_i 10–40 kPa, high mode V_r = 0 and low
mode V_r = 40 cm³, as the report computes them: :func:`spsc.study.metrics.headline`) with one
thing changed from the report's setup:

* ``baseline`` — the catalogue's TPU 60A, a frictionless plate, t0 = 1 mm, y over 0–6 mm;
* ``mu_0.3`` / ``mu_0.6`` — Coulomb friction on the plate (``--friction 0.3``, ``0.6``);
* ``stick`` — a plate that lets nothing slide (``--friction stick``: the upper bound of
  friction);
* ``t0_0.9`` / ``t0_1.1`` — the printed wall 0.1 mm thinner or thicker;
* ``y_0-4`` / ``y_0-8`` — the means over a shorter or a longer stroke (the paper averages over
  "each type's y_s range" and does not print it);
* ``stiffest`` — all of the stiffening ones at once (sticking plate, 1.1 mm wall, 0–8 mm);
* ``material_NAME`` — a material file of your own (``spsc fit-material --out``, e.g. a fit of
  a published tension test of printed TPU 60A), and ``stiffest_NAME`` the stiffening ones with
  it. The catalogue holds no such data: its licence must let you use it, and its source is
  cited from the data file's ``#`` lines (the material file keeps them).

    spsc bench-gap --out build/bench-gap [--material-row FIT.json] [--factors NAME,...]
                   [--workers N | --scheduler ADDR]   (about 90 min on 2 cores, 75 of them
                                                       the Coulomb rows)

writes ``summary.json`` and ``bench-gap.png``; ``spsc report --bench-gap DIR`` shows them.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from spsc.core.jsonio import write_json

__all__ = ["Spec", "Factor", "SPECS", "FACTORS", "MODES", "PRESSURES", "TYPES", "run_gap",
           "jobs", "curve_of", "material_rows", "select"]

#: the report's setup: the modes' reservoirs (mm³) and the setup pressures (kPa gauge)
MODES = {"high": 0.0, "low": 40000.0}
PRESSURES = (10.0, 20.0, 30.0, 40.0)
TYPES = "ABCD"
#: plate positions per mm of stroke (the report's 25 over 6 mm)
POINTS_PER_MM = 4


@dataclass(frozen=True)
class Spec:
    """One set of wall-model runs: the plate's ``friction``, the wall thickness ``t0`` (mm),
    the ``stroke`` (mm) and the ``material`` (a material file; empty: the study's)."""

    name: str
    friction: str = "0"
    t0: float = 1.0
    stroke: float = 6.0
    material: str = ""


@dataclass(frozen=True)
class Factor:
    """One row: its ``label``, the runs it reads (``spec``) and the stroke its means are
    taken over (``window``, mm)."""

    name: str
    label: str
    spec: str
    window: float = 6.0
    source: str = ""


SPECS = {s.name: s for s in (Spec("long", stroke=8.0), Spec("mu0.3", friction="0.3"),
                             Spec("mu0.6", friction="0.6"), Spec("stick", friction="stick"),
                             Spec("thin", t0=0.9), Spec("thick", t0=1.1),
                             Spec("stiffest", friction="stick", t0=1.1, stroke=8.0))}
FACTORS = (Factor("baseline", "the report's setup", "long"),
           Factor("mu_0.3", "Coulomb friction μ = 0.3 on the plate", "mu0.3"),
           Factor("mu_0.6", "Coulomb friction μ = 0.6 on the plate", "mu0.6"),
           Factor("stick", "a plate that lets nothing slide", "stick"),
           Factor("t0_0.9", "wall 0.9 mm (printed 0.1 mm thin)", "thin"),
           Factor("t0_1.1", "wall 1.1 mm (printed 0.1 mm thick)", "thick"),
           Factor("y_0-4", "means over y = 0–4 mm", "long", 4.0),
           Factor("y_0-8", "means over y = 0–8 mm", "long", 8.0),
           Factor("stiffest", "all stiffening ones at once (stick, 1.1 mm, 0–8 mm)",
                  "stiffest", 8.0))


def material_rows(paths) -> tuple[dict, tuple]:
    """The run sets and rows of material files (``--material-row``): the material alone and
    with the stiffening factors; each row cites the material's source and its data's notes."""
    from spsc.materials.file import material_from_record, read_material_file

    specs, factors = {}, []
    for path in paths:
        record = read_material_file(path)
        m = material_from_record(record, str(path))
        data = record.get("data", [])
        notes = "; ".join(dict.fromkeys(n for d in data for n in d.get("notes", [])))
        source = f"{m.source}" + (f"; data: {notes}" if notes else "")
        one, stiff = (Spec(f"material:{m.name}", material=str(path)),
                      Spec(f"stiffest:{m.name}", "stick", 1.1, 8.0, str(path)))
        specs |= {one.name: one, stiff.name: stiff}
        factors += [Factor(f"material_{m.name}", f"material {m.name} (μ0 "
                           f"{m.shear_modulus:.2f} MPa)", one.name, source=source),
                    Factor(f"stiffest_{m.name}", f"{m.name} and all stiffening ones",
                           stiff.name, 8.0, source)]
    return specs, tuple(factors)


def select(names) -> tuple:
    """The built-in rows named in ``names`` (``--factors``; None: all), the baseline always
    first; a one-line error for an unknown name."""
    from spsc.core.errors import ParameterError

    if names is None:
        return FACTORS
    known = {f.name: f for f in FACTORS}
    bad = [n for n in names if n not in known]
    if bad or not names:
        raise ParameterError("factors", ",".join(names), "names among " + ", ".join(known))
    return tuple(f for f in FACTORS if f.name == "baseline" or f.name in names)


def jobs(specs, types=TYPES, pressures=PRESSURES) -> list[tuple]:
    """Every (spec name, type, setup pressure, mode) to run."""
    return [(s, t, p, m) for s in specs for m in MODES for t in types for p in pressures]


def curve_of(spec: Spec, type_name: str, pressure_kPa: float, mode: str, material_name: str):
    """The wall model's curve of one job (a Dask task)."""
    from spsc.cad.geometry import preset
    from spsc.core.setup import Setup
    from spsc.materials import material
    from spsc.models import MODELS

    geometry = preset(type_name, t0=spec.t0)
    setup = Setup.of(geometry, material(spec.material or material_name),
                     pressure_kPa=pressure_kPa, reservoir_mm3=MODES[mode],
                     stroke_mm=spec.stroke, points=int(round(spec.stroke * POINTS_PER_MM)) + 1,
                     friction=spec.friction)
    wall = MODELS["wall"]
    return wall.curve(setup, wall.Options()).curve


def _window(curve, y_end: float):
    keep = curve.y_mm <= y_end + 1e-9
    return curve.replace(y_mm=curve.y_mm[keep], force_N=curve.force_N[keep],
                         pressure_kPa=curve.pressure_kPa[keep],
                         contact_area_mm2=curve.contact_area_mm2[keep],
                         volume_change_mm3=curve.volume_change_mm3[keep],
                         converged=curve.converged[keep],
                         message=tuple(np.asarray(curve.message, object)[keep]), series={})


def _row(factor: Factor, curves: dict, types, pressures) -> dict:
    from spsc.study.metrics import headline

    out = {"factor": factor.name, "label": factor.label, "window_mm": factor.window,
           "source": factor.source}
    partial = []
    for mode in MODES:
        by_type = {}
        for t in types:
            cs = [curves[(factor.spec, t, p, mode)] for p in pressures]
            by_type[t] = [_window(c, factor.window) for c in cs]
            partial += [f"{t} {mode} {p:g} kPa" for c, p in zip(cs, pressures)
                        if not np.all(c.converged[c.y_mm <= factor.window + 1e-9])]
        h = headline(by_type)
        out[f"stiffness_{mode}"], out[f"sensitivity_{mode}"] = h["stiffness"], h["sensitivity"]
    out["partial"] = partial
    return out


def run_gap(out, bench: dict, *, bench_source: str = "", material_name: str = "tpu60a",
            types=TYPES, pressures=PRESSURES, factors=FACTORS, materials=(), client=None,
            progress=None) -> dict:
    """Run the factors' wall curves (on the Dask ``client``, else here one after another)
    into ``out``: ``summary.json`` (a row per factor and per material file of ``materials``,
    the ``bench``'s means — ``{quantity: value}`` of the headline's four, from
    ``bench_source`` — and each row against them and against the baseline) and
    ``bench-gap.png``; returns the summary. ``progress(done, total)`` after each curve."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    extra_specs, extra = material_rows(materials)
    all_specs = SPECS | extra_specs
    factors = tuple(factors) + extra
    # the Coulomb runs first: they take five times as long, so the workers end together
    specs = sorted({f.spec for f in factors},
                   key=lambda n: (all_specs[n].friction in ("0", "stick"), n))
    todo = jobs(specs, types, pressures)
    t0 = time.perf_counter()
    curves = {}
    if client is None:
        for k, (s, t, p, m) in enumerate(todo):
            curves[(s, t, p, m)] = curve_of(all_specs[s], t, p, m, material_name)
            if progress is not None:
                progress(k + 1, len(todo))
    else:
        from distributed import as_completed

        futures = {client.submit(curve_of, all_specs[j[0]], *j[1:], material_name,
                                 pure=False): j for j in todo}
        for k, fut in enumerate(as_completed(futures)):
            curves[futures[fut]] = fut.result()
            if progress is not None:
                progress(k + 1, len(todo))
    rows = [_row(f, curves, types, pressures) for f in factors]
    base = next((r for r in rows if r["factor"] == "baseline"), rows[0])
    for r in rows:
        r["against_bench_pct"] = {q: 100 * (r[q] / v - 1) for q, v in bench.items()}
        r["against_baseline_pct"] = {q: 100 * (r[q] / base[q] - 1) for q in bench}
    summary = {"material": material_name, "types": list(types), "pressures_kPa":
               list(pressures), "modes": MODES, "bench": bench,
               "bench_source": bench_source, "rows": rows,
               "curves": len(todo), "seconds": time.perf_counter() - t0}
    write_json(out / "summary.json", summary)
    _figure(summary, out / "bench-gap.png")
    return summary


def _figure(summary, path) -> None:
    """One panel per quantity, a horizontal bar per row: the row's mean over the bench's
    (fourteen rows stay readable, each named once on the shared axis)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows, bench = summary["rows"], summary["bench"]
    qs = list(bench)
    fig, axes = plt.subplots(1, len(qs), sharey=True, figsize=(11.0, 1.2 + 0.32 * len(rows)),
                             constrained_layout=True)
    y = np.arange(len(rows))[::-1]
    for ax, q in zip(np.atleast_1d(axes), qs):
        ratio = [r[q] / bench[q] for r in rows]
        ax.barh(y, ratio, color=["0.55" if r["factor"] == "baseline" else "C0" for r in rows])
        ax.axvline(1.0, color="k", lw=1)
        for yi, v in zip(y, ratio):
            ax.text(v + 0.02, yi, f"{v:.2f}", va="center", fontsize=7)
        ax.set_xlim(0.0, 1.2 * max(max(ratio), 1.0))
        ax.set_title(q.replace("_", " "), fontsize=9)
        ax.set_xlabel("wall model / bench", fontsize=8)
    axes[0].set_yticks(y, [r["label"] for r in rows], fontsize=7)
    fig.savefig(path, dpi=110)
    plt.close(fig)
