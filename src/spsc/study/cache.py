"""On-disk cache of runs: one directory per run, named by its label and key, holding
``result.json`` (the payload) and any files the run wrote (VTUs).

A directory is written under a temporary name and renamed into place, so an interrupted run
never leaves a half entry that a later run would take for a result. Several processes (the
report's Dask workers, two reports sharing a cache) may store runs at once, even the same run:
the rename is atomic, and an entry that is already there and valid is kept (the newcomer's copy
of the same inputs and code is dropped), so a reader sees no entry or a whole one, never a mix.
"""

from __future__ import annotations

import errno
import json
import os
import shutil
import tempfile
import uuid
from pathlib import Path

from spsc.core.jsonio import dumps, write_json

__all__ = ["Cache", "DEFAULT_ROOT"]

DEFAULT_ROOT = Path("build/cache")
#: attempts to rename a finished entry into place while other writers move stale ones aside
_INSTALL_TRIES = 5


class Cache:
    """Runs under ``root/runs/<label>-<key16>/``; meshes under ``root/fem`` (``mesh_dir``)."""

    def __init__(self, root=DEFAULT_ROOT):
        self.root = Path(root)

    @property
    def runs_dir(self) -> Path:
        return self.root / "runs"

    @property
    def mesh_dir(self) -> Path:
        return self.root / "fem"

    def entry(self, run) -> Path:
        return self.runs_dir / f"{run.label}-{run.key()[:16]}"

    def get(self, run) -> dict | None:
        """The stored payload of ``run`` (with ``"dir"`` set to its directory), or None."""
        d = self.entry(run)
        f = d / "result.json"
        if not f.is_file():
            return None
        try:
            payload = json.loads(f.read_text(encoding="utf-8"))
        except (OSError, json.JSONDecodeError):
            return None
        if payload.get("key") != run.key():
            return None
        payload["dir"] = str(d)
        return payload

    def put(self, run, compute) -> dict:
        """``compute(directory)`` → payload dict (JSON-able; NaN stored as null); stored with
        the run's key and inputs, atomically. Returns the stored payload (with ``"dir"``): ours,
        or the equal one another process stored first."""
        self.runs_dir.mkdir(parents=True, exist_ok=True)
        final = self.entry(run)
        tmp = Path(tempfile.mkdtemp(prefix=f".{final.name}.", dir=self.runs_dir))
        try:
            payload = dict(compute(tmp))
            payload.update(key=run.key(), inputs=run.inputs(), label=run.label)
            write_json(tmp / "result.json", payload)
            stored = self._install(run, tmp, final)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise
        if stored is not None:
            shutil.rmtree(tmp, ignore_errors=True)
            return stored
        payload["dir"] = str(final)
        return json.loads(dumps(payload))  # exactly what a later get() reads

    def _install(self, run, tmp: Path, final: Path) -> dict | None:
        """Rename ``tmp`` to ``final``; None when done. A valid entry already at ``final`` (the
        same run, stored meanwhile by another process) is kept and returned instead; a stale
        or broken one is first renamed aside (atomic) and then removed."""
        for _ in range(_INSTALL_TRIES):
            try:
                os.rename(tmp, final)  # atomic; refused while final is a non-empty directory
                return None
            except OSError as exc:
                if exc.errno not in (errno.EEXIST, errno.ENOTEMPTY):
                    raise
            stored = self.get(run)
            if stored is not None:
                return stored
            aside = final.with_name(f".{final.name}.old-{uuid.uuid4().hex[:12]}")
            try:
                os.rename(final, aside)
            except FileNotFoundError:  # another writer moved it first
                continue
            shutil.rmtree(aside, ignore_errors=True)
        raise OSError(errno.EBUSY, "other processes keep replacing the cache entry", str(final))
