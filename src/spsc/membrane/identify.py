"""Identification of the geometric curves from one bench test (sec. 3.1, eqs. 39–40), and
prediction at other setups through the lumped model (eqs. 6–7).

A bench file is a CSV with columns ``y_mm``, ``force_N``, ``pressure_kPa`` (gauge) and optionally
``elastic_force_N`` (F_el, measured open to atmosphere); ``#`` lines are comments.
A(y) = (F − F_el)/(P − P_amb) (eq. 39), ΔV(y) = ξV_b,i [1 − (P_i/P)^(1/n)] (eq. 40).
"""

from __future__ import annotations

import csv
import io
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError, require

from spsc.core.constants import KPA_PER_MPA
from spsc.core.curve import Curve
from .lumped import Setup, lumped_curve

__all__ = ["BenchData", "read_bench", "identify", "predict", "REQUIRED", "OPTIONAL"]

REQUIRED = ("y_mm", "force_N", "pressure_kPa")
OPTIONAL = ("elastic_force_N",)
#: Recognised quantity prefixes and the unit each must carry.
_UNITS = {"y": "mm", "force": "N", "pressure": "kPa", "elastic_force": "N"}


@dataclass(frozen=True)
class BenchData:
    """One bench test: plate travel y (mm), force F (N), gauge pressure p (kPa; None for an
    open chamber's test), F_el (N or None)."""

    y_mm: np.ndarray
    force_N: np.ndarray
    pressure_kPa: np.ndarray | None
    elastic_force_N: np.ndarray | None = None
    source: str = ""

    def __post_init__(self):
        y = np.asarray(self.y_mm, float)
        if y.size < 3:
            raise ParameterError("bench rows", y.size, ">= 3 data rows")
        for name in ("force_N", "pressure_kPa", "elastic_force_N"):
            if getattr(self, name) is None:
                continue
            a = np.asarray(getattr(self, name), float)
            if a.shape != y.shape:
                raise ParameterError(f"len({name})", a.size, f"= len(y_mm) = {y.size}")
            if not np.all(np.isfinite(a)):
                raise ParameterError(name, "non-finite value", "finite numbers")
        d = np.diff(y)
        if np.any(d <= 0):
            k = int(np.argmax(d <= 0)) + 1
            raise ParameterError(f"y_mm (row {k + 1})", float(y[k]),
                                 f"> previous value {y[k - 1]:g} (y must increase monotonically)")


def _header_check(header: list[str], required=REQUIRED) -> None:
    for col in header:
        m = re.fullmatch(r"(y|force|pressure|elastic_force)_(\w+)", col)
        if m and col not in REQUIRED + OPTIONAL:
            q, unit = m.group(1), m.group(2)
            raise ParameterError(f"column {col}", unit,
                                 f"unit {_UNITS[q]}: name the column {q}_{_UNITS[q]}")
    missing = [c for c in required if c not in header]
    if missing:
        optional = [c for c in REQUIRED + OPTIONAL if c not in required]
        raise ParameterError("missing column", missing[0],
                             "a header with " + ", ".join(required)
                             + "".join(f" [, {c}]" for c in optional))


def _read_text(path: Path) -> str:
    """The text of a bench file: UTF-8 with or without a byte-order mark (a spreadsheet's
    "CSV UTF-8"), else Latin-1 (every byte is a character: a comment typed in a Windows editor
    reads, and a data field that is not a number is refused by its row and column)."""
    if path.is_dir():
        raise ParameterError("bench file", str(path), "a CSV file (this is a folder)")
    raw = path.read_bytes()
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        return raw.decode("latin-1")


