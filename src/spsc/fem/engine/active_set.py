"""Frictionless contact with a rigid plate z = z_plate moving down onto the model: the one
primal–dual active set of both discretisations.

An active unknown's height is prescribed at the plate (its vertical displacement is eliminated
like a support) and its contact force is the reaction λ_a = −r_a ≥ 0 (N). An active unknown is
released when its reaction pulls (λ_a < −tol) and an inactive one activated when it passes the
plate. With exact enforcement there is no penalty parameter to tune, which is what makes the
thin walls robust; the plate force is Σ λ_a over the active unknowns (× symmetry), the integral
of the discrete contact pressure.

A curved indenter (:class:`~spsc.core.indenter.Indenter`: sphere, cylinder, wedge) is met at
the height its lower surface has over the node's current lateral position, z_tip − gap +
S(x, y); an active node's height then follows its lateral unknowns (:mod:`.leaning`) and its
reaction pushes along the body's normal. ``indenter`` None is the plate.
"""

from __future__ import annotations

import numpy as np

__all__ = ["heights", "first_contact", "jumps", "start", "update", "started", "stepped",
           "plate_force", "surface", "lateral_of", "curved"]


def curved(indenter) -> bool:
    """Whether ``indenter`` (None: the plate) is a curved body."""
    return indenter is not None and indenter.curved


def lateral_of(model, dofs) -> np.ndarray:
    """The lateral unknowns (k, len(dofs)) of the contact unknowns ``dofs``."""
    return model.surface.lateral_of(dofs)


def surface(model, x, dofs, indenter):
    """(S, ∇S, ∇²S) of ``indenter`` over the current lateral positions of the contact
    unknowns ``dofs`` (:meth:`~spsc.core.indenter.Indenter.surface`), and their lateral
    unknowns."""
    lat = lateral_of(model, dofs)
    S, dS, d2S = indenter.surface(model.surface.height[lat] + x[lat], model.surface.gap[dofs])
    return S, dS, d2S, lat


def heights(model, x, dofs, indenter=None) -> np.ndarray:
    """Where the indenter's tip meets the contact unknowns ``dofs`` at the state x (mm):
    reference height plus displacement plus gap, less the curved body's rise S over the
    node (−inf where the body has no lower surface)."""
    on = model.surface
    h = on.height[dofs] + x[dofs] + on.gap[dofs]
    if not curved(indenter):
        return h
    return h - surface(model, x, dofs, indenter)[0]


def first_contact(model, x, indenter=None) -> float:
    """The tip's height at first contact (mm): the highest contact point (on the plate)."""
    return float(np.max(heights(model, x, model.surface.dofs, indenter)))


def jumps(model, x, plate, active, indenter=None) -> np.ndarray:
    """How far each active unknown must move to lie on the indenter (mm)."""
    if plate is None:
        return np.zeros(0)
    if curved(indenter):
        return plate - heights(model, x, active, indenter)
    return plate - model.surface.gap[active] - model.surface.height[active] - x[active]


def started(dofs, active, passed, settings) -> np.ndarray:
    """The set a unilateral body's Newton solve starts from: ``active`` (none if None); with
    the semi-smooth strategy also the unknowns of ``dofs`` that ``passed(dofs)`` finds past
    the body by more than the contact tolerance."""
    active = np.zeros(0, int) if active is None else np.asarray(active)
    if not settings.semismooth:
        return active
    return np.union1d(active.astype(int), dofs[passed(dofs)])


def stepped(dofs, active, reaction, passed, force_tol):
    """One step of the primal–dual active set of a unilateral body over the unknowns
    ``dofs``: the new set, or None if it is unchanged (the fixed point). Kept: the active
    unknowns whose ``reaction`` (N, pushing > 0) does not pull below −``force_tol``; taken
    in: the inactive ones that ``passed(inactive)`` finds past the body."""
    keep = reaction >= -force_tol
    inactive = np.setdiff1d(dofs, active, assume_unique=True)
    new = inactive[passed(inactive)]
    if new.size == 0 and np.all(keep):
        return None
    return np.union1d(np.asarray(active)[keep], new)


def start(model, x, plate, active, settings, indenter=None) -> np.ndarray:
    """The plate's set a Newton solve starts from (:func:`started`; none without a plate)."""
    if plate is None:
        return np.zeros(0, int)
    return started(model.surface.dofs, active, lambda d: heights(model, x, d, indenter) >
                   plate + settings.contact_tolerance, settings)


def update(model, x, reaction, plate, active, force_tol, gap_tol, indenter=None):
    """The plate's new active set, or None if it is unchanged (:func:`stepped`): the inactive
    unknowns past the plate by more than ``gap_tol`` (mm) are taken in."""
    return stepped(model.surface.dofs, active, reaction,
                   lambda d: heights(model, x, d, indenter) > plate + gap_tol, force_tol)


def plate_force(model, r, active) -> float:
    """Plate force (N, whole part): the active unknowns' reactions summed, × symmetry."""
    return float((-r[np.asarray(active)]).sum()) * model.symmetry
