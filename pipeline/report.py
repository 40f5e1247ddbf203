"""The validation report: one self-contained ``index.html`` (local PNGs, no CDN) with the data
files beside it, built from the cached runs of a :class:`~.study.Study`.

Comparisons follow DESIGN.md: FEM F against membrane p·A + FEM F_el (the open chamber), FEM P
against membrane P; errors over the FEM's plate positions; headline means of dF/dy and dP/dy
over the stroke and the setup pressures, per type and mode, then over types; JND depth = first
y where |F_high − F_low| ≥ max(0.1·F_low, 5 N). The paper's numbers are only those printed in
its text (sec. 3.1): 5.0 → 8.0 N/mm, 0.5 → 6.1 kPa/mm (low → high, TPU 60A, bench),
JND ≈ 5 mm.
"""

from __future__ import annotations

import hashlib
import html
import json
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import time
from dataclasses import asdict
from importlib import metadata
from pathlib import Path

import numpy as np

from spsc.membrane.lumped import jnd_depth

from . import figures
from .figures import interp
from .study import MODELS, Study, code_version

__all__ = ["PAPER", "build_report", "headline", "errors", "versions"]

#: the plotting code's version: part of every cached figure's key
_FIG_CODE = hashlib.sha256(Path(figures.__file__).read_bytes()
                           + Path(__file__).read_bytes()).hexdigest()[:16]

#: the paper's printed bench figures (sec. 3.1; abstract): TPU 60A, Table 1 geometry, mean over
#: the four types, y_s range and p_i ∈ [10, 40] kPa
PAPER = {"stiffness_N_per_mm": {"low": 5.0, "high": 8.0},
         "sensitivity_kPa_per_mm": {"low": 0.5, "high": 6.1},
         "jnd_mm": 5.0}


# -- numbers ----------------------------------------------------------------------------------
def with_f_el(curve, f_el):
    """Membrane (or simplified) curve with force p·A + F_el(y) (FEM open chamber, linearly
    interpolated on the curve's grid; NaN beyond its last converged point)."""
    if f_el is None:
        return curve
    return curve.replace(force_N=curve.force_N + interp(f_el.y_mm, f_el.force_N)(curve.y_mm),
                         model=f"{curve.model}+F_el")


def errors(fem, ref) -> dict:
    """Max and RMS of (ref − FEM) at the FEM's plate positions, per column, where both are
    finite; also the RMS relative to the FEM's largest magnitude (%)."""
    out = {}
    for col in ("force_N", "pressure_kPa", "contact_area_mm2", "volume_change_mm3"):
        r = interp(ref.y_mm, getattr(ref, col))(fem.y_mm)
        f = getattr(fem, col)
        ok = np.isfinite(r) & np.isfinite(f)
        if not ok.any():
            out[col] = {"max": math.nan, "rms": math.nan, "rms_pct": math.nan, "n": 0}
            continue
        d = r[ok] - f[ok]
        scale = float(np.max(np.abs(f[ok])))
        rms = float(np.sqrt(np.mean(d**2)))
        out[col] = {"max": float(d[np.argmax(np.abs(d))]), "rms": rms,
                    "rms_pct": 100 * rms / scale if scale > 0 else math.nan, "n": int(ok.sum())}
    return out


def _mean_slope(curve, col) -> float:
    g = curve.stiffness() if col == "force_N" else curve.sensitivity()
    return float(np.nanmean(g)) if np.isfinite(g).any() else math.nan


def headline(curves_by_type: dict) -> dict:
    """``{type: [Curve per pressure]}`` → per type and overall mean stiffness (N/mm) and
    sensitivity (kPa/mm): mean over the stroke, then the pressures, then the types."""
    per = {}
    for t, cs in curves_by_type.items():
        cs = [c for c in cs if c is not None]
        per[t] = {"stiffness": float(np.mean([_mean_slope(c, "force_N") for c in cs]))
                  if cs else math.nan,
                  "sensitivity": float(np.mean([_mean_slope(c, "pressure_kPa") for c in cs]))
                  if cs else math.nan, "n": len(cs)}
    vals = [v for v in per.values() if v["n"]]
    return {"types": per,
            "stiffness": float(np.mean([v["stiffness"] for v in vals])) if vals else math.nan,
            "sensitivity": float(np.mean([v["sensitivity"] for v in vals])) if vals else math.nan}


