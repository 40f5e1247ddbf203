"""A result file that is reused only while what computed it is the same: its inputs and the
code of the modules that computed it (each with every ``spsc`` module it imports). The key sits
beside the file (``NAME.key``); a missing, different or unreadable key means compute again.

The long studies (the fingertip's and the haptic chamber's part-FEM curves, minutes to an hour
each) keep their curves this way, as :class:`~.cache.Cache` keeps a study's runs.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

__all__ = ["KeyedFile", "input_key"]


def input_key(inputs, modules=()) -> str:
    """sha256 of ``inputs`` (JSON-able; paths and numbers as text) and of the source of
    ``modules`` and of every spsc module they import (:func:`~.runs.source_closure`)."""
    from .runs import source_closure

    h = hashlib.sha256(json.dumps(inputs, sort_keys=True, default=str).encode("utf-8"))
    files = sorted({p for m in modules for p in source_closure(m)})
    for path in files:
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()


class KeyedFile:
    """``path`` with the key of what computed it (``path.key`` beside it)."""

    def __init__(self, path, key: str):
        self.path = Path(path)
        self.key = key
        self.key_path = self.path.with_name(self.path.name + ".key")

    @property
    def valid(self) -> bool:
        """The file exists and was computed by the same inputs and code."""
        try:
            return self.path.exists() and self.key_path.read_text().strip() == self.key
        except OSError:
            return False

    def mark(self) -> None:
        """Record that ``path`` now holds the result of this key."""
        self.key_path.write_text(self.key + "\n")
