"""``spsc fatigue``: will the chamber last? The squeeze cycle of the paper's fatigue test
(sec. 3.2: 50 kPa on the 40 cm³ reservoir, squeezed from rest to full stroke and back) in the
wall model: the largest principal stretch and strain-energy density over the cycle, where
they peak on the wall, and the life (cycles) from the energy amplitude at the hot spot through
a power law whose one constant is calibrated on the material's Table 2 test.

    spsc fatigue --type C --material tpu60a [--pressure 50] [--reservoir 40000] [--stroke 6]
                 [--exponent F] [--json F] [--png F]
    spsc fatigue --study [--out build/durability]   # the report's durability study

Exit 0 when the cycle reached the full stroke, 1 when it did not (what was computed is still
written), 2 on invalid input.
"""

from __future__ import annotations

import sys

from spsc.cli.options import (add_geometry_options, add_output_options, add_quiet_option,
                              check_output_file, geometry_from_args, geometry_given, integer,
                              number)
from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import check_load

__all__ = ["register", "run"]

VERB = "fatigue"


def register(subparsers) -> None:
    p = subparsers.add_parser(VERB, help="the squeeze cycle's peak strain and energy, the hot "
                              "spot and the fatigue life (the paper's sec. 3.2)",
                              description=__doc__.split("\n\n")[0])
    add_geometry_options(p)
    g = p.add_argument_group("the cycle (defaults: the paper's fatigue test)")
    g.add_argument("--material", default="tpu60a", metavar="NAME|FILE.json",
                   help="catalogue material (tpu60a, elastic50a, silicone40a, as40; default "
                   "tpu60a): its Table 2 test calibrates the life; or a material file with a "
                   "fatigue entry (its own law, or its own Type B test)")
    g.add_argument("--pressure", type=number("pressure", "kPa gauge"), default=50.0,
                   metavar="KPA", help="setup pressure, kPa gauge (default 50, Table 2)")
    g.add_argument("--reservoir", type=number("reservoir", "mm³"), default=40000.0,
                   metavar="MM3", help="reservoir on the closed valve, mm³ (default 40000, "
                   "the paper's)")
    g.add_argument("--stroke", type=number("stroke", "mm"), default=6.0, metavar="MM",
                   help="plate travel from first contact at full squeeze, mm (default 6: the "
                   "paper does not state its y_max; the static tests' stroke)")
    g.add_argument("--points", type=integer("points"), default=13, metavar="N",
                   help="plate positions of the squeeze, y = 0 included (default 13)")
    g.add_argument("--exponent", type=number("exponent"), default=None, metavar="F",
                   help="the crack-growth exponent F of N ∝ W_a^(−F) (default the "
                   "material's: 4, a non-crystallising elastomer; 2 for a crystallising one)")
    add_output_options(p, json="write the result JSON here", csv=None,
                       png="draw the wall's energy amplitude and the hot spot here")
    s = p.add_argument_group("the report's study")
    s.add_argument("--study", action="store_true", help="the durability study spsc report "
                   "shows: every material calibrated, Types A-D in TPU 60A, other strokes and "
                   "pressures, the puncture test on three meshes (15-20 minutes)")
    s.add_argument("--out", default=None, metavar="DIR", help="the study's folder (default "
                   "build/durability, where spsc report looks); only with --study")
    add_quiet_option(p)
    p.set_defaults(func=run)


def _study(args) -> int:
    from spsc.cli.options import check_output_dir
    from spsc.studies.durability import DEFAULT_DIR, run_study

    alone = [o for o in ("json", "png", "exponent") if getattr(args, o) is not None]
    if alone or geometry_given(args):
        name = alone[0] if alone else "type"
        raise ParameterError(name, getattr(args, name) if alone else args.type or "a chamber",
                             "not with --study (the study runs its own chambers and writes "
                             "its own files)")
    out = check_output_dir("--out", args.out or DEFAULT_DIR)
    s = run_study(out, progress=(lambda m: None) if args.quiet else
                  (lambda m: print(m, file=sys.stderr)))
    print(f"spsc fatigue: the durability study in {s['seconds']:.0f} s -> {out}/summary.json, "
          "lives.png, fields-C.png")
    return 0 if all(r["converged"] for r in s["types"].values()) else 1


