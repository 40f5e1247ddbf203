"""Test data of a material: uniaxial, equibiaxial and planar (pure shear) tension tests read from
CSV, as stretch λ (-) and nominal (engineering) stress P (MPa).

A file has a header line; ``#`` lines are comments, and ``# test: equibiaxial`` in one names the
test. Columns are found by name (case-insensitive, any separators):

- the deformation: ``stretch`` (or ``lambda``, ``λ``), else ``strain``: in ``%`` when the name
  says so (``strain_pct``, ``strain_%``, ``strain (percent)``), else dimensionless;
- the stress: a name with ``stress`` (not true or Cauchy stress: nominal = force / initial
  area) and its unit in the name: ``MPa`` (or ``N/mm2``), ``kPa``, ``Pa``, ``psi``, ``kgf/cm2``
  (Treloar's unit); without a unit MPa is assumed and said;
- optionally ``test`` (or ``mode``): the test of each row, so one file can hold several tests.

Delimiter: comma, semicolon or tab (from the header; with semicolons or tabs a decimal comma is
read). Text: UTF-8 with or without a byte-order mark, else Latin-1. ``strain_unit`` /
``stress_unit`` override what the names say. Every problem is one :class:`ParameterError`
naming the file, the row and the column.
"""

from __future__ import annotations

import csv
import hashlib
import io
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError
from .kinematics import TESTS

__all__ = ["TestData", "read_tests", "test_name", "STRESS_UNITS", "STRAIN_UNITS"]

#: Stress units (MPa per unit) and the spellings recognised in a column name.
STRESS_UNITS = {"MPa": 1.0, "kPa": 1e-3, "Pa": 1e-6, "psi": 6.894757293168361e-3,
                "kgf/cm2": 0.0980665}
_STRESS_SPELLINGS = (("kgf/cm2", r"kgf?/cm(2|²|\^2)"), ("MPa", r"mpa|n/mm(2|²|\^2)"),
                     ("kPa", r"kpa"), ("Pa", r"pa|n/m(2|²|\^2)"), ("psi", r"psi"))
_STRESS_WORDS = {"stress", "nominal", "engineering", "eng", "p", "first", "piola", "pk1"}
#: Strain units: ``-`` (ε = λ − 1), ``%`` (ε = 100 (λ − 1)) or ``stretch`` (the column is λ).
STRAIN_UNITS = ("-", "%", "stretch")
_TEST_ALIASES = {"uniaxial": "uniaxial", "uniaxial tension": "uniaxial", "ut": "uniaxial",
                 "simple tension": "uniaxial", "equibiaxial": "equibiaxial",
                 "biaxial": "equibiaxial", "equibiaxial tension": "equibiaxial",
                 "et": "equibiaxial", "bt": "equibiaxial", "planar": "planar",
                 "planar tension": "planar", "pure shear": "planar", "ps": "planar"}


def test_name(text) -> str | None:
    """The test named by ``text`` (``uniaxial``, ``equibiaxial``, ``planar`` or an alias such as
    ``pure shear``, ``biaxial``), or None."""
    key = re.sub(r"[\s_-]+", " ", str(text).strip().lower())
    return _TEST_ALIASES.get(key)


@dataclass(frozen=True)
class TestData:
    """One test: its kind, stretches λ (-) and nominal stresses P (MPa), and where it came
    from (file, sha256 of the file's bytes, what was assumed reading it, and the file's own
    ``#`` comment lines: where the data comes from, so a material file can cite it)."""

    __test__ = False  # not a pytest class

    test: str
    stretch: np.ndarray
    stress_MPa: np.ndarray
    file: str = ""
    sha256: str = ""
    columns: dict = field(default_factory=dict)
    notes: tuple = ()

    @property
    def file_label(self) -> str:
        """The file's name (without its folder)."""
        return Path(self.file).name

    @property
    def points(self) -> int:
        return int(np.asarray(self.stretch).size)

    def within(self, lo: float, hi: float) -> "TestData":
        """The points with lo <= λ <= hi."""
        keep = (self.stretch >= lo) & (self.stretch <= hi)
        return TestData(self.test, self.stretch[keep], self.stress_MPa[keep], self.file,
                        self.sha256, self.columns, self.notes)


