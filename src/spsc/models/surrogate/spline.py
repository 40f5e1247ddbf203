"""Cubic splines on a fixed grid as linear weights: S(t) = Σ_j β_j(t) f_j, with not-a-knot
ends (the spline scipy's CubicSpline builds by default), so a map of many designs on the same
grid is interpolated by one matrix product, in NumPy alone."""

from __future__ import annotations

import numpy as np

__all__ = ["SplineGrid"]

_POWERS = np.arange(4.0)


class SplineGrid:
    """The not-a-knot cubic spline's weights on the increasing ``grid`` (≥ 4 points).

    On the interval [x_i, x_i+1] of length h_i, with b = (t − x_i)/h_i and M the second
    derivatives' weights (M f = S''), the weights are the cubic in b

        β(t) = (1 − b) e_i + b e_i+1 + (h_i²/6) [(−2b + 3b² − b³) M_i + (b³ − b) M_i+1],

    stored as its four coefficient rows per interval (``table``, (n − 1) × 4 × n), so a batch
    of points is one gather and one product with (1, b, b², b³) (the end intervals' cubics continue beyond the
    grid)."""

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
        c = (h * h / 6)[:, None]
        Mi, Mj, E = self.M[:-1], self.M[1:], np.eye(n)
        self.table = np.stack([E[:-1], c * (-2 * Mi - Mj) - E[:-1] + E[1:], c * (3 * Mi),
                               c * (Mj - Mi)], axis=1)

    def weights(self, t, slope: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
        """(β(t), β′(t)): (… × n) each, the value's and the slope's weights (the end
        intervals' cubics continue beyond the grid); β′ None without ``slope``."""
        t = np.asarray(t, float)
        i = np.searchsorted(self.x, t) - 1
        np.maximum(i, 0, out=i)
        np.minimum(i, self.x.size - 2, out=i)
        b = (t - self.x[i]) / self.h[i]
        P = self.table[i]  # … × 4 × n
        powers = np.empty(b.shape + (4,))  # 1, b, b², b³
        powers[..., 0] = 1.0
        powers[..., 1] = b
        np.multiply(b, b, out=powers[..., 2])
        np.multiply(powers[..., 2], b, out=powers[..., 3])
        W = np.matmul(powers[..., None, :], P)[..., 0, :]
        if not slope:
            return W, None
        slopes = powers[..., :3] * (_POWERS[1:] / self.h[i][..., None])  # 1, 2b, 3b² over h
        D = np.matmul(slopes[..., None, :], P[..., 1:, :])[..., 0, :]
        return W, D
