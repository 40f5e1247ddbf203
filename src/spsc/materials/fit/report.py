"""What ``spsc fit-material`` writes: the fit report (``--json``, schema ``spsc.material-fit``),
the figure (``--png``) and the material file (``--out``, schema ``spsc.material``, read by
:func:`spsc.materials.material` for every model's ``--material``)."""

from __future__ import annotations

import math
from pathlib import Path

from spsc.core.jsonio import write_json

__all__ = ["REPORT_SCHEMA", "data_records", "material_file_record", "fit_report",
           "write_outputs"]

REPORT_SCHEMA = "spsc.material-fit"


def _version() -> str:
    from importlib import metadata

    try:
        return metadata.version("spsc")
    except metadata.PackageNotFoundError:
        return "unknown"


def data_records(tests) -> list[dict]:
    """Each test of each file: its name, path, sha256 of its bytes, test, points, columns and
    the file's comment lines (``notes``: where the data comes from)."""
    return [{"file": d.file_label, "path": str(d.file), "sha256": d.sha256, "test": d.test,
             "points": d.points, "columns": d.columns, "notes": list(d.notes),
             "stretch_range": [float(d.stretch.min()), float(d.stretch.max())]}
            for d in tests]


def _finite_range(rng) -> list:
    return [v if math.isfinite(v) else None for v in rng]


def material_file_record(fit, tests, *, name: str, rng, weighting: str, why: str) -> dict:
    """The material file of ``fit`` (a LawFit): constants in MPa, the fit's statistics and
    stability, the data's files and hashes."""
    from spsc.materials.file import material_record

    d = fit.drucker
    stats = {"range": _finite_range(rng), "stretch_ranges": fit.data_ranges,
             "tests": sorted({t.test for t in tests}), "weighting": weighting,
             "r2": fit.r2, "rms_MPa": fit.rms_MPa,
             "stderr": dict(zip(fit.names, fit.stderr)),
             "ci95": {k: list(v) for k, v in zip(fit.names, fit.ci95)},
             "initial_shear_modulus_MPa": fit.shear_modulus,
             "drucker_checked": list(d.checked), "drucker_stable": d.stable,
             "drucker_stable_range": d.as_dict()["stable_range"],
             "drucker_unstable": d.as_dict()["unstable"],
             "drucker_stable_over_data": fit.stable_over_data,
             "converged": fit.converged, "condition_number": fit.condition,
             "notes": list(fit.notes), "choice": why}
    files = ", ".join(dict.fromkeys(t.file_label for t in tests))
    source = (f"spsc fit-material {_version()}: {fit.name} fitted to {files} ({weighting} "
              f"residuals)")
    return material_record(name, fit.name, fit.constants(), source=source, fit=stats,
                           data=data_records(tests))


def fit_report(fits: dict, tests, *, chosen, why: str, rng, weighting: str, notes,
               material_path) -> dict:
    """The ``--json`` report: every law's fit, the data and which law the material file took."""
    return {"schema": REPORT_SCHEMA, "schema_version": 1, "spsc_version": _version(),
            "data": data_records(tests), "read": list(notes), "range": _finite_range(rng),
            "weighting": weighting,
            "fits": {k: (None if f is None else f.summary()) for k, f in fits.items()},
            "material_file": {"law": None if chosen is None else chosen.name, "why": why,
                              "path": None if material_path is None else str(material_path)}}


def write_outputs(args, tests, fits, chosen, why, rng, notes, prony=None,
                  mullins=None) -> None:
    """Write what the options ask for (their paths were checked before the fit); ``prony``
    the material file's Prony entry (:func:`~.prony.prony_record`) or None; ``mullins`` its
    softening's entry (:func:`~spsc.materials.mullins_fit.mullins_record`) or None."""
    if args.out is not None and chosen is not None:
        name = args.name or Path(args.out).stem
        record = material_file_record(chosen, tests, name=name, rng=rng,
                                      weighting=args.weighting, why=why)
        extra = {k: v for k, v in (("prony", prony), ("mullins", mullins)) if v is not None}
        write_json(args.out, dict(record, **extra))
        print(f"material file {args.out} ({chosen.name}, name {name!r}): use it as "
              f"--material {args.out}")
    if args.json is not None:
        write_json(args.json, fit_report(fits, tests, chosen=chosen, why=why, rng=rng,
                                         weighting=args.weighting, notes=notes,
                                         material_path=args.out))
    if args.png is not None:
        from spsc.materials.fit.figure import plot_fits

        plot_fits(fits, tests, args.png, chosen=None if chosen is None else chosen.name)
