"""Where a sweep's rows go, durably: every finished row is appended to a journal
(``OUT.journal.jsonl``, one JSON object a line, flushed and fsync'ed as it arrives), and the
table (Parquet, and CSV on request) is written from the journal, atomically, periodically and
at the end.

The journal is the truth: a sweep killed at any moment keeps every row it finished, and a re-run
with the same output reads it back, skips the designs already done (status ok, partial or
invalid) and computes the failed ones again. A key that occurs more than once (a retried
design) counts once, with its last row. A half-written last line (the process died while
writing it) is ignored and the next row starts on a line of its own.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from spsc.sweep.evaluate import BAND_COLUMNS, COLUMNS, DONE, INPUTS, METRICS

__all__ = ["SweepStore", "journal_path", "read_table"]


def journal_path(out) -> Path:
    """The journal beside the table: ``results.parquet`` -> ``results.journal.jsonl``."""
    return Path(out).with_suffix(".journal.jsonl")


class SweepStore:
    """The rows of the sweep writing to ``out`` (a ``.parquet`` path)."""

    def __init__(self, out):
        self.out = Path(out)
        self.journal = journal_path(out)
        self._file = None

    # -- the journal -----------------------------------------------------------------------
    def rows(self) -> dict:
        """key -> last row, in the order the keys first appeared."""
        rows = {}
        if self.journal.exists():
            with open(self.journal, encoding="utf-8") as f:
                for line in f:
                    try:
                        row = json.loads(line)
                    except ValueError:  # a line cut short when a run was killed
                        continue
                    if isinstance(row, dict) and row.get("key"):
                        rows[row["key"]] = row
        elif self.out.exists():  # a table without its journal: its rows are done too
            for row in read_table(self.out).to_dict("records"):
                rows[row["key"]] = _plain(row)
        return rows

    def done(self) -> set:
        """Keys a re-run skips: their last row is ok, partial or invalid."""
        return {k for k, r in self.rows().items() if r.get("status") in DONE}

    def open(self) -> None:
        """Open the journal for appending (seeded from a journal-less table, so its rows are
        kept), starting on a fresh line."""
        if not self.journal.exists() and self.out.exists():
            seed = list(self.rows().values())
            with open(self.journal, "w", encoding="utf-8") as f:
                for row in seed:
                    f.write(_line(row))
        self._file = open(self.journal, "a+", encoding="utf-8")
        if self._file.tell() > 0:
            self._file.seek(self._file.tell() - 1)
            if self._file.read(1) != "\n":
                self._file.write("\n")

    def append(self, row: dict) -> None:
        """Append one row and make it durable (flush + fsync) before returning."""
        self.extend([row])

    def extend(self, rows) -> None:
        """Append rows and make them durable together (one flush + fsync: a batched model's
        chunk of 2000 rows is one write, not 2000)."""
        if self._file is None:
            self.open()
        self._file.write("".join(_line(row) for row in rows))
        self._file.flush()
        os.fsync(self._file.fileno())

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None

    # -- the table -------------------------------------------------------------------------
    def table(self, keys=None):
        """The rows as a DataFrame of :data:`COLUMNS`, one per key (its last row); ``keys``: only
        these, in this order (the sweep's own designs)."""
        rows = self.rows()
        if keys is not None:
            rows = {k: rows[k] for k in keys if k in rows}
        return frame(rows.values())

    def write(self, keys=None, csv=None):
        """Write the table to ``out`` (Parquet, replaced atomically) and ``csv`` if given;
        returns the DataFrame."""
        df = self.table(keys)
        tmp = self.out.with_name(self.out.name + ".tmp")
        df.to_parquet(tmp, engine="pyarrow", index=False)
        os.replace(tmp, self.out)
        if csv:
            df.to_csv(csv, index=False)
        return df


def frame(rows):
    """A DataFrame of :data:`COLUMNS` with their dtypes: inputs and metrics as floats (type
    and material as strings), ``printable`` a nullable boolean."""
    import pandas as pd

    df = pd.DataFrame(list(rows), columns=list(COLUMNS))
    for c in INPUTS + METRICS + ("seconds", "life_cycles", "energy_amplitude_MPa",
                                 "peak_stretch") + BAND_COLUMNS:
        if c not in ("type", "material"):
            df[c] = pd.to_numeric(df[c], errors="coerce").astype("float64")
    for c in ("type", "material", "printability", "status", "message", "key", "life_message"):
        df[c] = df[c].astype("string")
    df["printable"] = df["printable"].astype("boolean")
    return df


def read_table(path):
    """A sweep's table (Parquet or CSV) as written by :meth:`SweepStore.write`."""
    import pandas as pd

    path = Path(path)
    df = pd.read_csv(path) if path.suffix.lower() == ".csv" else pd.read_parquet(path)
    return frame(df.to_dict("records"))


def _plain(row: dict) -> dict:
    """A table row as JSON-able Python values (pandas' NA and NaN -> None)."""
    import pandas as pd

    return {k: None if pd.isna(v) else (v.item() if hasattr(v, "item") else v)
            for k, v in row.items()}


def _line(row: dict) -> str:
    return json.dumps({k: row.get(k) for k in COLUMNS}, allow_nan=True,
                      ensure_ascii=False) + "\n"
