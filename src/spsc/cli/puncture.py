"""``spsc puncture``: the paper's puncture test in the wall model (sec. 3.2, Table 2). A cone
(half-angle 30°, tip Ø 0.1 mm) pressed on the dome of a chamber at 50 kPa on its 40 cm³
reservoir, through its height until the membrane is pinched on the base: the probe's force,
the largest principal stretch under the tip, and the force at which it reaches the
material's stretch at break (its datasheet's elongation at break).

    spsc puncture [--type B] [--material tpu60a] [--elongation-at-break PCT]
                  [--mesh coarse|medium|fine|all] [--friction stick|0] [--json F] [--png F]

Exit 0 when the walk reached the base, 1 when it stopped short (what it computed is still
printed and written), 2 on invalid input.
"""

from __future__ import annotations

import sys

from spsc.cli.options import (add_geometry_options, add_output_options, add_quiet_option,
                              check_output_file, geometry_from_args, geometry_given, number)
from spsc.core.errors import ParameterError, require

__all__ = ["register", "run"]

VERB = "puncture"
#: the meshes of :data:`spsc.fem.wall.puncture.MESHES` by name
MESH_NAMES = ("coarse", "medium", "fine")


def register(subparsers) -> None:
    p = subparsers.add_parser(VERB, help="the paper's puncture test: a cone through the dome "
                              "onto the base, the stretch under the tip and the force at break",
                              description=__doc__.split("\n\n")[0])
    add_geometry_options(p)
    g = p.add_argument_group("the test (defaults: the paper's)")
    g.add_argument("--material", default="tpu60a", metavar="NAME|FILE.json",
                   help="catalogue material or material file (default tpu60a); its failure "
                   "criterion from the catalogue or the file's failure entry")
    g.add_argument("--elongation-at-break", dest="elongation", default=None,
                   type=number("elongation_at_break", "%"), metavar="PCT",
                   help="the material's elongation at break, %% (your datasheet's; overrides "
                   "the catalogue's)")
    g.add_argument("--pressure", type=number("pressure", "kPa gauge"), default=50.0,
                   metavar="KPA", help="setup pressure, kPa gauge (default 50, Table 2)")
    g.add_argument("--reservoir", type=number("reservoir", "mm³"), default=40000.0,
                   metavar="MM3", help="reservoir on the closed valve, mm³ (default 40000)")
    g.add_argument("--probe", default="cone:angle=60,r=0.05", metavar="BODY",
                   help="the probe (default cone:angle=60,r=0.05: half-angle 30°, tip Ø 0.1 "
                   "mm, the paper's)")
    g.add_argument("--friction", default="stick", metavar="stick|0",
                   help="the probe holds what it touches (stick, default: PLA on an "
                   "elastomer) or lets it slide (0, the frictionless bound)")
    g.add_argument("--mesh", default="coarse", metavar="|".join(MESH_NAMES + ("all",)),
                   help="the wall's mesh under the tip: coarse 0.04 mm and 4 layers (default, "
                   "seconds), medium 0.02 mm and 8, fine 0.01 mm and 16 (minutes), or all "
                   "three (the convergence)")
    add_output_options(p, json="write the result JSON here", csv=None,
                       png="draw force and stretch against travel here")
    add_quiet_option(p)
    p.set_defaults(func=run)


def _criterion(args):
    from spsc.materials.catalogue import failure
    from spsc.materials.failure import Failure

    if args.elongation is not None:
        return Failure(args.elongation, None, "--elongation-at-break"), "--elongation-at-break"
    return failure(args.material)


