"""``spsc calibrate``: the material's stiffness from a bench test of the user's chamber, through
the wall model, and the predicted curves at other setups.

    spsc calibrate BENCH.csv --type D --pressure 0|KPA [--reservoir MM3] [--material NAME]
                   [--predict-pressures 10,20,30,40] [--predict-reservoirs 0,40000]
                   [--mesh-size MM] [--layers N] [--json F] [--png F] [--quiet]

BENCH.csv: columns y_mm (plate travel from first contact) and force_N; with --pressure > 0
also pressure_kPa (gauge) if it was measured. --pressure 0 is the open chamber's test
(F_el(y), the paper's Fig. 5b). Exit 0 with the calibrated material, 2 on invalid input.
"""

from __future__ import annotations

import sys

import numpy as np

from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import PRESSURE_MAX_KPA
from spsc.models.wall import wall_size_check

from spsc.studies.calibration import identification, mean_slope, plot_calibration
from spsc.cli.options import (PLOT_SUFFIXES, Once, add_gas_options, add_geometry_options,
                              add_output_options, add_quiet_option, check_output_file,
                              geometry_from_args, integer, number, number_list)


def register(subparsers) -> None:
    p = subparsers.add_parser("calibrate", help="calibrate the material's stiffness on a bench "
                              "test (wall model) and predict other setups",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("bench", help="bench CSV: y_mm, force_N[, pressure_kPa]")
    add_geometry_options(p)
    g = p.add_argument_group("setup of the bench test")
    add_gas_options(g, pressure_required=True, pressure_help="setup pressure of the test, kPa "
                    "gauge (required; 0: the open chamber, vented)")
    g.add_argument("--material", default="tpu60a",
                   help="the law to calibrate (its stiffness is scaled; default tpu60a)")
    m = p.add_argument_group("wall model discretisation")
    m.add_argument("--mesh-size", type=number("mesh size", "mm"), default=None, metavar="MM",
                   help="element edge along the wall, mm (default: 0.5 dome, 1.0 stadium)")
    m.add_argument("--layers", type=integer("layers"), default=2, metavar="N",
                   help="quadratic elements through the wall (default 2)")
    m.add_argument("--force", action="store_true",
                   help="run beyond the size limits (the estimate is printed first)")
    q = p.add_argument_group("predictions with the calibrated material")
    q.add_argument("--predict-pressures", default="10,40", metavar="KPA,...", action=Once,
                   help="kPa gauge, comma-separated (default 10,40; '' for none)")
    q.add_argument("--predict-reservoirs", default="0,40000", metavar="MM3,...", action=Once,
                   help="mm³, comma-separated (default 0,40000: high and low mode)")
    q.add_argument("--predict-stroke", type=number("predict_stroke", "mm"), default=4.0,
                   metavar="MM", help="stroke of the predicted curves, mm (default 4)")
    add_output_options(p, json="write the calibration, its curve and the predictions here",
                       csv=None, png="plot bench vs calibrated model and the predictions here")
    p.add_argument("--out", metavar="MATERIAL.json",
                   help="write the calibrated law as a material file (use it as --material)")
    add_quiet_option(p)
    p.set_defaults(func=run)


def _predictions(args) -> list[tuple[float, float]]:
    if not str(args.predict_pressures).strip():
        return []
    pressures = number_list("predict-pressures", args.predict_pressures, ge=0,
                            le=PRESSURE_MAX_KPA, unit="kPa gauge", distinct=True)
    reservoirs = number_list("predict-reservoirs", args.predict_reservoirs, ge=0, unit="mm³",
                             distinct=True)
    return [(p, r) for r in reservoirs for p in pressures]


def run(args) -> int:
    from spsc.core.progress import progress_bar

    from spsc.core.loadcase import check_load
    from spsc.core.setup import Setup
    from spsc.fem.wall.calibrate import calibrate
    from spsc.core.bench import REQUIRED, read_bench
    from spsc.materials import material
    from spsc.models import MODELS

    if args.json is not None:
        check_output_file("--json", args.json)
    if args.png is not None:
        check_output_file("--png", args.png, PLOT_SUFFIXES)
    if args.out is not None:
        check_output_file("--out", args.out, (".json",))
    geom = geometry_from_args(args)
    mat = material(args.material)
    require("pressure", args.pressure, ge=0, le=PRESSURE_MAX_KPA, unit="kPa gauge")
    wall = MODELS["wall"]
    options = wall.Options(mesh_size=args.mesh_size, layers=args.layers)
    setups = _predictions(args)
    require("predict_stroke", args.predict_stroke, gt=0, lt=geom.h,
            unit=f"mm, below the chamber height h = {geom.h:g} mm")
    bench = read_bench(args.bench, required=REQUIRED[:2])
    check_load(geom, pressure_kPa=args.pressure, reservoir_mm3=args.reservoir,
               stroke_mm=float(bench.y_mm[-1]), points=2, polytropic_n=args.polytropic_n)
    if args.pressure == 0 and bench.pressure_kPa is not None and np.any(bench.pressure_kPa != 0):
        raise ParameterError("bench pressure_kPa", float(np.max(np.abs(bench.pressure_kPa))),
                             "0 for an open-chamber test (--pressure 0), or give --pressure")
    wall_size_check("calibrate", geom, args.mesh_size, args.layers, 16, force=args.force,
                    quiet=args.quiet, points=17)
    bar = progress_bar(desc="spsc calibrate", unit="solve", disable=args.quiet, file=sys.stderr)
    try:
        def solve(m, stroke_mm, points, p=args.pressure, r=args.reservoir):
            setup = Setup.of(geom, m, pressure_kPa=p, reservoir_mm3=r, stroke_mm=stroke_mm,
                             points=points, polytropic_n=args.polytropic_n)
            return wall.curve(setup, options).curve

        cal = calibrate(bench, geom, mat, pressure_kPa=args.pressure,
                        reservoir_mm3=args.reservoir, polytropic_n=args.polytropic_n,
                        progress=lambda: bar.update(1), solve=solve)
        preds = [solve(cal.material, args.predict_stroke, 17, p, r) for p, r in setups]
        bar.update(len(preds))
    finally:
        bar.close()
    idents = identification(bench, geom, setups, pressure_kPa=args.pressure,
                            reservoir_mm3=args.reservoir, polytropic_n=args.polytropic_n)
    _summary(args, cal, mat, preds)
    if idents:
        _compare(preds, idents, min(float(bench.y_mm[-1]), args.predict_stroke))
    if args.json:
        _write_json(args.json, cal, mat, preds, idents)
    if args.png:
        plot_calibration(args.png, bench, cal, preds, args.pressure)
    if args.out:
        _write_material(args, cal, mat)
        print(f"material file {args.out} ({cal.material.law}, name '{cal.material.name}'): "
              f"use it as --material {args.out}")
    return 0


def _write_material(args, cal, mat) -> None:
    """The calibrated law as a material file (``spsc.material``, provenance user-fit), with
    the bench file's hash and the calibration's residual."""
    import hashlib
    from pathlib import Path

    from spsc.core.jsonio import write_json
    from spsc.materials.file import LAW_CONSTANTS, material_record

    m = cal.material
    if m.law not in LAW_CONSTANTS:  # Ogden's or a registered law: its own constants
        constants = {k: v for k, v in m.identity().items() if k != "law"}
    else:
        names = {ij: name for name, ij in LAW_CONSTANTS[m.law].items()}
        constants = {names[(i, j)]: c for i, j, c in m.coefficients}
    digest = hashlib.sha256(Path(args.bench).read_bytes()).hexdigest()
    fit = {"calibration": {"start_material": mat.name, "scale": cal.scale,
                           "model": "wall", "pressure_kPa": args.pressure,
                           "reservoir_mm3": args.reservoir,
                           "force_rms_N": cal.force_rms_N,
                           "pressure_rise_rms_kPa": cal.pressure_rms_kPa,
                           "relative_rms": cal.relative_rms}}
    data = [{"file": str(args.bench), "sha256": digest, "test": "chamber bench test",
             "points": int(cal.y_mm.size)}]
    write_json(args.out, material_record(cal.material.name, cal.material.law, constants,
                                         source=cal.material.source, fit=fit, data=data))


def _compare(preds, idents, y_end: float) -> None:
    """Mean stiffness and sensitivity over [0, y_end] mm of both predictions, per setup."""
    print(f"calibrated wall model vs the paper's identification (eqs. 39-40) on the same test, "
          f"mean slopes over 0-{y_end:.3g} mm:")
    print(f"{'p_i_kPa':>8} {'V_r_mm3':>9} {'k_wall':>8} {'k_ident':>8} {'S_wall':>8} "
          f"{'S_ident':>8}")
    for w, i in zip(preds, idents):
        print(f"{w.setup['p_i_kPa']:8.4g} {w.setup['reservoir_mm3']:9.6g} "
              f"{mean_slope(w, w.force_N, y_end):8.4g} "
              f"{mean_slope(i, i.force_N, y_end):8.4g} "
              f"{mean_slope(w, w.pressure_kPa, y_end):8.4g} "
              f"{mean_slope(i, i.pressure_kPa, y_end):8.4g}")


def _summary(args, cal, mat, preds) -> None:
    mode = "open chamber" if args.pressure == 0 else \
        f"p_i = {args.pressure:g} kPa, V_r = {args.reservoir:g} mm³"
    print(f"calibrated {mat.name} on {args.bench} ({mode}, {cal.y_mm.size} points, "
          f"{cal.evaluations} wall solves): stiffness x {cal.scale:.4g}, "
          f"initial shear modulus {mat.shear_modulus:.4g} -> "
          f"{cal.material.shear_modulus:.4g} MPa")
    rms_p = "" if cal.pressure_rms_kPa is None else \
        f", pressure-rise {cal.pressure_rms_kPa:.3g} kPa"
    print(f"residual RMS: force {cal.force_rms_N:.3g} N{rms_p}; "
          f"relative {100 * cal.relative_rms:.2f} %")
    if preds:
        print(f"{'p_i_kPa':>8} {'V_r_mm3':>9} {'F_end_N':>9} {'p_end_kPa':>10} {'k_N/mm':>8} "
              f"{'S_kPa/mm':>9}")
    for c in preds:
        print(f"{c.setup['p_i_kPa']:8.4g} {c.setup['reservoir_mm3']:9.6g} {c.force_N[-1]:9.3f} "
              f"{c.pressure_kPa[-1]:10.3f} {c.mean_stiffness():8.4g} {c.mean_sensitivity():9.4g}")


def _write_json(path, cal, mat, preds, idents) -> None:
    from spsc.core.jsonio import write_json
    from spsc.materials.file import LAW_CONSTANTS

    m = cal.material
    write_json(path, {
        "schema": "spsc.calibration", "schema_version": 1,
        "material": {"name": m.name, "law": m.law, "source": m.source, **(
                     {"constants": m.identity()} if m.law not in LAW_CONSTANTS else
                     {"coefficients": [{"i": i, "j": j, "C_MPa": c}
                                       for i, j, c in m.coefficients]}),
                     "shear_modulus_MPa": m.shear_modulus},
        "start_material": mat.name, "scale": cal.scale, "evaluations": cal.evaluations,
        "residual": {"force_rms_N": cal.force_rms_N, "pressure_rise_rms_kPa": cal.pressure_rms_kPa,
                     "relative_rms": cal.relative_rms, "y_mm": cal.y_mm.tolist(),
                     "force_N": cal.force_residual_N.tolist(),
                     "pressure_kPa": None if cal.pressure_residual_kPa is None
                     else cal.pressure_residual_kPa.tolist()},
        "curve": cal.curve.to_dict(),
        "predictions": [c.to_dict() for c in preds],
        "identification_predictions": [c.to_dict() for c in idents]})
