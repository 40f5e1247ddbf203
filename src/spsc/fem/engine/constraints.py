"""The constraints of one Newton iteration and the reduced tangent they leave.

The plate prescribes its active unknowns (each moved by its jump onto the plate); a rigid tie
(the 3D solid's insert, :class:`~spsc.fem.engine.protocol.Tie`) aliases its slave unknowns onto
one master, u_s = u_m + jump_s. Both are eliminated from the linear system: the tangent is
restricted to the free unknowns (:class:`Reduction`: its upper triangle read straight from the
fixed-pattern CSR, the slaves summed into the master's row and column, PᵀKP; or
:class:`Submatrix`, the free block as assembled, for solvers that take the whole matrix) or,
where nothing is aliased and the solver takes the upper triangle, kept on every unsupported
unknown with the constrained ones as unit rows (:class:`Masked`): its sparsity pattern does not
change with the contact active set, so the solver's symbolic analysis is done once per mesh.
A curved indenter's active heights lean on their nodes' lateral unknowns (``lean``: u_z =
Σ_k ∂S/∂x_k u_k + jump, :mod:`.leaning`), restricted by :class:`~.leaning.Leaning`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

__all__ = ["Constraints", "Reduction", "Submatrix", "Masked", "constraint_key"]


def constraint_key(free, slaves, lean=None) -> bytes:
    """The identity of a constraint set: the free mask, the aliased and the leaning
    unknowns."""
    key = free.tobytes() + (b"" if slaves is None else np.asarray(slaves).tobytes())
    return key if lean is None or not len(lean) else key + b"|" + np.asarray(lean).tobytes()


@dataclass(frozen=True, eq=False)
class Constraints:
    """The constraints of one Newton iteration over the ``n`` unknowns of the Newton system:
    the plate's prescribed unknowns ``presc`` moving by ``jump`` (mm), the tie's
    ``slaves`` following ``master`` plus ``sjump`` (mm) and a curved indenter's ``lean``
    unknowns, each moving by ``ljump`` (mm) plus ``slope`` (k, len(lean)) times the moves of
    its lateral unknowns ``lat`` (k, len(lean)); ``curv`` (k, k, len(lean), 1/mm): the
    surface's Hessian there, for the tangent's curvature term."""

    n: int
    presc: np.ndarray
    jump: np.ndarray
    slaves: np.ndarray
    sjump: np.ndarray
    master: int
    lean: np.ndarray = field(default_factory=lambda: np.zeros(0, int))
    ljump: np.ndarray = field(default_factory=lambda: np.zeros(0))
    lat: np.ndarray = field(default_factory=lambda: np.zeros((0, 0), int))
    slope: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    curv: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0)))

    @classmethod
    def join(cls, n: int, parts) -> "Constraints":
        """The constraints of several bodies at once (:mod:`.bodies`), each part over the
        same ``n`` unknowns: their prescribed, aliased and leaning unknowns side by side, in
        the parts' order. At most one part aliases (one master)."""
        parts = list(parts)
        if len(parts) == 1:
            return parts[0]
        if not parts:
            return cls(n, np.zeros(0, int), np.zeros(0), np.zeros(0, int), np.zeros(0), -1)
        masters = {p.master for p in parts if p.slaves.size}
        if len(masters) > 1:
            raise ValueError("Constraints.join: two bodies alias onto different masters")
        leaning = [p for p in parts if p.lean.size]

        def cat(name, axis=0):
            return np.concatenate([getattr(p, name) for p in leaning], axis=axis)

        lean = {} if not leaning else dict(
            lean=cat("lean"), ljump=cat("ljump"), lat=cat("lat", 1), slope=cat("slope", 1),
            curv=cat("curv", 2))
        return cls(n, np.concatenate([p.presc for p in parts]),
                   np.concatenate([p.jump for p in parts]),
                   np.concatenate([p.slaves for p in parts]),
                   np.concatenate([p.sjump for p in parts]),
                   masters.pop() if masters else -1, **lean)

    def shift(self) -> np.ndarray:
        """The part of the step the constraints fix (full vector)."""
        s = np.zeros(self.n)
        s[self.presc] = self.jump
        s[self.slaves] = self.sjump
        if self.lean.size:
            s[self.lean] = self.ljump
        return s

    def condense(self, v) -> np.ndarray:
        """Pᵀv in full numbering: the slaves' entries added to the master's, a leaning
        unknown's entry times its slopes added to its lateral unknowns', theirs zeroed."""
        if not self.slaves.size and not self.lean.size:
            return v
        w = v.copy()
        if self.slaves.size:
            w[self.master] += v[self.slaves].sum()
            w[self.slaves] = 0.0
        if self.lean.size:
            for k in range(self.lat.shape[0]):
                np.add.at(w, self.lat[k], self.slope[k] * v[self.lean])
            w[self.lean] = 0.0
        return w

    def free(self, fixed) -> np.ndarray:
        """The free unknowns: neither supported (``fixed``), prescribed, aliased nor
        leaning."""
        free = ~fixed
        free[self.presc] = False
        free[self.slaves] = False
        free[self.lean] = False
        return free

    @property
    def reacting(self) -> np.ndarray:
        """The unknowns whose reactions are the indenter's: the leaning ones, then the
        prescribed ones."""
        return np.concatenate([self.lean, self.presc]) if self.lean.size else self.presc

    def nearly_settled(self, tol: float) -> bool:
        """Every constraint holds, a curved body's to ``tol`` (mm: its second-order rest,
        which cannot change which nodes touch nor make the residual a poor merit)."""
        return self.settled or (bool(self.lean.size) and self.held_settled
                                and np.max(np.abs(self.ljump)) <= tol)

    @property
    def held_settled(self) -> bool:
        """The plate's and the tie's constraints hold (jumps ≤ 1e-12 mm)."""
        return max(np.max(np.abs(self.jump), initial=0.0),
                   np.max(np.abs(self.sjump), initial=0.0)) <= 1e-12

    @property
    def settled(self) -> bool:
        """Every constraint holds (jumps ≤ 1e-12 mm)."""
        return max(np.max(np.abs(self.jump), initial=0.0),
                   np.max(np.abs(self.sjump), initial=0.0),
                   np.max(np.abs(self.ljump), initial=0.0)) <= 1e-12


