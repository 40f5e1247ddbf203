"""The one nonlinear engine of the wall model and the 3D FEM: load steps as data, Newton's
method with one active set for the plate, one line search and one stability check, and one
result type."""

from .result import NewtonFailure, Record, Result
from .steps import CloseValve, Inflate, Load, Press

__all__ = ["CloseValve", "Inflate", "Load", "NewtonFailure", "Press", "Record", "Result"]
