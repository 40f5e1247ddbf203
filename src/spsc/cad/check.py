"""The printability gate: is a mesh a printable bladder, and does it match its design?

``check_mesh(path_or_arrays, design=..., process="fdm")`` returns a :class:`CheckReport` whose
entries each say ``name, passed, value, limit, message`` (+ ``details``). ``passed`` is True/False
for a gating check and None for a report-only one (or a check that could not be measured because
a gating check it depends on failed). The part prints standing on its base: build direction +z,
print plane x–y (paper Table 2 note 3). Lengths mm, areas mm², volumes mm³, angles degrees.

Checks
------
watertight          no boundary edges (pymeshlab).
manifold            no non-2-manifold edges or vertices (pymeshlab).
oriented            every edge used once in each direction, skins outward and cavities inward.
self_intersections  number of faces crossing a non-adjacent face = 0 (pymeshlab).
one_part            solid parts = 1 (shells not inside another shell, or inside an even number).
genus               genus of the printed surface (pymeshlab) = design ``genus``; report-only
                    without it. A bladder whose bore opens the cavity is one shell of genus 0;
                    each through hole (flange screw hole) adds 1.
min_wall            closest-point distance from the cavity surface to every other surface of the
                    capped solid (exact point-to-triangle, VTK), over the wall region, >= the
                    process minimum less ``WALL_TOL_MM`` (+ ``MESH_THINNING_MM`` with a design
                    ``geometry``, whose exact wall the rule judges). Samples: cavity vertices,
                    face centroids and seeded area-uniform points (~1 per 0.2 x 0.2 mm).
                    Reports the minimum, its location and the 1 % quantile.
cavity_count        enclosed cavity shells of the capped solid; gated against ``cavities``.
cavity_volume       volume enclosed by the cavity shell(s) of the capped solid; gated against
                    ``cavity_volume_mm3`` within ``volume_rtol`` when the design gives it.
bbox                extents (and corners) of the printed mesh; gated against ``bbox_mm``
                    within max(0.5 mm, 1 % of the extent) per axis when given.
overhang            report-only: area of faces facing down more than ``max_overhang_deg`` from
                    vertical, plate faces excluded, outside (chamber, nipple, bore) and in the
                    cavity (its ceiling, a bridge).
printability        with a design ``geometry``: the printability rule on the chamber (wall and
                    outer-wall overhang; :mod:`spsc.cad.printability`, the verdict of sweeps and
                    of the design search, says why the overhang gates). Absent without it.

The design dict (contract with cad/solids.py; sidecar ``<stem>.design.json``)
---------------------------------------------------------------------------
All keys optional; unknown keys are ignored (keep provenance there freely).

``geometry``           {"w", "h", "l", "t0", "n1", "n2", "cy"} (mm): the chamber, judged by the
                        printability rule; min_wall then allows ``MESH_THINNING_MM`` more.
``cavity_volume_mm3``  float > 0. Analytic cavity volume (SPSCGeometry.cavity_volume()).
``volume_rtol``        float > 0, default 0.002. Allowed |mesh − analytic| / analytic.
``cavities``           int >= 1. Expected number of enclosed cavities with the port capped.
``genus``              int >= 0. Expected genus of the printed (uncapped) surface.
``bbox_mm``            [dx, dy, dz], expected extents of the printed part (mm), or its bounds
                        [[xmin, ymin, zmin], [xmax, ymax, zmax]] (then the corners are checked
                        too, with the same tolerance).
``port``               {"axis_point": [x, y, z], "axis_dir": [dx, dy, dz], "radius": r,
                        "z_range": [z0, z1]}: the bore to plug (a cylinder of radius r on the
                        axis between heights z0 and z1; a side port gives "s_range": [s0, s1],
                        distances along axis_dir, instead) before measuring the cavity. Put the
                        inner end flush with where the bore meets the cavity (z = 0 here): a plug
                        reaching into it removes π r² per mm of overshoot from the volume.
``wall_region``        {"z_min": z}: only cavity points with z >= z_min count for min_wall (e.g.
                        above the floor, so the floor and the wall–floor fillet are not judged).
``exclude``            [{"center": [x, y, z], "radius": r}, ...]: balls around feature edges
                        (port lip, pocket rims) whose cavity points do not count for min_wall.

Without a ``port`` the cavity is any shell enclosed by another; a single-shell mesh without a
port has no measurable cavity and min_wall / cavity_volume are report-only.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from . import meshtopo as mt
from .checkdesign import design_path_for, load_design, parse_design
from spsc.core.errors import ParameterError, require
from .meshload import load_mesh, weld
from .printability import printability
from .process import MESH_THINNING_MM, WALL_TOL_MM, Process, process as get_process

__all__ = ["Check", "CheckReport", "check_mesh", "load_design", "parse_design",
           "design_path_for", "WALL_TOL_MM"]

#: Sample spacing (mm) of the cavity surface for min_wall.
SAMPLE_SPACING_MM = 0.2


@dataclass(frozen=True)
class Check:
    """One check: ``passed`` True/False when gating, None when report-only or not measurable."""

    name: str
    passed: bool | None
    value: object
    limit: object
    message: str
    details: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        return _plain({"name": self.name, "passed": self.passed, "value": self.value,
                       "limit": self.limit, "message": self.message, "details": self.details})


@dataclass(frozen=True)
class CheckReport:
    """All checks of one mesh; ``passed`` if no gating check failed."""

    source: str
    process: Process
    min_wall_mm: float
    checks: tuple[Check, ...]
    passed: bool = field(init=False)
    failed: tuple[str, ...] = field(init=False)

    def __post_init__(self):
        failed = tuple(c.name for c in self.checks if c.passed is False)
        object.__setattr__(self, "failed", failed)
        object.__setattr__(self, "passed", not failed)

    def __getitem__(self, name: str) -> Check:
        for c in self.checks:
            if c.name == name:
                return c
        raise KeyError(name)

    def to_dict(self) -> dict:
        return _plain({"source": self.source, "process": self.process.name,
                       "min_wall_mm": self.min_wall_mm, "passed": self.passed,
                       "failed": list(self.failed), "checks": [c.as_dict() for c in self.checks]})

    def to_json(self, path: str | os.PathLike) -> None:
        """Write :meth:`to_dict` to ``path``, ``source`` (a mesh file) relative to the folder
        of ``path``: a folder of a part and its check.json moved elsewhere still points at
        the part."""
        path = Path(path)
        data = self.to_dict()
        if self.source != "<arrays>":
            data["source"] = os.path.relpath(Path(self.source).resolve(), path.resolve().parent)
        path.write_text(json.dumps(data, indent=2) + "\n", encoding="utf-8")

    def summary(self) -> str:
        """A few lines: size, parts and genus, cavity volume, min wall, overhang, verdict."""
        c = {k.name: k for k in self.checks}
        bb, tri = c["bbox"].value, c["bbox"].details.get("triangles")
        lines = [f"{self.source}: {tri} triangles, {bb[0]:.2f} x {bb[1]:.2f} x {bb[2]:.2f} mm, "
                 f"{c['one_part'].value} part(s), genus "
                 f"{'n/a' if c['genus'].value is None else c['genus'].value}"]
        lines += [c[k].message for k in ("cavity_count", "cavity_volume", "min_wall", "overhang",
                                         "printability") if k in c]
        lines.append("PASSED" if self.passed else "FAILED: " + ", ".join(self.failed))
        return "\n".join(lines)


# -- the gate -------------------------------------------------------------------------------------
def check_mesh(source, *, design: dict | str | os.PathLike | None = None, process: str = "fdm",
               min_wall: float | None = None) -> CheckReport:
    """Run every printability check on a mesh.

    Parameters
    ----------
    source : path (STL or 3MF) or ``(vertices, faces)`` arrays (mm) or an object with
        ``.vertices`` and ``.faces`` (e.g. a trimesh).
    design : dict, path of a design JSON, or None. See the module docstring for the keys.
    process : ``fdm`` | ``sla`` | ``molding`` (cad/process.py).
    min_wall : float, optional. Overrides the process minimum wall (mm), > 0.
    """
    proc = get_process(process)
    limit = proc.min_wall_mm if min_wall is None else require("min_wall", min_wall, gt=0, unit="mm")
    if isinstance(design, (str, os.PathLike)):
        design = load_design(design)
    design = parse_design(design)
    if isinstance(source, (str, os.PathLike)):
        name = str(source)
        v, f = load_mesh(source)
    else:
        name = "<arrays>"
        v, f = source if isinstance(source, tuple) else (source.vertices, source.faces)
        v, f = weld(v, f)
        if len(f) == 0:
            raise ParameterError("mesh", "no triangles", "a mesh with triangles")
    checks = _run(v, f, design, proc, limit)
    return CheckReport(source=name, process=proc, min_wall_mm=limit, checks=tuple(checks))


def _run(v, f, design, proc, limit) -> list[Check]:
    topo = mt.topology(v, f)
    closed = topo["boundary_edges"] == 0
    manifold = topo["non_two_manifold_edges"] == 0 and topo["non_two_manifold_vertices"] == 0
    n_self = mt.self_intersecting_faces(v, f)
    parts = mt.shells(v, f)
    depth = mt.nesting_depth(v, f, parts)
    n_parts = int(np.sum(depth % 2 == 0))
    checks = [
        Check("watertight", closed, int(topo["boundary_edges"]), 0,
              "closed surface" if closed else
              f"{topo['boundary_edges']} boundary edges"
              + (f" ({topo['number_holes']} holes)" if topo["number_holes"] > 0 else "")),
        Check("manifold", manifold, int(topo["non_two_manifold_edges"]
                                       + topo["non_two_manifold_vertices"]), 0,
              "2-manifold" if manifold else
              f"{topo['non_two_manifold_edges']} non-manifold edges, "
              f"{topo['non_two_manifold_vertices']} non-manifold vertices"),
        _oriented(v, f, parts, depth, closed and manifold),
        Check("self_intersections", n_self == 0, n_self, 0,
              "no self-intersections" if n_self == 0 else f"{n_self} self-intersecting faces"),
        Check("one_part", n_parts == 1, n_parts, 1,
              f"{n_parts} solid part(s) from {len(parts)} shell(s)"),
        _genus(topo, closed and manifold, design.get("genus")),
    ]
    cav = _cavities(v, f, design, closed and manifold)
    checks += [_cavity_count(cav, design),
               _min_wall(cav, design, limit, proc),
               _cavity_volume(cav, design),
               _bbox(v, f, design),
               _overhang(v, f, cav, proc)]
    return checks + ([_rule(design["geometry"], proc, limit)] if "geometry" in design else [])


def _rule(geometry, proc, limit) -> Check:
    """The printability rule on the design's chamber, with the gate's minimum wall."""
    v = printability(geometry, replace(proc, min_wall_mm=limit))
    return Check("printability", v.ok, v.measures, v.limits,
                 "printability rule: " + (v.summary if v.ok else "; ".join(v.reasons)),
                 {"reasons": list(v.reasons), "summary": v.summary})


def _oriented(v, f, parts, depth, measurable) -> Check:
    if not measurable:
        return Check("oriented", None, None, None, "not measured: not a closed 2-manifold")
    half = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    twice = len(half) - len(np.unique(half, axis=0))
    vols = np.array([mt.signed_volume(v, f[p]) for p in parts])
    inverted = int(np.sum((vols > 0) != (depth % 2 == 0)))
    ok = twice == 0 and inverted == 0
    msg = "consistent, skins outward" if ok else \
        f"{twice} edges used twice in one direction, {inverted} shell(s) inside out"
    return Check("oriented", ok, twice + inverted, 0, msg)


def _genus(topo, measurable, expected) -> Check:
    if not measurable:
        return Check("genus", None, None, expected, "not measured: not a closed 2-manifold")
    g = int(topo["genus"])
    if expected is None:
        return Check("genus", None, g, None, f"genus {g} (no design value)")
    return Check("genus", g == expected, g, expected, f"genus {g}, design {expected}")


def _cavities(v, f, design, measurable) -> dict:
    """The capped solid split into cavity shells and the rest; ``reason`` if not available."""
    if not measurable:
        return {"reason": "not measured: not a closed 2-manifold"}
    if "port" in design:
        capped = mt.cap_ports(v, f, design["port"])
        if capped is None:
            return {"reason": "not measured: manifold3d rejected the mesh"}
        cv, cf = capped
    else:
        cv, cf = v, f
    parts = mt.shells(cv, cf)
    depth = mt.nesting_depth(cv, cf, parts)
    inner = [p for p, d in zip(parts, depth) if d % 2 == 1]
    if not inner:
        why = "the port cap left no enclosed cavity (check design port)" if "port" in design \
            else ("no enclosed cavity: a solid part, or a bore open to the outside (give the "
                  "design's port to cap it)")
        return {"reason": why, "expected": "port" in design or "cavity_volume_mm3" in design}
    return {"v": cv, "f": cf, "cavities": inner,
            "others": [p for p, d in zip(parts, depth) if d % 2 == 0]}


def _min_wall(cav, design, limit, proc) -> Check:
    # with a geometry the rule judges its exact wall; the mesh fails beyond its tessellation
    tol = WALL_TOL_MM + (MESH_THINNING_MM if "geometry" in design else 0.0)
    lim = {"min_wall_mm": limit, "tolerance_mm": tol, "process": proc.name}
    if "reason" in cav:
        return Check("min_wall", False if cav.get("expected") else None, None, lim,
                     f"min wall {cav['reason']}")
    v, f = cav["v"], cav["f"]
    pts_all, d_all = [], []
    for i, p in enumerate(cav["cavities"]):
        pts = mt.sample_surface(v, f[p], SAMPLE_SPACING_MM)
        keep = np.ones(len(pts), dtype=bool)
        if "wall_region" in design:
            keep &= pts[:, 2] >= design["wall_region"]["z_min"]
        for ball in design.get("exclude", []):
            keep &= np.linalg.norm(pts - ball["center"], axis=1) > ball["radius"]
        pts = pts[keep]
        if not len(pts):
            continue
        rest = np.concatenate(cav["others"] + [q for j, q in enumerate(cav["cavities"]) if j != i])
        pts_all.append(pts)
        d_all.append(mt.surface_distance(pts, v, f[rest]))
    if not pts_all:
        return Check("min_wall", False, None, lim, "min wall: no cavity point in the wall region")
    pts, d = np.vstack(pts_all), np.concatenate(d_all)
    k = int(np.argmin(d))
    dmin, p01 = float(d[k]), float(np.percentile(d, 1))
    ok = dmin >= limit - tol
    x, y, z = pts[k]
    msg = (f"min wall {dmin:.3f} mm at ({x:.2f}, {y:.2f}, {z:.2f}), 1 % quantile {p01:.3f} mm "
           f"({proc.name} limit {limit:g} mm)")
    return Check("min_wall", ok, dmin, lim, msg,
                 {"location_mm": pts[k], "percentile_1_mm": p01, "samples": len(d)})


def _cavity_count(cav, design) -> Check:
    expected = design.get("cavities")
    if "reason" in cav:
        return Check("cavity_count", False if expected else None, None, expected,
                     f"cavity count {cav['reason']}")
    n = len(cav["cavities"])
    return Check("cavity_count", None if expected is None else n == expected, n, expected,
                 f"{n} enclosed cavit{'y' if n == 1 else 'ies'} {_capped(design)}"
                 + ("" if expected is None else f" (design {expected})"))


def _capped(design) -> str:
    """How the cavities were counted: with the design's port(s) capped, or as found (a part
    whose design names no port: nothing was capped, the cavities are sealed in the mesh)."""
    if "port" not in design:
        return "(no port in the design: nothing capped)"
    ports = design["port"]
    return "with the ports capped" if isinstance(ports, list) and len(ports) > 1 \
        else "with the port capped"


def _cavity_volume(cav, design) -> Check:
    analytic, rtol = design.get("cavity_volume_mm3"), design["volume_rtol"]
    if "reason" in cav:
        return Check("cavity_volume", False if cav.get("expected") and analytic else None, None,
                     analytic, f"cavity volume {cav['reason']}")
    vol = sum(abs(mt.signed_volume(cav["v"], cav["f"][p])) for p in cav["cavities"])
    if analytic is None:
        return Check("cavity_volume", None, vol, None,
                     f"cavity {vol:.1f} mm^3 in {len(cav['cavities'])} shell(s) (no design value)")
    err = (vol - analytic) / analytic
    return Check("cavity_volume", abs(err) <= rtol, vol, {"analytic_mm3": analytic, "rtol": rtol},
                 f"cavity {vol:.1f} mm^3, design {analytic:.1f} mm^3 ({100 * err:+.3f} %)",
                 {"relative_error": err})


def _bbox(v, f, design) -> Check:
    used = v[np.unique(f)]
    lo, hi = used.min(axis=0), used.max(axis=0)
    ext = hi - lo
    det = {"min_mm": lo, "max_mm": hi, "triangles": len(f)}
    want = design.get("bbox_mm")
    if want is None:
        return Check("bbox", None, ext, None, "bbox {:.2f} x {:.2f} x {:.2f} mm".format(*ext), det)
    tol = np.maximum(0.5, 0.01 * np.asarray(want["extents"]))
    dev = np.abs(ext - want["extents"])
    if "min" in want:
        dev = np.maximum(dev, np.maximum(np.abs(lo - want["min"]), np.abs(hi - want["max"])))
    ok = bool(np.all(dev <= tol))
    return Check("bbox", ok, ext, {**want, "tolerance_mm": tol},
                 "bbox {:.2f} x {:.2f} x {:.2f} mm, design {:.2f} x {:.2f} x {:.2f}".format(
                     *ext, *want["extents"]) + ("" if ok else
                                               f" (off by up to {dev.max():.2f} mm)"), det)


def _overhang(v, f, cav, proc) -> Check:
    """Downward faces steeper than the overhang limit, build-plate faces excluded (report)."""
    area, n = mt.face_areas(v, f), mt.face_normals(v, f)
    zmin = v[np.unique(f), 2].min()
    on_plate = np.all(v[f, 2] <= zmin + 1e-3, axis=1)
    # a face is down-facing at angle a from vertical when -n_z = sin(a)
    steep = (-n[:, 2] > math.sin(math.radians(proc.max_overhang_deg)) + 1e-12) & ~on_plate
    cavity = np.zeros(len(f), dtype=bool)
    if "reason" not in cav:
        cv = cav["v"][np.unique(cav["f"][np.concatenate(cav["cavities"])])]
        scale = float(np.ptp(v, axis=0).max())
        dist, _ = cKDTree(cv).query(v[f].reshape(-1, 3))
        cavity = np.all(dist.reshape(-1, 3) <= 1e-7 * scale, axis=1)
    out_a, cav_a = float(area[steep & ~cavity].sum()), float(area[steep & cavity].sum())
    out_t, cav_t = float(area[~cavity].sum()), float(area[cavity].sum())
    pct = (lambda a, t: 100.0 * a / t if t > 0 else 0.0)
    inside = (f"cavity ceiling {cav_a:.1f} mm^2 ({pct(cav_a, cav_t):.1f} %)" if cavity.any()
              else "cavity not separated")
    msg = (f"overhang > {proc.max_overhang_deg:g} deg from vertical: outer {out_a:.1f} mm^2 "
           f"({pct(out_a, out_t):.1f} %), {inside} [report only]")
    return Check("overhang", None, {"outer_mm2": out_a, "cavity_mm2": cav_a},
                 {"max_overhang_deg": proc.max_overhang_deg}, msg,
                 {"outer_percent": pct(out_a, out_t), "cavity_percent": pct(cav_a, cav_t),
                  "cavity_measured": "reason" not in cav})


def _plain(x):
    """JSON-ready copy: numpy scalars and arrays to Python numbers and lists."""
    if isinstance(x, dict):
        return {str(k): _plain(val) for k, val in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(val) for val in x]
    if isinstance(x, np.ndarray):
        return _plain(x.tolist())
    if isinstance(x, np.generic):
        return x.item()
    return None if isinstance(x, float) and not math.isfinite(x) else x
