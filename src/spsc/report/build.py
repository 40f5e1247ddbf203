"""The validation report: one self-contained ``index.html`` (local PNGs, no CDN) with the data
files and ``summary.json`` beside it, built from the cached runs of a :class:`~.study.Study`.

Three parts: the metrics (:mod:`.metrics`, pure functions of curves), the sections as data
(:mod:`.render_sections`) and the HTML (:mod:`.render`, Jinja2 templates); figures in
:mod:`.figures`. The paper's printed bench figures come from :mod:`.paper_bench`, the commit
and tree state from :mod:`.provenance`.
"""

from __future__ import annotations

import shutil
import time
from dataclasses import asdict
from pathlib import Path

from spsc.core.jsonio import write_json

from spsc.report.bench import bench_section
from spsc.report.figures import FigureCache
from spsc.report.paper import paper_bench
from spsc.study.provenance import Provenance, provenance, versions
from spsc.report.bench_figure import bench_gap_figure
from spsc.report.overview import overview_section
from spsc.report.render import draw_figures, render_page
from spsc.report.fingertip import fingertip_section
from spsc.report.haptic import haptic_section
from spsc.report.time import time_section
from spsc.report.gap import gap_section
from spsc.report.surrogate import surrogate_section
from spsc.report.durability import durability_section
from spsc.report.mold import mold_section
from spsc.report.sweep import sweep_section
from spsc.report.sections import (FigureOutput, Results, comparison_section, convergence_section,
                              headline_section, jnd_section, runs_section)
from spsc.study.runs import Study, code_version

__all__ = ["build_report", "write_run_data"]


#: the sections' own folders in a report (emptied before it is written)
SECTION_DIRS = ("sweep", "mold", "haptic", "time", "gap", "surrogate", "durability")


def build_report(study: Study, outcomes: dict, out_dir, *, command: str = "",
                 wall_seconds: float | None = None, render: bool = True, fig_cache=None,
                 source: Provenance | None = None, bench=None, executor: str = "",
                 sweep=None, fingertip=None, molds=(), haptic=None, time_study=None,
                 gap=None, surrogate=None, durability=None, band=None) -> Path:
    """Write ``out_dir/index.html`` with ``figures/``, ``data/`` and ``summary.json`` beside
    it; returns the HTML path. ``outcomes`` is :func:`~.runner.run_all`'s result;
    ``fig_cache``: a directory where figures are kept by a hash of what they show (None:
    always drawn); ``render``: draw the FEM shapes; ``source``: the commit and tree state the
    report is built from (default: this checkout's, now); ``bench``: a
    :class:`~.bench_section.BenchSpec` of the user's bench test, calibrated and compared with
    the paper's identification in its own section (None: no such section); ``executor``: how
    the runs were computed (e.g. "on 2 local Dask worker processes"), beside the wall time;
    ``sweep``: ``(table, command)`` of the design-space sweep (:mod:`.report_sweep`), whose
    page is written into ``out_dir/sweep/`` and linked (None: no such section);
    ``fingertip``: the folder of a fingertip FEM study (:mod:`.report_fingertip`; None or no
    study there: the section says how to make it); ``molds``: the types whose mold is built,
    gated and rendered (:mod:`.report_mold`; empty: no such section); ``haptic``: the folder
    of the haptic chamber's study (:mod:`.report_haptic`; as ``fingertip``); ``time_study``:
    the folder of the time-domain study (:mod:`.time`; as ``fingertip``); ``gap``: the folder
    of the bench-gap study (:mod:`.gap`), ``surrogate`` the surrogate's check
    (:mod:`.surrogate`), ``durability`` the durability study (:mod:`.durability`): as
    ``fingertip``; ``band``: the headline band's record
    (:func:`~spsc.study.headline_band.run_headline_band`; None: no band)."""
    out = Path(out_dir)
    figs, data = out / "figures", out / "data"
    for d in [figs, data] + [out / k for k in SECTION_DIRS]:
        if d.exists():
            shutil.rmtree(d)
    for d in (figs, data):
        d.mkdir(parents=True)
    source = provenance() if source is None else source
    res = Results(outcomes)
    fig_out = FigureOutput(figs, FigureCache(res.key, fig_cache), render)
    write_run_data(outcomes, data)
    ctx = {"study": study, "study_rows": _study_rows(study), "command": command,
           "generated": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "wall_seconds": wall_seconds,
           "executor": executor,
           "provenance": {"commit": source.commit, "clean": source.clean,
                          "describe": source.describe()},
           "runs": runs_section(outcomes), "paper": paper_bench(),
           "headline": headline_section(study, res), "jnd": jnd_section(study, res),
           "comparison": comparison_section(study, res, fig_out),
           "convergence": convergence_section(study, res, fig_out),
           "versions": versions({m.name: code_version(m.name) for m in study.models}),
           "bench": bench_section(bench, study, figs) if bench is not None else None,
           "sweep": sweep_section(*sweep, out, study) if sweep is not None else None,
           "mold": mold_section(out, molds, render=render) if molds else None,
           **_studies(out, fingertip=fingertip, haptic=haptic, time=time_study, gap=gap,
                      surrogate=surrogate, durability=durability)}
    ctx["overview"] = overview_section(study, ctx["headline"], ctx["comparison"],
                                       ctx["convergence"], ctx["paper"])
    ctx["band"] = _band(band, study, ctx["paper"])
    drawn, ctx["figure_notes"] = draw_figures(
        figs, [("bench-gap", bench_gap_figure, ctx["overview"]["bench_gap"], ctx["band"])])
    ctx["overview"]["figure"] = drawn.get("bench-gap")
    write_json(out / "summary.json", _summary(ctx))
    path = out / "index.html"
    path.write_text(render_page(ctx), encoding="utf-8")
    return path


