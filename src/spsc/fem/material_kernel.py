"""The nearly incompressible law's stress and tangent at every quadrature point, compiled
(Numba): the same formulas as :meth:`~spsc.fem.material.NearlyIncompressible.stress_tangent`,
one point at a time in registers instead of some thirty NumPy passes over (n, 3, 3) arrays
(3,400 points of a stadium wall: 6.4 ms → 0.3 ms; issue 26's profile).

The catalogue law's derivatives W1 = ∂W/∂Ī1, W2, W11, W12, W22 stay NumPy (any law of
:mod:`spsc.materials`); the kernels take them as arrays. Where Numba is absent the NumPy
formulas run (:data:`AVAILABLE`).
"""

from __future__ import annotations

import numpy as np

try:  # pragma: no cover - depends on the install
    from numba import njit

    AVAILABLE = True
except ImportError:  # pragma: no cover
    AVAILABLE = False

    def njit(*args, **kwargs):
        return (lambda f: f) if not args or not callable(args[0]) else args[0]

__all__ = ["AVAILABLE", "cofactor", "determinant", "invariants", "stress", "stress_tangent"]


@njit(cache=True, inline="always")
def _point(f, C, G, H):
    """Fill C = FᵀF, G = F⁻ᵀ and H = I1 F − F C of one point ``f`` (3×3 scratch arrays, no
    allocation: small NumPy products in a loop would call BLAS); return (I1, I2, J)."""
    for i in range(3):
        for j in range(3):
            C[i, j] = f[0, i] * f[0, j] + f[1, i] * f[1, j] + f[2, i] * f[2, j]
    I1 = C[0, 0] + C[1, 1] + C[2, 2]
    cc = 0.0
    for i in range(3):
        for j in range(3):
            cc += C[i, j] * C[i, j]
    I2 = 0.5 * (I1 * I1 - cc)
    # the cofactor matrix; G_iJ = (F⁻¹)_Ji = cof_iJ / J
    G[0, 0] = f[1, 1] * f[2, 2] - f[1, 2] * f[2, 1]
    G[0, 1] = f[1, 2] * f[2, 0] - f[1, 0] * f[2, 2]
    G[0, 2] = f[1, 0] * f[2, 1] - f[1, 1] * f[2, 0]
    G[1, 0] = f[0, 2] * f[2, 1] - f[0, 1] * f[2, 2]
    G[1, 1] = f[0, 0] * f[2, 2] - f[0, 2] * f[2, 0]
    G[1, 2] = f[0, 1] * f[2, 0] - f[0, 0] * f[2, 1]
    G[2, 0] = f[0, 1] * f[1, 2] - f[0, 2] * f[1, 1]
    G[2, 1] = f[0, 2] * f[1, 0] - f[0, 0] * f[1, 2]
    G[2, 2] = f[0, 0] * f[1, 1] - f[0, 1] * f[1, 0]
    J = f[0, 0] * G[0, 0] + f[0, 1] * G[0, 1] + f[0, 2] * G[0, 2]
    for i in range(3):
        for j in range(3):
            G[i, j] /= J
            H[i, j] = I1 * f[i, j] - (f[i, 0] * C[0, j] + f[i, 1] * C[1, j]
                                      + f[i, 2] * C[2, j])
    return I1, I2, J


@njit(cache=True, inline="always")
def _isochoric(f, G, H, I1, I2, j23, j43, i, j):
    """(∂Ī1/∂F, ∂Ī2/∂F) at entry (i, j) of one point, j23 = J^(−2/3), j43 = J^(−4/3) (eq. of
    :class:`~spsc.fem.material.NearlyIncompressible`)."""
    return (j23 * (2.0 * f[i, j] - (2.0 / 3.0) * I1 * G[i, j]),
            j43 * (2.0 * H[i, j] - (4.0 / 3.0) * I2 * G[i, j]))


@njit(cache=True)
def _determinant(F):
    n = F.shape[0]
    J = np.empty(n)
    for k in range(n):
        f = F[k]
        J[k] = (f[0, 0] * (f[1, 1] * f[2, 2] - f[1, 2] * f[2, 1])
                + f[0, 1] * (f[1, 2] * f[2, 0] - f[1, 0] * f[2, 2])
                + f[0, 2] * (f[1, 0] * f[2, 1] - f[1, 1] * f[2, 0]))
    return J


@njit(cache=True)
def _cofactor(F):
    n = F.shape[0]
    J, cof = np.empty(n), np.empty((n, 3, 3))
    C, H = np.empty((3, 3)), np.empty((3, 3))
    for k in range(n):
        _, _, J[k] = _point(F[k], C, cof[k], H)
        cof[k] *= J[k]
    return J, cof


@njit(cache=True)
def _invariants(F):
    n = F.shape[0]
    I1, I2, J = np.empty(n), np.empty(n), np.empty(n)
    C, G, H = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    for k in range(n):
        I1[k], I2[k], J[k] = _point(F[k], C, G, H)
    return I1, I2, J


@njit(cache=True)
def _stress(F, p, W1, W2):
    n = F.shape[0]
    P = np.empty((n, 3, 3))
    C, G, H = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    for k in range(n):
        f = F[k]
        I1, I2, J = _point(f, C, G, H)
        j23, j43 = J ** (-2.0 / 3.0), J ** (-4.0 / 3.0)
        pJ = p[k] * J
        for i in range(3):
            for j in range(3):
                d1, d2 = _isochoric(f, G, H, I1, I2, j23, j43, i, j)
                P[k, i, j] = W1[k] * d1 + W2[k] * d2 + pJ * G[i, j]
    return P