def versions() -> dict:
    """Python, platform and every installed dependency of spsc (plus test extras present)."""
    out = {"python": sys.version.split()[0], "platform": platform.platform(),
           "cpus": os.cpu_count(),
           "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "(unset)")}
    try:
        reqs = metadata.requires("spsc") or []
    except metadata.PackageNotFoundError:
        reqs = []
    pyproject = Path(__file__).resolve().parents[1] / "pyproject.toml"
    if pyproject.is_file():  # the source's list (the installed metadata may be older)
        import tomllib

        proj = tomllib.loads(pyproject.read_text(encoding="utf-8")).get("project", {})
        reqs = list(proj.get("dependencies", [])) + [
            r for extra in proj.get("optional-dependencies", {}).values() for r in extra] + reqs
    names = ["spsc"] + [re.split(r"[\s;\[<>=!~,]", r, maxsplit=1)[0] for r in reqs]
    names += ["vtk", "mkl"]
    for n in dict.fromkeys(names):
        try:
            out[n] = metadata.version(n)
        except metadata.PackageNotFoundError:
            pass
    out["git"] = _git()
    out["code_versions"] = {m: code_version(m) for m in MODELS}
    return out


def _git() -> str:
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True, timeout=10, cwd=Path(__file__).parent)
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=10,
                               cwd=Path(__file__).parent)
        if head.returncode:
            return "unknown"
        return head.stdout.strip() + (" (with uncommitted changes)" if dirty.stdout.strip()
                                      else "")
    except (OSError, subprocess.SubprocessError):
        return "unknown"


# -- HTML helpers -----------------------------------------------------------------------------
def _f(v, fmt=".3g"):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "—"
    return format(v, fmt)


def _table(header, rows, cls="") -> str:
    h = "".join(f"<th>{html.escape(str(c))}</th>" for c in header)
    body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in r) + "</tr>" for r in rows)
    return f'<table class="{cls}"><thead><tr>{h}</tr></thead><tbody>{body}</tbody></table>'


_CSS = """body{font-family:sans-serif;max-width:1200px;margin:1em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;margin:.5em 0 1.2em;font-size:90%}
td,th{border:1px solid #bbb;padding:2px 7px;text-align:right}th{background:#eee}
td:first-child,th:first-child{text-align:left}img{max-width:100%}
.fail{color:#b00}.note{background:#fff6d5;padding:.4em .8em;border-left:4px solid #e0b000}
code,pre{background:#f4f4f4}h2{border-bottom:1px solid #ccc;margin-top:1.6em}"""


# -- the report -------------------------------------------------------------------------------
class _Lookup:
    """Curves and payloads of the outcomes, and a figure cache: a figure is a function of the
    runs it shows (their keys) and of the plotting code, so a re-run copies it."""

    def __init__(self, outcomes, fig_cache=None):
        self.o = outcomes
        self.fig_cache = None if fig_cache is None else Path(fig_cache)

    def curve(self, run):
        oc = self.o.get(run)
        return oc.curve if oc is not None and oc.ok else None

    def payload(self, run):
        oc = self.o.get(run)
        return oc.payload if oc is not None and oc.ok else None

    def figure(self, path: Path, runs, make, *extra) -> Path:
        """``make(path)`` unless a figure of the same runs, extra inputs and code is cached."""
        parts = [path.name, list(map(str, extra)), _FIG_CODE]
        for r in runs:
            oc = self.o.get(r) if r is not None else None
            parts.append(oc.payload["key"] if oc is not None and oc.ok else None)
        key = hashlib.sha256(json.dumps(parts, default=str).encode()).hexdigest()[:16]
        cached = None if self.fig_cache is None else self.fig_cache / f"{path.stem}-{key}.png"
        if cached is not None and cached.is_file():
            shutil.copyfile(cached, path)
            return path
        make(path)
        if cached is not None and path.is_file():
            cached.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, cached)
        return path


