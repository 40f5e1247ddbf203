"""The Prony series from a cyclic test: a uniaxial tension loaded and unloaded at a known
rate (issue 52), the stress against time and stretch, over the relaxed law the tension test
gave.

The law is the wall's (:mod:`spsc.fem.viscous`, Simo 1987), in uniaxial tension of the
incompressible material: C = diag(λ², 1/λ, 1/λ) in fixed principal directions, each Prony term
a stress Q_i with Q̇_i + Q_i/τ_i = β_i Ṡ_iso, the isochoric stress of the relaxed law W(Ī1, Ī2)

    S_iso = 2 (W₁ + I₁ W₂) I − 2 W₂ C − ⅔ (I₁ W₁ + 2 I₂ W₂) C⁻¹,

and the pressure that keeps the lateral faces free (S₂₂ = 0), so the nominal stress is

    P(t) = λ [S₁₁ − S₂₂ / λ³],   S = S_iso + Σ_i Q_i,                                (C1)

stepped with the wall model's own rule (the midpoint of the convolution:
Q_i ← a_i Q_i + β_i e^{−Δt/2τ_i} ΔS_iso, a_i = e^{−Δt/τ_i}). For fixed times τ_i the
stress is linear in the β_i, so the fit is :mod:`.prony`'s: times on a logarithmic grid
across the test's time scales, the amplitudes by non-negative least squares (every term
dissipates), then amplitudes and times refined together. Two rates (or a hold) are needed to
tell the times apart; one cycle at one rate fixes only a blend of them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError

from .law import uniaxial_isochoric_stress
from .prony import Prony

__all__ = ["CyclicFit", "cyclic_stress", "fit_cyclic", "read_cyclic", "cyclic_record"]

_MAX_POINTS = 1500


def _histories(t: np.ndarray, s_iso: np.ndarray, taus) -> np.ndarray:
    """h_i (n, 2, k): the Prony variables of unit β for each τ_i, by the wall's step rule."""
    n, k = len(t), len(taus)
    h = np.zeros((n, 2, k))
    dt = np.diff(t)
    tau = np.asarray(taus, float)
    for j in range(1, n):
        a = np.exp(-dt[j - 1] / tau)
        b = np.exp(-dt[j - 1] / (2.0 * tau))
        h[j] = a * h[j - 1] + b * (s_iso[j] - s_iso[j - 1])[:, None]
    return h


