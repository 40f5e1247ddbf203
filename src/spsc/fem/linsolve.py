"""Moved to :mod:`spsc.fem.engine.linsolve`: this path re-exports it for code outside ``spsc.fem``
until that code imports the new path."""

from .engine.linsolve import Factor, available_solvers, factorize, solve_rank_one

__all__ = ["Factor", "available_solvers", "factorize", "solve_rank_one"]