def build_report(study: Study, outcomes: dict, out_dir, *, command: str = "",
                 wall_seconds: float | None = None, render: bool = True,
                 fig_cache=None) -> Path:
    """Write ``out_dir/index.html`` with ``figures/`` and ``data/`` beside it; returns the
    HTML path. ``outcomes`` is :func:`~.runner.run_all`'s result; ``fig_cache``: a directory
    where figures are kept by a hash of what they show (None: always drawn)."""
    out = Path(out_dir)
    figs, data = out / "figures", out / "data"
    for d in (figs, data):
        if d.exists():
            shutil.rmtree(d)
        d.mkdir(parents=True)
    L = _Lookup(outcomes, fig_cache)
    S = []  # html sections
    summary = {"study": asdict(study), "command": command, "failed": [], "comparison": {},
               "headline": {}, "jnd_mm": {}, "convergence": [], "runs": []}

    # data files of every run
    for run, oc in outcomes.items():
        row = {"label": run.label, "model": run.model, "ok": oc.ok, "cached": oc.cached,
               "seconds": oc.seconds, "error": oc.error}
        if oc.ok:
            c = oc.curve
            c.to_json(data / f"{run.label}.json")
            c.to_csv(data / f"{run.label}.csv")
            row.update(converged=bool(oc.payload.get("converged")),
                       message=oc.payload.get("message", ""),
                       instability=oc.payload.get("instability", ""),
                       dofs=oc.payload.get("dofs"),
                       newton_iterations=oc.payload.get("newton_iterations"))
        else:
            summary["failed"].append({"label": run.label, "error": oc.error})
        summary["runs"].append(row)

    p_c = study.compare_pressure_kPa
    # -- per type and mode: curves and shapes ----------------------------------------------
    comp_html, err_rows = [], []
    for mat in study.materials:
        for t in study.types:
            f_el = L.curve(study.fem_run(t, mat, "open")) if study.fem else None
            for mode in study.mode_names:
                mem_run = study.membrane("membrane", t, mat, p_c, mode)
                mem, sim = L.curve(mem_run), L.curve(study.membrane("simplified", t, mat, p_c,
                                                                    mode))
                fem_run = study.fem_run(t, mat, mode) if study.fem else None
                fem = L.curve(fem_run) if fem_run else None
                tag = f"{t}-{mat}-{mode}"
                title = (f"Type {t}, {mat}, {mode} stiffness (V_r = "
                         f"{study.reservoir(mode) / 1000:g} cm³), p_i = {p_c:g} kPa")
                sim_run = study.membrane("simplified", t, mat, p_c, mode)
                f_el_run = study.fem_run(t, mat, "open") if study.fem else None
                png = L.figure(figs / f"curves-{tag}.png", (fem_run, mem_run, sim_run, f_el_run),
                               lambda path: figures.curves_figure(
                                   path, title, fem=fem, membrane=mem, simplified=sim,
                                   f_el=f_el), title)
                block = [f"<h3>{html.escape(title)}</h3>", f'<img src="figures/{png.name}">']
                if render and fem_run is not None:
                    png = L.figure(figs / f"shapes-{tag}.png", (mem_run, fem_run),
                                   lambda path: _shapes(path, title, L.payload(mem_run),
                                                        L.payload(fem_run)), title)
                    block.append(f'<img src="figures/{png.name}">')
                comp_html.append("\n".join(block))
                if fem is not None and mem is not None:
                    e = errors(fem, with_f_el(mem, f_el))
                    summary["comparison"][tag] = e
                    err_rows.append([f"{t}", mode] + [
                        f"{_f(e[c]['max'])} / {_f(e[c]['rms'])} ({_f(e[c]['rms_pct'], '.2g')} %)"
                        for c in ("force_N", "pressure_kPa", "contact_area_mm2",
                                  "volume_change_mm3")])
                elif study.fem:
                    err_rows.append([t, mode] + ['<span class="fail">no result</span>'] * 4)

    # -- headline ------------------------------------------------------------------------
    head_html = []
    for mat in study.materials:
        rows = []
        res = {}
        for mode in study.mode_names:
            by_type, by_type_nofel = {}, {}
            for t in study.types:
                f_el = L.curve(study.fem_run(t, mat, "open")) if study.fem else None
                cs = [L.curve(study.membrane("membrane", t, mat, p, mode))
                      for p in study.pressures_kPa]
                by_type[t] = [with_f_el(c, f_el) if c is not None else None for c in cs]
                by_type_nofel[t] = cs
            res[mode] = {"membrane+F_el": headline(by_type),
                         "membrane p·A": headline(by_type_nofel)}
            if study.fem:
                res[mode]["FEM"] = headline({t: [L.curve(study.fem_run(t, mat, mode))]
                                             for t in study.types})
        summary["headline"][mat] = res
        for mode in study.mode_names:
            h, h0 = res[mode]["membrane+F_el"], res[mode]["membrane p·A"]
            hf = res[mode].get("FEM")
            paper_k = PAPER["stiffness_N_per_mm"].get(mode) if mat == "tpu60a" else None
            paper_s = PAPER["sensitivity_kPa_per_mm"].get(mode) if mat == "tpu60a" else None
            rows.append([mode, _f(h["stiffness"]), _f(h0["stiffness"]),
                         _f(hf["stiffness"]) if hf else "—", _f(paper_k),
                         _f(h["sensitivity"]), _f(hf["sensitivity"]) if hf else "—",
                         _f(paper_s)])
        if len(study.mode_names) == 2 and "high" in res and "low" in res:
            hi, lo = res["high"]["membrane+F_el"], res["low"]["membrane+F_el"]
            rows.append(["high / low", _f(hi["stiffness"] / lo["stiffness"]), "—", "—",
                         _f(8.0 / 5.0) if mat == "tpu60a" else "—",
                         _f(hi["sensitivity"] / lo["sensitivity"]), "—",
                         _f(6.1 / 0.5) if mat == "tpu60a" else "—"])
        per_type = []
        for mode in study.mode_names:
            for t in study.types:
                v = res[mode]["membrane+F_el"]["types"][t]
                per_type.append([t, mode, _f(v["stiffness"]), _f(v["sensitivity"]), v["n"]])
        head_html.append(
            f"<h3>{html.escape(mat)}</h3>" + _table(
                ["mode", "stiffness membrane + F_el (N/mm)", "membrane p·A only",
                 f"FEM (p_i = {p_c:g} kPa only)", "paper, bench (N/mm)",
                 "sensitivity membrane (kPa/mm)", f"FEM (p_i = {p_c:g} kPa only)",
                 "paper, bench (kPa/mm)"], rows)
            + "<p>Per type (membrane + F_el):</p>"
            + _table(["type", "mode", "stiffness (N/mm)", "sensitivity (kPa/mm)",
                      "pressures"], per_type))

    # -- JND --------------------------------------------------------------------------------
    jnd_rows = []
    for mat in study.materials:
        if not {"high", "low"} <= set(study.mode_names):
            break
        for t in study.types:
            f_el = L.curve(study.fem_run(t, mat, "open")) if study.fem else None
            row = [t, html.escape(mat)]
            jt = {}
            for p in study.pressures_kPa:
                hi = L.curve(study.membrane("membrane", t, mat, p, "high"))
                lo = L.curve(study.membrane("membrane", t, mat, p, "low"))
                j, cell = _jnd(with_f_el(hi, f_el) if hi is not None else None,
                               with_f_el(lo, f_el) if lo is not None else None)
                jt[f"membrane+F_el p{p:g}"] = j
                row.append(cell)
            if study.fem:
                j, cell = _jnd(*(L.curve(study.fem_run(t, mat, m)) for m in ("high", "low")))
                jt[f"FEM p{p_c:g}"] = j
                row.append(cell)
            summary["jnd_mm"][f"{t}-{mat}"] = jt
            jnd_rows.append(row)
    jnd_head = (["type", "material"] + [f"membrane + F_el, p_i = {p:g} kPa (mm)"
                                        for p in study.pressures_kPa]
                + ([f"FEM, p_i = {p_c:g} kPa (mm)"] if study.fem else []))

    # -- convergence and timing ---------------------------------------------------------
    conv_html = ""
    if study.fem:
        conv_html = _convergence(study, L, outcomes, figs, summary)
    timing_rows = []
    for run, oc in outcomes.items():
        p = oc.payload or {}
        status = ("ok" if p.get("converged") else
                  f"not converged: {html.escape(str(p.get('message', '')))}") if oc.ok else \
            f'<span class="fail">failed: {html.escape(oc.error)}</span>'
        if p.get("instability"):
            status += f"; instability: {html.escape(p['instability'])}"
        timing_rows.append([html.escape(run.label), run.model, _f(oc.seconds, ".2f"),
                            "yes" if oc.cached else "no", p.get("dofs") or "—", status])
    total_compute = sum(oc.seconds for oc in outcomes.values() if math.isfinite(oc.seconds))

    # -- page -------------------------------------------------------------------------------
    ver = versions()
    summary["versions"] = ver
    fails = summary["failed"]
    S.append(f"<h1>SPSC validation report — study “{html.escape(study.name)}”</h1>")
    S.append(f"<p>Generated {time.strftime('%Y-%m-%d %H:%M:%S %Z')} by <code>"
             f"{html.escape(command)}</code>. The runs took "
             f"{_f(wall_seconds, '.1f')} s wall-clock (cache hits included); their compute "
             "time when made "
             f"{total_compute:.1f} s.</p>")
    if study.note:
        S.append(f'<p class="note">{html.escape(study.note)}</p>')
    S.append(_study_table(study))
    notes = []
    for run, oc in outcomes.items():
        p = oc.payload or {}
        if oc.ok and (not p.get("converged", True) or p.get("instability")):
            c = oc.curve
            reach = c.y_mm[c.converged][-1] if c.converged.any() else float("nan")
            txt = f"<code>{html.escape(run.label)}</code>: converged up to y = {reach:g} mm"
            if p.get("message") and not p.get("converged", True):
                txt += f"; {html.escape(p['message'])}"
            if p.get("instability"):
                txt += f"; <b>instability</b>: {html.escape(p['instability'])}"
            notes.append(f"<li>{txt}</li>")
    if notes:
        S.append("<h2>Solver notes</h2><p>Points not converged are NaN in the data and left "
                 "out of every metric (means, errors, JND); where the open chamber's F_el is "
                 "missing, membrane + F_el is too.</p><ul>" + "".join(notes) + "</ul>")
    if fails:
        S.append('<h2 class="fail">Failed runs</h2><ul>' + "".join(
            f'<li class="fail"><code>{html.escape(f["label"])}</code>: '
            f'{html.escape(f["error"])}</li>' for f in fails) + "</ul>")
    plist = ", ".join(f"{p:g}" for p in study.pressures_kPa)
    S.append("<h2>Headline: mean stiffness and sensitivity, low vs high mode</h2>"
             "<p>Mean of dF/dy and dP/dy over y ∈ [0, "
             f"{study.stroke_mm:g}] mm and p_i ∈ {{{plist}}} kPa per type and mode, then over "
             "the types. Computed here: membrane P and p·A plus the "
             "FEM open-chamber F_el(y) (the paper added its measured F_el to its model the same "
             "way). The paper's values are its bench means over the four TPU 60A types (sec. 3.1), "
             "the only numbers it prints; no plotted data is used.</p>" + "".join(head_html))
    if jnd_rows:
        S.append("<h2>JND depth per type</h2><p>First y where |F_high − F_low| ≥ "
                 "max(0.1·F_low, 5 N). Paper (bench, Fig. 5(e), p_i = 10 kPa): "
                 f"≈ {PAPER['jnd_mm']:g} mm for all types, A and D slightly better.</p>"
                 + _table(jnd_head, jnd_rows))
    if study.fem:
        S.append("<h2>Membrane vs FEM: errors over the stroke</h2><p>Membrane − FEM at the "
                 "FEM plate positions, signed largest / RMS (RMS as % of the FEM's largest "
                 f"magnitude); p_i = {p_c:g} kPa. Force: membrane p·A + FEM F_el against FEM F; "
                 "area: the membrane's is the flattened area, the FEM's the outer surface "
                 "touching the plate (DESIGN.md).</p>"
                 + _table(["type", "mode", "F (N)", "P (kPa)", "A (mm²)", "ΔV (mm³)"],
                          err_rows))
    S.append("<h2>Curves and deformed shapes per type and mode</h2>"
             "<p>F(y), P(y), A(y), ΔV(y) of FEM (points), membrane (line) and simplified "
             "(dashed) models; y from first contact with the inflated chamber (the open "
             "chamber's from first contact at rest). Deformed shapes: FEM quarter model "
             "mirrored to the full part, rendered from its VTU, beside the membrane meridian and "
             "the FEM cavity section in the middle plane (y = 0).</p>" + "\n".join(comp_html))
    if conv_html:
        S.append(conv_html)
    S.append("<h2>Runs and timing</h2><p>Seconds: compute time when the run was made "
             "(cached runs keep theirs).</p>" + _table(
                 ["run", "model", "seconds", "cached", "unknowns", "status"], timing_rows))
    S.append("<h2>Versions</h2>" + _table(["component", "version"], [
        [html.escape(k), html.escape(json.dumps(v) if isinstance(v, dict) else str(v))]
        for k, v in ver.items()]))
    S.append(f"<h2>Command</h2><pre>{html.escape(command)}</pre><p>Data: <code>data/</code> "
             "(one JSON and CSV per run, DESIGN.md format), <code>summary.json</code>.</p>")
    page = ("<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>SPSC validation "
            f"report</title><style>{_CSS}</style></head><body>\n" + "\n".join(S)
            + "\n</body></html>\n")
    (out / "summary.json").write_text(json.dumps(_clean(summary), indent=1, default=str) + "\n", encoding="utf-8")
    path = out / "index.html"
    path.write_text(page, encoding="utf-8")
    return path


