"""``spsc fit-material``: hyperelastic laws fitted to the user's own tension tests, with their
statistics and Drucker stability, a figure, and a material file every model takes as
``--material FILE.json``.

    spsc fit-material DATA.csv [DATA2.csv ...] [--test uniaxial|equibiaxial|planar ...]
        [--law neo-hookean|mooney-rivlin|yeoh|ogden|all] [--ogden-terms N] [--range LMIN:LMAX]
        [--strain-unit -|%|stretch] [--stress-unit MPa|kPa|Pa|psi|kgf/cm2]
        [--weighting relative|absolute] [--name NAME] [--json F] [--png F] [--out MATERIAL.json]
        [--relaxation RELAX.csv | --cyclic CYCLE.csv] [--mullins SOFTEN.csv]
    spsc fit-material --list-catalogue

``--relaxation`` fits a Prony series (the wall's viscoelasticity, :mod:`spsc.materials.prony`)
to a relaxation test — a CSV of t_s and the stress or modulus of a held strain — and writes its
terms into the material file beside the hyperelastic law (the relaxed response). ``--cyclic``
fits them to a cyclic uniaxial test instead — a CSV of t_s, stretch and stress_MPa loaded and
unloaded (two rates tell the times apart) — over the law this command fits
(:mod:`spsc.materials.prony_cyclic`).

Several files (or a file with a ``test`` column) fit jointly: one set of constants, every test
in the residual. Exit 0; 1 when the law written is not Drucker-stable over its own data, has no
positive initial shear modulus or did not converge, or no law could be written (what was found
is still written, the reason on stderr); 2 on invalid input (one line on stderr).
"""

from __future__ import annotations

import sys

from spsc.core.errors import ParameterError, require_integer

from spsc.cli.options import PLOT_SUFFIXES, check_output_file, integer, warn

__all__ = ["register", "run", "parse_range"]

VERB = "fit-material"
LAW_CHOICES = ("neo-hookean", "mooney-rivlin", "yeoh", "ogden", "all")


def register(subparsers) -> None:
    from spsc.materials.data import STRAIN_UNITS, STRESS_UNITS

    p = subparsers.add_parser(VERB, help="fit hyperelastic laws to tension tests; write a "
                              "material file", description=__doc__.split("\n\n")[0])
    p.add_argument("data", nargs="*", metavar="DATA.csv", help="test data: a stretch or strain "
                   "column and a nominal stress column (units from the names)")
    p.add_argument("--test", action="append", metavar="TEST", type=_test,
                   help="uniaxial, equibiaxial or planar (pure shear): once for every file, or "
                   "once per file in order (default: the file's '# test:' line, its test "
                   "column, else uniaxial)")
    p.add_argument("--law", choices=LAW_CHOICES, default="all",
                   help="the law to fit (default all: every law; the material file takes the "
                   "best Drucker-stable invariant-based one)")
    p.add_argument("--ogden-terms", type=integer("ogden_terms"), default=2, metavar="N",
                   help="Ogden pairs (mu_k, alpha_k), 1-3 (default 2)")
    p.add_argument("--range", dest="stretch_range", metavar="LMIN:LMAX", default=None,
                   help="fit only the points with LMIN <= stretch <= LMAX (either may be empty)")
    p.add_argument("--strain-unit", choices=STRAIN_UNITS, default=None,
                   help="the deformation column is strain in - or %%, or stretch (default: "
                   "from its name)")
    units = {u.lower(): u for u in STRESS_UNITS}
    p.add_argument("--stress-unit", choices=tuple(STRESS_UNITS), default=None,
                   type=lambda text: units.get(text.strip().lower(), text),
                   help="unit of the nominal stress column (default: from its name)")
    p.add_argument("--weighting", choices=("relative", "absolute"), default="relative",
                   help="residuals relative to each stress (default, as Abaqus) or absolute")
    p.add_argument("--name", default=None, help="the material's name (default: the --out "
                   "file's stem, else the first data file's)")
    p.add_argument("--list-catalogue", action="store_true",
                   help="list the catalogue materials (law, constants, provenance) and exit")
    p.add_argument("--relaxation", metavar="RELAX.csv", default=None, help="a relaxation test "
                   "(t_s and stress or modulus): fit Prony terms into the material file")
    p.add_argument("--mullins", metavar="SOFTEN.csv", default=None, help="a loading-unloading "
                   "uniaxial test of the virgin material (stretch, stress_MPa, in the order "
                   "measured): the Ogden-Roxburgh softening's r, m, beta over the fitted law "
                   "(spsc.materials.mullins_fit), a 'mullins' entry of the material file")
    p.add_argument("--cyclic", metavar="CYCLE.csv", default=None, help="a cyclic uniaxial test "
                   "(t_s, stretch, stress_MPa: loaded and unloaded, at two rates): fit Prony "
                   "terms over the fitted law into the material file")
    g = p.add_argument_group("outputs (checked before any work)")
    g.add_argument("--json", metavar="FILE", help="every law's fit, statistics and stability")
    g.add_argument("--png", metavar="FILE", help="data against every law, one panel per test")
    g.add_argument("--out", metavar="MATERIAL.json", help="the material file (--material F)")
    p.set_defaults(func=run)


