"""Bench data: one test of a chamber on the bench, F(y) and P(y) (and F_el(y)) read from CSV.

A bench file is a CSV with columns ``y_mm``, ``force_N``, ``pressure_kPa`` (gauge) and optionally
``elastic_force_N`` (F_el, measured open to atmosphere); ``#`` lines are comments.
Identification (eqs. 39–40, :mod:`spsc.membrane.identify`) and calibration
(:mod:`spsc.fem.wall.calibrate`) read it.
"""

from __future__ import annotations

import csv
import io
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import ParameterError

__all__ = ["BenchData", "read_bench", "REQUIRED", "OPTIONAL"]

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
