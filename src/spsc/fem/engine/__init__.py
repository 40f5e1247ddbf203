"""The one nonlinear engine of the wall model and the 3D FEM.

A discretisation (:class:`~.protocol.Discretisation`: residual, tangent, the gas's rank-one
term, the surface a body meets, its inertia count) is driven by one :func:`~.walk.solve`
over load steps given as data (:mod:`.steps`), with one Newton loop (:mod:`.newton`) over the bodies
that constrain it (:mod:`.bodies`: the plate's active set, :mod:`.active_set`; a tie; the
base under the cavity), one line search (:mod:`.search`), one stability check and one
result (:mod:`.result`). Where the two discretisations' Newton methods differ in a way that
changes numbers, :class:`~.settings.Settings` names the choice and each discretisation's
``default_settings()`` keeps its own.
"""

from .newton import Converged, newton
from .result import NewtonFailure, Record, Result, Stop
from .settings import Settings
from .steps import CloseValve, Cycle, Inflate, Load, Press, SwitchValve, load_steps
from .walk import solve

__all__ = ["CloseValve", "Converged", "Cycle", "Inflate", "Load", "NewtonFailure", "Press",
           "Record", "SwitchValve",
           "Result", "Settings", "Stop", "load_steps", "newton", "solve"]
