"""The fingertip study (issue 14, ``make fingertip-fem``): the fused fingertip of sec. 4.1 in
the 3D FEM, pressed by a plate on the pulp and on the distal edge, in both modes at two setup
pressures; the five FSR pocket forces; the same presses on a single Type A chamber of the same
size; and the fast estimate (:mod:`.fused_estimate`) against the FEM.

Every curve is a JSON file under ``OUT/curves/``, kept with the key of its inputs and of the
code that computed it (:mod:`spsc.study.keyed`): reused while both are the same, computed again
when either changed. ``OUT/summary.json`` holds the figures the report shows. The part is the one ``spsc
fingertip`` builds (default :class:`~spsc.cad.specs.FingertipSpec`), in Silicone 40A (the
paper's fingertip material); the mount is the underside and the slot for the gripper finger
(the design file's ``fem.mount``); the plate sites are the design file's ``pulp`` (straight
down) and ``distal`` (along the distal chamber's axis); the low mode opens a 40 cm³ reservoir
(the paper's).
"""

from __future__ import annotations

import hashlib
import json
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from spsc.core.curve import Curve
from spsc.core.errors import ParameterError

__all__ = ["FingertipStudy", "CASES", "run_study", "case_name"]

#: (site, mode, setup pressure kPa)
CASES = tuple((site, mode, p) for site in ("pulp", "distal") for mode in ("high", "low")
              for p in (10.0, 40.0))
LOW_RESERVOIR_MM3 = 40000.0
#: the cases whose deformed state is rendered
RENDERED = (("pulp", "high", 40.0), ("distal", "high", 40.0))


def case_name(site, mode, pressure) -> str:
    return f"{site}-{mode}-{pressure:g}kPa"


@dataclass(frozen=True)
class FingertipStudy:
    """The study's setup: mesh size at the chambers' walls (mm), stroke (mm) and points,
    material, the cases; ``single`` and ``fast``: run the single-chamber and fast-estimate
    comparisons."""

    mesh_size_mm: float = 2.0
    stroke_mm: float = 3.0
    points: int = 7
    material: str = "silicone40a"
    cases: tuple = CASES
    single: bool = True
    fast: bool = True
    fast_model: str = "wall"

    def __post_init__(self):
        unknown = [c for c in self.cases if tuple(c) not in CASES]
        if unknown or not self.cases:
            raise ParameterError("cases", self.cases, "one or more of the study's cases "
                                 f"{CASES}")
        seen = set()
        for c in self.cases:
            if tuple(c) in seen:
                raise ParameterError("cases", case_name(*c), "each case once (it is given "
                                     "twice: it would run twice)")
            seen.add(tuple(c))


def _part(out: Path) -> tuple[Path, dict]:
    """The fingertip's STL and design file under ``out/part`` (built once)."""
    stl = out / "part" / "fingertip.stl"
    design = stl.with_name("fingertip.design.json")
    if not (stl.exists() and design.exists()):
        from spsc.cad.export import export_part, tessellate
        from spsc.cad.fingertip import MESH_TOLERANCE, build_fingertip

        tip = build_fingertip()
        export_part(tip.solid, tip.design, stl.parent, "fingertip",
                    mesh=tessellate(tip.solid, *MESH_TOLERANCE))
    return stl, json.loads(design.read_text(encoding="utf-8"))


