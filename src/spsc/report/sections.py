"""The report's sections as data: each function takes the study and its outcomes and returns
what the template shows (numbers, not HTML) and what ``summary.json`` keeps.

The models are the study's (:data:`spsc.models.MODELS`): every sweep model (membrane, simplified,
…) is drawn, compared with the FEM, and enters the headline and the JND table, with the FEM's
open-chamber F_el(y) added to its force when it has no bending (docs/design.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from spsc.report import figures
from spsc.study.metrics import Jnd, headline, headline_row, jnd, model_errors, with_f_el
from spsc.study.runs import Study

__all__ = ["FigureOutput", "Results", "runs_section", "comparison_section", "headline_section",
           "jnd_section", "convergence_section"]


class Results:
    """The outcomes of a study's runs, looked up by run (None for a missing or failed run)."""

    def __init__(self, outcomes: dict):
        self.outcomes = outcomes

    def curve(self, run):
        oc = self.outcomes.get(run) if run is not None else None
        return oc.curve if oc is not None and oc.ok else None

    def payload(self, run):
        oc = self.outcomes.get(run) if run is not None else None
        return oc.payload if oc is not None and oc.ok else None

    def key(self, run):
        p = self.payload(run)
        return p["key"] if p else None

    def f_el(self, study: Study, type_: str, mat: str):
        """The FEM open chamber's curve (F_el), or None without the FEM."""
        return self.curve(study.fem_run(type_, mat, "open")) if study.fem else None

    def sweep_curve(self, study, m, type_, mat, p, mode, f_el):
        """A sweep model's curve, with F_el added when the model has no bending."""
        c = self.curve(study.membrane(m.name, type_, mat, p, mode))
        return with_f_el(c, f_el) if c is not None and not m.bending else c


def _variant(m, with_fel: bool) -> str:
    return f"{m.name}+F_el" if with_fel else (m.name if m.bending else f"{m.name} p·A")


def runs_section(outcomes: dict) -> dict:
    """Per run: label, model, seconds, cached, unknowns, status; the solver notes (runs that
    stopped early or met an instability) and the failed runs."""
    rows, notes, failed = [], [], []
    for run, oc in outcomes.items():
        row = {"label": run.label, "model": run.model, "ok": oc.ok, "cached": oc.cached,
               "seconds": oc.seconds, "error": oc.error, "converged": False, "message": "",
               "instability": "", "unknowns": None, "iterations": None}
        if not oc.ok:
            failed.append({"label": run.label, "error": oc.error})
        else:
            s = oc.solver
            row.update(converged=s.converged, message=s.message, instability=s.instability,
                       unknowns=s.details.get("dofs"), iterations=s.iterations)
            if not s.converged or s.instability:
                c = oc.curve
                notes.append({"label": run.label, "message": "" if s.converged else s.message,
                              "instability": s.instability,
                              "reach": float(c.y_mm[c.converged][-1]) if c.converged.any()
                              else math.nan})
        rows.append(row)
    total = sum(oc.seconds for oc in outcomes.values() if math.isfinite(oc.seconds))
    return {"rows": rows, "notes": notes, "failed": failed, "compute_seconds": total}


@dataclass(frozen=True)
class FigureOutput:
    """Where figures are written (``dir``), their :class:`~.figures.FigureCache`, and whether
    the FEM shapes are rendered (``render``)."""

    dir: Path
    cache: figures.FigureCache
    render: bool = True


def comparison_section(study: Study, res: Results, figs: FigureOutput) -> dict:
    """Per type and mode (materials in turn): the curves figure of every model, the deformed
    shapes (FEM render beside the membrane meridian) and each sweep model's errors against
    the FEM at the comparison pressure."""
    blocks, errors, summary = [], [], {}
    p_c = study.compare_pressure_kPa
    for mat in study.materials:
        for t in study.types:
            f_el_run = study.fem_run(t, mat, "open") if study.fem else None
            for mode in study.mode_names:
                tag = f"{t}-{mat}-{mode}"
                title = (f"Type {t}, {mat}, {mode} stiffness (V_r = "
                         f"{study.reservoir(mode) / 1000:g} cm³), p_i = {p_c:g} kPa")
                fem_run = study.fem_run(t, mat, mode) if study.fem else None
                runs = [(m, study.membrane(m.name, t, mat, p_c, mode) if m.sweep else fem_run)
                        for m in study.models]
                images = [_curves_png(figs, res, tag, title, runs, f_el_run)]
                if figs.render and fem_run is not None:
                    images.append(_shapes_png(figs, res, tag, title, runs[0][1], fem_run))
                blocks.append({"id": f"curves-{tag}", "title": title, "images": images})
                if fem_run is None:
                    continue
                per = _errors(res, res.curve(fem_run), runs, res.curve(f_el_run))
                summary[tag] = {k: v for k, v in per.items() if v is not None}
                errors += [{"type": t, "mode": mode, "model": k, "errors": v}
                           for k, v in per.items()]
    return {"blocks": blocks, "errors": errors, "summary": summary}


def _errors(res, fem, runs, f_el) -> dict:
    out = {}
    for m, run in runs:
        if not m.sweep:
            continue
        c = res.curve(run)
        ok = c is not None and fem is not None
        out[_variant(m, f_el is not None and not m.bending)] = (
            model_errors(fem, with_f_el(c, None if m.bending else f_el)) if ok else None)
    return out


def _curves_png(figs, res, tag, title, runs, f_el_run) -> str:
    f_el = res.curve(f_el_run)
    pairs = [(m, res.curve(r)) for m, r in runs]
    png = figs.cache.draw(figs.dir / f"curves-{tag}.png", [r for _, r in runs] + [f_el_run],
                          lambda path: figures.curves_figure(path, title, pairs, f_el=f_el),
                          title)
    return png.name


