"""The one result type: a static curve F(y), P(y), A(y), ΔV(y), what produced it and how the
solve went.

Every model (membrane, simplified, wall, FEM, lumped) and the bench produce a :class:`Curve`.
Units are those of the edge (docs/design.md): y in mm from first contact with the inflated chamber
(the paper's contact depth y_s), force in N, gauge pressure in kPa, contact area in mm², volume
change in mm³ (cavity volume lost since first contact).

The result protocol is :class:`SolveInfo` (converged, message, how far it got, instability,
timing, iterations, model details), carried by the curve. JSON (schema ``spsc.curve``, version
:data:`SCHEMA_VERSION`) and CSV round-trip both; version-1 files (no ``schema_version``) load,
newer versions fail with a one-line error.
"""

from __future__ import annotations

import functools
import io
import json
import math
from decimal import Decimal
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

import numpy as np

from .errors import ParameterError
from .jsonio import read_json, to_jsonable, write_json
from .provenance import code_provenance
from .setup import SetupRecord

__all__ = ["Curve", "CURVE_COLUMNS", "SolveInfo", "SCHEMA", "SCHEMA_VERSION"]

#: Name and version of the JSON layout written by :meth:`Curve.to_dict`.
SCHEMA = "spsc.curve"
SCHEMA_VERSION = 3

#: Column names of the curve arrays, in JSON (``"curve"`` object) and CSV header order.
CURVE_COLUMNS = ("y_mm", "force_N", "pressure_kPa", "contact_area_mm2", "volume_change_mm3")
_META = ("model", "geometry", "material", "setup", "nominal_volume_mm3",
         "inflated_volume_mm3", "inflated_height_mm")


@dataclass(frozen=True)
class SolveInfo:
    """How a model's solve went: the one result protocol of every model.

    Parameters
    ----------
    converged : bool
        Every requested point converged.
    message : str
        Why and where it stopped (``"converged"`` when it did not stop early).
    y_reached_mm : float
        Last plate position that converged (mm; NaN if none).
    instability : str
        A detected limit point, buckling or snap-through ("" if none).
    seconds : float
        Wall-clock time of the solve (s).
    iterations : int
        Newton iterations over the whole load path.
    notes : tuple of str
        What the solver did that a user should know (continuation, mode switches).
    details : dict
        Model-specific facts (unknowns, elements, mesh size ...), JSON-able.
    """

    converged: bool = True
    message: str = "converged"
    y_reached_mm: float = float("nan")
    instability: str = ""
    seconds: float = float("nan")
    iterations: int = 0
    notes: tuple = ()
    details: dict = field(default_factory=dict)

    def __post_init__(self):
        object.__setattr__(self, "converged", bool(self.converged))
        object.__setattr__(self, "notes", tuple(str(n) for n in self.notes))
        object.__setattr__(self, "details", dict(self.details))
        v = self.y_reached_mm
        object.__setattr__(self, "y_reached_mm", float("nan") if v is None else float(v))
        v = self.seconds
        object.__setattr__(self, "seconds", float("nan") if v is None else float(v))

    def to_dict(self) -> dict:
        return to_jsonable({f.name: getattr(self, f.name) for f in fields(self)})

    @classmethod
    def from_dict(cls, data: dict) -> "SolveInfo":
        known = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in data.items() if k in known})


