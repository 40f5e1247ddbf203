"""``spsc identify``: A(y), ΔV(y) from one bench test (eqs. 39–40) and the predicted curves at
other setup pressures and reservoirs (eqs. 6–7).

    spsc identify bench.csv --pressure 40 --type D [--bladder-volume MM3] [--reservoir MM3]

The bench CSV has columns y_mm, force_N, pressure_kPa (gauge) and optionally elastic_force_N.
V_b,i defaults to the nominal cavity volume of the named type (or of the seven parameters).
"""

from __future__ import annotations

from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import PRESSURE_MAX_KPA

from spsc.cli.options import (Once, add_gas_options, add_geometry_options, add_output_options,
                      check_output_file, geometry_from_args, geometry_given, number,
                      number_list, warn)


def _floats(name: str, text: str, *, le: float | None = None, unit: str = "") -> list[float]:
    """Comma-separated numbers, each finite, >= 0 and <= ``le``; at least one, no empty item,
    no value twice (:func:`spsc.cli.options.number_list`)."""
    return list(number_list(name, text, ge=0, le=le, unit=unit, distinct=True))


def register(subparsers) -> None:
    p = subparsers.add_parser("identify", help="identify A(y), ΔV(y) from bench data",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("bench", help="bench CSV: y_mm, force_N, pressure_kPa[, elastic_force_N]")
    add_geometry_options(p)
    g = p.add_argument_group("setup of the bench test")
    add_gas_options(g, pressure_required=True,
                    pressure_help="setup pressure of the test, kPa gauge (required)")
    g.add_argument("--bladder-volume", type=number("bladder_volume", "mm³"), metavar="MM3",
                   help="V_b,i in mm³ (default: nominal cavity of the chamber)")
    q = p.add_argument_group("predictions")
    q.add_argument("--predict-pressures", default="10,20,30,40", metavar="KPA,...", action=Once,
                   help="kPa gauge, comma-separated (default 10,20,30,40)")
    q.add_argument("--predict-reservoirs", default="0,40000", metavar="MM3,...", action=Once,
                   help="mm³, comma-separated (default 0,40000)")
    add_output_options(p, json="write identified and predicted curves here",
                       csv="write the identified curve CSV here")
    p.set_defaults(func=run)


def run(args) -> int:
    from spsc.membrane.identify import identify, predict, read_bench
    from spsc.membrane.lumped import Setup

    if args.json is not None:
        check_output_file("--json", args.json)
    if args.csv is not None:
        check_output_file("--csv", args.csv)
    geometry, name = {}, ""
    if geometry_given(args):
        geom = geometry_from_args(args)
        geometry = geom.as_dict()
        vb = geom.cavity_volume() if args.bladder_volume is None else args.bladder_volume
    elif args.bladder_volume is not None:
        vb = args.bladder_volume
    else:
        raise ParameterError("bladder volume", None,
                             "--type, the seven parameters or --bladder-volume MM3")
    vb = require("bladder_volume", vb, gt=0, unit="mm³")
    pressures = _floats("predict-pressures", args.predict_pressures, le=PRESSURE_MAX_KPA,
                        unit="kPa gauge")
    reservoirs = _floats("predict-reservoirs", args.predict_reservoirs, unit="mm³")
    require("pressure", args.pressure, gt=0, le=PRESSURE_MAX_KPA, unit="kPa gauge")
    Setup(args.pressure, vb, args.reservoir, args.polytropic_n)  # the gas, validated
    bench = read_bench(args.bench)
    if len(bench.y_mm) > 100_000:  # a logger's stream, not a bench table: say what it costs
        warn("identify", f"the bench file holds {len(bench.y_mm):,} rows; the identification "
             "uses every one (a bench table of a few hundred to a few thousand rows is usual: "
             "decimate a logger's stream first)")
    ident = identify(bench, pressure_kPa=args.pressure, bladder_volume_mm3=vb,
                     reservoir_mm3=args.reservoir, polytropic_n=args.polytropic_n,
                     geometry=geometry, material=name)
    preds = [predict(ident, pressure_kPa=p, reservoir_mm3=r, bladder_volume_mm3=vb,
                     polytropic_n=args.polytropic_n, elastic_force_N=bench.elastic_force_N)
             for r in reservoirs for p in pressures]
    if args.json:
        # the Curve JSON of docs/design.md, the predictions under "extra"
        ident.to_json(args.json, extra={"predictions": [c.to_dict() for c in preds]})
    if args.csv:
        ident.to_csv(args.csv)
    print(f"identified from {args.bench}: p_i = {args.pressure:g} kPa, V_b,i = {vb:.1f} mm³, "
          f"V_r = {args.reservoir:g} mm³")
    print(f"{'y_mm':>7} {'A_mm2':>9} {'dV_mm3':>9}")
    step = max(1, (len(ident) - 1) // 10)
    for k in range(0, len(ident), step):
        print(f"{ident.y_mm[k]:7.3f} {ident.contact_area_mm2[k]:9.2f} {ident.volume_change_mm3[k]:9.2f}")
    print(f"{'p_i_kPa':>8} {'V_r_mm3':>9} {'F_end_N':>9} {'p_end_kPa':>10}")
    for c in preds:
        print(f"{c.setup['p_i_kPa']:8.4g} {c.setup['reservoir_mm3']:9.6g} {c.force_N[-1]:9.3f} "
              f"{c.pressure_kPa[-1]:10.3f}")
    return 0
