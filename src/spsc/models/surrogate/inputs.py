"""The Gaussian processes' inputs: the design ratios mapped to [0, 1] over the trained
bounds, on a log scale for those that act multiplicatively (h/w, t0/w, n1, n2: a profile's
exponent and a wall's slenderness matter by their ratios), linearly for c_y and l/w."""

from __future__ import annotations

import numpy as np

from .domain import BOUNDS, RATIOS

__all__ = ["unit_inputs", "LOG"]

#: the ratios taken on a log scale
LOG = ("h/w", "t0/w", "n1", "n2")


def unit_inputs(ratios, free) -> np.ndarray:
    """Rows of the six ratios (:data:`~.domain.RATIOS`) as the inputs in [0, 1] of the
    ``free`` ratios (values outside the bounds map outside [0, 1])."""
    r = np.atleast_2d(np.asarray(ratios, float))
    out = np.empty((r.shape[0], len(free)))
    for k, name in enumerate(free):
        lo, hi = BOUNDS[name]
        v = r[:, RATIOS.index(name)]
        if name in LOG:
            v, lo, hi = np.log(np.maximum(v, 1e-12)), np.log(lo), np.log(hi)
        out[:, k] = (v - lo) / (hi - lo)
    return out
