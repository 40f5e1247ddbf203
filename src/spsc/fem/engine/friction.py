"""Sticking contact on the rigid plate (``--friction stick``): a node that touches the plate
does not slide on it.

With the frictionless plate an active contact unknown's height is prescribed and its lateral
displacements are free. Sticking prescribes them too: each lateral unknown of an active node is
held where the node touched the plate, its *anchor*, and the anchor is dropped when the node
leaves the plate (its normal reaction pulls, :mod:`.active_set`). The lateral reactions are the
tangential tractions the plate must supply; with no slip there is no friction coefficient to
choose, so the answer is that of a plate with μ → ∞ (the upper bound of Coulomb friction) and
depends on no penalty factor.

A node is held from the end of the increment in which it touched: within that increment it
meets the plate frictionless, at the converged state its lateral displacements become its
anchor, and from the next increment on it does not move along the plate. This is the implicit
(backward Euler) reading of the touch-down; it depends on the increments alone, not on Newton's
path, its error is of first order in the increment (``bench/bench_friction.py``), and the plate
does no tangential work: a node slides only while its tangential reaction is zero.

A discretisation names each contact unknown's lateral unknowns in its surface's ``lateral``
(:class:`~.surface.ContactSurface`): an integer array (k, len(dofs)), k = 1 (the dome's radial displacement) or 2 (x and y),
−1 where a node has none; supported unknowns are never anchored.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Grip", "lateral", "release", "hold", "stuck", "tractions"]


@dataclass(frozen=True, eq=False)
class Grip:
    """The anchors of the stuck lateral unknowns: ``anchor`` over the Newton system's m
    unknowns (mm; NaN where an unknown is free)."""

    anchor: np.ndarray

    @classmethod
    def empty(cls, model) -> "Grip":
        """No node stuck yet."""
        return cls(np.full(len(model.fixed), np.nan))

    @property
    def held(self) -> np.ndarray:
        """The stuck unknowns."""
        return np.flatnonzero(~np.isnan(self.anchor))


def lateral(model, dofs) -> np.ndarray:
    """The lateral unknowns (k, len(dofs)) of the contact unknowns ``dofs`` (−1: none or
    supported)."""
    dofs = np.asarray(dofs, int)
    lat = np.asarray(model.surface.lateral_of(dofs), int)
    ok = lat >= 0
    ok[ok] = ~np.asarray(model.fixed)[lat[ok]]
    return np.where(ok, lat, -1)


def release(model, grip: Grip, active) -> Grip:
    """``grip`` without the anchors of nodes no longer among the plate's ``active``
    unknowns."""
    lat = lateral(model, active)
    keep = np.unique(lat[lat >= 0])
    anchor = np.full_like(grip.anchor, np.nan)
    anchor[keep] = grip.anchor[keep]
    return Grip(anchor)


def hold(model, grip: Grip, x, active) -> Grip:
    """``grip`` at the converged state x: the lateral unknowns of the ``active`` nodes that
    have no anchor yet anchored where they are."""
    lat = lateral(model, active)
    lat = lat[lat >= 0]
    anchor = grip.anchor.copy()
    new = lat[np.isnan(anchor[lat])]
    anchor[new] = x[new]
    return Grip(anchor)


def stuck(grip: Grip | None, x) -> tuple[np.ndarray, np.ndarray]:
    """(stuck unknowns, how far each must move to its anchor, mm)."""
    if grip is None:
        return np.zeros(0, int), np.zeros(0)
    held = grip.held
    return held, grip.anchor[held] - x[held]


def tractions(model, r, active, x=None, indenter=None) -> np.ndarray:
    """The tangential reaction (N, of the modelled part) on each of the ``active`` contact
    unknowns' nodes (0 on a node that slides): on the plate the norm of their lateral
    unknowns' reactions −r; on a curved ``indenter`` (at the state ``x``) what is left of
    the node's reaction (−r over its lateral and vertical unknowns) after its part along the
    body's normal there."""
    lat = lateral(model, active)
    t = np.where(lat >= 0, -np.asarray(r)[np.maximum(lat, 0)], 0.0)
    if indenter is None or not indenter.curved or not len(active):
        return np.sqrt((t ** 2).sum(axis=0))
    from .active_set import surface

    _, dS, _, _ = surface(model, x, np.asarray(active, int), indenter)
    f = np.vstack([t, -np.asarray(r)[np.asarray(active, int)]])  # (k + 1, n)
    normal = np.vstack([-dS, np.ones(dS.shape[1])])
    normal /= np.linalg.norm(normal, axis=0)
    f = f - normal * (f * normal).sum(axis=0)
    return np.sqrt((f ** 2).sum(axis=0))