def _text(path: Path) -> tuple[str, str]:
    if path.is_dir():
        raise ParameterError("data file", str(path), "a CSV file (this is a folder)")
    raw = path.read_bytes()
    if b"\x00" in raw:
        raise ParameterError("data file", str(path), "a text CSV (this is binary)")
    body = raw[3:] if raw.startswith(b"\xef\xbb\xbf") else raw  # a BOM, whatever follows
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError:
        text = body.decode("latin-1")
    return text, hashlib.sha256(raw).hexdigest()


def _unit(name: str, spellings) -> str | None:
    low = name.lower()
    found = {u for u, pat in spellings if re.search(rf"(?<![a-z]){pat}(?![a-z0-9])", low)}
    if len(found) > 1:
        return "?" + ",".join(sorted(found))
    return found.pop() if found else None


def _columns(fname: str, header: list[str]) -> dict:
    """Which header column is the deformation, the stress and the test (indices)."""
    low = [h.lower() for h in header]
    cols = {}
    for k, h in enumerate(low):
        if re.search(r"stretch|lambda|λ", h) and "deform" not in cols:
            cols["deform"], cols["deform_kind"] = k, "stretch"
    if "deform" not in cols:
        for k, h in enumerate(low):
            if "strain" in h:
                if re.search(r"true|log|hencky", h):
                    raise ParameterError(f"{fname}: column {header[k]!r}", header[k],
                                         "engineering strain or stretch (not log strain)")
                cols["deform"], cols["deform_kind"] = k, "strain"
                break
    stress = [k for k, h in enumerate(low) if "stress" in h]
    for k in stress:
        if re.search(r"true|cauchy", low[k]):
            raise ParameterError(f"{fname}: column {header[k]!r}", header[k],
                                 "nominal (engineering) stress: force / initial area")
    if len(stress) > 1:
        raise ParameterError(f"{fname}: stress columns", ", ".join(header[k] for k in stress),
                             "one stress column")
    if "deform" not in cols or not stress:
        raise ParameterError(f"{fname}: header", ",".join(header),
                             "a stretch (or strain) column and a stress column, e.g. "
                             "stretch,stress_MPa or strain_pct,stress_kPa")
    cols["stress"] = stress[0]
    tests = [k for k, h in enumerate(low) if h.strip() in ("test", "mode", "test_type")]
    if tests:
        cols["test"] = tests[0]
    return cols


def _units(fname: str, header, cols, strain_unit, stress_unit) -> tuple[str, str, list[str]]:
    """(deformation unit, stress unit, what was assumed)."""
    said = []
    dname, sname = header[cols["deform"]], header[cols["stress"]]
    if strain_unit is not None:
        dunit = strain_unit
        said.append(f"{dname!r} as {'stretch' if dunit == 'stretch' else 'strain in ' + dunit}"
                    " (--strain-unit)")
    elif cols["deform_kind"] == "stretch":
        dunit = "stretch"
        said.append(f"stretch from {dname!r}")
    else:
        dunit = "%" if re.search(r"%|pct|percent", dname.lower()) else "-"
        how = "named" if dunit == "%" else "assumed: no % in the name"
        said.append(f"strain in {dunit} from {dname!r} ({how})")
    if stress_unit is not None:
        sunit = stress_unit
        said.append(f"nominal stress in {sunit} from {sname!r} (--stress-unit)")
    else:
        sunit = _unit(sname, _STRESS_SPELLINGS)
        if sunit is not None and sunit.startswith("?"):
            raise ParameterError(f"{fname}: column {sname!r}", sname,
                                 "one stress unit in the name (found " + sunit[1:] + ")")
        if sunit is None:
            rest = [w for w in re.split(r"[^a-z%/²]+", sname.lower())
                    if w and w not in _STRESS_WORDS]
            if rest:
                raise ParameterError(f"{fname}: column {sname!r}", sname,
                                     "a stress unit of " + ", ".join(STRESS_UNITS)
                                     + " in the name, or --stress-unit")
            sunit = "MPa"
            said.append(f"nominal stress from {sname!r} in MPa (assumed: no unit in the "
                        "name; --stress-unit to set it)")
        else:
            said.append(f"nominal stress in {sunit} from {sname!r}")
    return dunit, sunit, said


