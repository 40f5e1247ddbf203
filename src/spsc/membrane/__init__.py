"""Fast physics of the SPSC: the lumped air-spring model (eqs. 1–9), the simplified
intersection model, the Yang–Feng membrane problem solved by a global Newton on a box-scheme
discretisation (eqs. 15–38), and identification from bench data (eqs. 39–40). The laws it
solves with are :mod:`spsc.materials`.

Every model returns a :class:`Curve` (``spsc.core.curve``).
"""

from spsc.core.curve import CURVE_COLUMNS, Curve
from .identify import BenchData, identify, predict, read_bench
from .lumped import (LOW_STIFFNESS_RESERVOIR_MM3, Setup, jnd_depth, lumped_curve,
                     mean_sensitivity, mean_stiffness)
from .simplified import simplified_curve
from .shape import Shape
from .solver import Inflation, MembraneResult, SolverSettings, inflate, solve

__all__ = [
    "CURVE_COLUMNS",
    "BenchData",
    "Curve",
    "LOW_STIFFNESS_RESERVOIR_MM3",
    "MembraneResult",
    "Setup",
    "Shape",
    "SolverSettings",
    "Inflation",
    "identify",
    "inflate",
    "jnd_depth",
    "lumped_curve",
    "mean_sensitivity",
    "mean_stiffness",
    "predict",
    "read_bench",
    "simplified_curve",
    "solve",
]
