"""Moved to :mod:`spsc.fem.wall.model`: this path re-exports it for code outside ``spsc.fem``
until that code imports the new path."""

from .wall.model import WallModel, WallSettings

__all__ = ["WallModel", "WallSettings"]
