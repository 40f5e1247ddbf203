"""JSON at the edge: NaN and ±inf become null, numpy scalars and arrays plain lists, in one place."""

from __future__ import annotations

import json
import math
from dataclasses import asdict, is_dataclass
from pathlib import Path

import numpy as np

__all__ = ["to_jsonable", "dumps", "write_json", "read_json"]


def to_jsonable(value):
    """``value`` with every non-finite float as None, numpy types as Python ones, tuples and
    arrays as lists, dataclasses as dicts and paths as strings (recursively)."""
    if isinstance(value, dict):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        return [to_jsonable(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [to_jsonable(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        v = float(value)
        return v if math.isfinite(v) else None
    if is_dataclass(value) and not isinstance(value, type):
        return to_jsonable(asdict(value))
    if isinstance(value, Path):
        return str(value)
    return value


def dumps(data, *, indent: int | None = 1) -> str:
    """Strict JSON text of ``data`` (no NaN tokens: they are null)."""
    return json.dumps(to_jsonable(data), indent=indent, allow_nan=False, ensure_ascii=False)


def write_json(path, data, *, indent: int | None = 1) -> Path:
    """Write ``data`` as UTF-8 JSON (atomically: a temporary file renamed over ``path``). A
    path that exists and is not a regular file (``/dev/null``, a pipe) is written into, never
    renamed over: run as root, the rename replaced the null device with a regular file."""
    path = Path(path)
    if path.exists() and not path.is_file():
        with open(path, "w", encoding="utf-8") as f:
            f.write(dumps(data, indent=indent) + "\n")
        return path
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(dumps(data, indent=indent) + "\n", encoding="utf-8")
    tmp.replace(path)
    return path


def read_json(path) -> dict:
    """A JSON file (UTF-8, a byte-order mark tolerated)."""
    return json.loads(Path(path).read_text(encoding="utf-8-sig"))