def _test(text: str) -> str:
    import argparse

    from spsc.materials.data import test_name

    t = test_name(text)
    if t is None:
        raise argparse.ArgumentTypeError(str(ParameterError(
            "test", text, "uniaxial, equibiaxial or planar (pure shear)")))
    return t


def parse_range(text: str | None) -> tuple[float, float]:
    """``LMIN:LMAX`` (either may be empty) -> (λmin, λmax); (1, inf) for None or empty ends.
    ParameterError naming ``--range`` and the whole text otherwise."""
    if text is None:
        return 1.0, float("inf")
    allowed = "LMIN:LMAX, stretches with 0 < LMIN < LMAX (e.g. 1:3, :2.5, 1.2:)"
    parts = str(text).split(":")
    if len(parts) != 2:
        raise ParameterError("--range", text, allowed)
    try:
        lo = float(parts[0]) if parts[0].strip() else 1.0
        hi = float(parts[1]) if parts[1].strip() else float("inf")
    except ValueError:
        raise ParameterError("--range", text, allowed) from None
    if not (0.0 < lo < hi) or lo == float("inf") or (parts[1].strip() and hi == float("inf")):
        raise ParameterError("--range", text, allowed)
    return lo, hi


def _within(tests, lo: float, hi: float):
    out = []
    for d in tests:
        kept = d.within(lo, hi)
        if kept.points == 0:
            raise ParameterError("--range", f"{lo:g}:{hi:g}", f"a range holding points of "
                                 f"{d.file_label} ({d.test}: stretch {d.stretch.min():g} .. "
                                 f"{d.stretch.max():g})")
        out.append(kept)
    return out


def _firsts(tests):
    """The first test of each file, in file order."""
    seen = {}
    for d in tests:
        seen.setdefault(d.file, d)
    return list(seen.values())


def prepare(args):
    """Every check before any fit: outputs, options, the files (read and checked) and the
    range. Returns (tests, notes, law names, range)."""
    from spsc.materials.data import read_tests

    for opt, suffixes in (("--json", None), ("--png", PLOT_SUFFIXES), ("--out", (".json",))):
        value = getattr(args, opt.lstrip("-"))
        if value is not None:
            check_output_file(opt, value, suffixes)
    if not args.data:
        raise ParameterError("DATA.csv", "none", "one or more test data files (or "
                             "--list-catalogue)")
    terms = require_integer("ogden_terms", args.ogden_terms, ge=1, le=3)
    if args.name is not None and not str(args.name).strip():
        raise ParameterError("--name", args.name, "a non-empty name")
    lo, hi = parse_range(args.stretch_range)
    tests, notes = read_tests(args.data, tests=args.test, strain_unit=args.strain_unit,
                              stress_unit=args.stress_unit)
    if args.stretch_range is not None:
        kept = _within(tests, lo, hi)
        notes = [n + f" ({sum(k.points for k in kept if k.file == d.file)} within --range "
                 f"{args.stretch_range})" for n, d in zip(notes, _firsts(tests))]
        tests = kept
    laws = LAW_CHOICES[:-1] if args.law == "all" else (args.law,)
    n = sum(d.points for d in tests)
    from spsc.materials.fit.laws import law as make_law

    need = {name: len(make_law(name, ogden_terms=terms).names) for name in laws}
    if all(n <= k for k in need.values()):
        raise ParameterError("data points", n, f"more than the constants of {args.law} "
                             f"({max(need.values()) if len(laws) == 1 else min(need.values())})")
    return tests, notes, laws, (lo, hi), terms


