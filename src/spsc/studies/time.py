"""The chamber in time, for the report: a scenario's trace (press, hold, switch, release), its
frequency response, and the squeeze–release hysteresis of Types A–D with the material's
viscoelastic wall.

    make time-study   (= spsc simulate examples/press-hold-switch.toml --study
                         --out build/time-study)

The trace and the Bode plot are :func:`spsc.dynamics.simulate.simulate` and
:func:`~spsc.dynamics.simulate.frequency_response` of the scenario (its map from the keyed
cache); every valve switch under load is measured as a step of the chamber pressure (the drop,
the time to settle within 2 % of it, :func:`spsc.dynamics.stiffness.step_metrics`). The
hysteresis is :func:`spsc.fem.wall.cycle.wall_cycle` of each Table 1 type, vented, squeezed
6 mm and released at 1 mm/s with the Prony terms of the scenario's material
(:func:`spsc.materials.viscosity`), against the paper's 8.1 / 3.8 / 4.0 / 4.5 N (sec. 3.1).
It takes about 3 min on a 2-core machine, so the report shows the folder it writes
(``summary.json`` and three figures) and does not run it.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from spsc.core.jsonio import write_json

__all__ = ["PAPER_HYSTERESIS_N", "switch_steps", "hysteresis", "run_time_study"]

#: the vented chambers' squeeze–release hysteresis the paper measured (sec. 3.1), N
PAPER_HYSTERESIS_N = {"A": 8.1, "B": 3.8, "C": 4.0, "D": 4.5}


def switch_steps(sim) -> list[dict]:
    """Each valve switch of a run as a step of the chamber pressure: before, after (where it
    relaxes to before the next switch or profile knot), the 10–90 % and 2 % settling times."""
    from spsc.dynamics.stiffness import step_metrics

    d = sim.trace
    t = d.t_s.to_numpy()
    knots = [float(k) for k in getattr(sim.scenario.press, "t_s", ())]
    out = []
    for ts, opened, why in sim.switches:
        ends = [k for k in knots + [s[0] for s in sim.switches] if k > ts + 1e-9] + [t[-1]]
        window = (t <= min(ends) + 1e-12)
        m = step_metrics(t[window], d.pressure_kPa.to_numpy()[window], ts)
        out.append({"t_s": ts, "valve": "open" if opened else "closed", "why": why,
                    "y_mm": float(np.interp(ts, t, d.y_mm)),
                    "pressure_before_kPa": m["before"], "pressure_after_kPa": m["final"],
                    "settle_2pct_ms": m["settle_s"] * 1e3, "rise_ms": m["rise_s"] * 1e3})
    return out


def hysteresis(material_name: str, types: str = "ABCD", *, stroke_mm: float = 6.0,
               speed_mm_s: float = 1.0, progress=None) -> tuple[list[dict], dict, str]:
    """(a row per type, the loops {type: (y, F load, F unload)}, the Prony terms' source)."""
    from spsc.cad.geometry import preset
    from spsc.core.errors import ParameterError
    from spsc.fem.wall.cycle import wall_cycle
    from spsc.materials import material, viscosity

    prony, source = viscosity(material_name)
    if prony is None:
        raise ParameterError("material", material_name, f"a material with Prony terms for the "
                             f"hysteresis ({source})")
    rows, loops = [], {}
    for k, t in enumerate(types):
        r = wall_cycle(preset(t), material(material_name), prony, stroke_mm=stroke_mm,
                       speed_mm_s=speed_mm_s, points=25)
        paper = PAPER_HYSTERESIS_N.get(t)
        rows.append({"type": t, "hysteresis_N": r.hysteresis_N, "at_mm": r.hysteresis_at_mm,
                     "dissipated_mJ": r.dissipated_mJ, "paper_N": paper,
                     "error_pct": None if paper is None else 100 * (r.hysteresis_N / paper - 1),
                     "complete": bool(r.complete), "seconds": r.seconds})
        loops[t] = (r.y_mm, r.force_load_N, r.force_unload_N)
        if progress is not None:
            progress(k + 1, len(types))
    return rows, loops, source


def _hysteresis_figure(loops, rows, path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(loops), figsize=(3.2 * len(loops), 3.2), sharey=True,
                             constrained_layout=True, squeeze=False)
    for ax, (t, (y, up, down)), row in zip(axes[0], loops.items(), rows):
        ax.plot(y, up, "C0", label="squeeze")
        ax.plot(y, down, "C1", label="release")
        paper = f", paper {row['paper_N']:g} N" if row["paper_N"] else ""
        ax.set_title(f"Type {t}: {row['hysteresis_N']:.2f} N{paper}", fontsize=9)
        ax.set_xlabel("travel y (mm)")
    axes[0][0].set_ylabel("plate force (N)")
    axes[0][0].legend(loc="upper left", fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run_time_study(scenario, out, *, cache_dir=None, types: str = "ABCD",
                   progress=None, workers: int | None = 1, scheduler: str | None = None) -> dict:
    """Run the study of ``scenario`` (:class:`~spsc.dynamics.scenario.Scenario`) into ``out``:
    ``trace/`` (what ``spsc simulate`` writes), ``bode/`` (``--bode``), ``hysteresis.png`` and
    ``summary.json``; returns the summary. ``progress(what, done, total)``; the map's levels
    on ``workers`` or ``scheduler`` (:func:`~spsc.dynamics.chamber_map.build_map`)."""
    from spsc.dynamics.output import write, write_bode
    from spsc.dynamics.simulate import frequency_response, simulate

    out = Path(out)
    t0 = time.perf_counter()
    sim = simulate(scenario, cache_dir=cache_dir, workers=workers, scheduler=scheduler)
    write(sim, out / "trace")
    t1 = time.perf_counter()
    table, bode = frequency_response(scenario, cache_dir=cache_dir, workers=workers,
                                     scheduler=scheduler)
    write_bode(table, bode, scenario, out / "bode")
    t2 = time.perf_counter()
    rows, loops, source = hysteresis(scenario.chamber.material, types, progress=None if
                                     progress is None else lambda d, n: progress("cycles", d, n))
    _hysteresis_figure(loops, rows, out / "hysteresis.png")
    summary = {"scenario": scenario.source, "complete": sim.complete, "message": sim.message,
               "switches": switch_steps(sim), "bode": bode, "hysteresis": rows,
               "prony_source": source, "material": scenario.chamber.material,
               "cycle": {"stroke_mm": 6.0, "speed_mm_s": 1.0, "vented": True},
               "seconds": {"trace": t1 - t0, "bode": t2 - t1,
                           "hysteresis": time.perf_counter() - t2,
                           "integrate": sim.seconds["integrate"]}}
    write_json(out / "summary.json", summary)
    return summary