def read_bench(source: str | Path, *, required=REQUIRED) -> BenchData:
    """Read a bench CSV (path, or the text itself if it contains a newline). Lines starting
    with ``#`` are comments; UTF-8 (a byte-order mark is skipped) or Latin-1. ``required``:
    the columns that must be there (an open chamber's test has no pressure)."""
    text = str(source)
    name = "<text>"
    if "\n" not in text:
        name = str(source)
        text = _read_text(Path(source))
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise ParameterError("bench file", name, "a CSV with a header line and data rows")
    rows = list(csv.reader(io.StringIO("\n".join(lines))))
    header = [h.strip() for h in rows[0]]
    _header_check(header, required)
    cols = {c: [] for c in header}
    for i, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise ParameterError(f"row {i} of {name}", len(row), f"{len(header)} fields")
        for c, v in zip(header, row):
            try:
                cols[c].append(float(v))
            except ValueError:
                raise ParameterError(f"row {i}, column {c}", v.strip(), "a number") from None
    return BenchData(np.array(cols["y_mm"]), np.array(cols["force_N"]),
                     np.array(cols["pressure_kPa"]) if "pressure_kPa" in cols else None,
                     np.array(cols["elastic_force_N"]) if "elastic_force_N" in cols else None,
                     source=name)


def identify(bench: BenchData, *, pressure_kPa: float, bladder_volume_mm3: float,
             reservoir_mm3: float = 0.0, polytropic_n: float = 1.0,
             geometry: dict | None = None, material: str = "") -> Curve:
    """A(y) (eq. 39) and ΔV(y) (eq. 40) from a bench test at setup ``pressure_kPa`` (kPa gauge)
    with bladder volume V_b,i and reservoir V_r (mm³). Returns the bench :class:`Curve`
    (model ``identified``) carrying the measured F, p and the identified A, ΔV."""
    setup = Setup(pressure_kPa, bladder_volume_mm3, reservoir_mm3, polytropic_n)
    if bench.pressure_kPa is None:
        raise ParameterError("missing column", "pressure_kPa", "the cavity pressure of the test")
    p = np.asarray(bench.pressure_kPa, float)
    tol = max(1.0, 0.2 * setup.p_i_kPa)
    if abs(p[0] - setup.p_i_kPa) > tol:
        raise ParameterError("pressure_kPa (first row)", float(p[0]),
                             f"within {tol:g} kPa of the setup pressure {setup.p_i_kPa:g} kPa "
                             "(check the units: kPa gauge, not Pa, bar or absolute)")
    if np.any(p <= 0):
        k = int(np.argmax(p <= 0))
        raise ParameterError(f"pressure_kPa (row {k + 2})", float(p[k]), "> 0 kPa gauge")
    f_el = np.zeros_like(p) if bench.elastic_force_N is None else bench.elastic_force_N
    area = 1e3 * (bench.force_N - f_el) / p  # N / kPa = 1e3 mm²
    # eq. 40: ΔV = ξ V_b,i (1 − (P_i/P)^(1/n)), the gas law solved for the volume
    dv = setup.bladder_volume_mm3 - setup.gas().volume(p / KPA_PER_MPA)
    return Curve(bench.y_mm, bench.force_N, p, area, dv, model="identified",
                 geometry=geometry or {}, material=material, setup=setup.as_dict(),
                 nominal_volume_mm3=bladder_volume_mm3, inflated_volume_mm3=bladder_volume_mm3)


def predict(identified: Curve, *, pressure_kPa: float, reservoir_mm3: float,
            bladder_volume_mm3: float, polytropic_n: float = 1.0, elastic_force_N=None) -> Curve:
    """The lumped model (eqs. 6–7) on the identified A(y), ΔV(y) at another setup pressure
    (kPa gauge) and reservoir (mm³); F_el(y) (N) is added if given."""
    require("pressure", pressure_kPa, ge=0, unit="kPa gauge")
    setup = Setup(pressure_kPa, bladder_volume_mm3, reservoir_mm3, polytropic_n)
    return lumped_curve(identified.y_mm, np.maximum(identified.contact_area_mm2, 0.0),
                        identified.volume_change_mm3, setup, elastic_force_N=elastic_force_N,
                        geometry=identified.geometry, material=identified.material,
                        model="predicted", nominal_volume_mm3=identified.nominal_volume_mm3)
