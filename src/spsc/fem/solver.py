"""Moved to :mod:`spsc.fem.engine` (this path is kept for code outside ``spsc.fem``)."""

from .engine import (CloseValve, Inflate, NewtonFailure, Press, Record, Result, Settings, newton,
                     solve)

__all__ = ["Inflate", "CloseValve", "Press", "Settings", "Record", "Result", "NewtonFailure",
           "solve", "newton"]
