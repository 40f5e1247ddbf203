"""Sensing logs: LOG.csv or LOG.parquet with the columns ``t_s`` (s, strictly increasing),
``pressure_kPa`` (gauge; another column with ``pressure_column``), and optionally
``valve_open`` (0/1), ``fsr_1`` … ``fsr_N`` (N, fsr_1 at the base, fsr_N at the tip) and
``angle_deg`` (the finger's closure). Other columns are ignored. Every problem is one
:class:`~spsc.core.errors.ParameterError` naming the column, the value and what is allowed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError

__all__ = ["Log", "read_log", "LineReader", "noise_of", "start_of"]


@dataclass
class Log:
    """The checked columns (numpy arrays; None when absent); ``fsr`` (n, N)."""

    t_s: np.ndarray
    pressure_kPa: np.ndarray
    valve_open: np.ndarray | None = None
    fsr: np.ndarray | None = None
    angle_deg: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.t_s)

    @property
    def rate_Hz(self) -> float:
        """The sampling rate from the median interval."""
        return float(1.0 / np.median(np.diff(self.t_s))) if len(self) > 1 else 1000.0


def _fsr_names(columns) -> list[str]:
    found = sorted((int(c[4:]), c) for c in columns
                   if c.startswith("fsr_") and c[4:].isdigit())
    names = [c for _, c in found]
    if names and [k for k, _ in found] != list(range(1, len(found) + 1)):
        raise ParameterError("fsr columns", ", ".join(names), "fsr_1 … fsr_N without a gap")
    return names


def _column(df, name: str, *, allow=None) -> np.ndarray:
    try:
        v = df[name].to_numpy(dtype=float)
    except (ValueError, TypeError):
        raise ParameterError(name, "text", "numbers") from None
    bad = np.flatnonzero(~np.isfinite(v))
    if bad.size:
        raise ParameterError(f"{name} (row {bad[0] + 1})", v[bad[0]], "a finite number")
    if allow is not None:
        out = np.flatnonzero(~np.isin(v, allow))
        if out.size:
            raise ParameterError(f"{name} (row {out[0] + 1})", v[out[0]],
                                 " or ".join(f"{a:g}" for a in allow))
    return v


def frame_to_log(df, pressure_column: str = "pressure_kPa") -> Log:
    """The :class:`Log` of a DataFrame, checked."""
    for need in ("t_s", pressure_column):
        if need not in df.columns:
            raise ParameterError("log columns", ", ".join(map(str, df.columns)) or "none",
                                 f"a column {need} (t_s, {pressure_column}[, valve_open, "
                                 "fsr_1..fsr_N, angle_deg])")
    if len(df) < 2:
        raise ParameterError("log rows", len(df), "at least 2 samples")
    t = _column(df, "t_s")
    steps = np.flatnonzero(np.diff(t) <= 0)
    if steps.size:
        k = steps[0] + 1
        raise ParameterError(f"t_s (row {k + 1})", t[k],
                             f"strictly increasing (row {k} is {t[k - 1]:g} s)")
    fsr = _fsr_names(df.columns)
    return Log(t, _column(df, pressure_column),
               _column(df, "valve_open", allow=(0.0, 1.0)) if "valve_open" in df else None,
               np.column_stack([_column(df, c) for c in fsr]) if fsr else None,
               _column(df, "angle_deg") if "angle_deg" in df else None)


def read_log(path, pressure_column: str = "pressure_kPa") -> Log:
    """The log in ``path`` (.csv or .parquet), checked."""
    import pandas as pd

    p = Path(path)
    suffix = p.suffix.lower()
    if suffix not in (".csv", ".parquet"):
        raise ParameterError("log", str(path), "a .csv or .parquet file")
    if not p.is_file():
        raise ParameterError("log", str(path), "an existing file")
    try:
        df = pd.read_parquet(p) if suffix == ".parquet" else pd.read_csv(p, comment="#")
    except (ValueError, OSError, UnicodeDecodeError) as exc:
        raise ParameterError("log", p.name, f"a readable {suffix[1:]} table "
                             f"({str(exc).splitlines()[0] if str(exc) else type(exc).__name__})") \
            from None
    df.columns = [str(c).strip() for c in df.columns]
    return frame_to_log(df, pressure_column)


class LineReader:
    """``--follow``: a header line, then one sample a line; :meth:`sample` gives the
    arguments of :meth:`~spsc.sensing.stream.SenseStream.push` as a dict."""

    def __init__(self, header: str, pressure_column: str = "pressure_kPa"):
        names = [h.strip() for h in header.strip().split(",")]
        for need in ("t_s", pressure_column):
            if need not in names:
                raise ParameterError("header", header.strip(), f"CSV column names with t_s "
                                     f"and {pressure_column}")
        self.idx = {n: i for i, n in enumerate(names)}
        self.names, self.pcol = names, pressure_column
        self.fsr = [self.idx[c] for c in _fsr_names(names)]
        self.line = 1

    def sample(self, text: str) -> dict | None:
        """The sample on the line (None for a blank or ``#`` line)."""
        self.line += 1
        if not text.strip() or text.lstrip().startswith("#"):
            return None
        fields = text.strip().split(",")
        if len(fields) != len(self.names):
            raise ParameterError(f"line {self.line}", len(fields), f"{len(self.names)} fields")
        try:
            v = [float(x) for x in fields]
        except ValueError:
            raise ParameterError(f"line {self.line}", text.strip(), "numbers") from None
        out = {"t_s": v[self.idx["t_s"]], "pressure_kPa": v[self.idx[self.pcol]]}
        if "valve_open" in self.idx:
            out["valve_open"] = v[self.idx["valve_open"]]
            if out["valve_open"] not in (0.0, 1.0):
                raise ParameterError(f"valve_open (line {self.line})", out["valve_open"], "0 or 1")
        if self.fsr:
            out["fsr"] = [v[i] for i in self.fsr]
        if "angle_deg" in self.idx:
            out["angle_deg"] = v[self.idx["angle_deg"]]
        return out


def noise_of(pressure_kPa) -> float:
    """σ of the sensor's white noise from the log itself: the median absolute first
    difference (robust to presses and steps), σ = 1.4826 MAD(ΔP)/√2 (kPa)."""
    d = np.diff(np.asarray(pressure_kPa, float))
    s = 1.4826 * float(np.median(np.abs(d - np.median(d)))) / math.sqrt(2.0)
    if not s > 0:
        raise ParameterError("noise", "0 (the log's first differences are all equal)",
                             "a log with sensor noise, or --noise KPA")
    return s


def start_of(t_s, pressure_kPa, noise_kPa: float, window_s: float = 0.1):
    """(the pressure at the log's first sample, kPa, from the line through its first
    ``window_s``; its rate kPa/s; whether that rate is beyond 6 standard errors: a press or
    a release under way, not a rest) — None for fewer than 5 samples in the window."""
    t = np.asarray(t_s, float)
    sel = t <= t[0] + window_s
    x, p = t[sel] - t[0], np.asarray(pressure_kPa, float)[sel]
    if p.size < 5:
        return None
    sxx = float(((x - x.mean()) ** 2).sum())
    rate = float(((x - x.mean()) * (p - p.mean())).sum() / sxx) if sxx > 0 else 0.0
    moving = sxx > 0 and abs(rate) > 6.0 * noise_kPa / math.sqrt(sxx)
    start = float(p.mean() - rate * x.mean()) if moving else float(np.median(p))
    return start, rate, moving
