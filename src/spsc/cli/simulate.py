"""``spsc simulate``: the chamber in time — the press of a scenario file on the chamber, its
valve, reservoir and gas, read by a pressure sensor.

    spsc simulate SCENARIO.toml --out DIR [--csv] [--cache DIR] [--quiet]
    spsc simulate SCENARIO.toml --bode --out DIR

Writes DIR/trace.parquet (t_s, y_mm, force_N, pressure_kPa, reservoir_kPa, valve_open, ...,
pressure_measured_kPa with a sensor), DIR/trace.csv with --csv, DIR/scenario.json (the
scenario echoed with the code that ran it) and DIR/trace.png; with --bode instead the response
to a small sinusoidal press about the scenario's [bode] point (DIR/bode.parquet, bode.json,
bode.png). The scenario's format:
docs/guides/time.md. Exit 0 when the whole press was integrated, 1 when it stopped early (the
trace so far is written, the reason on stderr), 2 on invalid input (one line on stderr).
"""

from __future__ import annotations

import sys
from pathlib import Path

from spsc.cli.options import add_quiet_option, check_output_dir
from spsc.core.errors import ParameterError

__all__ = ["register", "run"]

VERB = "simulate"


def register(subparsers) -> None:
    p = subparsers.add_parser(VERB, help="the chamber in time: press, valve, reservoir, gas "
                              "and sensor from a scenario file", description=__doc__.split(
                                  "\n\n")[0])
    p.add_argument("scenario", metavar="SCENARIO.toml", help="the scenario (TOML)")
    p.add_argument("--out", required=True, metavar="DIR", help="folder for the trace, the "
                   "echoed scenario and the figure (created)")
    p.add_argument("--csv", action="store_true", help="also write trace.csv")
    p.add_argument("--bode", action="store_true", help="the frequency response (dynamic "
                   "stiffness and sensitivity) about the scenario's [bode] point instead of "
                   "the trace")
    p.add_argument("--study", action="store_true", help="the report's time-domain study: "
                   "the trace, the Bode plot and the squeeze-release hysteresis of --types with "
                   "the material's Prony terms (about 3 min; DIR/summary.json, what spsc report "
                   "--time shows)")
    p.add_argument("--types", default="ABCD", metavar="ABCD", help="with --study: the Table 1 "
                   "types whose hysteresis is computed (default ABCD)")
    p.add_argument("--workers", default=None, metavar="N", help="local worker processes that "
                   "press the chamber map's levels when it is built (default: one per core)")
    p.add_argument("--scheduler", default=None, metavar="ADDR", help="address of a running "
                   "Dask scheduler (tcp://host:8786) instead")
    p.add_argument("--cache", metavar="DIR", default=None, help="where chamber maps are kept "
                   "(default: spsc-cache beside --out)")
    add_quiet_option(p)
    p.set_defaults(func=run)


def run(args) -> int:
    from spsc.dynamics.output import write
    from spsc.dynamics.scenario import read_scenario
    from spsc.dynamics.simulate import simulate

    from spsc.study.executor import check_cluster

    if args.bode and args.study:  # the study runs its own Bode plot; one of them was dropped
        raise ParameterError("--study", True, "without --bode (the study draws the Bode plot "
                             "of its scenario itself)")
    out = check_output_dir("--out", args.out)
    if args.cache is not None:  # where the map goes, checked before it is built (minutes)
        check_output_dir("--cache", args.cache)
    where = dict(zip(("workers", "scheduler"), check_cluster(args.workers, args.scheduler)))
    scenario = read_scenario(args.scenario)
    scenario.chamber.geometry()  # the chamber checked before any work
    from spsc.materials import material

    material(scenario.chamber.material)
    cache = Path(args.cache) if args.cache else out.absolute().parent / "spsc-cache"
    quiet = args.quiet
    bars, map_progress, progress = _bars(args, scenario)
    if args.bode:
        return _bode(scenario, out, cache, map_progress, bars, quiet, where)
    if args.study:
        return _study(scenario, out, cache, args.types, quiet, where)
    try:
        sim = simulate(scenario, cache_dir=cache, progress=progress, map_progress=map_progress,
                       **where)
    finally:
        for bar in bars.values():
            bar.close()
    files = write(sim, out, csv=args.csv)
    if not quiet:
        took = (f"the wall stepped in time {sim.seconds['wall']:.2f} s" if "wall" in sim.seconds
                else f"{sim.seconds['integrate']:.2f} s (chamber map {sim.seconds['map']:.2f} s)")
        print(f"spsc simulate: {len(sim.trace)} samples in {took} -> "
              + ", ".join(f.name for f in files), file=sys.stderr)
    if not sim.complete:
        print(f"spsc {VERB}: {sim.message}", file=sys.stderr)
        return 1
    return 0