@njit(cache=True)
def _tangent(F, p, W1, W2, W11, W12, W22):
    n = F.shape[0]
    P = np.empty((n, 3, 3))
    A = np.empty((n, 9, 9))
    C, G, H, b = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    U = np.empty((5, 9))
    for k in range(n):
        f = F[k]
        I1, I2, J = _point(f, C, G, H)
        j23 = J ** (-2.0 / 3.0)
        j43 = J ** (-4.0 / 3.0)
        pJ = p[k] * J
        w1, w2 = W1[k], W2[k]
        for i in range(3):
            for j in range(3):
                a = 3 * i + j
                U[0, a], U[1, a] = _isochoric(f, G, H, I1, I2, j23, j43, i, j)
                U[2, a], U[3, a], U[4, a] = G[i, j], f[i, j], H[i, j]
                P[k, i, j] = w1 * U[0, a] + w2 * U[1, a] + pJ * G[i, j]
                b[i, j] = f[i, 0] * f[j, 0] + f[i, 1] * f[j, 1] + f[i, 2] * f[j, 2]
        a1, a2 = w1 * j23, w2 * j43
        # the outer products Σ M_mn U_m ⊗ U_n (M as in stress_tangent_numpy)
        m00, m11, m01 = W11[k], W22[k], W12[k]
        m02, m12 = -(2.0 / 3.0) * w1, -(4.0 / 3.0) * w2
        m23, m33, m24, m22 = -(4.0 / 3.0) * a1, 4.0 * a2, -(8.0 / 3.0) * a2, pJ
        diag = 2.0 * a1 + 2.0 * a2 * I1
        cG = (2.0 / 3.0) * a1 * I1 + (4.0 / 3.0) * a2 * I2 - pJ
        two_a2 = 2.0 * a2
        # 𝔸 = ∂²Ψ/∂F∂F has the major symmetry: the upper triangle, mirrored
        for a in range(9):
            i, jj = a // 3, a % 3
            u0, u1, u2, u3 = U[0, a], U[1, a], U[2, a], U[3, a]
            for c in range(a, 9):
                kk, ll = c // 3, c % 3
                v = (u0 * (m00 * U[0, c] + m01 * U[1, c] + m02 * U[2, c])
                     + u1 * (m01 * U[0, c] + m11 * U[1, c] + m12 * U[2, c])
                     + u2 * (m22 * U[2, c] + m23 * U[3, c] + m24 * U[4, c])
                     + u3 * m33 * U[3, c])
                if a == c:
                    v += diag
                if i == kk:
                    v -= two_a2 * C[jj, ll]
                if jj == ll:
                    v -= two_a2 * b[i, kk]
                A[k, a, c] = A[k, c, a] = v + cG * G[i, ll] * G[kk, jj] \
                    - two_a2 * f[i, ll] * f[kk, jj]
    return P, A


def _flat(F, p):
    F = np.asarray(F, dtype=float)
    shape = F.shape[:-2]
    Ff = np.ascontiguousarray(F.reshape(-1, 3, 3))
    pf = np.ascontiguousarray(np.broadcast_to(np.asarray(p, dtype=float), shape).ravel())
    return shape, Ff, pf


def _flat1(x, shape):
    return np.ascontiguousarray(np.broadcast_to(np.asarray(x, dtype=float), shape).ravel())


def determinant(F):
    """J = det F for ``F`` (..., 3, 3) (NumPy's LU-based det where Numba is absent)."""
    if not AVAILABLE:
        return np.linalg.det(F)
    shape, Ff, _ = _flat(F, 0.0)
    return _determinant(Ff).reshape(shape)


def cofactor(F):
    """(J, J F⁻ᵀ): the determinant and the cofactor matrix of ``F`` (..., 3, 3)."""
    if not AVAILABLE:
        J = np.linalg.det(F)
        return J, J[..., None, None] * np.swapaxes(np.linalg.inv(F), -1, -2)
    shape, Ff, _ = _flat(F, 0.0)
    J, cof = _cofactor(Ff)
    return J.reshape(shape), cof.reshape(shape + (3, 3))


def invariants(F):
    """(I1, I2, J) of C = FᵀF for ``F`` (..., 3, 3)."""
    shape, Ff, _ = _flat(F, 0.0)
    return tuple(v.reshape(shape) for v in _invariants(Ff))


def stress(F, p, W1, W2):
    """The first Piola–Kirchhoff stress (MPa, (..., 3, 3)) at ``F`` with the pressure ``p``
    and the law's first derivatives W1, W2 at the isochoric invariants (eq. of
    :class:`~spsc.fem.material.NearlyIncompressible`)."""
    shape, Ff, pf = _flat(F, p)
    return _stress(Ff, pf, _flat1(W1, shape), _flat1(W2, shape)).reshape(shape + (3, 3))


def stress_tangent(F, p, W1, W2, W11, W12, W22):
    """(P, 𝔸): the stress and 𝔸 = ∂P/∂F ((..., 3, 3, 3, 3), index order [i, J, k, L])."""
    shape, Ff, pf = _flat(F, p)
    P, A = _tangent(Ff, pf, *(_flat1(w, shape) for w in (W1, W2, W11, W12, W22)))
    return P.reshape(shape + (3, 3)), A.reshape(shape + (3, 3, 3, 3))
