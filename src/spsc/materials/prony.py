"""The Prony series of a viscoelastic material, and its fit to a relaxation test.

g(t) = 1 + Σ_i β_i e^{−t/τ_i} is the isochoric stress of a strain held from t = 0 over the
relaxed (long-term) one: the hyperelastic law is the relaxed response, β_i the share each term
adds at once, τ_i its relaxation time (s). The wall model solves with it
(:mod:`spsc.fem.viscous`).

:func:`fit_relaxation` fits a relaxation test, stress (or modulus) against time, by the classic
method: relaxation times fixed on a logarithmic grid across the data (two a decade), the
amplitudes by non-negative least squares (so every term dissipates), the relaxed level with
them; terms with a zero amplitude are dropped; then amplitudes and times are refined together
by least squares in their logarithms (positive), kept if the residual falls. The amplitudes of neighbouring times trade off
(the inverse problem is ill-posed): what is determined, and checked, is the curve g(t).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError, require

__all__ = ["Prony", "PronyFit", "fit_relaxation", "read_relaxation", "prony_record",
           "prony_from_record"]


@dataclass(frozen=True)
class Prony:
    """Prony terms ``((beta_i, tau_i_s), ...)``: β_i ≥ 0 the term's stiffness relative to the
    relaxed law, τ_i > 0 its relaxation time (s)."""

    terms: tuple

    def __post_init__(self):
        terms = tuple((float(b), float(t)) for b, t in self.terms)
        if not terms:
            raise ParameterError("prony", "no terms", "at least one (beta, tau_s) pair")
        for i, (b, t) in enumerate(terms):
            require(f"prony beta_{i + 1}", b, ge=0, le=1e3)
            require(f"prony tau_{i + 1}", t, gt=0, le=1e9, unit="s")
        object.__setattr__(self, "terms", terms)

    def relaxation(self, t):
        """g(t) = 1 + Σ β_i e^{−t/τ_i}: the isochoric stress after a step, over the relaxed."""
        t = np.asarray(t, float)
        return 1.0 + sum(b * np.exp(-t / tau) for b, tau in self.terms)

    def factors(self, dt: float | None):
        """(a_i, b_i) arrays of a step Δt (s; None or inf: fully relaxed)."""
        if dt is None or math.isinf(dt):
            return np.zeros(len(self.terms)), np.zeros(len(self.terms))
        beta = np.array([b for b, _ in self.terms])
        tau = np.array([t for _, t in self.terms])
        return np.exp(-dt / tau), beta * np.exp(-dt / (2 * tau))


@dataclass(frozen=True)
class PronyFit:
    """The fitted series, the relaxed level (the data's unit), the RMS of the residual relative
    to the relaxed level, and the relaxation times tried."""

    prony: Prony
    relaxed: float
    rms_relative: float
    taus_tried: tuple


#: the most points a relaxation test is fitted on (more: a log-spaced sample of them)
_MAX_POINTS = 2000


def fit_relaxation(t_s, value, *, per_decade: int = 2) -> PronyFit:
    """Fit ``value``(t) = relaxed · g(t) to a relaxation test (``t_s`` in s, ≥ 0,
    increasing; ``value`` stress or modulus, any unit, positive, falling overall). A test of
    more than 2,000 points is fitted on a log-spaced sample of them (a logger's million rows
    made the least squares diverge)."""
    t = np.asarray(t_s, float)
    y = np.asarray(value, float)
    if t.ndim != 1 or t.size != y.size or t.size < 4:
        raise ParameterError("relaxation data", f"{t.size} points", "at least 4 (t, value) "
                             "pairs")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))) or np.any(t < 0) \
            or np.any(np.diff(t) <= 0) or t[-1] <= 0:
        raise ParameterError("relaxation time", "not increasing or below 0",
                             "times >= 0 s (0: the step's instant), increasing")
    if np.any(y <= 0):
        raise ParameterError("relaxation value", float(y.min()), "> 0 (stress or modulus)")
    if y[-1] > y[0]:
        raise ParameterError("relaxation value", f"rising from {y[0]:.4g} to {y[-1]:.4g}",
                             "a value that falls with time (a relaxation test at a held "
                             "strain; this rises, as a creep test's strain does)")
    if t.size > _MAX_POINTS:  # a logger's millions of rows: their log-spaced sample
        keep = np.unique(np.searchsorted(t, np.geomspace(t[t > 0][0], t[-1], _MAX_POINTS))
                         .clip(0, t.size - 1))
        keep = np.r_[0, keep] if t[0] == 0 else keep  # the step's instant stays
        t, y = t[keep], y[keep]
    lo, hi = math.floor(math.log10(t[t > 0][0])) - 1, math.ceil(math.log10(t[-1]))
    taus = 10.0 ** np.arange(lo, hi + 1e-9, 1.0 / per_decade)
    taus = taus[taus <= t[-1] * (1 + 1e-12)]  # longer ones would trade with the relaxed level
    # y = c0 + Σ c_i e^{−t/τ_i}, every c ≥ 0: c0 the relaxed level, β_i = c_i/c0
    basis = np.column_stack([np.ones_like(t)] + [np.exp(-t / tau) for tau in taus])
    scale = y.max()
    from scipy.optimize import nnls  # kept off the import of every verb

    c, _ = nnls(basis, y / scale)
    c *= scale
    if c[0] <= 0:
        raise ParameterError("relaxation data", "no relaxed level",
                             "a test long enough to show the relaxed stress")
    keep = c[1:] > 1e-8 * c[0]  # the rest do not show in the data
    c0, ci, ti = _polish(t, y / scale, c[0] / scale, c[1:][keep] / scale, taus[keep])
    c0, ci = c0 * scale, ci * scale
    terms = tuple((float(a / c0), float(tau)) for a, tau in zip(ci, ti))
    prony = Prony(terms or ((0.0, float(taus[0])),))
    model = c0 + sum(a * np.exp(-t / tau) for a, tau in zip(ci, ti))
    rms = float(np.sqrt(np.mean((model - y) ** 2)) / c0)
    return PronyFit(prony, float(c0), rms, tuple(float(v) for v in taus))


def _polish(t, y, c0, c, taus):
    """The grid's amplitudes and times refined together by least squares (in logs: they stay
    positive), kept only if the residual falls."""
    from scipy.optimize import least_squares

    if not len(c):
        return c0, c, taus
    n = len(c)

    def residual(z):
        # a trial step may overflow: its residual is then infinite and the step refused
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            a, tau = np.exp(z[1:n + 1]), np.exp(z[n + 1:])
            r = np.exp(z[0]) + np.exp(-t[:, None] / tau) @ a - y
        return np.where(np.isfinite(r), r, 1e30)

    z0 = np.log(np.concatenate([[c0], np.maximum(c, 1e-300), taus]))
    sol = least_squares(residual, z0, method="trf", x_scale="jac", max_nfev=200 * (2 * n + 1))
    if np.sum(sol.fun ** 2) >= np.sum(residual(z0) ** 2):
        return c0, c, taus
    z = sol.x
    order = np.argsort(z[n + 1:])
    return float(np.exp(z[0])), np.exp(z[1:n + 1])[order], np.exp(z[n + 1:])[order]


def read_relaxation(path) -> tuple[np.ndarray, np.ndarray, dict]:
    """(t_s, value, the file's record) of a relaxation test: a CSV with a time column ``t_s``
    (s) and one value column (stress or modulus, any unit: the fit is relative); one-line
    :class:`ParameterError` naming the file otherwise."""
    import hashlib
    from pathlib import Path

    import pandas as pd

    p = Path(path)
    try:
        raw = p.read_bytes()
        df = pd.read_csv(p, comment="#")
    except (OSError, ValueError) as exc:
        raise ParameterError("--relaxation", str(path), f"a readable CSV with t_s and a stress "
                             f"or modulus column ({str(exc).splitlines()[0]})") from None
    values = [c for c in df.columns if c != "t_s"]
    if "t_s" not in df.columns or len(values) != 1:
        raise ParameterError("--relaxation", p.name, "a CSV with the columns t_s and one value "
                             f"(stress or modulus); it has {', '.join(map(str, df.columns))}")
    t = pd.to_numeric(df["t_s"], errors="coerce").to_numpy(float)
    v = pd.to_numeric(df[values[0]], errors="coerce").to_numpy(float)
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(v))):
        raise ParameterError("--relaxation", p.name, "numbers in every row (a row is empty or "
                             "not a number)")
    return t, v, {"file": p.name, "sha256": hashlib.sha256(raw).hexdigest(),
                  "column": str(values[0]), "points": int(t.size)}


def prony_record(fit: PronyFit, data: dict, source: str = "") -> dict:
    """The ``prony`` entry of a material file: the terms, where they come from, the fit."""
    return {"terms": [list(t) for t in fit.prony.terms],
            "source": source or f"fitted by spsc fit-material to the relaxation test "
                                f"{data['file']}",
            "fit": {"rms_relative": fit.rms_relative, "relaxed": fit.relaxed,
                    "taus_tried_s": list(fit.taus_tried)}, "data": data}


def prony_from_record(record: dict, fname: str = "") -> Prony:
    """The :class:`Prony` of a material file's ``prony`` entry (one-line error naming it)."""
    where = f"material {fname}: prony" if fname else "prony"
    terms = record.get("terms") if isinstance(record, dict) else None
    try:
        return Prony(tuple((float(b), float(t)) for b, t in terms))
    except (TypeError, ValueError):
        raise ParameterError(where, terms, "a list of [beta, tau_s] pairs") from None