def _jnd(hi, lo):
    """(JND depth mm or NaN, table cell): "> y" when not reached up to the last plate position
    where both forces are known."""
    if hi is None or lo is None:
        return math.nan, '<span class="fail">no result</span>'
    j = jnd_depth(hi, lo)
    if math.isfinite(j):
        return j, f"{j:.2f}"
    ok = np.isfinite(hi.force_N) & np.isfinite(lo.force_N)
    return j, f"not reached by y = {hi.y_mm[ok][-1]:g}" if ok.any() else "—"


def _clean(v):
    """NaN → null, recursively (strict JSON)."""
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if isinstance(v, dict):
        return {str(k): _clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_clean(x) for x in v]
    return v


def _study_table(study: Study) -> str:
    rows = [["types", ", ".join(study.types)], ["materials", ", ".join(study.materials)],
            ["setup pressures (kPa)", ", ".join(f"{p:g}" for p in study.pressures_kPa)],
            ["FEM comparison pressure (kPa)", f"{study.compare_pressure_kPa:g}"],
            ["modes (reservoir, mm³)", ", ".join(f"{n} ({v:g})" for n, v in study.modes)],
            ["stroke (mm)", f"{study.stroke_mm:g}"],
            ["plate positions", f"FEM {study.fem_points}, membrane {study.membrane_points}"],
            ["FEM mesh (size mm, layers)", f"{study.mesh[0]:g}, {study.mesh[1]}" if study.fem
             else "FEM not run"]]
    return _table(["study", ""], rows)


