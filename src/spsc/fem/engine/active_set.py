"""Frictionless contact with a rigid plate z = z_plate moving down onto the model: the one
primal–dual active set of both discretisations.

An active unknown's height is prescribed at the plate (its vertical displacement is eliminated
like a support) and its contact force is the reaction λ_a = −r_a ≥ 0 (N). An active unknown is
released when its reaction pulls (λ_a < −tol) and an inactive one activated when it passes the
plate. With exact enforcement there is no penalty parameter to tune, which is what makes the
thin walls robust; the plate force is Σ λ_a over the active unknowns (× symmetry), the integral
of the discrete contact pressure.
"""

from __future__ import annotations

import numpy as np

__all__ = ["heights", "first_contact", "jumps", "start", "update", "plate_force"]


def heights(model, x, dofs) -> np.ndarray:
    """Where the plate meets the contact unknowns ``dofs`` at the state x (mm): reference
    height plus displacement plus gap."""
    return model.contact_height[dofs] + x[dofs] + model.contact_gap[dofs]


def first_contact(model, x) -> float:
    """The plate height of first contact (mm): the highest contact point."""
    return float(np.max(heights(model, x, model.contact_dofs)))


def jumps(model, x, plate, active) -> np.ndarray:
    """How far each active unknown must move to lie on the plate (mm)."""
    if plate is None:
        return np.zeros(0)
    return plate - model.contact_gap[active] - model.contact_height[active] - x[active]


def start(model, x, plate, active, settings) -> np.ndarray:
    """The active set a Newton solve starts from: the given one (none without a plate); with
    the semi-smooth strategy also every contact unknown past the plate."""
    if plate is None or active is None:
        active = np.zeros(0, int)
    active = np.asarray(active)
    if plate is None or not settings.semismooth:
        return active
    passed = heights(model, x, model.contact_dofs) > plate + settings.contact_tolerance
    return np.union1d(active.astype(int), model.contact_dofs[passed])


def update(model, x, reaction, plate, active, force_tol, gap_tol):
    """The new active set, or None if it is unchanged (the PDAS fixed point): the active
    unknowns whose ``reaction`` (N, pushing > 0) does not pull below −``force_tol``, and the
    inactive ones past the plate by more than ``gap_tol`` (mm)."""
    keep = reaction >= -force_tol
    inactive = np.setdiff1d(model.contact_dofs, active)
    new = inactive[heights(model, x, inactive) > plate + gap_tol]
    if new.size == 0 and np.all(keep):
        return None
    return np.union1d(np.asarray(active)[keep], new)


def plate_force(model, r, active) -> float:
    """Plate force (N, whole part): the active unknowns' reactions summed, × symmetry."""
    return float((-r[np.asarray(active)]).sum()) * model.symmetry
