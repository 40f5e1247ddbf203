"""Moved to :mod:`spsc.fem.solid.model`: this path re-exports it for code outside ``spsc.fem``
until that code imports the new path."""

from .solid.model import CLAMPED_QUARTER, Evaluation, FEMModel, Load

__all__ = ["CLAMPED_QUARTER", "Evaluation", "FEMModel", "Load"]