def _array(name: str, value) -> np.ndarray:
    a = np.array(value, dtype=float).reshape(-1)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class Curve:
    """A static curve of an SPSC pressed by a rigid plate.

    Parameters
    ----------
    y_mm, force_N, pressure_kPa, contact_area_mm2, volume_change_mm3 : array_like
        Plate travel from first contact (mm, strictly increasing), plate force (N), gauge
        pressure (kPa), contact area (mm²) and cavity volume lost since first contact (mm³).
        Points that were not computed (non-converged) hold NaN.
    model : str
        What produced the curve (``membrane``, ``simplified``, ``lumped``, ``fem``, ``bench`` …).
    geometry : dict
        The seven parameters (w, h, l, t0, n1, n2, cy), mm.
    material : str
        Material catalogue name (or ``""``).
    setup : SetupRecord or mapping
        The setup it was computed with (:class:`~spsc.core.setup.SetupRecord`: ``p_i_kPa``
        gauge, ``reservoir_mm3``, ``polytropic_n``, the contact, a part, how the model ran);
        a mapping of its flat keys becomes one.
    nominal_volume_mm3, inflated_volume_mm3 : float
        Cavity volume (bladder only) before and after inflation, mm³.
    inflated_height_mm : float
        Height of the cavity apex above z = 0 after inflation, mm.
    converged : array_like of bool, optional
        Per-point status (default: all True).
    message : tuple of str, optional
        Per-point reason ("" where converged).
    solver : SolveInfo, optional
        How the solve went (default: derived from the per-point status).
    series : dict of str to array_like, optional
        Further per-point columns a model measures (e.g. ``force_pocket1_N``, the force through
        a named contact surface), written after the five columns in JSON and CSV.
    """

    y_mm: np.ndarray
    force_N: np.ndarray
    pressure_kPa: np.ndarray
    contact_area_mm2: np.ndarray
    volume_change_mm3: np.ndarray
    model: str = "membrane"
    geometry: dict = field(default_factory=dict)
    material: str = ""
    setup: SetupRecord = field(default_factory=SetupRecord)
    nominal_volume_mm3: float = float("nan")
    inflated_volume_mm3: float = float("nan")
    inflated_height_mm: float = float("nan")
    converged: np.ndarray | None = None
    message: tuple[str, ...] | None = None
    solver: SolveInfo | None = None
    series: dict = field(default_factory=dict)

    def __post_init__(self):
        n = None
        for name in CURVE_COLUMNS:
            a = _array(name, getattr(self, name))
            if n is None:
                n = a.size
            elif a.size != n:
                raise ParameterError(f"len({name})", a.size, f"= len(y_mm) = {n}")
            object.__setattr__(self, name, a)
        y = _decimal_grid(self.y_mm)
        y.setflags(write=False)
        object.__setattr__(self, "y_mm", y)
        if n < 1:
            raise ParameterError("len(y_mm)", n, ">= 1 point")
        if np.any(~np.isfinite(self.y_mm)):
            raise ParameterError("y_mm", "non-finite value", "finite plate positions (mm)")
        if n > 1 and np.any(np.diff(self.y_mm) <= 0):
            k = int(np.argmax(np.diff(self.y_mm) <= 0)) + 1
            raise ParameterError(f"y_mm[{k}]", float(self.y_mm[k]),
                                 f"> y_mm[{k - 1}] = {self.y_mm[k - 1]:g} (strictly increasing)")
        conv = np.ones(n, bool) if self.converged is None else np.array(self.converged, bool)
        if conv.shape != (n,):
            raise ParameterError("len(converged)", conv.size, f"= len(y_mm) = {n}")
        conv.setflags(write=False)
        object.__setattr__(self, "converged", conv)
        msg = ("",) * n if self.message is None else tuple(str(m) for m in self.message)
        if len(msg) != n:
            raise ParameterError("len(message)", len(msg), f"= len(y_mm) = {n}")
        object.__setattr__(self, "message", msg)
        series = {}
        for name, values in dict(self.series or {}).items():
            if name in CURVE_COLUMNS or name in ("converged", "message") or not str(name):
                raise ParameterError("series name", name, "a column name other than "
                                     + ", ".join(CURVE_COLUMNS + ("converged", "message")))
            a = _array(name, values)
            if a.size != n:
                raise ParameterError(f"len({name})", a.size, f"= len(y_mm) = {n}")
            series[str(name)] = a
        object.__setattr__(self, "series", series)
        object.__setattr__(self, "geometry", dict(self.geometry))
        object.__setattr__(self, "setup", SetupRecord.of(self.setup))
        for name in ("nominal_volume_mm3", "inflated_volume_mm3", "inflated_height_mm"):
            v = getattr(self, name)
            object.__setattr__(self, name, float("nan") if v is None else float(v))
        if self.solver is None:
            first = next((m for m, c in zip(msg, conv) if not c), "")
            info = SolveInfo(converged=bool(conv.all()), message=first or "converged",
                             y_reached_mm=self.y_mm[conv][-1] if conv.any() else float("nan"))
            object.__setattr__(self, "solver", info)
        elif isinstance(self.solver, dict):
            object.__setattr__(self, "solver", SolveInfo.from_dict(self.solver))

    # -- derived quantities ------------------------------------------------------------------
    def __len__(self) -> int:
        return self.y_mm.size

    @property
    def all_converged(self) -> bool:
        return bool(np.all(self.converged))

    def stiffness(self) -> np.ndarray:
        """dF/dy in N/mm (second-order finite differences on the possibly uneven y grid)."""
        return _gradient(self.force_N, self.y_mm)

    def sensitivity(self) -> np.ndarray:
        """dP/dy in kPa/mm (second-order finite differences)."""
        return _gradient(self.pressure_kPa, self.y_mm)

    def mean_stiffness(self, *, reached: bool = False) -> float:
        """Mean of dF/dy over the stroke (N/mm): the integral mean (F(y_n) − F(y_0)) /
        (y_n − y_0), whatever the sampling (the mean of sampled slopes weighs the ends by the
        grid: 2.5 % between 13 and 25 points on a stiffening curve). NaN unless every point
        converged; ``reached``: over the converged points from the start instead."""
        return self._mean_slope(self.force_N, reached)

    def mean_sensitivity(self, *, reached: bool = False) -> float:
        """Mean of dP/dy over the stroke (kPa/mm), as :meth:`mean_stiffness`."""
        return self._mean_slope(self.pressure_kPa, reached)

    def _mean_slope(self, f, reached: bool) -> float:
        ok = np.asarray(self.converged, bool) & np.isfinite(f)
        if not reached and not ok.all():
            return float("nan")
        n = int(np.argmin(ok)) if not ok.all() else ok.size  # converged from the start
        if n < 2:
            return float("nan")
        return float((f[n - 1] - f[0]) / (self.y_mm[n - 1] - self.y_mm[0]))

    def replace(self, **changes) -> "Curve":
        return replace(self, **changes)

    # -- JSON --------------------------------------------------------------------------------
    def to_dict(self, extra: dict | None = None) -> dict:
        """The docs/design.md JSON object, schema ``spsc.curve`` v3 (NaN written as null).

        ``extra``: model-specific additions (meridians, VTU files ...) under the key ``extra``.
        """
        out = {"schema": SCHEMA, "schema_version": SCHEMA_VERSION}
        out |= {k: getattr(self, k) for k in _META}
        out["setup"] = self.setup.as_dict()
        curve = {k: getattr(self, k) for k in CURVE_COLUMNS}
        curve |= self.series
        curve["converged"] = self.converged
        curve["message"] = list(self.message)
        out["curve"] = curve
        out["solver"] = self.solver.to_dict()
        out["metrics"] = {"mean_stiffness_N_per_mm": self.mean_stiffness(),
                          "mean_sensitivity_kPa_per_mm": self.mean_sensitivity()}
        code = code_provenance()
        out["provenance"] = {"spsc_version": _version(), "commit": code.commit,
                             "clean_tree": code.clean}
        if extra:
            out["extra"] = extra
        return to_jsonable(out)

    def to_json(self, path: str | Path | None = None, *, extra: dict | None = None) -> str:
        """JSON text; written (UTF-8, atomically) to ``path`` if given."""
        data = self.to_dict(extra)
        if path is not None:
            write_json(path, data)
        return json.dumps(data, indent=1, allow_nan=False, ensure_ascii=False)

    @classmethod
    def from_dict(cls, data: dict) -> "Curve":
        """From a ``spsc.curve`` JSON object of version 1 (no ``schema_version``) to 3 (v3:
        the setup carries the contact, ``indenter`` and ``friction``; an older file's is the
        paper's plate unless it says otherwise)."""
        if not isinstance(data, dict) or "curve" not in data:
            raise ParameterError("JSON key", "curve", "an object with " + ", ".join(CURVE_COLUMNS))
        version = data.get("schema_version", 1)
        if data.get("schema", SCHEMA) != SCHEMA or version not in (1, 2, SCHEMA_VERSION):
            raise ParameterError("schema", f"{data.get('schema', SCHEMA)} v{version}",
                                 f"{SCHEMA} v1 to v{SCHEMA_VERSION} (a newer spsc wrote this "
                                 "file: upgrade spsc)")
        c = data["curve"]
        missing = [k for k in CURVE_COLUMNS if k not in c]
        if missing:
            raise ParameterError("curve key", missing[0], "present: " + ", ".join(CURVE_COLUMNS))
        arrays = {k: [np.nan if v is None else v for v in c[k]] for k in CURVE_COLUMNS}
        meta = {k: data[k] for k in _META if k in data}
        solver = data.get("solver") if version >= 2 else None
        series = {k: [np.nan if v is None else v for v in c[k]] for k in c
                  if k not in CURVE_COLUMNS and k not in ("converged", "message")}
        return cls(**arrays, **meta, converged=c.get("converged"),
                   message=tuple(c["message"]) if "message" in c else None,
                   solver=SolveInfo.from_dict(solver) if solver else None, series=series)

    @classmethod
    def from_json(cls, source: str | Path) -> "Curve":
        """From a JSON string or a path to a JSON file."""
        text = str(source)
        if not text.lstrip().startswith("{"):
            return cls.from_dict(read_json(source))
        return cls.from_dict(json.loads(text))

    # -- CSV ---------------------------------------------------------------------------------
    def to_csv(self, path: str | Path | None = None) -> str:
        """CSV with the five columns (plus ``converged``); metadata in ``# key: json`` lines."""
        buf = io.StringIO()
        for k in _META:
            v = self.setup.as_dict() if k == "setup" else getattr(self, k)
            buf.write(f"# {k}: {json.dumps(to_jsonable(v))}\n")
        extra = tuple(self.series)
        buf.write(",".join(CURVE_COLUMNS + extra + ("converged",)) + "\n")
        for i in range(len(self)):
            vals = [_fmt(getattr(self, k)[i]) for k in CURVE_COLUMNS]
            vals += [_fmt(self.series[k][i]) for k in extra]
            buf.write(",".join(vals + [str(int(self.converged[i]))]) + "\n")
        text = buf.getvalue()
        if path is not None:
            Path(path).write_text(text, encoding="utf-8")
        return text

    @classmethod
    def from_csv(cls, source: str | Path) -> "Curve":
        """From a CSV string (containing a newline) or a path written by :meth:`to_csv`."""
        text = str(source)
        if "\n" not in text:
            text = Path(source).read_text(encoding="utf-8-sig")
        meta, rows, header = {}, [], None
        for line in text.splitlines():
            if line.startswith("#"):
                key, _, val = line[1:].partition(":")
                if key.strip() in _META:
                    meta[key.strip()] = json.loads(val)
            elif line.strip():
                if header is None:
                    header = [h.strip() for h in line.split(",")]
                else:
                    rows.append([v.strip() for v in line.split(",")])
        if header is None:
            raise ParameterError("CSV", "no header", "a header line with " + ",".join(CURVE_COLUMNS))
        missing = [k for k in CURVE_COLUMNS if k not in header]
        if missing:
            raise ParameterError("CSV column", missing[0], "present: " + ",".join(CURVE_COLUMNS))
        cols = {k: [float(r[header.index(k)]) for r in rows] for k in CURVE_COLUMNS}
        conv = None
        if "converged" in header:
            conv = [bool(int(r[header.index("converged")])) for r in rows]
        series = {k: [float(r[header.index(k)]) for r in rows] for k in header
                  if k not in CURVE_COLUMNS and k != "converged"}
        return cls(**cols, **meta, converged=conv, series=series)


