"""``spsc sense``: the chamber as a sensor — force, depth and events from a pressure log.

    spsc sense LOG.csv|LOG.parquet --out DIR --type B [--material NAME|FILE.json]
               [--pressure KPA] [--reservoir MM3] [--noise auto|KPA] [--detector cusum|threshold]
               [--detectors NAME[,NAME]]
    spsc sense --follow --type B ... < samples.csv        (events as JSON lines on stdout)
    spsc sense --haptic-calibrate SQUEEZE.csv --out DIR [--haptic-fraction 0.02]
    spsc sense LOG.csv --haptic DIR/haptic.json --out DIR ...

LOG columns: t_s, pressure_kPa (gauge), optional valve_open (0/1), fsr_1..fsr_N (N), angle_deg.
The chamber as ``spsc curve`` takes it; ``--material`` may be the calibrated material file
``spsc calibrate --out`` writes. Writes DIR/estimate.parquet, DIR/events.json and
DIR/sense.png (docs/guides/sensing.md). Exit 0, 2 on invalid input (one line on stderr).
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from spsc.cli.options import (add_geometry_options, add_quiet_option, check_output_dir,
                              gas_option, geometry_from_args, number, warn)
from spsc.core.errors import ParameterError, require

__all__ = ["register", "run"]

VERB = "sense"
_CHUNK = 5000  # samples between progress-bar updates
#: the registry's detectors that run without --detectors, and when
_BUILT_IN = {"slip": "always", "compliance": "with --stiff-mm-per-deg", "leak": "always"}


def register(subparsers) -> None:
    p = subparsers.add_parser(VERB, help="force, depth and events (contact, release, slip, "
                              "switch, object compliance, a leak at rest) from a chamber's pressure log",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("log", nargs="?", metavar="LOG.csv|LOG.parquet", help="the log")
    p.add_argument("--out", metavar="DIR", help="folder for estimate.parquet, events.json, "
                   "sense.png (created; optional with --follow)")
    add_geometry_options(p)
    g = p.add_argument_group("the chamber and its circuit")
    g.add_argument("--design", metavar="FILE.design.json", default=None,
                   help="the chamber of a design file instead of --type: a bladder's "
                   "(spsc bladder) or spsc design's design.json (its best design, with its "
                   "material and setup pressure unless given)")
    g.add_argument("--material", default=None, metavar="NAME|FILE.json",
                   help="catalogue material or a material file (spsc calibrate --out; "
                   "default tpu60a)")
    g.add_argument("--pressure", type=number("pressure", "kPa gauge"), default=None,
                   metavar="KPA", help="setup pressure, kPa gauge (default 40)")
    g.add_argument("--reservoir", type=number("reservoir", "mm³"), default=40000.0,
                   metavar="MM3", help="reservoir volume, mm³ (default 40000, the paper's: a "
                   "sensing chamber switches to its reservoir, where spsc curve's default 0 is "
                   "the closed chamber)")
    g.add_argument("--stroke", type=number("stroke", "mm"), default=4.0, metavar="MM",
                   help="deepest plate travel the map covers, mm (default 4)")
    g.add_argument("--mesh-size", type=number("mesh size", "mm"), default=None, metavar="MM",
                   help="the wall model's element edge, mm (default: its own)")
    g.add_argument("--cache", metavar="DIR", default=None,
                   help="where chamber maps are kept (default: spsc-cache beside --out)")
    g.add_argument("--workers", default=None, metavar="N", help="local worker processes that "
                   "press the chamber map's levels when it is built (default: one per core)")
    g.add_argument("--scheduler", default=None, metavar="ADDR", help="address of a running "
                   "Dask scheduler (tcp://host:8786) instead")
    _sensing_options(p)
    h = p.add_argument_group("haptic loop (sec. 4.2)")
    h.add_argument("--haptic-calibrate", metavar="SQUEEZE.csv", default=None,
                   help="write DIR/haptic.json from a maximal squeeze in the low mode")
    h.add_argument("--haptic-fraction", type=number("haptic fraction"), default=0.02,
                   metavar="F", help="threshold = rest + F × max (default 0.02, the paper's)")
    h.add_argument("--haptic", metavar="HAPTIC.json", default=None,
                   help="run the haptic loop: joint angle per sample, valve/vibrate commands")
    add_quiet_option(p)
    p.set_defaults(func=run)


def _sensing_options(p) -> None:
    s = p.add_argument_group("sensing")
    s.add_argument("--noise", default="auto", metavar="auto|KPA", help="the sensor's σ, kPa "
                   "(auto: from the log's first differences; with --follow the ELVH's 0.086)")
    s.add_argument("--model-error", type=number("model error"), default=0.05, metavar="E",
                   help="the model's relative force error, 95 %% (default 0.05: an assumption, "
                   "see the guide; calibrate and set it)")
    s.add_argument("--smoothing", type=number("smoothing", "s"), default=0.005, metavar="S",
                   help="time constant of the pressure filter, s (default 0.005)")
    s.add_argument("--gas", default="1", metavar="N[,TAU]", help="the air's ratio of heat "
                   "capacities n and thermal time τ (s; inf: adiabatic), as spsc simulate's "
                   "gas = {n, thermal_time_s}: 1 the isothermal gas (default, the paper's "
                   "static tests), 1.4,0.5 air relaxing in 0.5 s (the examples' scenarios)")
    s.add_argument("--detector", choices=("cusum", "threshold"), default="cusum",
                   help="contact detector: CUSUM (default) or the paper's thresholds")
    s.add_argument("--detectors", default=None, metavar="NAME[,NAME]",
                   help="more event detectors of the registry (spsc.sensing.detectors."
                   "DETECTORS) with their default parameters, run after slip, compliance and "
                   "leak (default: none)")
    s.add_argument("--valve", choices=("open", "closed"), default="closed",
                   help="the valve at the start when the log has no valve_open column")
    s.add_argument("--stiff-mm-per-deg", type=number("stiff_mm_per_deg", "mm/deg"),
                   default=None, metavar="X", help="with angle_deg: stiff object above this "
                   "depth per degree of closure (off when not given)")
    s.add_argument("--pressure-column", default="pressure_kPa", metavar="NAME",
                   help="the pressure column (default pressure_kPa; a spsc simulate trace: "
                   "pressure_measured_kPa)")
    s.add_argument("--follow", action="store_true", help="read samples from standard input "
                   "(a CSV header, then a line each); print events as JSON lines")


def _check_chamber(args):
    """The chamber, its material, setup and the wall model's mesh, checked (the limits of
    ``spsc curve``) before any work: the geometry."""
    from spsc.core.loadcase import check_load
    from spsc.materials import material
    from spsc.models.wall import wall_size_check

    if args.cache is not None:  # where the map goes, checked before it is built (minutes)
        check_output_dir("--cache", args.cache)
    geometry = _geometry(args)
    args.chamber = geometry.as_dict()  # recorded in events.json
    material(args.material)
    check_load(geometry, pressure_kPa=args.pressure, reservoir_mm3=args.reservoir,
               stroke_mm=args.stroke, points=2, polytropic_n=1.0)
    wall_size_check(VERB, geometry, args.mesh_size, 2, 2, force=False, quiet=True, points=2)
    from spsc.study.executor import check_cluster

    args.workers, args.scheduler = check_cluster(args.workers, args.scheduler)
    return geometry


def _geometry(args):
    """The chamber of ``--design`` (its material and pressure filling what is not given) or
    of the geometry options; ``--material`` and ``--pressure`` get their defaults."""
    if args.design is None:
        geometry = geometry_from_args(args)
    else:
        from spsc.cli.options import PARAMS

        given = [k for k in ("type", *PARAMS) if getattr(args, k, None) is not None]
        if given:
            raise ParameterError("--" + given[0], getattr(args, given[0]),
                                 "not with --design (the design file is the chamber)")
        from spsc.cad.design_file import design_chamber

        chamber = design_chamber(args.design)
        geometry = chamber.geometry
        args.material = args.material or chamber.material
        args.pressure = args.pressure if args.pressure is not None else chamber.pressure_kPa
    args.material = args.material or "tpu60a"
    args.pressure = 40.0 if args.pressure is None else args.pressure
    return geometry


def _chamber(args, geometry):
    """The dense map of the chamber, built or from the cache, with a progress bar."""
    from spsc.core.progress import progress_bar

    from spsc.sensing import DenseMap
    from spsc.sensing.chamber import chamber_map

    out = Path(args.out) if args.out else Path.cwd() / "spsc-sense"
    cache = Path(args.cache) if args.cache else out.absolute().parent / "spsc-cache"
    bar = progress_bar(desc="chamber map", unit="level", disable=bool(args.quiet),
                       file=sys.stderr, leave=False)

    def progress(done, total):
        bar.total = total
        bar.update(done - bar.n)

    try:
        m = chamber_map(geometry.as_dict(), material=args.material, setup_kPa=args.pressure,
                        reservoir_mm3=args.reservoir, stroke_mm=args.stroke,
                        mesh_size=args.mesh_size, cache_dir=cache, progress=progress,
                        workers=args.workers, scheduler=args.scheduler)
    finally:
        bar.close()
    return DenseMap(m)


def _params(args, noise: float, rate_Hz: float):
    from spsc.sensing import EstimatorParams, SenseParams
    from spsc.sensing.detectors import ComplianceParams, ContactParams

    require("smoothing", args.smoothing, ge=0, le=10, unit="s")
    est = EstimatorParams(args.pressure, args.reservoir, noise, args.model_error,
                          smoothing_s=args.smoothing, valve_open=args.valve == "open",
                          gas=gas_option("--gas", args.gas))
    comp = (ComplianceParams(args.stiff_mm_per_deg) if args.stiff_mm_per_deg is not None
            else None)
    return SenseParams(est, ContactParams(method=args.detector), compliance=comp,
                       rate_Hz=rate_Hz, extra_detectors=args.extra_detectors)


def _noise(args, log=None) -> float:
    from spsc.dynamics.sensor import PRESETS
    from spsc.sensing.log import noise_of

    if str(args.noise).strip().lower() != "auto":
        try:
            value = float(str(args.noise).strip())
        except ValueError:
            raise ParameterError("noise", args.noise, "auto or a number (kPa)") from None
        return require("noise", value, gt=0, le=100, unit="kPa, or auto")
    return noise_of(log.pressure_kPa) if log is not None else PRESETS["elvh"]["noise_kPa"]


def _haptic_calibrate(args) -> int:
    from spsc.sensing.haptic import calibrate
    from spsc.sensing.log import read_log

    if not args.out:
        raise ParameterError("--out", None, "a folder for haptic.json")
    out = check_output_dir("--out", args.out)
    log = read_log(args.haptic_calibrate, args.pressure_column)
    cal = calibrate(log.t_s, log.pressure_kPa, fraction=args.haptic_fraction)
    out.mkdir(parents=True, exist_ok=True)
    cal.to_json(out / "haptic.json")
    print(f"spsc sense: haptic threshold {cal.threshold_kPa:.4g} kPa (rest {cal.rest_kPa:.4g} "
          f"+ {cal.fraction:g} × max {cal.max_kPa:.4g} kPa) -> {out / 'haptic.json'}",
          file=sys.stderr)
    return 0


def run(args) -> int:
    from spsc.sensing.detectors import parse_detectors

    # the registry's names, checked before any work
    args.extra_detectors = parse_detectors(args.detectors, "--detectors", _BUILT_IN)
    if args.haptic_calibrate:
        return _haptic_calibrate(args)
    if args.follow:
        if args.log not in (None, "-"):
            raise ParameterError("LOG", args.log, "none with --follow (samples come from "
                                 "standard input)")
        if args.out:
            check_output_dir("--out", args.out)
        return _follow(args)
    if not args.log:
        raise ParameterError("LOG", None, "a .csv or .parquet log (or --follow)")
    if not args.out:
        raise ParameterError("--out", None, "a folder for the outputs")
    check_output_dir("--out", args.out)
    return _batch(args)


def _haptic_loop(args):
    if not args.haptic:
        return None
    from spsc.sensing.haptic import HapticCalibration, HapticLoop

    return HapticLoop(HapticCalibration.from_json(args.haptic), smoothing_s=args.smoothing)


def _batch(args) -> int:
    from spsc.core.progress import progress_bar

    from spsc.sensing import SenseStream
    from spsc.sensing.log import read_log

    geometry = _check_chamber(args)
    log = read_log(args.log, args.pressure_column)
    loop = _haptic_loop(args)
    params = _params(args, _noise(args, log), log.rate_Hz)
    _check_rest(log, args.pressure, params.estimator.noise_kPa)
    stream = SenseStream(_chamber(args, geometry), params)
    n = len(log)
    v, fsr, ang = log.valve_open, log.fsr, log.angle_deg
    states, joints, commands = [], [], []
    bar = progress_bar(total=n, desc="spsc sense", unit="sample",
                       disable=bool(args.quiet) or n < 10**5, file=sys.stderr, leave=False)
    for i, (t, p) in enumerate(zip(log.t_s.tolist(), log.pressure_kPa.tolist())):
        st, _ = stream.push(t, p, None if v is None else v[i], None if fsr is None else fsr[i],
                            None if ang is None else ang[i])
        states.append(st)
        if loop is not None:
            theta, cmds = loop.push(t, p)
            joints.append(theta)
            commands += cmds
        if i % _CHUNK == _CHUNK - 1:
            bar.update(_CHUNK)
    bar.close()
    return _finish(args, stream, states, log.pressure_kPa, joints, commands)


def _finite_or_text(x: float):
    return x if math.isfinite(x) else str(x)


def _check_rest(log, setup_kPa: float, noise_kPa: float) -> None:
    """A warning when the log starts off the setup pressure by more than its noise allows (a
    sensor's offset, a wrong --pressure, a log that starts in a hold): the detectors measure
    from the setup, so the log reads as a contact from its first sample. A log whose
    pressure moves from its first sample (a press under way) is judged by where its line
    starts, not by its first 0.1 s's level."""
    from spsc.sensing.log import start_of

    head = start_of(log.t_s, log.pressure_kPa, noise_kPa)
    if head is None:
        return
    start, rate, moving = head
    sigmas = (start - setup_kPa) / noise_kPa
    if abs(sigmas) <= 4.0:
        return
    if moving:
        print(f"spsc sense: warning: the log starts moving ({rate:+.3g} kPa/s) from "
              f"{start:.4g} kPa, {sigmas:+.1f} σ from the setup pressure {setup_kPa:g} kPa: "
              "it starts in a press or a release, or --pressure is not the chamber's rest; "
              "the detectors measure from the setup", file=sys.stderr)
        return
    print(f"spsc sense: warning: the log starts at {start:.4g} kPa, {sigmas:+.1f} σ from "
          f"the setup pressure {setup_kPa:g} kPa; the detectors measure from the setup, so a "
          f"rest there reads as a contact. If the chamber was at rest there (a sensor's "
          f"offset, another setup), pass --pressure {start:.4g}; if the log starts in a "
          "hold, it is read as a contact from its first sample", file=sys.stderr)


def _finish(args, stream, states, pressures, joints, commands) -> int:
    from spsc.sensing.output import frame, write

    table = frame(states, pressures)
    if joints:
        table["joint_angle_deg"] = joints
    outside = int((~table.in_map).sum())
    if outside:
        warn(VERB, f"{outside} samples above the chamber map's pressures (the force is the "
             "map's deepest; a larger --stroke covers them)")
    if not args.out:
        return 0
    out = Path(args.out)
    prm = stream.params
    meta = {"samples": len(table), "noise_kPa": prm.estimator.noise_kPa,
            "model_error": prm.estimator.model_error, "detector": prm.contact.method,
            "detectors": [d.name for d in stream.detectors],
            "rate_Hz": prm.rate_Hz, "setup_kPa": prm.estimator.setup_kPa,
            "reservoir_mm3": prm.estimator.reservoir_mm3, "material": args.material,
            "gas": {"n": prm.estimator.gas.n,
                    "thermal_time_s": _finite_or_text(prm.estimator.gas.thermal_time_s)},
            "geometry": getattr(args, "chamber", None), "design": args.design}
    files = write(out, table, stream.events, meta, colours=stream.colours)
    if commands:
        files.append(out / "commands.json")
        files[-1].write_text(json.dumps(commands, indent=2, default=float) + "\n",
                             encoding="utf-8")
    if not args.quiet:
        counts = {}
        for e in stream.events:
            counts[e["kind"]] = counts.get(e["kind"], 0) + 1
        print(f"spsc sense: {len(table)} samples, events "
              + (", ".join(f"{k} {c}" for k, c in counts.items()) or "none") + " -> "
              + ", ".join(f.name for f in files), file=sys.stderr)
    return 0


def _follow(args) -> int:
    from spsc.sensing import SenseStream
    from spsc.sensing.log import LineReader

    geometry = _check_chamber(args)
    loop = _haptic_loop(args)
    params = _params(args, _noise(args), 1000.0)
    header = sys.stdin.readline()
    if not header.strip():
        raise ParameterError("standard input", "empty", "a CSV header line, then samples")
    reader = LineReader(header, args.pressure_column)
    stream = SenseStream(_chamber(args, geometry), params)
    states, pressures, joints, commands = [], [], [], []
    for line in sys.stdin:
        sample = reader.sample(line)
        if sample is None:
            continue
        st, events = stream.push(**sample)
        states.append(st)
        pressures.append(sample["pressure_kPa"])
        out = list(events)
        if loop is not None:
            theta, cmds = loop.push(sample["t_s"], sample["pressure_kPa"])
            joints.append(theta)
            commands += cmds
            out += cmds
        for e in out:
            print(json.dumps(e, default=float), flush=True)
    return _finish(args, stream, states, pressures, joints, commands)