def _shapes_png(figs, res, tag, title, mem_run, fem_run) -> str:
    png = figs.cache.draw(figs.dir / f"shapes-{tag}.png", (mem_run, fem_run),
                          lambda path: figures.shapes_panel(path, title, res.payload(mem_run),
                                                            res.payload(fem_run)), title)
    return png.name


def headline_section(study: Study, res: Results) -> dict:
    """Per material: the headline rows (each sweep model, with and without F_el when it has no
    bending, and the FEM at the comparison pressure only) and the per-type means."""
    out = {}
    for mat in study.materials:
        by_variant: dict[str, dict] = {}
        for mode in study.mode_names:
            for name, per_type in _headline_curves(study, res, mat, mode).items():
                by_variant.setdefault(name, {})[mode] = headline(per_type)
        rows = [headline_row(name, modes) for name, modes in by_variant.items()]
        per_type = [{"variant": name, "mode": mode, "type": t, **v}
                    for name, modes in by_variant.items() for mode, h in modes.items()
                    for t, v in h["types"].items() if name != "fem"]
        out[mat] = {"rows": rows, "per_type": per_type, "summary": by_variant}
    return out


def _headline_curves(study, res, mat, mode) -> dict:
    """{variant: {type: [curves over the setup pressures]}} of one material and mode."""
    out: dict[str, dict] = {}
    for t in study.types:
        f_el = res.f_el(study, t, mat)
        for m in study.sweep_models:
            variants = [(m, f_el is not None and not m.bending)]
            if variants[0][1]:
                variants.append((m, False))  # p·A alone: what the model itself predicts
            for mm, fel in variants:
                out.setdefault(_variant(mm, fel), {})[t] = [
                    res.sweep_curve(study, mm, t, mat, p, mode, f_el if fel else None)
                    for p in study.pressures_kPa]
        if study.fem:
            out.setdefault("fem", {})[t] = [res.curve(study.fem_run(t, mat, mode))]
    return out


def jnd_section(study: Study, res: Results) -> dict:
    """JND depth per type, material and model variant at every setup pressure (the FEM at the
    comparison pressure only): rows of cells, each a :class:`~.metrics.Jnd`, ``"failed"`` (a
    run of the pair failed) or None (not run at that pressure)."""
    pressures = study.all_pressures
    rows, summary = [], {}
    if not {"high", "low"} <= set(study.mode_names):
        return {"pressures": pressures, "rows": rows, "summary": summary}
    for mat in study.materials:
        for t in study.types:
            f_el = res.f_el(study, t, mat)
            for m in study.models:
                fel = f_el is not None and not m.bending
                cells = [_jnd_cell(study, res, m, t, mat, p, f_el if fel else None)
                         for p in pressures]
                name = _variant(m, fel)
                rows.append({"type": t, "material": mat, "variant": name, "cells": cells})
                summary.setdefault(f"{t}-{mat}", {}).update(
                    {f"{name} p{p:g}": c.depth_mm if isinstance(c, Jnd) else math.nan
                     for p, c in zip(pressures, cells) if c is not None})
    return {"pressures": pressures, "rows": rows, "summary": summary}


def _jnd_cell(study, res, m, t, mat, p, f_el):
    if not m.sweep:
        if p != study.compare_pressure_kPa:
            return None
        hi, lo = (res.curve(study.fem_run(t, mat, mode)) for mode in ("high", "low"))
    else:
        hi, lo = (res.sweep_curve(study, m, t, mat, p, mode, f_el) for mode in ("high", "low"))
    if hi is None or lo is None:
        return "failed"
    return jnd(hi, lo)


def convergence_section(study: Study, res: Results, figs: FigureOutput) -> dict | None:
    """The FEM mesh convergence of one type (high mode, comparison pressure): per mesh the
    unknowns, end force and pressure, max |ΔF| relative to the finest mesh, seconds."""
    if not study.fem:
        return None
    t, mat = study.convergence_type, study.materials[0]
    meshes = sorted(dict.fromkeys(tuple(m) for m in (*study.convergence_meshes, study.mesh)),
                    key=lambda m: -m[0])
    runs = [study.fem_run(t, mat, "high", m) for m in meshes]
    finest = res.curve(runs[-1])
    rows, curves = [], []
    for m, run in zip(meshes, runs):
        oc, c = res.outcomes.get(run), res.curve(run)
        row = {"mesh_mm": m[0], "layers": m[1]}
        if c is None:
            rows.append({**row, "error": oc.error if oc else "not run"})
            continue
        d = c.solver.details
        same = finest is not None and len(finest) == len(c)
        rel = (float(np.nanmax(np.abs(c.force_N - finest.force_N))
                     / np.nanmax(np.abs(finest.force_N))) if same else math.nan)
        rows.append({**row, "dofs": d.get("dofs"), "tetrahedra": d.get("tetrahedra"),
                     "force_end_N": float(c.force_N[-1]),
                     "pressure_end_kPa": float(c.pressure_kPa[-1]),
                     "max_rel_force_diff": rel, "seconds": oc.seconds})
        curves.append((f"{m[0]:g} mm, {m[1]} layer(s), {d.get('dofs')} unknowns", c))
    title = (f"Mesh convergence: Type {t}, {mat}, high stiffness, "
             f"p_i = {study.compare_pressure_kPa:g} kPa")
    image = figs.cache.draw(figs.dir / "convergence.png", runs, lambda path:
                            figures.convergence_figure(path, title, curves), title).name \
        if curves else None
    return {"type": t, "rows": rows, "image": image}