#: How far (units in the last place of the largest |y|) a plate position may be from the even
#: grid between the first and last for the curve's y to be that grid (np.linspace is within 1-2).
_GRID_ULPS = 4


def _decimal_grid(y: np.ndarray) -> np.ndarray:
    """``y`` (mm); an even grid (within :data:`_GRID_ULPS` ulp) recomputed in decimal
    arithmetic from its ends as written (``y_k = y_0 + (y_n - y_0) k / n``, each rounded once):
    the plate positions the user asked for, so a stroke of 3 mm in 21 points gives 0.45, not
    np.linspace's 0.44999999999999996, and JSON and CSV write them so. Any other y is kept."""
    y = np.array(y, dtype=float)
    n = y.size - 1
    if n < 2 or not np.all(np.isfinite(y)):
        return y
    even = np.linspace(y[0], y[-1], n + 1)
    if np.max(np.abs(y - even)) > _GRID_ULPS * np.spacing(np.max(np.abs(y))):
        return y
    y0, span = Decimal(repr(float(y[0]))), Decimal(repr(float(y[-1]))) - Decimal(repr(float(y[0])))
    return np.array([float(y0 + span * k / n) for k in range(n + 1)])


def _gradient(f: np.ndarray, y: np.ndarray) -> np.ndarray:
    if y.size < 2:
        return np.zeros_like(f)
    return np.gradient(f, y, edge_order=2 if y.size > 2 else 1)


def _fmt(x: float) -> str:
    return "nan" if not math.isfinite(x) else repr(float(x))


@functools.lru_cache(maxsize=1)
def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("spsc")
    except PackageNotFoundError:
        return "unknown"
