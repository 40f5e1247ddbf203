"""Membrane tensions of an incompressible hyperelastic sheet under biaxial stretch (eqs. 21–24).

T_i = t σ_i (N/mm, per unit deformed length). With W(I1, I2) of :mod:`.materials`,
T1 = (t0/λ2) ∂W/∂λ1 and T2 = (t0/λ1) ∂W/∂λ2, which expand to eqs. 22–23.
"""

from __future__ import annotations

import numpy as np

from spsc.materials import Material

__all__ = ["invariants", "tensions", "relaxed_tensions", "strain_energy_density"]


def invariants(l1, l2):
    """I1, I2 of eq. 24 for principal stretches λ1, λ2 and λ3 = 1/(λ1λ2) (eq. 21)."""
    a, b = l1 * l1, l2 * l2
    c = 1.0 / (a * b)
    return a + b + c, 1.0 / a + 1.0 / b + a * b


def strain_energy_density(material: Material, l1, l2):
    """W(λ1, λ2) in MPa (per unit reference volume)."""
    if material.kind == "stretches":
        return material.stretch_energy(l1, l2, 1.0 / (l1 * l2))
    return material.energy(*invariants(l1, l2))


def tensions(material: Material, t0: float, l1, l2):
    """(T1, T2) in N/mm, eqs. 22–23, for wall thickness t0 (mm) and stretches λ1, λ2.

    T1 = 2 t0 (λ1/λ2 − 1/(λ1³λ2³)) (W1 + λ2² W2),  T2 = 2 t0 (λ2/λ1 − 1/(λ1³λ2³)) (W1 + λ1² W2).

    A law in the principal stretches (Ogden's): T1 = t0 (τ1 − τ3)/(λ1 λ2), T2 likewise, with
    τa = λa ∂W/∂λa less their mean (:meth:`~spsc.materials.ogden.Ogden.kirchhoff`).
    """
    if material.kind == "stretches":
        l1, l2 = np.broadcast_arrays(np.asarray(l1, float), np.asarray(l2, float))
        tau = material.kirchhoff(np.stack([l1, l2, 1.0 / (l1 * l2)], axis=-1))
        scale = t0 / (l1 * l2)
        return scale * (tau[..., 0] - tau[..., 2]), scale * (tau[..., 1] - tau[..., 2])
    W1, W2 = material.dW(*invariants(l1, l2))
    c = 1.0 / (l1 * l2) ** 3
    T1 = 2.0 * t0 * (l1 / l2 - c) * (W1 + l2 * l2 * W2)
    T2 = 2.0 * t0 * (l2 / l1 - c) * (W1 + l1 * l1 * W2)
    return T1, T2


def relaxed_tensions(material: Material, t0: float, l1, l2):
    """(T1, T2) in N/mm of the relaxed (tension-field) membrane: a membrane carries no
    compression, so where the taut law would give T2 < 0 the hoop direction wrinkles (T2 = 0,
    uniaxial meridional tension), likewise for T1, and both vanish where the sheet is slack.

    T2 < 0 exactly where λ2 < λ1^(-1/2), the natural width under uniaxial tension; the wrinkled
    sheet's tension per unit *apparent* length is the uniaxial one scaled by λ_n/λ2.
    """
    l1, l2 = np.broadcast_arrays(np.asarray(l1, float), np.asarray(l2, float))
    T1, T2 = tensions(material, t0, l1, l2)
    with np.errstate(invalid="ignore", divide="ignore"):
        n1, n2 = 1.0 / np.sqrt(l1), 1.0 / np.sqrt(l2)
    hoop = (l2 < n1) & (l1 > 1.0)  # wrinkles along the meridian, tension along it only
    meri = (l1 < n2) & (l2 > 1.0) & ~hoop
    slack = (l1 <= n2) & (l2 <= n1) & ~hoop & ~meri
    if hoop.any():
        Tu, _ = tensions(material, t0, l1[hoop], n1[hoop])
        T1 = np.where(hoop, 0.0, T1)
        T1[hoop] = Tu * n1[hoop] / l2[hoop]
        T2 = np.where(hoop, 0.0, T2)
    if meri.any():
        _, Tu = tensions(material, t0, n2[meri], l2[meri])
        T2 = np.where(meri, 0.0, T2)
        T2[meri] = Tu * n2[meri] / l1[meri]
        T1 = np.where(meri, 0.0, T1)
    if slack.any():
        T1, T2 = np.where(slack, 0.0, T1), np.where(slack, 0.0, T2)
    return T1, T2
