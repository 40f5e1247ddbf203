"""What ``spsc sense`` writes: the estimate per sample (Parquet), the events (JSON) and a figure
of the trace with its events."""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd

__all__ = ["COLUMNS", "DEFAULT_COLOUR", "frame", "write", "figure"]

#: estimate.parquet's columns, in order
COLUMNS = ("t_s", "force_N", "force_lo_N", "force_hi_N", "depth_mm", "mode", "in_contact",
           "pressure_kPa", "pressure_filtered_kPa", "in_map")
#: the colour of an event whose kind no detector declares
DEFAULT_COLOUR = "k"


def frame(states, pressure_kPa) -> pd.DataFrame:
    """The estimate table of the stream's states and the log's pressures."""
    cols = list(zip(*states)) if states else [[] for _ in range(9)]
    d = dict(zip(("t_s", "force_N", "force_lo_N", "force_hi_N", "depth_mm", "mode",
                  "in_contact", "pressure_filtered_kPa", "in_map"), cols))
    d["pressure_kPa"] = np.asarray(pressure_kPa, float)
    out = pd.DataFrame(d)
    return out[list(COLUMNS)].astype({"in_contact": bool, "in_map": bool})


def write(out: Path, table: pd.DataFrame, events: list, meta: dict, *,
          png: bool = True, colours: Mapping[str, str] | None = None) -> list[Path]:
    """estimate.parquet, events.json (the events and what ran) and sense.png in ``out``
    (``colours``: each event kind's, as :attr:`~.stream.SenseStream.colours` gives them)."""
    out.mkdir(parents=True, exist_ok=True)
    files = [out / "estimate.parquet", out / "events.json"]
    table.to_parquet(files[0], index=False)
    files[1].write_text(json.dumps({"events": events, "run": meta}, indent=2, default=float)
                        + "\n", encoding="utf-8")
    if png and len(table):
        files.append(out / "sense.png")
        figure(table, events, files[-1], colours)
    return files


def figure(table: pd.DataFrame, events: list, path,
           colours: Mapping[str, str] | None = None) -> None:
    """Pressure (raw and filtered) and force with its 95 % band against time; the low mode
    shaded, each event a line coloured by its kind (``colours``: kind -> a Matplotlib colour,
    the detectors' own; a kind not in it :data:`DEFAULT_COLOUR`)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = table.t_s.to_numpy()
    fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True, constrained_layout=True)
    low = (table["mode"] == "low").to_numpy().astype(int)
    edges = np.flatnonzero(np.diff(np.r_[0, low, 0]))
    for ax in axes:
        for a, b in zip(edges[::2], edges[1::2]):
            ax.axvspan(t[a], t[min(b, len(t) - 1)], color="0.92", lw=0)
    ax = axes[0]
    ax.plot(t, table.pressure_kPa, color="C0", alpha=0.35, lw=0.7, label="sensor")
    ax.plot(t, table.pressure_filtered_kPa, "C0", lw=1.2, label="filtered")
    ax.set_ylabel("gauge pressure (kPa)")
    ax.legend(loc="upper right", fontsize=8)
    ax = axes[1]
    ax.fill_between(t, table.force_lo_N, table.force_hi_N, color="C1", alpha=0.25, lw=0,
                    label="95 % band")
    ax.plot(t, table.force_N, "C1", lw=1.2, label="force")
    ax.set_ylabel("force (N)")
    ax.set_xlabel("time (s); low mode (valve open) shaded")
    seen = set()
    for e in events:
        c = (colours or {}).get(e["kind"], DEFAULT_COLOUR)
        for a in axes:
            a.axvline(e["t_s"], color=c, lw=0.9, ls="--",
                      label=e["kind"] if a is ax and e["kind"] not in seen else None)
        seen.add(e["kind"])
    ax.legend(loc="upper right", fontsize=8)
    axes[0].set_title(f"spsc sense: {len(events)} events", fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
