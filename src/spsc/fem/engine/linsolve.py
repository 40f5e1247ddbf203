"""Sparse direct solvers for the symmetric indefinite Newton systems, chosen by measurement.

The reduced tangent (free unknowns) is symmetric: the mixed u–p hyperelastic block is, and the
follower-pressure stiffness p H is the Hessian of the enclosed volume on the admissible
displacements (the gas term is a separate rank-one update). It is indefinite (the pressure
block is negative definite), so:

* ``pardiso`` — MKL PARDISO through pypardiso, real symmetric indefinite (mtype −2, upper
  triangle, Bunch–Kaufman pivoting). The symbolic analysis (METIS ordering) is reused while
  the sparsity pattern does not change (active set unchanged), and the factorisation reports
  the inertia: more negative pivots than pressure unknowns means the displacement problem has
  lost stability (buckling, snap-through).
* ``pardiso-spd`` — PARDISO's Cholesky (mtype 2) first, for a tangent that is positive
  definite while the structure is stable (the wall model's condensed displacement problem):
  6.3 ms against LDLᵀ's 8.1 ms on the 4k-unknown stadium wall. A non-positive pivot (error −4:
  the matrix is indefinite) falls back to the LDLᵀ above, which counts the negative
  eigenvalues; a Cholesky that succeeds reports none.
* ``superlu`` — SciPy's SuperLU with its default COLAMD ordering, when pypardiso is absent.
  (MMD on Aᵀ + A was 16× slower than COLAMD on these 3D P2 systems.)
* ``superlu-sym`` — SuperLU in symmetric mode (MMD on Aᵀ + A, no off-diagonal pivoting): an
  LDLᵀ-like LU whose U diagonal carries the inertia (Sylvester), for the wall model's condensed
  displacement tangent (small, definite when stable); a vanishing pivot falls back to pivoted
  LU with the inertia unknown. It takes the matrix as assembled (``upper=False``).

Measured on the Type B quarter wall at 40 kPa (``python bench/bench_fem.py --solvers S:L``), one
core, factorisation / refactorisation with the analysis reused / solve:

* 27k unknowns (1.0 mm, 2 layers): PARDISO LDLᵀ 1.1 / 0.32 / 0.04 s; PARDISO LU (mtype 11)
  2.0 s; SuperLU COLAMD 5.9 s; SuperLU MMD_AT_PLUS_A 148 s.
* 78k unknowns (0.7 mm, 3 layers): PARDISO LDLᵀ 6.2 / 5.3 / 0.3 s; SuperLU COLAMD 90 s.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["solve_rank_one", "Factor", "factorize", "available_solvers", "FULL_INPUT"]


def _point_pypardiso_at_mkl() -> None:
    """Name MKL's runtime for pypardiso where pip puts it (``sys.prefix/lib``): unnamed,
    pypardiso searches the whole environment's tree for it, twice per process (1.5 s of a
    3D FEM curve's profile, every CLI call and Dask worker)."""
    import os
    import sys
    from pathlib import Path

    if "PYPARDISO_MKL_RT" not in os.environ:
        found = sorted(Path(sys.prefix, "lib").glob("libmkl_rt.so*"), key=lambda p: len(p.name))
        if found:
            os.environ["PYPARDISO_MKL_RT"] = str(found[0])


@functools.cache
def _probe() -> tuple[str, ...]:
    """The solvers this install has, probed once per process."""
    out = []
    try:
        _point_pypardiso_at_mkl()
        import pypardiso  # noqa: F401

        out.append("pardiso")
    except ImportError:  # pragma: no cover - depends on the install
        pass
    return tuple(out + ["superlu", "superlu-mmd"])


def available_solvers() -> list[str]:
    return list(_probe())


@dataclass(frozen=True, eq=False)
class Factor:
    """A factorisation: ``solve(b)`` for b of shape (n,) or (n, k); ``negative`` the number of
    negative eigenvalues (None when the solver does not report it); ``held()`` whether it
    can still solve (None: always; PARDISO's one factorisation per process is replaced by
    the next)."""

    solve: object
    negative: int | None
    held: object = None

    def __call__(self, b):
        return self.solve(b)

    def current(self) -> bool:
        """Whether this factorisation can still solve."""
        return self.held is None or bool(self.held())