def run(args) -> int:
    if args.list_catalogue:
        if args.data:
            raise ParameterError("--list-catalogue", " ".join(args.data), "given alone")
        print(catalogue_table())
        return 0
    from spsc.materials.fit.fitting import choose, fit_laws

    tests, notes, laws, rng, terms = prepare(args)
    if args.relaxation is not None and args.cyclic is not None:
        raise ParameterError("cyclic", args.cyclic, "without --relaxation (one test gives "
                             "the Prony terms)")
    cyclic = _read_cyclic(args.cyclic)
    soften = _read_mullins(args.mullins)
    prony = _relaxation(args.relaxation)
    for line in notes:
        print(f"spsc {VERB}: read {line}", file=sys.stderr)
    fits = fit_laws(laws, tests, weighting=args.weighting, ogden_terms=terms)
    for name, f in fits.items():
        if f is None:
            warn(VERB, f"{name} left out: not more data points than its constants")
    if args.law == "all":
        from spsc.materials.fit.resolution import resolution_MPa

        chosen, why = choose(fits, resolution_MPa(tests))
    else:
        chosen, why = fits[args.law], f"{args.law}: the law asked for (--law)"
    for f in fits.values():
        if f is not None:
            print(describe_fit(f))
    print(f"material file law: {why}")
    from spsc.materials.fit.report import write_outputs

    if cyclic is not None and chosen is not None:
        prony = _cyclic(cyclic, chosen, tests, rng, args)
    mullins = _mullins(soften, chosen, tests, rng, args) if soften is not None and \
        chosen is not None else None
    write_outputs(args, tests, fits, chosen, why, rng, notes, prony=prony, mullins=mullins)
    return _verdict(fits, chosen)


def _relaxation(path):
    """The ``prony`` entry of the relaxation test at ``path`` (None without one), printed."""
    if path is None:
        return None
    from spsc.materials.prony import fit_relaxation, prony_record, read_relaxation

    t, v, data = read_relaxation(path)
    fit = fit_relaxation(t, v)
    terms = ", ".join(f"beta {b:.4g} tau {tau:.4g} s" for b, tau in fit.prony.terms)
    print(f"prony ({data['file']}, {data['points']} points): {terms}; relaxed level "
          f"{fit.relaxed:.4g}, rms {fit.rms_relative:.2%} of it")
    return prony_record(fit, data)


def _read_cyclic(path):
    """The cyclic test at ``path`` (None without one), read before any fit."""
    if path is None:
        return None
    from spsc.materials.prony_cyclic import read_cyclic

    return read_cyclic(path)


def _cyclic(test, chosen, tests, rng, args):
    """The ``prony`` entry fitted to the cyclic ``test`` over the ``chosen`` law, printed."""
    from spsc.materials.file import material_from_record
    from spsc.materials.fit.report import material_file_record
    from spsc.materials.prony_cyclic import cyclic_record, fit_cyclic

    record = material_file_record(chosen, tests, name="cyclic", rng=rng,
                                  weighting=args.weighting, why="")
    t, lam, stress, data = test
    fit = fit_cyclic(material_from_record(record), t, lam, stress)
    terms = ", ".join(f"beta {b:.4g} tau {tau:.4g} s" for b, tau in fit.prony.terms)
    print(f"prony ({data['file']}, {data['points']} points, over {chosen.name}): {terms}; "
          f"rms {fit.rms_relative:.2%} of the largest stress")
    return cyclic_record(fit, data)