#: the studies a report shows: context key -> its section's builder (study folder, report)
_STUDY_SECTIONS = {"fingertip": fingertip_section, "haptic": haptic_section,
                   "time": time_section, "gap": gap_section, "surrogate": surrogate_section,
                   "durability": durability_section}


def _band(record, study, paper) -> dict | None:
    """The headline band's section (None: no band asked for or not the paper's material)."""
    if record is None or study.materials[0] != paper.material:
        return None
    from spsc.report.band import band_section
    from spsc.study.headline_band import DECLARED_SOURCES, DECLARED

    source = Path(record["tolerance"]["source"])
    declared = source.resolve() == DECLARED.resolve()
    name = ("the report's declared set (spsc/report/data/" + DECLARED.name + ")" if declared
            else source.name)
    return band_section(record, paper, DECLARED_SOURCES if declared else None, name)


def _studies(out, **folders) -> dict:
    """Each study's section from its folder (None: the study is not asked for)."""
    return {k: None if folders[k] is None else _STUDY_SECTIONS[k](folders[k], out)
            for k in _STUDY_SECTIONS}


def write_run_data(outcomes: dict, directory: Path) -> None:
    """One JSON (docs/design.md format, with its solver block) and one CSV per successful run."""
    for run, oc in outcomes.items():
        if oc.ok:
            oc.curve.to_json(directory / f"{run.label}.json")
            oc.curve.to_csv(directory / f"{run.label}.csv")


def _summary(ctx: dict) -> dict:
    """What ``summary.json`` keeps: the numbers of every section, the study, the provenance."""
    runs = ctx["runs"]
    overview = {k: v for k, v in ctx["overview"].items() if k != "bench_gap"}
    return {"study": asdict(ctx["study"]), "command": ctx["command"],
            "overview": overview, "bench_gap": ctx["overview"]["bench_gap"],
            "executor": ctx["executor"],
            "provenance": ctx["provenance"], "failed": runs["failed"], "runs": runs["rows"],
            "comparison": ctx["comparison"]["summary"],
            "headline": {mat: h["summary"] for mat, h in ctx["headline"].items()},
            "jnd_mm": ctx["jnd"]["summary"],
            "convergence": (ctx["convergence"] or {}).get("rows", []),
            "bench": ctx["bench"],
            "sweep": ctx["sweep"],
            "fingertip": ctx["fingertip"],
            "mold": ctx["mold"],
            "haptic": ctx["haptic"],
            "time": ctx["time"],
            "gap": ctx["gap"],
            "band": ctx["band"],
            "versions": ctx["versions"]}


def _study_rows(study: Study) -> list[tuple[str, str]]:
    return [("types", ", ".join(study.types)), ("materials", ", ".join(study.materials)),
            ("models", ", ".join(m.name for m in study.models)),
            ("setup pressures (kPa)", ", ".join(f"{p:g}" for p in study.pressures_kPa)),
            ("FEM comparison pressure (kPa)", f"{study.compare_pressure_kPa:g}"),
            ("modes (reservoir, mm³)", ", ".join(f"{n} ({v:g})" for n, v in study.modes)),
            ("stroke (mm)", f"{study.stroke_mm:g}"),
            ("plate positions", f"FEM {study.fem_points}, other models {study.membrane_points}"),
            ("FEM mesh (size mm, layers)",
             f"{study.mesh[0]:g}, {study.mesh[1]}" if study.fem else "FEM not run")]
