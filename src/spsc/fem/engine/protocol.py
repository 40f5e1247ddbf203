"""What the engine asks of a discretisation: the :class:`Discretisation` protocol.

A discretisation holds the state x (n unknowns). Newton's linear system is on its first m
unknowns — all of them for the 3D solid, whose mixed u–p system is solved at once; the
displacements for the wall model, whose element pressures are condensed out and recovered by
:meth:`~Discretisation.expand` — and the first n_u of those are displacements (mm). For one
:class:`~spsc.fem.engine.steps.Load` it evaluates

    r(x) = r_int(x) − p g(u),   K = K_int − p H,   (the gas:) − (dp/dV · symmetry) g gᵀ,

g = ∂V/∂u the cavity volume's gradient (mm²) and H its Hessian (the follower pressure's
stiffness, paper eq. 37's V on the discrete cavity); the gas's rank-one term is returned apart,
c = −dp/dV · symmetry ≥ 0 with g, so the engine solves it by Sherman–Morrison. A rigid body
meets its :class:`~.surface.ContactSurface` (the vertical displacement unknowns of the outer
surface) where their nodes' reference heights plus displacement plus gap reach it.
"""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np

from .linsolve import Factor
from .settings import Settings
from .load import Load
from .surface import ContactSurface

__all__ = ["Evaluation", "Tie", "Discretisation"]


class Evaluation(Protocol):
    """The residual and tangent of one state under one load."""

    r: np.ndarray  #: residual of the Newton system's m unknowns (N; displacements first)
    K: Any  #: tangent of the Newton system (sparse m × m, N/mm), None if not asked for
    g: np.ndarray  #: ∂V/∂u of the cavity over the n_u displacements (mm²)
    c: float  #: the gas's rank-one coefficient −dp/dV · symmetry (MPa/mm³), 0 without gas
    pressure: float  #: cavity gauge pressure (MPa)
    volume: float  #: gas volume (mm³)


class Tie(Protocol):
    """A rigid body met unilaterally from inside the model (the 3D solid's insert): its
    constrained unknowns are aliased onto ``master``, u_s = u_master + jump_s."""

    master: int

    def constraints(self, x, engaged) -> tuple[np.ndarray, np.ndarray]:
        """(slave unknowns, their jumps, mm) at the state x with the ``engaged`` nodes."""

    def update(self, x, r, engaged, force_tol: float, gap_tol: float) -> np.ndarray | None:
        """The new engaged set (a primal–dual active set), or None if unchanged."""

    def force(self, r, engaged) -> float:
        """The body's force on the model (N, of the modelled part)."""


class Discretisation(Protocol):
    """A model the engine solves (:class:`spsc.fem.solid.model.FEMModel`,
    :class:`spsc.fem.wall.model.WallModel`)."""

    n: int  #: unknowns of the state x
    n_u: int  #: displacement unknowns (the first n_u of x and of the Newton system)
    symmetry: int  #: copies of the modelled part in the whole (forces and areas × symmetry)
    fixed: np.ndarray  #: bool over the Newton system's m unknowns: supported
    #: the outer surface a rigid body meets (its unknowns, where they sit, what it measures)
    surface: ContactSurface
    #: the cavity wall's surface that may come down onto the base (:class:`~.bodies.Floor`;
    #: heights measured from the base), or None: the base is not modelled
    floor: ContactSurface | None
    tie: Tie | None  #: a rigid body inside the model, or None
    force_floor: float  #: smallest force scale of the convergence test (N)
    #: exceptions that fail a load (the increment is cut); ``inadmissible``: that reject a
    #: trial state of the line search
    recoverable: tuple
    inadmissible: tuple
    #: a rate-dependent material's history (:mod:`spsc.fem.viscous`), None for an elastic one
    viscous: Any

    def default_settings(self) -> Settings:
        """The engine settings this discretisation is solved with unless told otherwise."""

    def zero_state(self) -> np.ndarray:
        """The undeformed state (n,)."""

    def evaluate(self, x, load: Load, *, tangent: bool = True) -> Evaluation:
        """Residual (and tangent) at x under ``load``."""

    def reuse(self, ev: Evaluation, tangent_ev: Evaluation) -> Evaluation:
        """ev (made without its tangent) completed by ``tangent_ev``'s tangent, for a
        modified Newton step (only with ``settings.modified_newton``)."""

    def volume(self, x) -> float:
        """The gas volume (mm³) at x."""

    def commit(self, x, load: Load) -> None:
        """Close a converged load: a rate-dependent material keeps its history at x."""

    def system_residual(self, ev: Evaluation) -> np.ndarray:
        """The right-hand side's residual of the Newton system (m): r, or r with the
        condensed unknowns' residuals folded in."""

    def expand(self, ev: Evaluation, dx) -> np.ndarray:
        """The step of all n unknowns from the Newton system's step dx (m)."""

    def pressure_error(self, ev: Evaluation) -> float:
        """Relative error of equations outside the Newton residual (the wall's condensed
        pressure equations; 0 when every equation is in r)."""

    def admissible(self, x) -> bool:
        """No element inverted at x."""

    def unstable_modes(self, factor: Factor, c: float, gc) -> int | None:
        """Negative eigenvalues of the displacement problem from the inertia of ``factor``
        (the restricted tangent without the gas) with the gas's c and restricted g (None:
        unknown)."""