def run(args) -> int:
    from spsc.cad.geometry import preset
    from spsc.core.indenter import parse_indenter
    from spsc.core.jsonio import write_json
    from spsc.core.progress import progress_bar
    from spsc.fem.wall.puncture import MESHES, puncture
    from spsc.materials import material

    geometry = geometry_from_args(args) if geometry_given(args) else preset("B", l=0.0)
    if geometry.l > 0:
        raise ParameterError("l", geometry.l, "0 (the probe presses a dome's apex: --l 0)")
    mesh = str(args.mesh).strip().lower()
    if mesh not in MESH_NAMES + ("all",):
        raise ParameterError("mesh", args.mesh, ", ".join(MESH_NAMES + ("all",)))
    friction = {"stick": "stick", "0": "none"}.get(str(args.friction).strip().lower())
    if friction is None:
        raise ParameterError("friction", args.friction, "stick or 0")
    probe = parse_indenter(args.probe)
    if not probe.axisymmetric or not probe.curved:
        raise ParameterError("probe", args.probe, "a cone or a sphere on the dome's axis "
                             "(cone:angle=DEG,r=MM, sphere:R=MM)")
    require("pressure", args.pressure, gt=0, le=200, unit="kPa gauge")
    require("reservoir", args.reservoir, ge=0, le=1e7, unit="mm³")
    law = material(args.material)
    criterion, source = _criterion(args)
    json_path = check_output_file("--json", args.json, (".json",)) if args.json is not None \
        else None
    png_path = check_output_file("--png", args.png, (".png",)) if args.png is not None \
        else None
    chosen = list(MESHES) if mesh == "all" else [MESHES[MESH_NAMES.index(mesh)]]
    runs = []
    for m in chosen:
        bar = progress_bar(desc=f"spsc puncture ({m.label})", unit="point",
                           disable=bool(args.quiet), file=sys.stderr)

        def progress(done, total, bar=bar):
            bar.total = total
            bar.update(done - bar.n)

        try:
            runs.append(puncture(geometry, law, m, probe=probe.spec,
                                 pressure_kPa=args.pressure, reservoir_mm3=args.reservoir,
                                 friction=friction, progress=progress))
        finally:
            bar.close()
    _print(runs, criterion, source, probe.spec)
    doc = _document(geometry, runs, criterion, source, args)
    if json_path:
        write_json(json_path, doc)
    if png_path:
        from spsc.studies.puncture_figure import draw

        draw(runs, criterion, png_path)
    return 0 if all(r.converged for r in runs) else 1


def _print(runs, criterion, source, probe) -> None:
    first = runs[0]
    print(f"{first.material}: {probe} on the dome, the tip {first.clearance_mm:.3f} mm "
          f"above the base at first contact; probe {first.friction}")
    for r in runs:
        rows = r.rows()
        shown = [row for row in rows if abs(row["travel_mm"] % 4) < 1e-6] + rows[-1:]
        cells = "  ".join(f"{row['travel_mm']:.4g} mm {row['force_N']:.2f} N λ1 "
                          f"{row['stretch']:.2f}" for row in shown)
        state = "reached the base" if r.converged else f"stopped: {r.message}"
        print(f"  {r.mesh.label} ({r.seconds:.0f} s, {state}): {cells}")
    if criterion is None:
        print(f"no failure criterion: {source}")
        return
    print(f"criterion: λ1 = {criterion.stretch:g} (elongation at break "
          f"{criterion.elongation_pct:g} %; {source})")
    for r in runs:
        f = r.failure(criterion)
        if f["reached"]:
            print(f"  {r.mesh.label}: failure at {f['force_N']:.3g} N "
                  f"({f['travel_mm']:.4g} mm of travel)")
        else:
            print(f"  {r.mesh.label}: not reached; the force is above {f['force_N']:.3g} N "
                  f"(λ1 {f['stretch']:.3g} at {f['travel_mm']:.4g} mm, where the walk ended)")


def _document(geometry, runs, criterion, source, args) -> dict:
    """The ``--json`` document (schema ``spsc.puncture`` v1)."""
    from spsc.core.provenance import code_provenance

    out = []
    for r in runs:
        run = {"mesh": {"size_mm": r.mesh.size_mm, "apex_mm": r.mesh.apex_mm,
                        "layers": r.mesh.layers}, "friction": r.friction,
               "clearance_mm": r.clearance_mm, "points": r.rows(),
               "converged": r.converged, "message": r.message, "seconds": r.seconds}
        if criterion is not None:
            run["failure"] = r.failure(criterion)
        out.append(run)
    return {"schema": "spsc.puncture", "schema_version": 1, "geometry": geometry.as_dict(),
            "material": str(args.material), "probe": args.probe,
            "pressure_kPa": args.pressure, "reservoir_mm3": args.reservoir,
            "criterion": None if criterion is None else {
                "elongation_pct": criterion.elongation_pct, "stretch": criterion.stretch,
                "strength_MPa": criterion.strength_MPa, "source": source},
            "criterion_missing": None if criterion is not None else source,
            "runs": out, "provenance": {"commit": code_provenance().commit}}
