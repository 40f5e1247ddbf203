"""A factorisation updated for a few changed contact constraints (Sherman–Morrison–Woodbury).

When the plate's active set changes by k unknowns, the masked tangent
(:class:`~.constraints.Masked`: every unsupported unknown kept, the prescribed ones as unit
rows and columns) changes only in those k rows and columns: A₁ = A₀ + E with E = E_Δ P_Δᵀ +
P_Δ E_Δᵀ − P_Δ E_ΔΔ P_Δᵀ = U C Uᵀ, U = [E_Δ, P_Δ] (n × 2k), C = [[0, I], [I, −E_ΔΔ]],
C⁻¹ = [[E_ΔΔ, I], [I, 0]]. Then

    A₁⁻¹ b = y − Z S⁻¹ Uᵀ y,   y = A₀⁻¹ b,   Z = A₀⁻¹ U,   S = C⁻¹ + Uᵀ Z,

one 2k-column solve with A₀'s factorisation and a 2k × 2k dense system instead of a new
factorisation. Both matrices are of one tangent (the factorised one): the step is a modified
Newton step on the new set; its inertia follows from A₀'s by Haynsworth's inertia additivity.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from .constraints import Masked
from .linsolve import Factor

__all__ = ["updated"]


def _masked(values, r, c, held) -> np.ndarray:
    """Entries (r, c) of a :class:`~.constraints.Masked` matrix with the prescribed unknowns
    ``held``: K's value, 0 in a prescribed row or column, 1 on a prescribed diagonal."""
    out = np.where(held[r] | held[c], 0.0, values)
    out[(r == c) & held[r]] = 1.0
    return out


def updated(factor: Factor, old, new, K, max_rank: int) -> Factor | None:
    """A factorisation of ``new``'s restriction of K from ``factor``, that of ``old``'s, when
    both are :class:`~.constraints.Masked` on the same unknowns and at most ``max_rank``
    of them changed between prescribed and free; else None."""
    if not (isinstance(old, Masked) and isinstance(new, Masked)) \
            or not np.array_equal(old.index, new.index) or not factor.current():
        return None
    delta = np.flatnonzero(old.held != new.held)
    k = delta.size
    if k == 0 or k > max_rank:
        return None
    # E's upper triangle on the common pattern: nonzero only in the changed rows and columns
    n = new.n
    col = np.full(n, -1)
    col[delta] = np.arange(k)
    r, c = new.rows, new.indices
    p = np.flatnonzero((col[r] >= 0) | (col[c] >= 0))
    r, c, kv = r[p], c[p].astype(np.int64), K.data[new.sel[p]]
    v = _masked(kv, r, c, new.held) - _masked(kv, r, c, old.held)
    E = np.zeros((n, k))  # E_Δ: the columns Δ of the symmetric E
    on = col[c] >= 0
    np.add.at(E, (r[on], col[c[on]]), v[on])
    below = (col[r] >= 0) & (r != c)
    np.add.at(E, (c[below], col[r[below]]), v[below])
    P = np.zeros((n, k))
    P[delta, np.arange(k)] = 1.0
    U = np.hstack([E, P])
    eye = np.eye(k)
    c_inv = np.block([[E[delta], eye], [eye, np.zeros((k, k))]])
    Z = factor(U)
    S = c_inv + U.T @ Z
    lu = sla.lu_factor(S)

    def solve(b):
        y = factor(b)
        return y - Z @ sla.lu_solve(lu, U.T @ y)

    return Factor(solve, _negative(factor.negative, S), factor.current)


def _negative(before, S) -> int | None:
    """A₁'s negative eigenvalues from A₀'s: the bordered [[A₀, U], [Uᵀ, −C⁻¹]] has the
    inertia of A₀ plus that of its Schur complement −S, and of −C⁻¹ plus that of A₁
    (Haynsworth), so neg(A₁) = neg(A₀) + pos(S) − pos(C⁻¹), and pos(C⁻¹) = k:
    C⁻¹ = Pᵀ [[0, I], [I, 0]] P with P = [[I, 0], [E_ΔΔ/2, I]]. None if A₀'s is unknown."""
    if before is None:
        return None
    S = 0.5 * (S + S.T)  # symmetric up to round-off
    return int(before + np.sum(np.linalg.eigvalsh(S) > 0) - S.shape[0] // 2)