def run(args) -> int:
    from spsc.core.jsonio import write_json
    from spsc.fem.wall.durability import paper_fatigue_law, squeeze_cycle
    from spsc.materials import material
    from spsc.materials.catalogue import FATIGUE_TESTS

    if args.study:
        return _study(args)
    if args.out is not None:
        raise ParameterError("out", args.out, "only with --study (--json, --png for one "
                             "chamber)")
    geometry = geometry_from_args(args) if geometry_given(args) else _type_b()
    from spsc.sweep.life import check_life_materials

    name = str(args.material).strip()
    name = name.lower() if name.lower() in FATIGUE_TESTS else name
    check_life_materials([name], "spsc fatigue")
    if args.exponent is not None:
        require("exponent", args.exponent, gt=1, le=20)
    lc = check_load(geometry, pressure_kPa=args.pressure, reservoir_mm3=args.reservoir,
                    stroke_mm=args.stroke, points=args.points, polytropic_n=1.0)
    require("points", lc.points, ge=3, unit="plate positions, y = 0 included")
    json_path = check_output_file("--json", args.json, (".json",)) if args.json is not None \
        else None
    png_path = check_output_file("--png", args.png, (".png",)) if args.png is not None else None
    if not args.quiet:
        print(f"spsc fatigue: calibrating {name} on its Table 2 test, then the cycle ...",
              file=sys.stderr)
    law = paper_fatigue_law(name, args.exponent)
    cycle = squeeze_cycle(geometry, material(name), pressure_kPa=args.pressure,
                          reservoir_mm3=args.reservoir, stroke_mm=args.stroke,
                          points=args.points)
    peaks = cycle.peaks()
    w_a = cycle.energy_amplitude_MPa
    other = 2.0 if law.exponent != 2.0 else 4.0
    life, life_other = law.life(w_a), law.with_exponent(other).life(w_a)
    hot = peaks["energy_amplitude"]
    bound = "at least " if law.runout else ""
    print(f"hot spot: energy amplitude {w_a:.4g} MPa on the {hot['face']} face, "
          f"{hot['height_mm']:.2f} mm above the base, {hot['radius_mm']:.2f} mm from the axis")
    print(f"largest stretch {peaks['stretch_max']['value']:.4f} ({peaks['stretch_max']['face']}"
          f", z {peaks['stretch_max']['height_mm']:.2f} mm); at the clamped base's corner "
          f"{peaks['stretch_max_with_base']['value']:.4f} (singular, not used)")
    print(f"life {bound}{life:.3g} cycles (F = {law.exponent:g}; {bound}{life_other:.3g} with "
          f"F = {other:g}); {law.source}")
    doc = _document(geometry, cycle, peaks, law, life, other, life_other)
    if json_path:
        write_json(json_path, doc)
    if png_path:
        from spsc.studies.fatigue_figure import draw

        draw(cycle, geometry, law, life, png_path)
    return 0 if cycle.converged else 1


def _document(geometry, cycle, peaks, law, life, other, life_other) -> dict:
    """The ``--json`` document (schema ``spsc.fatigue`` v1)."""
    from spsc.core.provenance import code_provenance

    return {"schema": "spsc.fatigue", "schema_version": 1, "geometry": geometry.as_dict(),
            "setup": cycle.setup, "peaks": peaks,
            "energy_amplitude_MPa": cycle.energy_amplitude_MPa, "life_cycles": life,
            "life_is_lower_bound": law.runout,
            "life_other_exponent": {"exponent": other, "cycles": life_other},
            "law": {"exponent": law.exponent, "calibration_amplitude_MPa": law.amplitude_MPa,
                    "calibration_cycles": law.cycles, "runout": law.runout,
                    "source": law.source},
            "force_N": cycle.force_N, "pressure_kPa": cycle.pressure_kPa,
            "reached_mm": cycle.reached_mm, "converged": cycle.converged,
            "message": cycle.message, "seconds": cycle.seconds,
            "provenance": {"commit": code_provenance().commit}}


def _type_b():
    from spsc.cad.geometry import preset

    return preset("B")