def _shapes(path, title, mem_payload, fem_payload) -> Path:
    """Renders of the FEM VTUs (inflated, pressed) beside the meridians, into ``path``."""
    renders = []
    if fem_payload:
        d = Path(fem_payload["dir"])
        for k, cap in (("inflated", "FEM inflated"), ("pressed", "FEM pressed")):
            name = fem_payload.get("vtu", {}).get(k)
            if name and (d / name).is_file():
                png = path.with_name(f"render-{path.stem}-{k}.png")
                try:
                    figures.render_vtu(d / name, png, plate=k == "pressed")
                except Exception as exc:  # noqa: BLE001 — a failed render must not stop it
                    print(f"spsc report: render of {d / name} failed: {exc}", file=sys.stderr)
                    continue
                if k == "pressed" and fem_payload.get("pressed_y_mm") is not None:
                    cap += f", y = {fem_payload['pressed_y_mm']:g} mm"
                renders.append((png, cap))
    mer = (mem_payload or {}).get("meridians")
    plates = []
    if mer and mer.get("pressed"):
        plates.append(max(mer["pressed"]["eta"]))
    figures.shapes_figure(path, "Deformed shapes — " + title, renders=renders, membrane=mer,
                          fem=(fem_payload or {}).get("sections"), plates=plates)
    for png, _ in renders:  # composed into the figure; the HTML shows only that
        png.unlink(missing_ok=True)
    return path


