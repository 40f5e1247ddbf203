"""A test's CSV of named columns, read for a fit (``spsc fit-material``'s ``--cyclic`` and
``--mullins``): the columns as float arrays and the file's record (name, SHA-256, points), or
one :class:`~spsc.core.errors.ParameterError` naming the option and the file."""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError

__all__ = ["read_columns"]


def read_columns(path, option: str, columns: tuple) -> tuple:
    """(each of ``columns`` as a float array, …, the record ``{file, sha256, points}``)."""
    import pandas as pd

    names = ", ".join(columns[:-1]) + " and " + columns[-1]
    p = Path(path)
    try:
        raw = p.read_bytes()
        df = pd.read_csv(p, comment="#")
    except (OSError, ValueError) as exc:
        raise ParameterError(option, str(path), f"a readable CSV with {names} "
                             f"({str(exc).splitlines()[0]})") from None
    missing = [c for c in columns if c not in df.columns]
    if missing:
        raise ParameterError(option, p.name, f"a CSV with the columns {names}; it lacks "
                             f"{', '.join(missing)}")
    cols = [pd.to_numeric(df[c], errors="coerce").to_numpy(float) for c in columns]
    if not all(np.all(np.isfinite(c)) for c in cols):
        raise ParameterError(option, p.name, "numbers in every row (a row is empty or not "
                             "a number)")
    return (*cols, {"file": p.name, "sha256": hashlib.sha256(raw).hexdigest(),
                    "points": int(cols[0].size)})
