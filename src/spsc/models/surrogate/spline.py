"""Cubic splines on a fixed grid as linear weights: S(t) = Σ_j β_j(t) f_j, with not-a-knot
ends (the spline scipy's CubicSpline builds by default), so a map of many designs on the same
grid is interpolated by one matrix product, in NumPy alone."""

from __future__ import annotations

import numpy as np

__all__ = ["SplineGrid"]


class SplineGrid:
    """The not-a-knot cubic spline's weights on the increasing ``grid`` (≥ 4 points)."""

    def __init__(self, grid):
        x = np.asarray(grid, float)
        n, h = x.size, np.diff(x)
        A, R = np.zeros((n, n)), np.zeros((n, n))
        for i in range(1, n - 1):
            A[i, i - 1:i + 2] = h[i - 1] / 6, (h[i - 1] + h[i]) / 3, h[i] / 6
            R[i, i - 1:i + 2] = 1 / h[i - 1], -1 / h[i - 1] - 1 / h[i], 1 / h[i]
        # not-a-knot: the third derivative is continuous at the second and last-but-one points
        A[0, :3] = -1 / h[0], 1 / h[0] + 1 / h[1], -1 / h[1]
        A[-1, -3:] = -1 / h[-2], 1 / h[-2] + 1 / h[-1], -1 / h[-1]
        self.x, self.h, self.M = x, h, np.linalg.solve(A, R)  # second derivatives = M @ f

    def weights(self, t, slope: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
        """(β(t), β′(t)): (… × n) each, the value's and the slope's weights (the end
        intervals' cubics continue beyond the grid); β′ None without ``slope``."""
        t = np.asarray(t, float)
        x, M = self.x, self.M
        i = np.clip(np.searchsorted(x, t) - 1, 0, x.size - 2)
        h = x[i + 1] - x[i]
        a, b = (x[i + 1] - t) / h, (t - x[i]) / h
        Mi, Mj = M[i], M[i + 1]
        W = ((a**3 - a) * h * h / 6)[..., None] * Mi + ((b**3 - b) * h * h / 6)[..., None] * Mj
        parts = [(W, a, b)]
        D = None
        if slope:
            D = (-(3 * a * a - 1) * h / 6)[..., None] * Mi + ((3 * b * b - 1) * h / 6)[..., None] * Mj
            parts.append((D, -1.0 / h, 1.0 / h))
        # the linear part: a at node i and b at node i + 1 (flat indices, no n × n identity)
        at = np.arange(i.size) * x.size + i.ravel()
        for out, lo, hi in parts:
            flat = out.reshape(-1)
            flat[at] += np.ravel(lo)
            flat[at + 1] += np.ravel(hi)
        return W, D