def _convergence(study, L, outcomes, figs, summary) -> str:
    rows, curves = [], []
    t, mat = study.convergence_type, study.materials[0]
    meshes = sorted(dict.fromkeys(tuple(m) for m in (*study.convergence_meshes, study.mesh)),
                    key=lambda m: -m[0])
    runs = [study.fem_run(t, mat, "high", m) for m in meshes]
    finest = L.curve(runs[-1])
    for m, run in zip(meshes, runs):
        oc = outcomes.get(run)
        c = L.curve(run)
        if c is None:
            rows.append([f"{m[0]:g}", m[1], "—", "—", "—", "—", "—",
                         f'<span class="fail">{html.escape(oc.error if oc else "not run")}</span>'])
            continue
        p = oc.payload
        curves.append((f"{m[0]:g} mm, {m[1]} layer(s), {p.get('dofs')} unknowns", c))
        dF = (np.nanmax(np.abs(c.force_N - finest.force_N)) / np.nanmax(np.abs(finest.force_N))
              if finest is not None and len(finest) == len(c) else math.nan)
        row = {"mesh_mm": m[0], "layers": m[1], "dofs": p.get("dofs"),
               "tetrahedra": p.get("tetrahedra"), "force_end_N": float(c.force_N[-1]),
               "pressure_end_kPa": float(c.pressure_kPa[-1]), "max_rel_force_diff": float(dF),
               "seconds": oc.seconds}
        summary["convergence"].append(row)
        rows.append([f"{m[0]:g}", m[1], p.get("dofs"), p.get("tetrahedra"),
                     _f(row["force_end_N"], ".4g"), _f(row["pressure_end_kPa"], ".4g"),
                     _f(100 * dF, ".2g") + " %", _f(oc.seconds, ".1f")])
    img = ""
    if curves:
        title = (f"Mesh convergence: Type {t}, {mat}, high stiffness, "
                 f"p_i = {study.compare_pressure_kPa:g} kPa")
        png = L.figure(figs / "convergence.png", runs,
                       lambda path: figures.convergence_figure(path, title, curves), title)
        img = f'<img src="figures/{png.name}">'
    return ("<h2>FEM mesh convergence and timing</h2>"
            f"<p>Type {t}, high stiffness, p_i = {study.compare_pressure_kPa:g} kPa; max |ΔF| "
            "over "
            "the stroke relative to the finest mesh's largest force. Seconds: one core "
            "(OMP_NUM_THREADS as set when run).</p>"
            + _table(["mesh (mm)", "layers", "unknowns", "tetrahedra", f"F at y = "
                      f"{study.stroke_mm:g} mm (N)", "P there (kPa)", "max ΔF vs finest",
                      "seconds"], rows) + img)