def _fem_case(study, stl, design, site, mode, pressure, path: Path, vtu: Path | None, log):
    """One press of the fingertip: the part model of the registry (its settings those of
    ``spsc fem --part``)."""
    from spsc.core.loadcase import check_load
    from spsc.core.setup import Contact, Setup
    from spsc.fem.part import ContactPatch, Part
    from spsc.materials import material
    from spsc.models import MODELS

    fem = design["fem"]
    s = fem["sites"][site]
    contacts = tuple(ContactPatch(c["name"], tuple(c["center"]), tuple(c["normal"]),
                                  c["radius"], c["insert_mm"]) for c in fem["contacts"])
    body = Part(str(stl), fem["mount"], plate_normal=tuple(s["normal"]), plate_at=tuple(s["at"]),
                design=design, contacts=contacts)
    load = check_load(None, pressure_kPa=pressure,
                      reservoir_mm3=LOW_RESERVOIR_MM3 if mode == "low" else 0.0,
                      stroke_mm=study.stroke_mm, points=study.points, polytropic_n=1.0)
    setup = Setup(body, material(study.material), load, Contact())
    model = MODELS["part"]
    options = model.Options(mesh_size=study.mesh_size_mm, vtu=vtu)
    t0 = time.perf_counter()
    out = model.curve(setup, options, progress=lambda d, n: log(
        f"    step {d}/{n} ({time.perf_counter() - t0:.0f} s)"))
    curve = out.curve
    log(f"  {path.stem}: {curve.solver.details.get('dofs', 0):,} unknowns "
        f"(mesh {curve.solver.details.get('mesh_seconds', float('nan')):.0f} s)")
    extra = {"vtu": [str(Path(vtu) / v) for v in out.extra["vtu"]]} if vtu is not None else {}
    curve.to_json(path, extra=extra or None)
    return curve


def _single_case(study, geometry, mode, pressure, path: Path) -> Curve:
    """The single chamber's 3D FEM curve, through the model registry (its settings those of
    ``spsc curve --model fem``)."""
    from spsc.core.setup import Setup
    from spsc.materials import material
    from spsc.models import MODELS

    fem = MODELS["fem"]
    setup = Setup.of(geometry, material(study.material), pressure_kPa=pressure,
                     reservoir_mm3=LOW_RESERVOIR_MM3 if mode == "low" else 0.0,
                     stroke_mm=study.stroke_mm, points=study.points)
    curve = fem.curve(setup, fem.Options(mesh_size=1.0, layers=2)).curve
    curve.to_json(path)
    return curve


def _kept(path: Path, inputs: dict, modules) -> tuple:
    """(the kept curve or None, its KeyedFile): the curve at ``path`` if it was computed from
    ``inputs`` by the present code of ``modules``."""
    from spsc.study.keyed import KeyedFile, input_key

    keyed = KeyedFile(path, input_key(inputs, modules))
    return (Curve.from_json(path) if keyed.valid else None), keyed


def run_study(study: FingertipStudy, out, *, stl=None, design=None, spec=None,
              log=print) -> dict:
    """Run (or reuse) every curve of ``study`` under ``out`` on the fingertip ``stl`` with its
    ``design`` dict and ``spec`` (default: the default fingertip, built under ``out/part``);
    returns and writes the summary."""
    from spsc.cad.specs import FingertipSpec

    out = Path(out)
    (out / "curves").mkdir(parents=True, exist_ok=True)
    if stl is None:
        stl, design = _part(out)
    spec = spec or FingertipSpec()
    chambers = {"pulp": spec.pulp, "distal": spec.distal}
    channel = design["cavity_volume_mm3"] - spec.pulp.cavity_volume() - spec.distal.cavity_volume()
    summary = {"mesh_size_mm": study.mesh_size_mm, "material": study.material,
               "stroke_mm": study.stroke_mm, "low_reservoir_mm3": LOW_RESERVOIR_MM3,
               "cavity_volume_mm3": design["cavity_volume_mm3"], "channel_mm3": channel,
               "cases": {}}
    setup = {"mesh_size_mm": study.mesh_size_mm, "stroke_mm": study.stroke_mm,
             "points": study.points, "material": study.material}
    part = hashlib.sha256(Path(stl).read_bytes()).hexdigest()
    for site, mode, p in study.cases:
        name = case_name(site, mode, p)
        row = {"site": site, "mode": mode, "pressure_kPa": p}
        case = {**setup, "site": site, "mode": mode, "pressure_kPa": p}
        path = out / "curves" / f"fem-{name}.json"
        t0 = time.perf_counter()
        fem, keyed = _kept(path, {**case, "part": part, "design": design},
                           ("spsc.models.part", "spsc.fem.engine"))
        if fem is None:
            log(f"fingertip FEM {name}")
            vtu = out / "vtu" / name if (site, mode, p) in RENDERED else None
            fem = _fem_case(study, stl, design, site, mode, p, path, vtu, log)
            keyed.mark()
            log(f"  done in {time.perf_counter() - t0:.0f} s: {fem.solver.message}")
        row["fem"] = _metrics(fem)
        if study.single:
            spath = out / "curves" / f"single-{name}.json"
            single, keyed = _kept(spath, {**case, "chamber": chambers[site].as_dict()},
                                  ("spsc.models.fem",))
            if single is None:
                single = _single_case(study, chambers[site], mode, p, spath)
                keyed.mark()
            row["single"] = _metrics(single)
            row["sensitivity_ratio_fused_to_single"] = _ratio(fem, single)
        if study.fast:
            fast = _fast_case(study, out / "curves" / f"fast-{name}.json", case, chambers,
                              channel)
            row["fast"] = _metrics(fast)
            row["fast_error"] = _errors(fast, fem)
        summary["cases"][name] = row
    (out / "summary.json").write_text(json.dumps(summary, indent=1, allow_nan=False,
                                                 default=_nan_to_none), encoding="utf-8")
    return summary


