"""Which restriction of the tangent a constraint set takes (:mod:`.constraints`,
:mod:`.leaning`)."""

from __future__ import annotations

from .constraints import Constraints, Masked, Reduction, Submatrix
from .leaning import Leaning

__all__ = ["restriction"]


def restriction(K, free, con: Constraints, full_input: bool, r=None):
    """The tangent's restriction for the constraint set: :class:`~.leaning.Leaning` (bound to
    the residual ``r`` of its curvature term) under a curved indenter, the free block as
    assembled when the solver takes the whole matrix and nothing is aliased, :class:`Masked`
    when it takes the upper triangle and nothing is aliased, else :class:`Reduction`."""
    if con.lean.size:
        return Leaning(K, free, con).bind(con, r)
    if con.slaves.size:
        return Reduction(K, free, con.slaves, con.master)
    if full_input:
        return Submatrix(free)
    return Masked(K, free, con.presc)
