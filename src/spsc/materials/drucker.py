"""Drucker stability of a fitted law along the three test paths.

Drucker's postulate for an incompressible hyperelastic material: every increment of log strain
dε does positive work with the stress increment it causes, dσ : dε > 0. With e3 = −e1 − e2 the
work is (σ1 − σ3) de1 + (σ2 − σ3) de2, and σa − σ3 = ∂Ŵ/∂ea for Ŵ(e1, e2) = W(e^e1, e^e2,
e^(−e1−e2)); so the material is stable at a state when the 2 × 2 tangent D = ∂²Ŵ/∂e∂e is
positive definite (the check commercial codes run on fitted laws). It is checked along the
uniaxial, equibiaxial and planar paths for λ in [0.1, 10] (nominal strain −0.9 to 9: tension
and compression), and the ranges where it fails are found to 1e-6 relative by root finding on
D's smaller eigenvalue.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .kinematics import TESTS, stretches

__all__ = ["CHECK_RANGE", "DruckerResult", "drucker", "min_eigenvalue"]

#: The stretches checked in each test (λ = 0.1 … 10).
CHECK_RANGE = (0.1, 10.0)


def min_eigenvalue(law, params, test: str, lam) -> np.ndarray:
    """Smaller eigenvalue of Drucker's tangent D (MPa) along ``test`` at stretches ``lam``."""
    H11, H12, H22 = law.log_hessian(*stretches(test, lam), params)
    return 0.5 * (H11 + H22) - np.sqrt(0.25 * (H11 - H22) ** 2 + H12**2)


@dataclass(frozen=True)
class DruckerResult:
    """Where a law is Drucker-unstable: ``unstable[test]`` is a tuple of (λ_from, λ_to)
    intervals within ``checked`` (λ); ``stable_range[test]`` the stable interval around λ = 1
    (None when λ = 1 itself is unstable)."""

    checked: tuple[float, float]
    unstable: dict

    @property
    def stable(self) -> bool:
        return not any(self.unstable.values())

    @property
    def stable_range(self) -> dict:
        out = {}
        for test, spans in self.unstable.items():
            lo, hi = self.checked
            for a, b in spans:
                if b <= 1.0:
                    lo = max(lo, b)
                elif a >= 1.0:
                    hi = min(hi, a)
                else:
                    lo = hi = None
                    break
            out[test] = None if lo is None else (lo, hi)
        return out

    def stable_over(self, ranges: dict) -> bool:
        """Stable on each ``ranges[test] = (λmin, λmax)``."""
        return not any(a < hi and b > lo for test, (lo, hi) in ranges.items()
                       for a, b in self.unstable.get(test, ()))

    def describe(self) -> str:
        """One phrase: ``stable for 0.1 <= λ <= 10 in every test`` or where it is not."""
        lo, hi = self.checked
        if self.stable:
            return f"Drucker-stable for {lo:g} <= stretch <= {hi:g} in every test"
        parts = []
        for test, spans in self.unstable.items():
            for a, b in spans:
                parts.append(f"{test} {_span(a, b, lo, hi)}")
        return "Drucker-UNSTABLE: " + "; ".join(parts)

    def as_dict(self) -> dict:
        return {"checked": list(self.checked), "stable": self.stable,
                "unstable": {t: [list(s) for s in v] for t, v in self.unstable.items()},
                "stable_range": {t: (None if r is None else list(r))
                                 for t, r in self.stable_range.items()}}


def _span(a: float, b: float, lo: float, hi: float) -> str:
    if a <= lo and b >= hi:
        return "everywhere"
    if a <= lo:
        return f"stretch < {b:.4g}"
    if b >= hi:
        return f"stretch > {a:.4g}"
    return f"{a:.4g} < stretch < {b:.4g}"


def _intervals(f, grid: np.ndarray) -> list[tuple[float, float]]:
    """The sub-intervals of [grid[0], grid[-1]] where f <= 0, edges refined by brentq."""
    bad = f(grid) <= 0.0
    spans = []
    k = 0
    while k < len(grid):
        if not bad[k]:
            k += 1
            continue
        j = k
        while j + 1 < len(grid) and bad[j + 1]:
            j += 1
        a = grid[0] if k == 0 else brentq(f, grid[k - 1], grid[k], xtol=1e-12, rtol=1e-6)
        b = grid[-1] if j == len(grid) - 1 else brentq(f, grid[j], grid[j + 1], xtol=1e-12,
                                                        rtol=1e-6)
        spans.append((float(a), float(b)))
        k = j + 1
    return spans


def drucker(law, params, *, checked: tuple[float, float] = CHECK_RANGE,
            tests: tuple[str, ...] = TESTS, points: int = 2001) -> DruckerResult:
    """Drucker stability of ``law`` with ``params`` along each test for λ in ``checked``,
    sampled at ``points`` log-spaced stretches (λ = 1 included) then refined."""
    lo, hi = checked
    grid = np.unique(np.concatenate([np.geomspace(lo, hi, points), [1.0]]))
    unstable = {}
    for test in tests:
        def f(lam, test=test):
            return min_eigenvalue(law, params, test, lam)
        unstable[test] = tuple(_intervals(f, grid))
    return DruckerResult((lo, hi), unstable)
