"""Threads for the wall model's arithmetic: its dense blocks are small and batched, its sparse
factorisation is not.

OpenBLAS (NumPy's BLAS here) spins its threads on small blocks: one assembly of the wall took
2.8 s instead of 0.01 s on the loaded 2-core machine, so the wall runs with one OpenBLAS thread.
PARDISO (MKL, a BLAS of its own to threadpoolctl) keeps its threads: the Table 1 stadium's
4k-unknown Cholesky takes 4.7 ms on two against 8.1 ms on one, and the whole curve 1.8 → 1.6 s
(issue 26). Where MKL's threads are already capped (``MKL_NUM_THREADS=1`` in the sweep's Dask
workers, :data:`spsc.study.executor.WORKER_ENV`) the cap stands.
"""

from __future__ import annotations

__all__ = ["one_blas_thread"]


def one_blas_thread():
    """A context in which OpenBLAS (and BLIS) use one thread; MKL keeps its own setting."""
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits={"openblas": 1, "blis": 1})
