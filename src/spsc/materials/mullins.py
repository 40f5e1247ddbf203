"""Ogden–Roxburgh constants of the Mullins effect (R. W. Ogden, D. G. Roxburgh, Proc. R. Soc.
Lond. A 455 (1999) 2861-2877; the β W_m term of Dorfmann & Ogden 2004) and the damage variable
η of eq. (M1), :mod:`spsc.fem.mullins`'s law. A material's own constants are a record
``{"r": ..., "m": ..., "beta": ...}`` (the catalogue's :data:`~.catalogue.MULLINS`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import erf

from spsc.core.errors import require

__all__ = ["MullinsParams"]


@dataclass(frozen=True)
class MullinsParams:
    """Ogden–Roxburgh constants: ``r`` (> 1, the softening's extent), ``m`` (MPa, > 0, its
    spread in energy) and ``beta`` (≥ 0, its growth with the largest energy)."""

    r: float
    m: float
    beta: float = 0.0

    def __post_init__(self):
        require("mullins r", self.r, gt=1, le=1e3)
        require("mullins m", self.m, gt=0, le=100, unit="MPa")
        require("mullins beta", self.beta, ge=0, le=10)

    def eta(self, w0, w_max):
        """(η, ∂η/∂W₀) at the isochoric energies ``w0`` and their largest so far ``w_max``
        (MPa; arrays), eq. (M1)."""
        w_m = np.maximum(w_max, w0)
        s = self.m + self.beta * w_m
        a = (w_m - w0) / s
        eta = 1.0 - erf(a) / self.r
        d = np.where(w_m > w0, 2.0 * np.exp(-a * a) / (self.r * math.sqrt(math.pi) * s), 0.0)
        return eta, d
