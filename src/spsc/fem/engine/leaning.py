"""A curved indenter's constraints eliminated from the Newton system: each active node's
height leans on its own lateral unknowns.

An active node stays on the body's lower surface, u_z = φ(u_lat) = z_tip − gap + S(X_lat +
u_lat) − Z (:mod:`spsc.core.indenter`), so its height is no unknown of its own: with P the
map from the reduced unknowns to all (1 on a free unknown, ∂S/∂x_k from a lateral unknown to
its node's height, 1 from the tie's master to its slaves) the reduced problem's gradient is
Pᵀr and its Hessian

    PᵀKP + Σ_a r_z,a ∇²S_a    (on node a's lateral unknowns),

the second term the surface's curvature carrying the contact force (the consistent tangent:
Newton converges quadratically on a sphere as on the plate). The reaction left in r at a
node, (r_lat, r_z) = r_z (−∇S, 1), is normal to the surface: the contact is frictionless. On
the plate (∇S = 0) this is the prescription of :mod:`.active_set`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .constraints import Constraints, constraint_key

__all__ = ["Leaning"]


class Leaning:
    """Upper triangle of PᵀKP (+ the curvature term) on the free unknowns. The gather from
    K's fixed-pattern data is built once per constraint set; the slopes and the curvature
    term are bound per iteration (:meth:`bind`)."""

    upper = True
    aliases = True  #: :meth:`put` moves the tie's slaves itself

    def __init__(self, K, free, con: Constraints):
        n = int(free.sum())
        new = np.cumsum(free) - 1
        lat_free = free[con.lat]  # (k, na): a lateral unknown on a symmetry plane drops out
        count = free.astype(np.int64)
        count[con.lean] = lat_free.sum(axis=0)
        count[con.slaves] = 1
        tptr = np.concatenate([[0], np.cumsum(count)])
        column = np.zeros(tptr[-1], np.int64)  # each term's reduced unknown
        on = np.flatnonzero(free)
        column[tptr[on]] = new[on]
        column[tptr[con.slaves]] = new[con.master] if con.slaves.size else 0
        slot = tptr[con.lean][None, :] + np.cumsum(lat_free, axis=0) - lat_free
        self.slope_slot = slot[lat_free]
        self.slope_take = np.flatnonzero(lat_free.ravel())
        column[self.slope_slot] = new[con.lat[lat_free]]
        self.n_terms = int(tptr[-1])
        rows = np.repeat(np.arange(K.shape[0]), np.diff(K.indptr))
        cols = K.indices
        ci, cj = count[rows], count[cols]
        pairs = ci * cj
        self.entry = np.repeat(np.arange(K.nnz), pairs)
        off = np.arange(self.entry.size) - np.repeat(np.cumsum(pairs) - pairs, pairs)
        cje = cj[self.entry]
        ti = tptr[rows[self.entry]] + off // cje
        tj = tptr[cols[self.entry]] + off % cje
        a, b = column[ti], column[tj]
        keep = a <= b
        self.entry, self.ti, self.tj = self.entry[keep], ti[keep], tj[keep]
        uniq, self.gather = np.unique(a[keep] * n + b[keep], return_inverse=True)
        self.indptr = np.searchsorted(uniq, np.arange(n + 1) * n)
        self.indices = (uniq % n).astype(np.int32)
        self._curvature_slots(con, free, new, n, uniq)
        self.n, self.new, self.free = n, new, free
        self.key = constraint_key(free, con.slaves, con.lean)
        self.con, self.weight, self.cval = con, None, None

    def _curvature_slots(self, con, free, new, n, uniq) -> None:
        """Where each active node's ∇²S term lands in the reduced data (its lateral block)."""
        k, na = con.lat.shape
        kk, ll, aa = np.meshgrid(np.arange(k), np.arange(k), np.arange(na), indexing="ij")
        la, lb = con.lat[kk, aa], con.lat[ll, aa]
        ok = free[la] & free[lb]
        ra, rb = new[la], new[lb]
        ok &= ra <= rb
        key = ra[ok] * n + rb[ok]
        pos = np.searchsorted(uniq, key)
        if np.any(pos >= uniq.size) or np.any(uniq[np.minimum(pos, uniq.size - 1)] != key):
            raise ValueError("Leaning: a node's lateral block is missing from K's pattern")
        self.cpos, self.cflat, self.cnode = pos, np.flatnonzero(ok.ravel()), aa[ok]

    def bind(self, con: Constraints, r=None) -> "Leaning":
        """Take ``con``'s slopes and curvatures and the reactions r_z of the residual ``r``
        (N; None: no curvature term)."""
        coef = np.ones(self.n_terms)
        coef[self.slope_slot] = con.slope.ravel()[self.slope_take]
        self.weight = coef[self.ti] * coef[self.tj]
        self.cval = np.zeros(self.cpos.size) if r is None else \
            np.asarray(r)[con.lean][self.cnode] * con.curv.ravel()[self.cflat]
        self.con = con
        return self

    def take(self, v) -> np.ndarray:
        """The system's entries of a full-numbering vector (already condensed)."""
        return v[self.free]

    def put(self, step, dx) -> None:
        """Add P dx to the full step: the free unknowns, the leaning heights, the slaves."""
        con = self.con
        step[self.free] += dx
        for k in range(con.lat.shape[0]):
            lat = con.lat[k]
            on = self.free[lat]
            step[con.lean[on]] += con.slope[k, on] * dx[self.new[lat[on]]]
        if con.slaves.size:
            step[con.slaves] += step[con.master]

    def matrix(self, K):
        data = np.bincount(self.gather, weights=K.data[self.entry] * self.weight,
                           minlength=len(self.indices))
        np.add.at(data, self.cpos, self.cval)
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n,) * 2)
