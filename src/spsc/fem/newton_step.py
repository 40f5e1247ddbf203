"""The constrained Newton step: the free unknowns' tangent read from the fixed-pattern CSR, the
plate's prescribed unknowns moved by their jumps, a rigid insert's unknowns aliased onto its own
(u_s = u_m + jump, eliminated as PᵀKP), and the gas's rank-one term by Sherman–Morrison."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .linsolve import factorize, solve_rank_one

__all__ = ["Reduction", "Constraints", "linear_step", "constraint_key"]


class Reduction:
    """Upper triangle of K restricted to the free unknowns, read straight from the data array
    of the full fixed-pattern CSR (no sparse slicing per iteration); rebuilt when the free set
    changes (supports, contact active set). Aliased unknowns (``slaves``, each u_s = u_master
    + a known jump: a rigid insert's constraints) are summed into the master's row and column,
    PᵀKP, by a precomputed gather."""

    def __init__(self, K, free, slaves=None, master=None):
        rows = np.repeat(np.arange(K.shape[0]), np.diff(K.indptr))
        cols = K.indices
        new = np.cumsum(free) - 1
        live = free
        aliased = slaves is not None and len(slaves) > 0
        if aliased:
            new, live = new.copy(), free.copy()
            new[slaves], live[slaves] = new[master], True
        r_all, c_all = new[rows], new[cols]
        keep = live[rows] & live[cols] & (r_all <= c_all)
        self.sel = np.nonzero(keep)[0]
        r, c = r_all[keep], c_all[keep]
        n = int(free.sum())
        self.gather = None
        if aliased:
            key, self.gather = np.unique(r.astype(np.int64) * n + c, return_inverse=True)
            r, c = key // n, key % n
        self.indptr = np.concatenate([[0], np.cumsum(np.bincount(r, minlength=n))])
        self.indices = c.astype(np.int32)
        self.n = n
        self.key = constraint_key(free, slaves)

    def upper(self, K):
        data = K.data[self.sel]
        if self.gather is not None:
            data = np.bincount(self.gather, weights=data, minlength=len(self.indices))
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n,) * 2)


def constraint_key(free, slaves) -> bytes:
    return free.tobytes() + (b"" if slaves is None else np.asarray(slaves).tobytes())


@dataclass(frozen=True, eq=False)
class Constraints:
    """The constraints of one Newton iteration: the plate's prescribed unknowns ``presc``
    moving by ``jump``, and the insert's ``slaves`` following ``master`` plus ``sjump``."""

    n: int
    presc: np.ndarray
    jump: np.ndarray
    slaves: np.ndarray
    sjump: np.ndarray
    master: int

    def shift(self) -> np.ndarray:
        """The part of the step the constraints fix (full vector)."""
        s = np.zeros(self.n)
        s[self.presc] = self.jump
        s[self.slaves] = self.sjump
        return s

    def condense(self, v) -> np.ndarray:
        """Pᵀv in full numbering: the slaves' entries added to the master's, theirs zeroed."""
        if not self.slaves.size:
            return v
        w = v.copy()
        w[self.master] += v[self.slaves].sum()
        w[self.slaves] = 0.0
        return w

    @property
    def settled(self) -> bool:
        return max(np.max(np.abs(self.jump), initial=0.0),
                   np.max(np.abs(self.sjump), initial=0.0)) <= 1e-12


def linear_step(model, ev, reduction, free, con: Constraints, settings):
    """The Newton step on the free unknowns, PᵀKP Δy = −Pᵀ(r + K s) with s the constrained part
    of the step (the plate's jump, the insert's) and P the aliasing of the insert's slaves (the
    gas's rank-one term by Sherman–Morrison): (step, negative pivots of the factor or None)."""
    n_u, n = model.disc.n_u, model.disc.n
    factor = factorize(reduction.upper(ev.K), settings.solver, upper=True)
    s = con.shift()
    moved = bool(np.any(s))
    rhs = -ev.r - ev.K @ s if moved else -ev.r
    rhs = con.condense(rhs)[free]
    if ev.c > 0.0:
        gf = np.zeros(n)
        gf[:n_u] = ev.g
        gc = con.condense(gf)[free]
        if moved:
            rhs -= ev.c * gc * (gf @ s)
        dx = solve_rank_one(factor, ev.c, gc, rhs)
    else:
        dx = factor(rhs)
    step = s
    step[free] += dx
    if con.slaves.size:
        step[con.slaves] += step[con.master]
    return step, factor.negative