def _number(fname: str, row: int, col: str, text: str, decimal_comma: bool) -> float:
    t = text.strip()
    if decimal_comma:
        t = t.replace(",", ".")
    try:
        v = float(t)
    except ValueError:
        raise ParameterError(f"{fname} row {row}, column {col!r}", text.strip(),
                             "a number") from None
    if not np.isfinite(v):
        raise ParameterError(f"{fname} row {row}, column {col!r}", text.strip(),
                             "a finite number (NaN rows are not data)")
    return v


def _decimals(text: str) -> int:
    """Decimals a number is written with (trailing zeros count: 1.50 has 2; 2.5e-05 has 6;
    1e3 has -3), the resolution of the value being 10**-decimals."""
    mantissa, _, exponent = text.strip().lower().replace(",", ".").partition("e")
    return len(mantissa.partition(".")[2]) - int(exponent or 0)


#: a comment line naming the file's test: ``# test: equibiaxial``
_TEST_LINE = re.compile(r"#\s*test\s*[:=]\s*(.+?)\s*$", re.I)


def _declared_test(fname: str, comments: list[str]) -> str | None:
    for c in comments:
        m = _TEST_LINE.match(c)
        if m:
            t = test_name(m.group(1))
            if t is None:
                raise ParameterError(f"{fname}: '# test:' line", m.group(1),
                                     "uniaxial, equibiaxial or planar")
            return t
    return None


def _rows(fname: str, text: str):
    """(comment lines, header, data rows with their line numbers, decimal comma?)."""
    lines = text.splitlines()
    comments = [ln.strip() for ln in lines if ln.lstrip().startswith("#")]
    body = [(k + 1, ln) for k, ln in enumerate(lines)
            if ln.strip() and not ln.lstrip().startswith("#")]
    if not body:
        raise ParameterError("data file", fname, "a CSV with a header line and data rows")
    head = body[0][1]
    delim = ";" if ";" in head else "\t" if "\t" in head else ","
    reader = csv.reader(io.StringIO("\n".join(ln for _, ln in body)), delimiter=delim)
    rows = list(reader)
    header = [h.strip() for h in rows[0]]
    data = list(zip((n for n, _ in body[1:]), rows[1:]))
    if not data:
        raise ParameterError("data file", fname, "data rows under the header (it has none)")
    return comments, header, data, delim != ","


def _check_test(fname: str, test: str, lam: np.ndarray, P: np.ndarray, rows: list[int],
                dcol: str, scol: str) -> None:
    """Tension-test data: λ > 0, λ >= 1, strictly increasing; stress rising overall."""
    for k, v in enumerate(lam):
        if v <= 0:
            raise ParameterError(f"{fname} row {rows[k]}, column {dcol!r}", float(v),
                                 "a stretch > 0 (a strain > -1)")
        if v < 1.0 - 1e-9:
            raise ParameterError(f"{fname} row {rows[k]}, column {dcol!r}", float(v),
                                 f"stretch >= 1: {test} tension data (compression is not "
                                 "supported)")
        if k and v <= lam[k - 1]:
            raise ParameterError(f"{fname} row {rows[k]}, column {dcol!r}", float(v),
                                 f"> {lam[k - 1]:g} of the row before: the stretch must "
                                 "increase (one loading curve per test; unloading or a second "
                                 "specimen goes in another file)")
    if lam.size >= 2 and not P[-1] > P[0]:
        raise ParameterError(f"{fname}, column {scol!r}", f"{P[0]:g} .. {P[-1]:g}",
                             "a nominal stress that increases with the stretch")
    _check_stress(fname, test, P, rows, scol)


#: A tension test's stress may dip below zero, or below the largest stress before it, by this
#: fraction of its largest stress (a load cell's zero offset and noise); more is refused.
STRESS_NOISE = 0.01


def _check_stress(fname: str, test: str, P: np.ndarray, rows: list[int], scol: str) -> None:
    """Nominal stress in tension: not negative, and not falling as the stretch grows (by more
    than STRESS_NOISE of the largest stress; Drucker's condition for the data)."""
    tol = STRESS_NOISE * float(np.max(np.abs(P)))
    running = np.maximum.accumulate(P)
    for k, v in enumerate(P):
        if v < -tol:
            raise ParameterError(f"{fname} row {rows[k]}, column {scol!r}", f"{v:g} MPa",
                                 f"a nominal stress >= 0 in {test} tension")
        if running[k] - v > tol:
            raise ParameterError(f"{fname} row {rows[k]}, column {scol!r}", f"{v:g} MPa",
                                 f">= {running[k]:g} MPa of a row before (less "
                                 f"{100 * STRESS_NOISE:g} % noise): the stress must not fall "
                                 "as the stretch grows (one loading curve per test)")


