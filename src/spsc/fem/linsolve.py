"""Moved to :mod:`spsc.fem.engine.linsolve` (this path is kept for code outside ``spsc.fem``)."""

from .engine.linsolve import Factor, available_solvers, factorize, solve_rank_one

__all__ = ["solve_rank_one", "Factor", "factorize", "available_solvers"]