def _read_mullins(path):
    """The loading-unloading test at ``path`` (None without one), read before any fit."""
    if path is None:
        return None
    from spsc.materials.mullins_fit import read_mullins

    return read_mullins(path)


def _mullins(test, chosen, tests, rng, args):
    """The ``mullins`` entry fitted to the loading-unloading ``test`` over the ``chosen``
    law, printed."""
    from spsc.materials.file import material_from_record
    from spsc.materials.fit.report import material_file_record
    from spsc.materials.mullins_fit import fit_mullins, mullins_record

    if getattr(chosen, "kind", "invariants") != "invariants" and not hasattr(chosen, "dW"):
        raise ParameterError("--mullins", args.mullins, "over a law in the invariants (the "
                             "fit's uniaxial stress is written in them)")
    record = material_file_record(chosen, tests, name="mullins", rng=rng,
                                  weighting=args.weighting, why="")
    lam, stress, data = test
    fit = fit_mullins(material_from_record(record), lam, stress)
    prm = fit.params
    print(f"mullins ({data['file']}, {fit.softened_points} softened points, over "
          f"{chosen.name}): r {prm.r:.4g}, m {prm.m:.4g} MPa, beta {prm.beta:.4g}; rms "
          f"{fit.rms_relative:.2%} of the largest stress")
    return mullins_record(fit, data)


def _verdict(fits, chosen) -> int:
    status = 0
    for name, f in fits.items():
        if f is None:
            continue
        for note in f.notes:
            warn(VERB, f"{name}: {note}")
        if not f.drucker.stable:
            warn(VERB, f"{name}: {f.drucker.describe()}")
    if chosen is None:
        print(f"spsc {VERB}: no material file: no invariant-based law with a positive initial "
              "shear modulus could be fitted", file=sys.stderr)
        return 1
    if chosen.shear_modulus <= 0:
        print(f"spsc {VERB}: unusable: {chosen.name} has initial shear modulus "
              f"{chosen.shear_modulus:.4g} MPa <= 0", file=sys.stderr)
        status = 1
    if not chosen.converged:
        print(f"spsc {VERB}: not converged: {chosen.name}: {chosen.message}", file=sys.stderr)
        status = 1
    if not chosen.stable_over_data:
        print(f"spsc {VERB}: unstable: {chosen.name} is not Drucker-stable over its own data "
              f"({chosen.drucker.describe()})", file=sys.stderr)
        status = 1
    return status


def describe_fit(f) -> str:
    """The fit of one law in a few lines: constants ± 95 % half-widths, μ0, R² and RMS per
    test, Drucker stability."""
    rows = [f"{f.name}:"]
    for name, v, (lo, hi), se in zip(f.names, f.params, f.ci95, f.stderr):
        unit = "" if name.startswith("alpha") else " MPa"
        rows.append(f"  {name:7s} = {v: .6g}{unit}  (stderr {se:.3g}; 95 %: {lo:.6g} .. "
                    f"{hi:.6g})")
    rows.append(f"  initial shear modulus mu0 = {f.shear_modulus:.6g} MPa")
    rows.append("  R²: " + ", ".join(f"{t} {v:.4f}" for t, v in f.r2.items())
                + "; RMS: " + ", ".join(f"{t} {v:.3g} MPa" for t, v in f.rms_MPa.items()))
    rows.append(f"  {f.drucker.describe()}")
    return "\n".join(rows)


def catalogue_table() -> str:
    """The catalogue: name, law, constants (MPa), μ0, provenance and source, one block each."""
    from spsc.materials import CATALOGUE

    names = {(1, 0): "C10", (0, 1): "C01", (2, 0): "C20", (3, 0): "C30"}
    lines = []
    for key, m in CATALOGUE.items():
        consts = ", ".join(f"{names.get((i, j), f'C{i}{j}')} = {c:.6g}"
                           for i, j, c in m.coefficients)
        lines.append(f"{key}: {m.law}, {consts} MPa (mu0 = {m.shear_modulus:.4g} MPa); "
                     f"provenance: {m.provenance}")
        lines.append(f"  source: {m.source}")
    return "\n".join(lines)