def read_file(path, *, test: str | None = None, strain_unit: str | None = None,
              stress_unit: str | None = None) -> tuple[list[TestData], str]:
    """The tests in one CSV file and one line saying what was read and assumed. ``test``
    (``--test``) names the test of a file without a ``test`` column; it must agree with a
    ``# test:`` line if the file has one; with neither, the test is uniaxial (and said)."""
    p = Path(str(path))
    fname = p.name
    text, digest = _text(p)
    comments, header, data, dcomma = _rows(str(path), text)
    cols = _columns(fname, header)
    dunit, sunit, said = _units(fname, header, cols, strain_unit, stress_unit)
    declared = _declared_test(fname, comments)
    notes = tuple(c.lstrip("#").strip() for c in comments
                  if not _TEST_LINE.match(c) and c.lstrip("#").strip())
    if "test" in cols and (test or declared):
        raise ParameterError(f"{fname}: test", test or declared,
                             "not given: the file's 'test' column names the test of each row")
    if test and declared and test != declared:
        raise ParameterError("--test", test, f"the test {fname} declares ('# test: "
                             f"{declared}'), or no --test for it")
    groups: dict[str, list] = {}
    for line, row in data:
        if len(row) != len(header):
            raise ParameterError(f"{fname} row {line}", len(row), f"{len(header)} fields")
        if "test" in cols:
            t = test_name(row[cols["test"]])
            if t is None:
                raise ParameterError(f"{fname} row {line}, column {header[cols['test']]!r}",
                                     row[cols["test"]].strip(), "uniaxial, equibiaxial or "
                                     "planar")
        else:
            t = test or declared or "uniaxial"
        d = _number(fname, line, header[cols["deform"]], row[cols["deform"]], dcomma)
        s = _number(fname, line, header[cols["stress"]], row[cols["stress"]], dcomma)
        groups.setdefault(t, []).append((line, d, s, _decimals(row[cols["deform"]]),
                                         _decimals(row[cols["stress"]])))
    out = []
    for t in (t for t in TESTS if t in groups):
        lines, d, s, dd, sd = (np.array(v) for v in zip(*groups[t]))
        lam = d if dunit == "stretch" else 1.0 + d * (0.01 if dunit == "%" else 1.0)
        P = s * STRESS_UNITS[sunit]
        _check_test(fname, t, lam, P, list(lines), header[cols["deform"]],
                    header[cols["stress"]])
        out.append(TestData(t, lam, P, str(path), digest,
                            {"deformation": header[cols["deform"]], "unit": dunit,
                             "stress": header[cols["stress"]], "stress_unit": sunit,
                             "deformation_decimals": int(dd.max()),
                             "stress_decimals": int(sd.max())}, notes))
    where = ("tests from its 'test' column" if "test" in cols else
             f"{out[0].test} (" + ("--test" if test else "'# test:' line" if declared
                                   else "assumed: no --test, '# test:' line or test column")
             + ")")
    counts = ", ".join(f"{d.points} {d.test}" for d in out)
    return out, f"{fname}: {where}; " + "; ".join(said) + f"; {counts} points"


def read_tests(paths, *, tests=None, strain_unit: str | None = None,
               stress_unit: str | None = None) -> tuple[list[TestData], list[str]]:
    """Every file's tests and one line per file saying what was assumed. ``tests`` (the
    ``--test`` options): none, one for every file, or one per file in order."""
    paths = list(paths)
    tests = list(tests or [])
    if len(tests) not in (0, 1, len(paths)):
        raise ParameterError("--test", " ".join(tests),
                             f"given once (for every file) or once per file ({len(paths)})")
    per_file = tests * len(paths) if len(tests) == 1 else tests or [None] * len(paths)
    seen = set()
    for path in paths:
        key = Path(str(path)).resolve()
        if key in seen:
            raise ParameterError("data file", str(path), "each file once (it is given twice)")
        seen.add(key)
    data, notes = [], []
    for path, test in zip(paths, per_file):
        d, note = read_file(path, test=test, strain_unit=strain_unit, stress_unit=stress_unit)
        data += d
        notes.append(note)
    return data, notes
