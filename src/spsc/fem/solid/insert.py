"""A rigid insert inside the cavity: a flat-faced body (a coin vibration motor) seated on a
ledge of the wall and met from above by the wall it sits under.

The insert translates along the press axis (z of the model frame) only: its faces are flat and
frictionless, so its lateral place does not load the wall, and its tilt is held (an apex press
on the axis does not excite it; a press far off the axis would). Its bottom face rests on the
``seat`` nodes (the ledge under its rim: their vertical displacements are all the insert's, w);
its top face meets the ``top`` nodes (the wall above it) unilaterally — an engaged node's height
is tied to the face, z + u_z = z_top + w, and it is released when the insert would pull it
down. In the solver both are the same linear constraint, u_s = u_m + jump_s on the node's z
unknown, eliminated by aliasing it to the master unknown (the first seat node's u_z): no
penalty, no extra unknown, and the tangent stays the exact one of the constrained problem.

The insert's force (N) is the sum of the engaged top nodes' reactions (≥ 0: it pushes the wall
up); by its own equilibrium the seat carries the same. Its volume is taken off the gas.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["RigidInsert", "InsertTie", "insert_constraints", "update_engaged", "insert_force"]


@dataclass(frozen=True, eq=False)
class RigidInsert:
    """A rigid insert in the model frame (mm, mm³): node indices of the ``seat`` it rests on
    and the ``top`` wall it may meet, the z of its bottom face ``z_bottom`` and its ``height``
    in the reference state, its ``volume`` (displaced from the gas) and a ``name``."""

    name: str
    seat: np.ndarray = field(repr=False)
    top: np.ndarray = field(repr=False)
    z_bottom: float
    height: float
    volume: float

    def __post_init__(self):
        seat, top = np.asarray(self.seat, np.int64), np.asarray(self.top, np.int64)
        if seat.size == 0:
            raise ValueError(f"insert {self.name}: no seat node (it rests on nothing)")
        if np.intersect1d(seat, top).size:
            raise ValueError(f"insert {self.name}: a node is both seat and top")
        object.__setattr__(self, "seat", seat)
        object.__setattr__(self, "top", top)

    @property
    def master(self) -> int:
        """The unknown carrying the insert's translation w: the first seat node's u_z."""
        return int(3 * self.seat[0] + 2)

    @property
    def z_top(self) -> float:
        return self.z_bottom + self.height


def insert_constraints(insert: RigidInsert, X, x, engaged):
    """(slave unknowns, jumps) of the insert's constraints at the state ``x``: every seat node
    but the master and every engaged top node, u_s = u_m + jump_s after the step (the jump
    closes what the constraint misses now; zero once it holds)."""
    w = x[insert.master]
    seat = insert.seat[1:]
    engaged = np.asarray(engaged, np.int64)
    slaves = np.concatenate([3 * seat + 2, 3 * engaged + 2])
    target = np.concatenate([
        X[seat, 2] - X[insert.seat[0], 2],  # the seat stays as it was relative to the master
        np.full(engaged.size, insert.z_top - X[insert.seat[0], 2])]) + w
    here = np.concatenate([X[seat, 2], X[engaged, 2]]) - X[insert.seat[0], 2] + x[slaves]
    return slaves, target - here


def insert_force(insert: RigidInsert, r, engaged) -> float:
    """The insert's force (N): the engaged top nodes' reactions, the wall pushed up (+z)."""
    return float(np.sum(r[3 * np.asarray(engaged, np.int64) + 2]))


def update_engaged(insert: RigidInsert, X, x, r, engaged, force_tol, gap_tol):
    """The new engaged set (a primal–dual active set, as the plate's), or None if unchanged:
    a top node below the insert's top face by more than ``gap_tol`` engages, an engaged one
    whose reaction pulls (< −``force_tol``) is released."""
    engaged = np.asarray(engaged, np.int64)
    keep = r[3 * engaged + 2] >= -force_tol
    free = np.setdiff1d(insert.top, engaged)
    face = insert.z_top + x[insert.master]
    new = free[X[free, 2] + x[3 * free + 2] < face - gap_tol]
    if new.size == 0 and np.all(keep):
        return None
    return np.union1d(engaged[keep], new)


@dataclass(frozen=True, eq=False)
class InsertTie:
    """The insert as the engine's tie (:class:`spsc.fem.engine.protocol.Tie`): its functions
    bound to the model's reference coordinates ``X`` (mm)."""

    insert: RigidInsert
    X: np.ndarray = field(repr=False)

    @property
    def master(self) -> int:
        return self.insert.master

    def constraints(self, x, engaged):
        return insert_constraints(self.insert, self.X, x, engaged)

    def update(self, x, r, engaged, force_tol, gap_tol):
        return update_engaged(self.insert, self.X, x, r, engaged, force_tol, gap_tol)

    def force(self, r, engaged) -> float:
        return insert_force(self.insert, r, engaged)