def _fast_case(study, path: Path, case: dict, chambers: dict, channel: float) -> Curve:
    """The fast estimate of one case (kept while its inputs and code are the same)."""
    from spsc.materials import material
    from spsc.studies.fused import fused_estimate

    site, mode, p = case["site"], case["mode"], case["pressure_kPa"]
    fast, keyed = _kept(path, {**case, "chambers": {k: g.as_dict() for k, g in chambers.items()},
                               "channel_mm3": channel, "model": study.fast_model},
                        ("spsc.studies.fused",))
    if fast is None:
        t1 = time.perf_counter()
        others = [g for k, g in chambers.items() if k != site]
        fast = fused_estimate(chambers[site], others, material(study.material),
                              pressure_kPa=p, channel_mm3=channel,
                              reservoir_mm3=LOW_RESERVOIR_MM3 if mode == "low" else 0.0,
                              stroke_mm=study.stroke_mm, points=study.points,
                              model=study.fast_model)
        fast = fast.replace(solver=fast.solver.__class__(
            **{**fast.solver.to_dict(), "seconds": time.perf_counter() - t1}))
        fast.to_json(path)
        keyed.mark()
    return fast


def _nan_to_none(x):
    return None


def _metrics(c: Curve) -> dict:
    ok = c.converged
    return {"y_mm": c.y_mm.tolist(), "force_N": _list(c.force_N),
            "pressure_kPa": _list(c.pressure_kPa),
            "pockets_N": {k[6:-2]: _list(v) for k, v in c.series.items()},
            "mean_stiffness_N_per_mm": _num(c.mean_stiffness(reached=True)),
            "mean_sensitivity_kPa_per_mm": _num(c.mean_sensitivity(reached=True)),
            "converged": bool(ok.all()), "seconds": _num(c.solver.seconds),
            "dofs": c.solver.details.get("dofs"), "message": c.solver.message}


def _ratio(a: Curve, b: Curve) -> float | None:
    return _num(a.mean_sensitivity(reached=True) / b.mean_sensitivity(reached=True))


def _errors(fast: Curve, fem: Curve) -> dict:
    """Relative errors of the fast estimate against the FEM over the points both reached,
    y > 0: force, and pressure rise from the setup pressure (max |·| and at the full stroke)."""
    ok = fem.converged & fast.converged & (fem.y_mm > 0)
    if not ok.any():
        return {"force_max": None, "pressure_rise_max": None}
    eF = fast.force_N[ok] / fem.force_N[ok] - 1
    dp_fem = fem.pressure_kPa[ok] - fem.pressure_kPa[0]
    eP = (fast.pressure_kPa[ok] - fast.pressure_kPa[0]) / dp_fem - 1
    return {"force_max": _num(np.max(np.abs(eF))), "force_end": _num(eF[-1]),
            "pressure_rise_max": _num(np.max(np.abs(eP))), "pressure_rise_end": _num(eP[-1]),
            "y_end_mm": float(fem.y_mm[ok][-1])}


def _list(a) -> list:
    return [None if not np.isfinite(v) else float(v) for v in a]


def _num(x) -> float | None:
    x = float(x)
    return x if np.isfinite(x) else None
