"""What a report was built from: the git commit, whether the tree was clean, the versions.

A report is reproducible when it names a commit and the working tree had no change against it
(``git status --porcelain`` empty: no modified, staged or untracked file), so checking out that
commit and running the same command gives the same report.
"""

from __future__ import annotations

import os
import platform
import re
import subprocess
import sys
from importlib import metadata
from pathlib import Path

from spsc.core.provenance import Provenance, _git, provenance

__all__ = ["Provenance", "provenance", "committed_report_dir", "versions"]

_HERE = Path(__file__).resolve().parent


def committed_report_dir(where: Path = _HERE) -> Path | None:
    """``reports/validation`` of the checkout holding ``where`` (the committed report), or None
    outside a git checkout."""
    try:
        top = _git("rev-parse", "--show-toplevel", cwd=where)
    except (OSError, subprocess.SubprocessError):
        return None
    return None if top.returncode else Path(top.stdout.strip()) / "reports" / "validation"


def versions(code_versions: dict | None = None) -> dict:
    """Python, platform and every installed dependency of spsc (plus test extras present),
    and the code version of each model."""
    out = {"python": sys.version.split()[0], "platform": platform.platform(),
           "cpus": os.cpu_count(),
           "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "(unset)")}
    for name in _dependency_names():
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            pass
    if code_versions:
        out["code_versions"] = dict(code_versions)
    return out


def _dependency_names() -> list[str]:
    try:
        reqs = metadata.requires("spsc") or []
    except metadata.PackageNotFoundError:
        reqs = []
    pyproject = _HERE.parents[2] / "pyproject.toml"
    if pyproject.is_file():  # the source's list (the installed metadata may be older)
        import tomllib

        proj = tomllib.loads(pyproject.read_text(encoding="utf-8")).get("project", {})
        reqs = list(proj.get("dependencies", [])) + [
            r for extra in proj.get("optional-dependencies", {}).values() for r in extra] + reqs
    names = ["spsc"] + [re.split(r"[\s;\[<>=!~,]", r, maxsplit=1)[0] for r in reqs]
    return list(dict.fromkeys(names + ["vtk", "mkl"]))
