"""The cavity volume of many chambers at once, in closed form (the chamber's own
:meth:`~spsc.cad.geometry.SPSCGeometry.cavity_volume` is this for one)."""

from __future__ import annotations

import numpy as np

__all__ = ["cavity_volumes"]


def cavity_volumes(w, h, l, n1, n2, cy):
    """The cavity volume (mm³) of chambers given as arrays (or numbers) of their parameters,
    V = ∫₀ʰ [π r(z)² + 2 l r(z)] dz with r(z) = w̄ (1 − |z/h̄ − c_y|^n2)^(1/n1) (eqs. 10–14),
    exactly: with s = z/h̄ − c_y running from −c_y to 1, each integral is
    ∫₀^S (1 − s^n2)^a ds = B(S^n2; 1/n2, a + 1) / n2, an incomplete beta function, taken on
    both sides of the widest section (s = 0)."""
    from scipy.special import beta, betainc  # at the top, every verb's start-up paid for it

    w, h, l, n1, n2, cy = np.broadcast_arrays(*(np.asarray(v, float)
                                                for v in (w, h, l, n1, n2, cy)))
    h_bar = h / (1.0 + cy)
    w_bar = w / (1.0 - cy**n2) ** (1.0 / n1)

    def below(S, a):  # ∫₀^S (1 − s^n2)^a ds
        return betainc(1.0 / n2, a + 1.0, S**n2) * beta(1.0 / n2, a + 1.0) / n2

    def span(a):  # ∫ from s = −c_y to 1
        return below(cy, a) + below(1.0, a)

    return np.pi * h_bar * w_bar**2 * span(2.0 / n1) + 2.0 * l * h_bar * w_bar * span(1.0 / n1)