class _Pardiso:
    """One PyPardisoSolver per matrix type for the process: creating one searches the file
    system for libmkl_rt, and keeping it lets the analysis be reused across Newton
    iterations. ``mtype`` −2: real symmetric indefinite (LDLᵀ), 2: positive definite
    (Cholesky)."""

    def __init__(self, mtype: int = -2):
        _point_pypardiso_at_mkl()
        import pypardiso

        self.ps = pypardiso.PyPardisoSolver(mtype=mtype)
        self.ps.set_statistical_info_off()
        self.key = None
        self.U = None
        self.serial = 0  # the factorisation PARDISO holds now

    def factor(self, A, upper: bool = False) -> Factor:
        U = A if upper else sp.triu(A, format="csr")
        U.sort_indices()
        n = U.shape[0]
        if np.any(np.diff(U.indptr) == 0):
            raise np.linalg.LinAlgError("singular matrix: empty row")
        key = (n, U.nnz, hash(U.indptr.tobytes()), hash(U.indices.tobytes()))
        if key != self.key:
            if self.key is not None:
                self.ps.set_phase(-1)
                self.ps._call_pardiso(self.U, np.zeros((self.U.shape[0], 1)))
            self.ps.set_phase(11)
            self.ps._call_pardiso(U, np.zeros((n, 1)))
            self.key = key
            # MKL filled in its defaults (iparm[0] = 1 now): keep them but iparm[7] = 0,
            # iterative refinement only after perturbed pivots. Its default two steps on
            # every solve made one 5x slower (2.2 against 0.4 ms), same residual (issue 26).
            self.ps.iparm[0], self.ps.iparm[7] = 1, 0
        self.ps.set_phase(22)
        self.serial += 1  # a failed factorisation spoils the factors held too
        self.ps._call_pardiso(U, np.zeros((n, 1)))
        self.U = U
        negative = 0 if self.ps.mtype == 2 else int(self.ps.iparm[22])
        ps, serial = self.ps, self.serial

        def solve(b):
            if self.serial != serial:
                # one solver per process: a later factorisation replaced this one's factors
                raise RuntimeError("a PARDISO factor was used after a later factorisation")
            b = np.asarray(b, dtype=float)
            ps.set_phase(33)
            x = ps._call_pardiso(U, np.asfortranarray(b.reshape(n, -1)))
            return x.reshape(b.shape)

        return Factor(solve, negative, lambda: self.serial == serial)


_PARDISO: dict[int, _Pardiso] = {}


def _pardiso(mtype: int) -> _Pardiso:
    if mtype not in _PARDISO:
        _PARDISO[mtype] = _Pardiso(mtype)
    return _PARDISO[mtype]


def _cholesky_first(A, upper: bool) -> Factor:
    """PARDISO's Cholesky, else (not positive definite) its LDLᵀ with the inertia."""
    import pypardiso

    try:
        return _pardiso(2).factor(A, upper)
    except pypardiso.pardiso_wrapper.PyPardisoError as exc:
        if exc.value != -4:  # −4: a zero or negative pivot, the matrix is not definite
            raise
    return _pardiso(-2).factor(A, upper)


def factorize(A: sp.spmatrix, solver: str = "auto", *, upper: bool = False) -> Factor:
    """Factorise the symmetric matrix ``A`` once; the result solves for any right-hand side.
    ``upper``: A holds only its upper triangle (CSR)."""
    if solver == "auto":
        solver = available_solvers()[0]
    if solver == "pardiso":
        return _pardiso(-2).factor(sp.csr_matrix(A), upper)
    if solver == "pardiso-spd":
        return _cholesky_first(sp.csr_matrix(A), upper)
    if upper:
        A = sp.csr_matrix(A)
        A = A + sp.triu(A, k=1).T
    if solver == "superlu-sym":
        return _symmetric_lu(A)
    if solver in ("superlu", "superlu-mmd"):
        spec = "COLAMD" if solver == "superlu" else "MMD_AT_PLUS_A"
        lu = spla.splu(sp.csc_matrix(A), permc_spec=spec)
        return Factor(lambda b: lu.solve(np.asarray(b, dtype=float)), None)
    raise ValueError(f"unknown sparse solver {solver!r}: one of {available_solvers()}")


def _symmetric_lu(A) -> Factor:
    """LDLᵀ-like LU without off-diagonal pivoting (symmetric mode): its U diagonal carries the
    inertia. Where a pivot vanishes SuperLU pivots off the diagonal after all (its row and
    column permutations differ): the signs of U's diagonal then say nothing, and the inertia is
    reported unknown (None) and, like a tiny pivot, the default pivoted LU solves."""
    A = sp.csc_matrix(A)
    try:
        lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
        d = lu.U.diagonal()
        if np.array_equal(lu.perm_r, lu.perm_c) and np.all(np.isfinite(d)) \
                and np.min(np.abs(d)) > 1e-13 * np.max(np.abs(d)):
            return Factor(lu.solve, int(np.sum(d < 0)))
    except RuntimeError:
        pass  # exactly singular in symmetric mode
    return Factor(spla.splu(A).solve, None)


#: solvers that take the matrix as assembled, not its upper triangle
FULL_INPUT = frozenset({"superlu-sym"})


def solve_rank_one(factor_solve, c: float, g: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Solve (K + c g gᵀ) x = r given ``factor_solve`` = K⁻¹ applied to an (n, k) array
    (Sherman–Morrison, one factorisation, two right-hand sides)."""
    sol = factor_solve(np.column_stack([r, g]))
    y, z = sol[:, 0], sol[:, 1]
    return y - z * (c * (g @ y) / (1.0 + c * (g @ z)))
