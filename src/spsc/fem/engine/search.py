"""The line search of a Newton step, α ∈ {1, ½, ¼, …} (``settings.search``).

* ``residual`` — backtracking on the residual norm of the free unknowns: the first α that
  reduces it (Armijo-like), else the α with the smallest residual among admissible trials (1 if
  none is). The full step is evaluated with its tangent: it is accepted nearly always, and then
  that evaluation is the next iteration's. With a pending jump of the constraints the residual
  of the unconstrained state is no merit to descend on: the full step is taken, and if it
  inverts an element the load fails (the walk cuts the increment). No inverted trial is ever
  taken: when every trial inverts one, the load fails at once.
* ``admissible`` — the largest α that inverts no element (full Newton steps otherwise: the
  condensed mixed form's residual is no merit function to descend on).
"""

from __future__ import annotations

import numpy as np

from .result import NewtonFailure

__all__ = ["line_search"]

#: trial step lengths of each search
TRIALS = {"residual": 5, "admissible": 8}


def _residual(model, x, step, free, load, base, con, tangent):
    best, best_alpha, alpha = np.inf, 1.0, 1.0
    why = "a non-finite residual"  # unless an evaluation raised
    for _ in range(TRIALS["residual"]):
        xt = x + alpha * step
        try:
            ev = model.evaluate(xt, load, tangent=tangent and alpha == 1.0)
            rt = np.linalg.norm(con.condense(ev.r)[free])
        except (np.linalg.LinAlgError, *model.inadmissible) as exc:
            ev, rt, why = None, np.inf, str(exc)
        if np.isinf(base) and not np.isfinite(rt):
            # a step onto new constraints that inverts the mesh: the increment is too long.
            # Halving it here only wandered (the fingertip's inserts: 25 iterations, then the
            # same failure); the walk cuts the increment instead
            raise NewtonFailure(f"the step onto the new contact constraints fails: {why}")
        if rt <= base * (1 - 1e-4 * alpha) or np.isinf(base):
            return alpha, ev if alpha == 1.0 else None
        if rt < best:
            best, best_alpha = rt, alpha
        alpha *= 0.5
    if not np.isfinite(best):
        raise NewtonFailure(f"every trial step fails down to α = {2 * alpha:g}: {why}")
    return best_alpha, None


def _admissible(model, x, step):
    alpha = 1.0
    for _ in range(TRIALS["admissible"]):
        if model.admissible(x + alpha * step):
            return alpha, None
        alpha *= 0.5
    raise NewtonFailure("every trial step inverts an element")


def line_search(model, x, step, free, load, con, rt, settings, *, tangent: bool = True):
    """(α, the evaluation at x + α step if it was made (with its tangent unless not
    ``tangent``: a modified Newton iteration follows), else None) for the step from x; ``rt``
    is the (tie-condensed) residual at x."""
    if not settings.line_search:
        return 1.0, None
    if settings.search == "admissible":
        return _admissible(model, x, step)
    base = np.linalg.norm(rt[free]) if con.nearly_settled(settings.contact_tolerance) \
        else np.inf
    return _residual(model, x, step, free, load, base, con, tangent)
