"""Material files: a fitted (or any) hyperelastic law as JSON, loaded by every model through
:func:`spsc.materials.material` beside the catalogue names.

The file (``schema`` ``spsc.material``, ``schema_version`` 1)::

    {"schema": "spsc.material", "schema_version": 1, "name": "my-tpu", "law": "yeoh",
     "constants": {"C10": 0.52, "C20": -0.004, "C30": 0.0003},      # MPa
     "bulk_ratio": 2000, "provenance": "user-fit", "source": "...",
     "fit": {...}, "data": [{"file": ..., "sha256": ..., "test": ..., "points": ...}]}

Constants are in MPa: ``C10`` (neo-Hookean), ``C10, C01`` (Mooney–Rivlin), ``C10, C20, C30``
(Yeoh), or ``mu`` and ``alpha`` lists (Ogden, W = Σ μk/αk (λ1^αk + λ2^αk + λ3^αk − 3)).
``bulk_ratio`` (κ/μ0) or ``bulk_modulus_MPa`` records the compressibility the models should
use; the incompressible fit cannot measure it. An Ogden file loads as the
:class:`~.ogden.Ogden` law, which the wall model, the 3D FEM and the membranes solve in the
principal stretches.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from spsc.core.errors import ParameterError
from .law import PROVENANCES, Material

__all__ = ["SCHEMA", "SCHEMA_VERSION", "INVARIANT_LAWS", "LAW_CONSTANTS", "LAWS", "register_law",
           "material_record", "read_material_file", "load_material", "material_from_record"]

SCHEMA = "spsc.material"
SCHEMA_VERSION = 1
#: The κ/μ0 the nearly incompressible models use by default (fem.material, fem.wall_model).
DEFAULT_BULK_RATIO = 2000.0

#: law -> the (i, j) exponent of each named constant C_ij of W(I1, I2).
LAW_CONSTANTS = {
    "neo-hookean": {"C10": (1, 0)},
    "mooney-rivlin": {"C10": (1, 0), "C01": (0, 1)},
    "yeoh": {"C10": (1, 0), "C20": (2, 0), "C30": (3, 0)},
}
INVARIANT_LAWS = tuple(LAW_CONSTANTS)


def _ogden(name: str, constants: dict, source: str, provenance: str):
    from .ogden import Ogden

    return Ogden(name, tuple(constants["mu"]), tuple(constants["alpha"]), source, provenance)


#: The other laws a material file may name: law -> build(name, constants, source,
#: provenance), the solving law (a class with ``kind`` "invariants" or "stretches", its
#: constants checked by its constructor in one line). A new law is its class and one
#: :func:`register_law` line.
LAWS = {"ogden": _ogden}


def register_law(name: str, build) -> None:
    """Let material files name the law ``name`` (lower case), built by ``build`` (see
    :data:`LAWS`)."""
    LAWS[str(name).strip().lower()] = build


def _law_names() -> tuple[str, ...]:
    return INVARIANT_LAWS + tuple(LAWS)


def material_record(name: str, law: str, constants: dict, *, source: str = "",
                    provenance: str = "user-fit", bulk_ratio: float = DEFAULT_BULK_RATIO,
                    fit: dict | None = None, data: list | None = None) -> dict:
    """The JSON object of a material file (constants in MPa, named as in the module doc)."""
    return {"schema": SCHEMA, "schema_version": SCHEMA_VERSION, "name": str(name),
            "law": law, "constants": constants, "bulk_ratio": bulk_ratio,
            "provenance": provenance, "source": source, "fit": fit or {}, "data": data or []}


def _refuse(path, allowed: str):
    raise ParameterError("material", str(path), allowed)


def read_material_file(path) -> dict:
    """The checked record of a material file (any law, Ogden included): schema, version, law,
    finite constants, bulk data. One-line :class:`ParameterError` naming ``material`` and the
    file on a missing or unreadable file, another schema, an unknown law or bad constants."""
    p = Path(str(path).strip())
    if not p.exists():
        _refuse(path, "a catalogue name or an existing material file (.json): no such file")
    if not p.is_file():
        _refuse(path, "a material file (.json), not a folder or a device")
    try:
        record = json.loads(p.read_bytes().decode("utf-8-sig"))
    except (UnicodeDecodeError, ValueError) as exc:
        _refuse(path, f"a JSON material file ({str(exc).splitlines()[0]})")
    except OSError as exc:
        _refuse(path, f"a readable material file ({exc.strerror})")
    if not isinstance(record, dict) or record.get("schema") != SCHEMA:
        _refuse(path, f"a material file with \"schema\": \"{SCHEMA}\" (spsc fit-material "
                "--out writes one)")
    if record.get("schema_version") != SCHEMA_VERSION:
        _refuse(path, f"schema_version {SCHEMA_VERSION} (this file has "
                f"{record.get('schema_version')!r}: written by another spsc version?)")
    law = str(record.get("law", "")).strip().lower()
    if law not in _law_names():
        raise ParameterError(f"material {p.name}: law", record.get("law"),
                             "one of " + ", ".join(_law_names()))
    record = dict(record, law=law)
    mu0 = _check_constants(p.name, law, record.get("constants"))
    _check_bulk(p.name, record, mu0)
    prov = record.get("provenance", "user-fit")
    if prov not in PROVENANCES:
        raise ParameterError(f"material {p.name}: provenance", prov,
                             "one of " + ", ".join(PROVENANCES))
    return record


def _finite(where: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ParameterError(where, value, "a finite number (MPa)")
    return float(value)


def _check_constants(fname: str, law: str, constants) -> float:
    """Refuse missing, unknown or non-finite constants; the initial shear modulus μ0 (MPa)."""
    if not isinstance(constants, dict):
        raise ParameterError(f"material {fname}: constants", constants,
                             "an object of named constants in MPa")
    if law == "ogden":
        mu, alpha = constants.get("mu"), constants.get("alpha")
        if (not isinstance(mu, list) or not isinstance(alpha, list) or not mu
                or len(mu) != len(alpha)):
            raise ParameterError(f"material {fname}: constants", constants,
                                 "\"mu\" and \"alpha\": lists of equal length (MPa, -)")
        for k, (m, a) in enumerate(zip(mu, alpha)):
            _finite(f"material {fname}: mu[{k}]", m)
            if _finite(f"material {fname}: alpha[{k}]", a) == 0.0:
                raise ParameterError(f"material {fname}: alpha[{k}]", a, "a non-zero number")
        mu0 = 0.5 * sum(m * a for m, a in zip(mu, alpha))
    elif law in LAWS:  # a registered law checks its own constants
        mu0 = LAWS[law](fname, constants, "", "user-fit").shear_modulus
    else:
        names = LAW_CONSTANTS[law]
        missing = [n for n in names if n not in constants]
        if missing or set(constants) - set(names):
            raise ParameterError(f"material {fname}: constants", sorted(constants),
                                 f"exactly {', '.join(names)} for {law} (MPa)")
        for n in names:
            _finite(f"material {fname}: {n}", constants[n])
        mu0 = 2.0 * (constants["C10"] + constants.get("C01", 0.0))
    if mu0 <= 0:
        raise ParameterError(f"material {fname}: initial shear modulus", mu0, "> 0 (MPa)")
    return mu0


def _check_bulk(fname: str, record: dict, mu0: float) -> None:
    """The bulk data must be positive and, for now, the models' κ/μ0 = 2000: the models take
    their bulk ratio from their settings, and a file asking for another one is refused rather
    than silently ignored."""
    ratios = []
    for key, scale in (("bulk_ratio", 1.0), ("bulk_modulus_MPa", 1.0 / mu0)):
        if record.get(key) is not None:
            v = _finite(f"material {fname}: {key}", record[key])
            if v <= 0:
                raise ParameterError(f"material {fname}: {key}", v, "> 0")
            ratios.append((key, v, v * scale))
    for key, v, ratio in ratios:
        if not math.isclose(ratio, DEFAULT_BULK_RATIO, rel_tol=1e-6):
            raise ParameterError(f"material {fname}: {key}", v,
                                 f"kappa/mu0 = {DEFAULT_BULK_RATIO:g} (the models' nearly "
                                 "incompressible bulk ratio; another value is not passed to "
                                 "the models yet)")


def material_from_record(record: dict, path: str = ""):
    """The solving law of a checked record: a :class:`Material` W(I1, I2) (neo-Hookean,
    Mooney–Rivlin, Yeoh) or a law of :data:`LAWS` (Ogden's, or one registered)."""
    law = record["law"]
    name = str(record.get("name") or Path(path).stem)
    source = record.get("source") or f"material file {path}"
    if law in LAWS:
        return LAWS[law](name, record["constants"], source, record.get("provenance", "user-fit"))
    constants = record["constants"]
    coefficients = tuple((i, j, float(constants[n])) for n, (i, j) in LAW_CONSTANTS[law].items())
    return Material(name, law, coefficients, source, record.get("provenance", "user-fit"))


def load_material(path):
    """The solving law of the material file ``path`` (:func:`material_from_record`; one-line
    ParameterError naming ``material`` on any problem)."""
    return material_from_record(read_material_file(path), str(path))
