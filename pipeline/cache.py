"""On-disk cache of runs: one directory per run, named by its label and key, holding
``result.json`` (the payload) and any files the run wrote (VTUs).

A directory is written under a temporary name and renamed into place, so an interrupted run
never leaves a half entry that a later run would take for a result.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path

from spsc.core.jsonio import dumps, write_json

__all__ = ["Cache", "DEFAULT_ROOT"]

DEFAULT_ROOT = Path("build/cache")


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
        the run's key and inputs, atomically. Returns the stored payload (with ``"dir"``)."""
        self.runs_dir.mkdir(parents=True, exist_ok=True)
        final = self.entry(run)
        tmp = Path(tempfile.mkdtemp(prefix=f".{final.name}.", dir=self.runs_dir))
        try:
            payload = dict(compute(tmp))
            payload.update(key=run.key(), inputs=run.inputs(), label=run.label)
            write_json(tmp / "result.json", payload)
            if final.exists():
                shutil.rmtree(final)
            os.replace(tmp, final)
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise
        payload["dir"] = str(final)
        return json.loads(dumps(payload))  # exactly what a later get() reads

