"""spsc haptic: the haptic chamber's cost — Type D, the haptic chamber without and with its
motor in the part FEM (three curves, 10–15 min on 2 cores; a curve is reused while its command,
part and code are the same), the summary and figure where ``spsc report`` finds them."""

from __future__ import annotations

from spsc.cli.options import check_output_dir, number

_COLUMNS = ("force_N", "dp_kPa", "stiffness_N_per_mm", "sensitivity_kPa_per_mm", "kPa_per_N",
            "start_stiffness_N_per_mm", "start_sensitivity_kPa_per_mm",
            "end_stiffness_N_per_mm", "end_sensitivity_kPa_per_mm")


def register(sub) -> None:
    p = sub.add_parser("haptic", help="the haptic chamber's cost in the part FEM (motor and film "
                       "against the plain Type D)", description=__doc__.split("\n\n")[0])
    p.add_argument("--mesh-size", type=number("mesh size", "mm"), default=1.2, metavar="MM",
                   help="element edge of the part meshes, mm (default 1.2)")
    p.add_argument("--out", default="build/haptic-fem",
                   help="output folder (default build/haptic-fem, where spsc report looks)")
    p.add_argument("--parts", default="build", help="where the bladders are (build/bladder-D "
                   "and build/bladder-D-haptic; made when missing)")
    p.set_defaults(func=run)


def run(args) -> int:
    from spsc.core.errors import require
    from spsc.studies.haptic import LABELS, changes, run_study

    require("mesh size", args.mesh_size, gt=0.2, le=5.0, unit="mm")
    out = check_output_dir("--out", args.out)
    parts = check_output_dir("--parts", args.parts)  # the bladders are made there if missing
    curves, rows = run_study(out, parts, args.mesh_size)
    print(f"{'case':30s} {'F(4) N':>7s} {'ΔP kPa':>7s} {'N/mm':>6s} {'kPa/mm':>6s} "
          f"{'kPa/N':>6s} {'0-1 mm: N/mm':>12s} {'kPa/mm':>6s} {'3-4 mm: N/mm':>12s} "
          f"{'kPa/mm':>6s} {'motor N':>7s} {'s':>5s}")
    widths = (7, 7, 6, 6, 6, 12, 6, 12, 6)
    for name in curves:
        r = rows[name]
        cells = " ".join(f"{r[k]:{w}.{3 if k == 'kPa_per_N' else 2}f}"
                         for k, w in zip(_COLUMNS, widths))
        print(f"{LABELS[name]:30s} {cells} {r.get('motor_force_N', float('nan')):7.2f} "
              f"{r['seconds']:5.0f}")
    for name, ref in (("film", "plain"), ("motor", "plain"), ("motor", "film")):
        v = changes(rows, name, ref)
        print(f"{LABELS[name]} vs {LABELS[ref]}: stiffness {v['stiffness_N_per_mm']:+.1f} % "
              f"(first mm {v['start_stiffness_N_per_mm']:+.1f} %), sensitivity "
              f"{v['sensitivity_kPa_per_mm']:+.1f} % (first mm "
              f"{v['start_sensitivity_kPa_per_mm']:+.1f} %), kPa per N {v['kPa_per_N']:+.1f} %")
    m = rows["motor"]
    print(f"the motor is met at y = {m.get('motor_met_at_mm')} mm and carries "
          f"{m.get('motor_force_N', float('nan')):.2f} N of the plate's {m['force_N']:.2f} N at "
          f"the end (peak {m.get('motor_peak_N', float('nan')):.2f} N)")
    print(f"written: {out / 'summary.json'}, {out / 'haptic-cost.png'}")
    return 0 if all(rows[name]["converged"] for name in curves) else 1
