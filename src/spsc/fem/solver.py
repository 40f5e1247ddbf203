"""Moved to :mod:`spsc.fem.engine`: this path re-exports it for code outside ``spsc.fem``
until that code imports the new path."""

from .engine import (CloseValve, Inflate, NewtonFailure, Press, Record, Result, Settings, newton,
                     solve)

__all__ = ["CloseValve", "Inflate", "NewtonFailure", "Press", "Record", "Result", "Settings",
           "newton", "solve"]