class Reduction:
    """Upper triangle of K restricted to the free unknowns, read straight from the data array
    of the full fixed-pattern CSR (no sparse slicing per iteration); rebuilt when the free set
    changes (supports, contact active set). Aliased unknowns (``slaves``, each u_s = u_master
    + a known jump: a rigid insert's constraints) are summed into the master's row and column,
    PᵀKP, by a precomputed gather."""

    upper = True

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
        self.free = free
        self.key = constraint_key(free, slaves)

    def take(self, v) -> np.ndarray:
        """The system's entries of a full-numbering vector (already condensed)."""
        return v[self.free]

    def put(self, step, dx) -> None:
        """Add the system's solution ``dx`` to the full step."""
        step[self.free] += dx

    def matrix(self, K):
        data = K.data[self.sel]
        if self.gather is not None:
            data = np.bincount(self.gather, weights=data, minlength=len(self.indices))
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n,) * 2)


class Submatrix:
    """K restricted to the free unknowns as assembled (both triangles), K[free][:, free]: for
    solvers that factorise the whole matrix. No aliasing."""

    upper = False

    def __init__(self, free):
        self.free = free
        self.key = constraint_key(free, None)

    def take(self, v) -> np.ndarray:
        return v[self.free]

    def put(self, step, dx) -> None:
        step[self.free] += dx

    def matrix(self, K):
        return K[self.free][:, self.free]


class Masked:
    """Upper triangle of K on every unknown that is free or prescribed by the plate (``free``
    ∪ ``presc``), the prescribed ones as unit rows and columns (their entries zeroed, 1 on the
    diagonal): the same solution on the free unknowns as :class:`Reduction` (Δ = 0 on the
    prescribed ones, whose move is the constraints' shift) and the same negative eigenvalues
    (the unit block adds positive ones), on a pattern that stays the same while the active set
    changes. Needs K's diagonal in its pattern (every assembled unknown has it)."""

    upper = True

    def __init__(self, K, free, presc):
        index = free.copy()
        index[presc] = True
        pat = _upper_pattern(K, index)
        held = ~free[index]  # the system's prescribed unknowns
        self.sel, self.indptr, self.indices, self.n = pat.sel, pat.indptr, pat.indices, pat.n
        self.rows = pat.r  # each stored entry's row (its column: ``indices``)
        rows = np.flatnonzero(held)
        self.unit = pat.diagonal[rows]
        if np.any(self.unit < 0):
            raise ValueError("Masked: a prescribed unknown has no diagonal entry in K's pattern")
        self.zero = np.flatnonzero(held[pat.r] | held[pat.c])
        self.index, self.held = index, held
        self.key = constraint_key(free, None)

    def take(self, v) -> np.ndarray:
        out = v[self.index]
        out[self.held] = 0.0
        return out

    def put(self, step, dx) -> None:
        dx = np.array(dx, dtype=float)
        dx[self.held] = 0.0
        step[self.index] += dx

    def matrix(self, K):
        data = K.data[self.sel]
        data[self.zero] = 0.0
        data[self.unit] = 1.0
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n,) * 2)


@dataclass(frozen=True, eq=False)
class _UpperPattern:
    """The upper triangle of a CSR pattern restricted to the unknowns ``index``: which stored
    entries (``sel``), their new rows and columns, the CSR arrays and each row's diagonal
    entry (its position among ``sel``, −1 if absent)."""

    sel: np.ndarray
    r: np.ndarray
    c: np.ndarray
    indptr: np.ndarray
    indices: np.ndarray
    diagonal: np.ndarray
    n: int


#: the last patterns built, keyed by the matrix's index buffer (kept alive) and the unknowns:
#: a model assembles every tangent on one pattern, and the active set changes only ``held``
_PATTERNS: dict = {}


def _upper_pattern(K, index) -> _UpperPattern:
    # scipy wraps the model's fixed index array in a new view each time: key on its buffer
    # (held alive below, so no other array can take its address)
    buffer = K.indices.__array_interface__["data"][0]
    key = (buffer, K.indices.size, K.shape[0], hash(index.tobytes()))
    hit = _PATTERNS.get(key)
    if hit is not None and np.array_equal(hit[1], index):
        return hit[2]
    rows = np.repeat(np.arange(K.shape[0]), np.diff(K.indptr))
    new = np.cumsum(index) - 1
    r_all, c_all = new[rows], new[K.indices]
    keep = index[rows] & index[K.indices] & (r_all <= c_all)
    sel = np.nonzero(keep)[0]
    r, c = r_all[keep], c_all[keep]
    n = int(index.sum())
    diagonal = np.full(n, -1, np.int64)
    on = np.flatnonzero(r == c)
    diagonal[r[on]] = on
    pat = _UpperPattern(sel, r, c, np.concatenate([[0], np.cumsum(np.bincount(r, minlength=n))]),
                        c.astype(np.int32), diagonal, n)
    if len(_PATTERNS) >= 4:
        _PATTERNS.pop(next(iter(_PATTERNS)))
    _PATTERNS[key] = (K.indices, index.copy(), pat)
    return pat
