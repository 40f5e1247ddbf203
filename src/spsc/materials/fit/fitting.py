"""Least-squares fit of a hyperelastic law to tension tests, jointly over every test given, with
the statistics a user needs to judge it.

The residual of point i of test t is (P_law(λi) − Pi)/si: relative (si = max(|Pi|, 1 % of the
test's largest stress), what Abaqus' material evaluation minimises; every test weighs alike
whatever its stress level) or absolute (si = 1 MPa). ``scipy.optimize.least_squares`` (trust
region reflective, with the law's bounds, analytic Jacobian) solves it from the law's starting
points (:mod:`.fit_laws`), keeping the lowest cost.

Statistics (Gauss–Newton at the optimum): s² = Σ r²/(n − p), covariance s² (JᵀJ)⁻¹ of the
weighted Jacobian J, standard error the root of its diagonal, 95 % interval ± t(0.975, n − p)
times it. R² = 1 − SS_res/SS_tot and the RMS error (MPa) of the unweighted stress per test.
Drucker stability (:mod:`.drucker`) over λ = 0.1–10 in every test, and over the fitted data.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import t as student_t

from spsc.core.errors import ParameterError
from ..drucker import DruckerResult, drucker
from .laws import OgdenLaw, law as make_law

__all__ = ["WEIGHTINGS", "LawFit", "fit_law", "fit_laws", "choose"]

WEIGHTINGS = ("relative", "absolute")
#: Relative residuals: the scale of a point is at least this fraction of its test's largest
#: stress (points at λ ≈ 1 carry no relative information).
RELATIVE_FLOOR = 0.01
#: Evaluations each starting point gets (the best one then runs to convergence, at most
#: MAX_EVALUATIONS): starts that wander off (an Ogden exponent towards 0 with its modulus
#: growing without bound) are dropped early.
SCOUT_EVALUATIONS, MAX_EVALUATIONS = 60, 500
#: A fit whose weighted Jacobian has a larger condition number is reported ill-conditioned.
ILL_CONDITIONED = 1e8


@dataclass(frozen=True)
class LawFit:
    """The fit of one law: constants (``params``, named ``names``; MPa and -), their standard
    errors and 95 % intervals, R² and RMS (MPa) per test, the optimiser's outcome, Drucker
    stability (checked range and over the data), the condition number of the problem."""

    law: object
    params: np.ndarray
    stderr: np.ndarray
    ci95: np.ndarray
    r2: dict
    rms_MPa: dict
    points: int
    cost: float
    converged: bool
    message: str
    condition: float
    at_bound: tuple
    drucker: DruckerResult
    data_ranges: dict
    seconds: float = 0.0
    notes: tuple = field(default_factory=tuple)

    @property
    def name(self) -> str:
        return self.law.name

    @property
    def names(self) -> tuple:
        return self.law.names

    @property
    def stable_over_data(self) -> bool:
        return self.drucker.stable_over(self.data_ranges)

    @property
    def shear_modulus(self) -> float:
        return self.law.shear_modulus(self.params)

    @property
    def aicc(self) -> float:
        """Corrected Akaike information criterion of the weighted residuals (lower: better;
        it charges each extra constant). Residuals below 1e-10 (relative) are round-off: the
        sum of squares is floored there, so laws that fit exactly rank by their size."""
        n, k = self.points, len(self.params)
        if n - k - 1 <= 0:
            return np.inf
        ss = max(2.0 * self.cost, n * 1e-20)
        return n * np.log(ss / n) + 2 * k + 2 * k * (k + 1) / (n - k - 1)

    def stress(self, test: str, lam) -> np.ndarray:
        return self.law.stress(test, lam, self.params)

    def constants(self) -> dict:
        return self.law.constants(self.params)

    def summary(self) -> dict:
        """The fit as JSON-ready data."""
        n = list(self.names)
        return {"law": self.name, "constants_MPa": self.constants(),
                "parameters": n, "values": self.params, "stderr": dict(zip(n, self.stderr)),
                "ci95": {k: list(v) for k, v in zip(n, self.ci95)},
                "initial_shear_modulus_MPa": self.shear_modulus,
                "r2": self.r2, "rms_MPa": self.rms_MPa, "points": self.points,
                "converged": self.converged, "message": self.message,
                "condition_number": self.condition, "at_bound": list(self.at_bound),
                "drucker": self.drucker.as_dict(), "drucker_stable_over_data":
                self.stable_over_data, "aicc": self.aicc, "seconds": self.seconds,
                "notes": list(self.notes)}


def _scales(tests, weighting: str) -> list[np.ndarray]:
    if weighting == "absolute":
        return [np.ones(d.points) for d in tests]
    floors = [RELATIVE_FLOOR * np.max(np.abs(d.stress_MPa)) for d in tests]
    return [np.maximum(np.abs(d.stress_MPa), f if f > 0 else 1.0)  # a test of zeros: 1 MPa
            for d, f in zip(tests, floors)]


def _linear_solver(tests, scales):
    """fit_linear(jac) -> the least-squares constants of a law linear in them."""
    def fit_linear(jac):
        A = np.vstack([jac(d.test, d.stretch) / s[:, None] for d, s in zip(tests, scales)])
        b = np.concatenate([d.stress_MPa / s for d, s in zip(tests, scales)])
        return np.linalg.lstsq(A, b, rcond=None)[0]
    return fit_linear


def _optimise(law, tests, scales):
    def residual(p):
        return np.concatenate([(law.stress(d.test, d.stretch, p) - d.stress_MPa) / s
                               for d, s in zip(tests, scales)])

    def jacobian(p):
        return np.vstack([law.jacobian(d.test, d.stretch, p) / s[:, None]
                          for d, s in zip(tests, scales)])

    def solve(x0, nfev):
        with np.errstate(over="ignore", invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            return least_squares(residual, x0, jac=jacobian, bounds=(lo, hi), method="trf",
                                 x_scale="jac", ftol=1e-12, xtol=1e-12, gtol=1e-12,
                                 max_nfev=nfev)

    lo, hi = law.lower, law.upper
    tried = []
    for x0 in law.starts(_linear_solver(tests, scales)):
        x0 = np.clip(np.nan_to_num(x0), lo + 1e-12 * np.isfinite(lo),
                     hi - 1e-12 * np.isfinite(hi))
        tried.append(solve(x0, SCOUT_EVALUATIONS))
    best = min(tried, key=lambda r: r.cost if np.isfinite(r.cost) else np.inf)
    return best if best.status > 0 else solve(best.x, MAX_EVALUATIONS)


def _statistics(r, n: int, p: int):
    """Standard errors, 95 % half-widths and the condition number from the Jacobian."""
    dof = n - p
    s2 = 2.0 * r.cost / dof
    sv, vt = np.linalg.svd(r.jac, full_matrices=False)[1:]
    cond = float(sv[0] / sv[-1]) if sv[-1] > 0 else np.inf
    keep = sv > sv[0] * 1e-14
    cov = (vt[keep].T / sv[keep] ** 2) @ vt[keep] * s2
    stderr = np.sqrt(np.maximum(np.diag(cov), 0.0))
    if not np.all(keep):  # a direction the data cannot see: those constants are unknown
        blind = np.abs(vt[~keep]).max(axis=0) > 1e-8
        stderr[blind] = np.inf
    return stderr, stderr * student_t.ppf(0.975, dof), cond


def _goodness(law, params, tests) -> tuple[dict, dict]:
    r2, rms = {}, {}
    for t in dict.fromkeys(d.test for d in tests):
        P = np.concatenate([d.stress_MPa for d in tests if d.test == t])
        Q = np.concatenate([law.stress(t, d.stretch, params) for d in tests if d.test == t])
        ss_tot = np.sum((P - P.mean()) ** 2)
        r2[t] = float(1.0 - np.sum((P - Q) ** 2) / ss_tot) if ss_tot > 0 else np.nan
        rms[t] = float(np.sqrt(np.mean((P - Q) ** 2)))
    return r2, rms


def _ranges(tests) -> dict:
    out = {}
    for d in tests:
        lo, hi = out.get(d.test, (np.inf, -np.inf))
        out[d.test] = (min(lo, float(d.stretch.min())), max(hi, float(d.stretch.max())))
    return out


def fit_law(law, tests, *, weighting: str = "relative") -> LawFit:
    """Fit ``law`` (a :mod:`.fit_laws` law or its name) jointly to ``tests``
    (:class:`~.material_data.TestData`). ParameterError when there are not more points than
    constants."""
    t0 = time.perf_counter()
    law = make_law(law) if isinstance(law, str) else law
    if weighting not in WEIGHTINGS:
        raise ParameterError("weighting", weighting, "one of " + ", ".join(WEIGHTINGS))
    n, p = sum(d.points for d in tests), len(law.names)
    if n <= p:
        raise ParameterError(f"data points for {law.name}", n,
                             f"more than its {p} constants")
    scales = _scales(tests, weighting)
    r = _optimise(law, tests, scales)
    stderr, half, cond = _statistics(r, n, p)
    ci = np.column_stack([r.x - half, r.x + half])
    r2, rms = _goodness(law, r.x, tests)
    tol = 1e-9 * np.maximum(1.0, np.abs(r.x))
    at_bound = tuple(nm for nm, x, lo, hi, e in zip(law.names, r.x, law.lower, law.upper, tol)
                     if x - lo <= e or hi - x <= e)
    notes = []
    if cond > ILL_CONDITIONED:
        notes.append(f"ill-conditioned (condition number {cond:.2g}): the data do not "
                     "determine every constant; their intervals are wide")
    loose = [nm for nm, x, e in zip(law.names, r.x, stderr) if not e < abs(x)]
    if loose:
        notes.append("not determined by the data: " + ", ".join(loose) + " (standard error "
                     "as large as the value; fewer constants or more tests)")
    if at_bound:
        notes.append("at a bound of the fit: " + ", ".join(at_bound))
    if law.shear_modulus(r.x) <= 0:
        notes.append(f"initial shear modulus {law.shear_modulus(r.x):.4g} MPa <= 0")
    return LawFit(law, r.x, stderr, ci, r2, rms, n, float(r.cost), bool(r.success),
                  str(r.message), cond, at_bound, drucker(law, r.x), _ranges(tests),
                  time.perf_counter() - t0, tuple(notes))


def fit_laws(names, tests, *, weighting: str = "relative", ogden_terms: int = 2) -> dict:
    """Fit each law of ``names`` (laws with more constants than points are left out: None)."""
    n = sum(d.points for d in tests)
    out = {}
    for name in names:
        law = OgdenLaw(ogden_terms) if name == "ogden" else make_law(name)
        out[name] = fit_law(law, tests, weighting=weighting) if n > len(law.names) else None
    return out


def choose(fits: dict, resolution: dict | None = None) -> tuple[LawFit | None, str]:
    """The law for the material file among the invariant-based fits (the models compute with
    W(I1, I2)): Drucker-stable over the whole checked range if any is, else stable over the
    data, else any; among those the lowest AICc, unless a law with fewer constants fits within
    the data's ``resolution`` (test -> RMS stress error of the data's rounding, MPa; see
    :mod:`.fit_resolution`) of it: then the simplest such law (AICc alone rewards fitting the
    rounding of exact data). Returns it and one sentence why."""
    cands = [f for name, f in fits.items() if f is not None and name != "ogden"
             and f.shear_modulus > 0]
    if not cands:
        return None, "no invariant-based law could be fitted"
    for level, pick in (("Drucker-stable over the whole check range", lambda f: f.drucker.stable),
                        ("Drucker-stable over the data (not beyond)", lambda f: f.stable_over_data),
                        ("NOT Drucker-stable over its own data", lambda f: True)):
        pool = [f for f in cands if pick(f)]
        if pool:
            best = min(pool, key=lambda f: f.aicc)
            why = f"{best.name}: lowest AICc among the invariant-based laws {level}"
            simpler = _within_resolution(best, pool, resolution or {})
            if simpler is not None:
                best, why = simpler, _simpler_why(simpler, best, level, resolution)
            others = ", ".join(f.name for f in pool if f is not best)
            why += f" (also: {others})" if others else ""
            if "ogden" in fits and fits["ogden"] is not None:
                why += "; ogden is reported, not chosen (--law ogden writes it)"
            return best, why
    return None, "no candidate"


def _within_resolution(best: LawFit, pool, resolution: dict) -> LawFit | None:
    """The law of ``pool`` with the fewest constants (then the lowest AICc) whose RMS misfit
    exceeds ``best``'s by no more than the data's resolution in every test
    (rms² <= rms_best² + resolution²: the extra misfit is the size of the rounding), or None."""
    if not resolution:
        return None
    ok = [f for f in pool if len(f.params) < len(best.params)
          and all(f.rms_MPa[t] ** 2 <= best.rms_MPa[t] ** 2 + resolution.get(t, 0.0) ** 2
                  for t in best.rms_MPa)]
    return min(ok, key=lambda f: (len(f.params), f.aicc)) if ok else None


def _simpler_why(simple: LawFit, best: LawFit, level: str, resolution: dict) -> str:
    rms = "; ".join(f"{t} RMS {simple.rms_MPa[t]:.3g} vs {best.rms_MPa[t]:.3g} MPa, "
                    f"resolution {resolution.get(t, 0.0):.3g} MPa" for t in best.rms_MPa)
    return (f"{simple.name}: fewest constants among the invariant-based laws {level} that fit "
            f"within the data's resolution of the lowest-AICc law, {best.name} ({rms})")