def _nominal(lam: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Eq. C1 from S (n, 2, ...) = (S₁₁, S₂₂)."""
    lam = lam.reshape((-1,) + (1,) * (s.ndim - 2))
    return lam * (s[:, 0] - s[:, 1] / lam ** 3)


def cyclic_stress(material, prony: Prony | None, t_s, stretch) -> np.ndarray:
    """The nominal stress (MPa) of the law ``material`` with ``prony`` (None: relaxed) driven
    through the stretches ``stretch`` at the times ``t_s`` (eq. C1, from rest)."""
    t, lam = np.asarray(t_s, float), np.asarray(stretch, float)
    s_iso = uniaxial_isochoric_stress(material, lam)
    total = s_iso.copy()
    if prony is not None:
        beta = np.array([b for b, _ in prony.terms])
        h = _histories(t, s_iso, [tau for _, tau in prony.terms])
        total = total + h @ beta
    return _nominal(lam, total)


@dataclass(frozen=True)
class CyclicFit:
    """The fitted series, the RMS of the stress residual relative to the test's largest
    stress, and the relaxation times tried."""

    prony: Prony
    rms_relative: float
    taus_tried: tuple


def fit_cyclic(material, t_s, stretch, stress, *, per_decade: int = 2) -> CyclicFit:
    """Fit the Prony terms over the relaxed law ``material`` to a cyclic uniaxial test:
    ``t_s`` (s, increasing), ``stretch`` (λ ≥ 1 in tension), ``stress`` (nominal, MPa)."""
    t, lam, y = (np.asarray(v, float) for v in (t_s, stretch, stress))
    if t.ndim != 1 or not (t.size == lam.size == y.size) or t.size < 6:
        raise ParameterError("cyclic data", f"{t.size} points", "at least 6 (t, stretch, "
                             "stress) rows")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(lam)) and np.all(np.isfinite(y))):
        raise ParameterError("cyclic data", "not finite", "numbers in every row")
    if np.any(np.diff(t) <= 0):
        raise ParameterError("cyclic time", "not increasing", "times increasing (s)")
    if np.any(lam <= 0) or lam.max() <= 1.0 + 1e-6:
        raise ParameterError("cyclic stretch", float(lam.max()), "stretches > 0 that load the "
                             "sample in tension (largest > 1)")
    if t.size > _MAX_POINTS:
        keep = np.unique(np.linspace(0, t.size - 1, _MAX_POINTS).round().astype(int))
        t, lam, y = t[keep], lam[keep], y[keep]
    span = t[-1] - t[0]
    step = float(np.min(np.diff(t)))
    lo, hi = math.floor(math.log10(step)), math.ceil(math.log10(span))
    taus = 10.0 ** np.arange(lo, hi + 1e-9, 1.0 / per_decade)
    s_iso = uniaxial_isochoric_stress(material, lam)
    relaxed = _nominal(lam, s_iso)
    basis = _nominal(lam, _histories(t - t[0], s_iso, taus))  # (n, k)
    scale = float(np.abs(y).max())
    from scipy.optimize import nnls  # kept off the import of every verb

    beta, _ = nnls(basis / scale, (y - relaxed) / scale)
    keep = beta > 1e-3 * max(float(beta.max(initial=0.0)), 1e-300)  # the rest do not show
    beta, taus_kept = _polish(material, t - t[0], lam, y, s_iso, beta[keep], taus[keep], scale)
    beta, taus_kept = _merged(beta, taus_kept)
    prony = Prony(tuple(zip(beta.tolist(), taus_kept.tolist())) or ((0.0, float(taus[0])),))
    model = cyclic_stress(material, prony, t - t[0], lam)
    rms = float(np.sqrt(np.mean((model - y) ** 2)) / scale)
    return CyclicFit(prony, rms, tuple(float(v) for v in taus))


def _polish(material, t, lam, y, s_iso, beta, taus, scale):
    """Amplitudes and times refined together (in logs: positive), kept if the residual
    falls."""
    from scipy.optimize import least_squares

    if not len(beta):
        return beta, taus
    n = len(beta)
    relaxed = _nominal(lam, s_iso)

    def residual(z):
        b, tau = np.exp(z[:n]), np.exp(z[n:])
        return (relaxed + _nominal(lam, _histories(t, s_iso, tau)) @ b - y) / scale

    z0 = np.log(np.concatenate([beta, taus]))
    sol = least_squares(residual, z0, method="trf", x_scale="jac", max_nfev=50 * (2 * n + 1))
    if np.sum(sol.fun ** 2) >= np.sum(residual(z0) ** 2):
        return beta, taus
    order = np.argsort(sol.x[n:])
    return np.exp(sol.x[:n])[order], np.exp(sol.x[n:])[order]


def _merged(beta, taus, within: float = 0.02):
    """Terms whose times agree within ``within`` (relative) as one: their amplitudes summed,
    their time the amplitude-weighted mean (the grid's neighbours converge onto one time and
    split its amplitude, which the data cannot tell apart)."""
    out_b, out_t = [], []
    for b, tau in sorted(zip(beta, taus), key=lambda bt: bt[1]):
        if out_t and tau <= out_t[-1] * (1 + within):
            w = out_b[-1] + b
            out_t[-1] = (out_b[-1] * out_t[-1] + b * tau) / w if w > 0 else tau
            out_b[-1] = w
        else:
            out_b.append(float(b))
            out_t.append(float(tau))
    return np.array(out_b), np.array(out_t)


def read_cyclic(path) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict]:
    """(t_s, stretch, nominal stress MPa, the file's record) of a cyclic test: a CSV with the
    columns ``t_s``, ``stretch`` and ``stress_MPa``; one-line :class:`ParameterError` naming
    the file otherwise."""
    from .testcsv import read_columns

    return read_columns(path, "--cyclic", ("t_s", "stretch", "stress_MPa"))


def cyclic_record(fit: CyclicFit, data: dict) -> dict:
    """The ``prony`` entry of a material file fitted to a cyclic test."""
    return {"terms": [list(t) for t in fit.prony.terms],
            "source": f"fitted by spsc fit-material to the cyclic test {data['file']} over "
                      "the hyperelastic law of this file (its relaxed response)",
            "fit": {"rms_relative": fit.rms_relative, "taus_tried_s": list(fit.taus_tried)},
            "data": data}
