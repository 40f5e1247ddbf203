"""The report's design-space section: a membrane sweep over the study's types, widths and wall
thicknesses (the study's material, compare pressure and low-mode reservoir), run on the same Dask
executor as the report's runs, with its own page (:mod:`.sweep_page`) in ``OUT/sweep/`` linked
from the report.

The table is cached under ``CACHE/sweeps/`` by the study's space and the membrane model's code
version (:func:`~.study.code_version`): a second report with nothing changed reads it back, a
change of the membrane code computes it again.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

__all__ = ["SPACES", "report_space", "run_report_sweep", "sweep_section"]

#: The swept inputs by study: w and t0 on grids (mm); the types are the study's.
SPACES = {"full": {"w": "8:14:7", "t0": "0.8:1.5:4"},
          "quick": {"w": "9:13:3", "t0": "0.8,1.2"}}
MODEL, PROCESS = "membrane", "fdm"


def report_space(study) -> dict:
    """The sweep's inputs (``spsc sweep`` option → spec) for ``study``."""
    grid = SPACES.get(study.name, SPACES["quick"])
    reservoir = max((v for _, v in study.modes), default=0.0)
    return {"type": ",".join(study.types), **grid, "material": study.materials[0],
            "pressure": f"{study.compare_pressure_kPa:g}", "reservoir": f"{reservoir:g}"}


def _table_path(study, cache_root: Path) -> Path:
    from spsc.study.runs import code_version

    spec = json.dumps([report_space(study), study.stroke_mm, MODEL, PROCESS], sort_keys=True)
    key = hashlib.sha256((spec + code_version(MODEL)).encode()).hexdigest()[:16]
    return Path(cache_root) / "sweeps" / f"report-{study.name}-{key}.parquet"


def run_report_sweep(study, cache_root, *, workers=None, scheduler=None,
                     progress: bool = True):
    """The sweep's table (pandas; computed, or read back from the cache) and its command."""
    from spsc.sweep.run import run_sweep
    from spsc.sweep.space import build_space

    spec = report_space(study)
    table = _table_path(study, cache_root)
    table.parent.mkdir(parents=True, exist_ok=True)
    df = run_sweep(build_space(spec), model=MODEL, process=PROCESS, points=None,
                   stroke_mm=study.stroke_mm, out=table, workers=workers, scheduler=scheduler,
                   progress=progress)
    command = " ".join(["spsc sweep"] + [f"--{k} {v}" for k, v in spec.items()]
                       + [f"--model {MODEL} --process {PROCESS} --stroke {study.stroke_mm:g} "
                          "--out sweep.parquet --html sweep"])
    return df, command


def sweep_section(df, command: str, out_dir, study) -> dict:
    """Write the sweep's page into ``out_dir/sweep/`` and return the report section's data:
    counts, the link, the front figure and the few best designs of the front."""
    from spsc.report.sweep_page import DEFAULT_FRONT, write_page

    page = write_page(df, Path(out_dir) / "sweep", model=MODEL, process=PROCESS,
                      stroke_mm=study.stroke_mm, points=None, front=DEFAULT_FRONT,
                      command=command, searched=["type", "w", "t0"])
    ok = df["status"] == "ok"
    printable = df["printable"].fillna(False).astype(bool)
    return {"designs": len(df), "ok": int(ok.sum()),
            "evaluated": int(df.attrs.get("sweep", {}).get("evaluated", 0)), "printable": int((ok & printable).sum()),
            "link": f"sweep/{page.name}",
            "figure": "sweep/figures/front.png" if (page.parent / "figures" / "front.png")
            .exists() else None,
            "modes_figure": "sweep/figures/modes.png" if (page.parent / "figures" /
                                                          "modes.png").exists() else None,
            "space": report_space(study), "command": command}