def _bars(args, scenario):
    """(the open bars, ``map_progress(done, total)``, ``progress(t, t_end)``): the chamber
    map's levels (the stepped wall's Bode: its frequencies) and the run's seconds."""
    from spsc.core.progress import progress_bar
    from spsc.dynamics.wall_time import stepped

    bars, quiet = {}, args.quiet
    what = ("spsc simulate --bode", "frequency") if args.bode and stepped(scenario) else \
        ("chamber map", "level")

    def map_progress(done, total):
        if not quiet:
            if "map" not in bars:
                bars["map"] = progress_bar(total=total, desc=what[0], unit=what[1],
                                           file=sys.stderr, leave=False)
            bars["map"].update(done - bars["map"].n)

    def progress(t, t_end):
        if not quiet:
            if "run" not in bars:
                bars["run"] = progress_bar(total=round(t_end, 6), desc="spsc simulate",
                                           unit="s", file=sys.stderr, leave=False,
                                           bar_format="{l_bar}{bar}| {n:.3g}/{total:.3g} s")
            bars["run"].update(round(t, 6) - bars["run"].n)

    return bars, map_progress, progress

def _bode(scenario, out, cache, map_progress, bars, quiet, where) -> int:
    from spsc.dynamics.output import write_bode
    from spsc.dynamics.simulate import frequency_response

    try:
        table, summary = frequency_response(scenario, cache_dir=cache, map_progress=map_progress,
                                            **where)
    finally:
        for bar in bars.values():
            bar.close()
    files = write_bode(table, summary, scenario, out)
    if not quiet:
        half = summary["sensitivity_halfway_Hz"]
        print(f"spsc simulate --bode: stiffness {summary['stiffness_low_f_N_per_mm']:.4g} -> "
              f"{summary['stiffness_high_f_N_per_mm']:.4g} N/mm, sensitivity "
              f"{summary['sensitivity_low_f_kPa_per_mm']:.4g} -> "
              f"{summary['sensitivity_high_f_kPa_per_mm']:.4g} kPa/mm"
              + (f", halfway at {half:.3g} Hz" if half else "") + " -> "
              + ", ".join(f.name for f in files), file=sys.stderr)
    return 0


def _study(scenario, out, cache, types, quiet, where) -> int:
    from spsc.core.progress import progress_bar

    from spsc.studies.time import run_time_study

    types = str(types).upper()
    if not types or any(t not in "ABCD" for t in types) or len(set(types)) != len(types):
        raise ParameterError("--types", types, "letters of ABCD, each once")
    bar = None

    def progress(what, done, total):
        nonlocal bar
        if quiet:
            return
        if bar is None:
            bar = progress_bar(total=total, desc="hysteresis cycles", unit="type",
                               file=sys.stderr, leave=False)
        bar.update(done - bar.n)

    if not quiet:
        print(f"spsc {VERB} --study: the trace, the Bode plot, then {len(types)} squeeze-release "
              "cycles (about 40 s each)", file=sys.stderr)
    try:
        summary = run_time_study(scenario, out, cache_dir=cache, types=types, progress=progress,
                                 **where)
    finally:
        if bar is not None:
            bar.close()
    if not quiet:
        rows = ", ".join(f"{r['type']} {r['hysteresis_N']:.2f} N" for r in summary["hysteresis"])
        print(f"spsc {VERB} --study: hysteresis {rows} -> {out}/summary.json", file=sys.stderr)
    return 0 if summary["complete"] and all(r["complete"] for r in summary["hysteresis"]) else 1
