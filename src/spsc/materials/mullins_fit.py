"""Ogden–Roxburgh constants from a loading–unloading test (issue 52): a uniaxial tension of the
virgin material loaded, unloaded and reloaded, the nominal stress against the stretch, over
the hyperelastic law the tension test gave (its primary path).

In uniaxial tension of the incompressible material (C = diag(λ², 1/λ, 1/λ)) the softened
nominal stress is the virgin one scaled by the damage of eq. (M1), :mod:`.mullins`:

    P(λ) = η(W(λ), W_m) · P₀(λ),   P₀ = λ (S_iso,11 − S_iso,22 / λ³),              (M2)

with W the law's energy at (Ī1, Ī2) = (λ² + 2/λ, 2λ + 1/λ²) and W_m its largest value so far
along the test. r, m and β follow by least squares on the unloading and reloading points
(r > 1, m > 0, β ≥ 0); the loading points past every earlier maximum carry no information
(η = 1 there). Rate effects are not separated: a slow test (or ``--cyclic`` for the Prony
terms) is the user's part.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError

from .mullins import MullinsParams
from .law import uniaxial_isochoric_stress

__all__ = ["MullinsFit", "mullins_stress", "fit_mullins", "read_mullins", "mullins_record"]


def _energy_and_virgin(material, lam: np.ndarray):
    c2 = 1.0 / lam
    i1, i2 = lam * lam + 2.0 * c2, 2.0 * lam + c2 * c2
    w = np.asarray(material.energy(i1, i2), float)
    s = uniaxial_isochoric_stress(material, lam)
    return w, lam * (s[:, 0] - s[:, 1] / lam ** 3)


def mullins_stress(material, params: MullinsParams, stretch) -> np.ndarray:
    """The nominal stress (MPa) along the uniaxial ``stretch`` history, eq. M2."""
    lam = np.asarray(stretch, float)
    w, p0 = _energy_and_virgin(material, lam)
    eta, _ = params.eta(w, np.maximum.accumulate(w))
    return eta * p0


@dataclass(frozen=True)
class MullinsFit:
    """The fitted constants, the RMS residual relative to the test's largest stress, and the
    number of softened points (unloading or reloading) the fit rests on."""

    params: MullinsParams
    rms_relative: float
    softened_points: int


def fit_mullins(material, stretch, stress) -> MullinsFit:
    """r, m, β of eq. M2 fitted to the test (``stretch``, nominal ``stress`` MPa) over the
    virgin ``material``; ParameterError when the test never unloads."""
    from scipy.optimize import least_squares

    lam, y = np.asarray(stretch, float), np.asarray(stress, float)
    w, p0 = _energy_and_virgin(material, lam)
    w_max = np.maximum.accumulate(w)
    soft = w < w_max * (1 - 1e-9)
    if soft.sum() < 3:
        raise ParameterError("--mullins", f"{int(soft.sum())} softened points", "a test that "
                             "unloads (at least 3 points below an earlier largest stretch)")

    def params(x):
        return MullinsParams(1.0 + math.exp(x[0]), math.exp(x[1]), x[2])

    def residual(x):
        eta, _ = params(x).eta(w[soft], w_max[soft])
        return eta * p0[soft] - y[soft]

    scale = float(np.max(w_max))
    best = None
    for r0 in (1.2, 2.0, 5.0):  # a few starts: the erf's plateau makes the fit multimodal
        for m0 in (0.1 * scale, scale):
            x0 = np.array([math.log(r0 - 1.0), math.log(max(m0, 1e-9)), 0.0])
            sol = least_squares(residual, x0, bounds=([-10, math.log(1e-8), 0.0],
                                                      [10, math.log(100.0), 10.0]))
            if best is None or sol.cost < best.cost:
                best = sol
    fitted = params(best.x)
    rms = float(np.sqrt(np.mean(residual(best.x) ** 2)) / max(np.abs(y).max(), 1e-300))
    return MullinsFit(fitted, rms, int(soft.sum()))


def read_mullins(path) -> tuple[np.ndarray, np.ndarray, dict]:
    """(stretch, nominal stress MPa, the file's record) of a loading–unloading test: a CSV
    with the columns ``stretch`` and ``stress_MPa`` in the order they were measured; one-line
    :class:`ParameterError` naming the file otherwise."""
    from .testcsv import read_columns

    lam, stress, data = read_columns(path, "--mullins", ("stretch", "stress_MPa"))
    if np.any(lam < 1.0):
        raise ParameterError("--mullins", data["file"], "stretches >= 1 (a tension test)")
    return lam, stress, data


def mullins_record(fit: MullinsFit, data: dict) -> dict:
    """The ``mullins`` entry of a material file fitted to a loading–unloading test."""
    prm = fit.params
    return {"r": prm.r, "m": prm.m, "beta": prm.beta,
            "source": f"fitted by spsc fit-material to the loading-unloading test "
                      f"{data['file']} (sha256 {data['sha256'][:12]}, {fit.softened_points} "
                      f"softened points, rms {fit.rms_relative:.2%} of the largest stress)"}
