"""Which code computed a result: the git commit of the checkout this package runs from and
whether its tree was clean (``git status --porcelain`` empty), for every file a verb writes
(the curve's ``provenance``, a simulation's echo, the report's page).
"""

from __future__ import annotations

import functools
import subprocess
from dataclasses import dataclass
from pathlib import Path

__all__ = ["Provenance", "provenance", "code_provenance"]

_HERE = Path(__file__).resolve().parent


@dataclass(frozen=True)
class Provenance:
    """``commit``: full hash of HEAD (None outside a git checkout); ``changes``: lines of
    ``git status --porcelain`` (modified, staged and untracked files)."""

    commit: str | None
    changes: tuple[str, ...] = ()

    @property
    def clean(self) -> bool:
        """A commit and no change against it: check it out to rebuild the same report."""
        return self.commit is not None and not self.changes

    def describe(self) -> str:
        """One line for the report and the command line."""
        if self.commit is None:
            return "not a git checkout: no commit to rebuild from"
        if self.clean:
            return f"commit {self.commit} (clean tree)"
        return (f"commit {self.commit} with {len(self.changes)} uncommitted change(s) "
                f"(e.g. {self.changes[0].strip()})")


def _git(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(["git", *args], capture_output=True, text=True, timeout=30, cwd=cwd)


def provenance(where: Path = _HERE) -> Provenance:
    """The commit and tree state of the checkout holding ``where`` (default: this code)."""
    try:
        head = _git("rev-parse", "HEAD", cwd=where)
        if head.returncode:
            return Provenance(None)
        status = _git("status", "--porcelain", cwd=where)
    except (OSError, subprocess.SubprocessError):
        return Provenance(None)
    if status.returncode:
        return Provenance(head.stdout.strip(), ("git status failed",))
    return Provenance(head.stdout.strip(), tuple(status.stdout.splitlines()))


@functools.lru_cache(maxsize=1)
def code_provenance() -> Provenance:
    """:func:`provenance` of this code, asked of git once per process (a sweep writes
    thousands of curves)."""
    return provenance()
