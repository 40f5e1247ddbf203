"""Reading and validating the design dict of the printability gate.

The keys and their meaning are the contract documented in :mod:`spsc.cad.check`.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError, require
from .geometry import PARAMS

__all__ = ["design_path_for", "load_design", "parse_design"]


def design_path_for(mesh_path: str | os.PathLike) -> Path:
    """The sidecar ``<stem>.design.json`` beside a mesh file."""
    p = Path(mesh_path)
    return p.with_name(p.stem + ".design.json")


def load_design(path: str | os.PathLike) -> dict:
    """Read a design sidecar JSON and validate it (keys: see :mod:`spsc.cad.check`); returns the
    dict as written, which :func:`check_mesh` parses (parsing is not idempotent)."""
    p = Path(path)
    if p.is_dir():
        raise ParameterError("design", str(p), "a JSON file (this is a folder)")
    if not p.is_file():
        raise FileNotFoundError(2, "no such file", str(p))
    try:
        data = json.loads(p.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise ParameterError("design", str(p),
                             f"a JSON object ({exc.__class__.__name__})") from None
    if not isinstance(data, dict):
        raise ParameterError("design", str(p), "a JSON object (this file holds a JSON "
                             f"{_JSON_TYPES.get(type(data), type(data).__name__)})")
    parse_design(data)
    return data


_JSON_TYPES = {list: "array", str: "string", int: "number", float: "number", bool: "boolean",
               type(None): "null"}


def parse_design(design: dict | None) -> dict:
    """Validated copy of a design dict: known keys checked and normalised, others dropped."""
    if design is None:
        design = {}
    if not isinstance(design, dict):
        raise ParameterError("design", design, "a dict (see spsc.cad.check)")
    out: dict = {}
    if "cavity_volume_mm3" in design:
        out["cavity_volume_mm3"] = require("cavity_volume_mm3", design["cavity_volume_mm3"],
                                           gt=0, unit="mm^3")
    out["volume_rtol"] = require("volume_rtol", design.get("volume_rtol", 0.002), gt=0, lt=1)
    if "cavities" in design:
        n = design["cavities"]
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise ParameterError("cavities", n, "an integer >= 1")
        out["cavities"] = n
    if "genus" in design:
        g = design["genus"]
        if isinstance(g, bool) or not isinstance(g, int) or g < 0:
            raise ParameterError("genus", g, "an integer >= 0")
        out["genus"] = g
    if "bbox_mm" in design:
        out["bbox_mm"] = _bbox(design["bbox_mm"])
    if "geometry" in design:
        out["geometry"] = _geometry(design["geometry"])
    if "port" in design:
        ports = design["port"]
        out["port"] = [_port(q) for q in ports] if isinstance(ports, list) and ports \
            else _port(ports)
    if "wall_region" in design:
        wr = design["wall_region"]
        if not isinstance(wr, dict) or "z_min" not in wr:
            raise ParameterError("wall_region", wr, 'a dict {"z_min": z}')
        out["wall_region"] = {"z_min": require("wall_region.z_min", wr["z_min"], unit="mm")}
    if "exclude" in design:
        ex = design["exclude"]
        if not isinstance(ex, (list, tuple)) or not all(isinstance(e, dict) for e in ex):
            raise ParameterError("exclude", ex, 'a list of {"center": [x, y, z], "radius": r}')
        out["exclude"] = [{"center": _vec("exclude.center", e.get("center")),
                           "radius": require("exclude.radius", e.get("radius"), gt=0, unit="mm")}
                          for e in ex]
    return out


def _geometry(g):
    """geometry: the chamber's seven parameters (mm), which the printability rule judges."""
    from .geometry import SPSCGeometry

    if isinstance(g, SPSCGeometry):
        return g
    keys = PARAMS
    if not isinstance(g, dict) or set(g) != set(keys):
        raise ParameterError("geometry", g, "a dict of the seven parameters " + ", ".join(keys))
    try:
        return SPSCGeometry(**{k: require(f"geometry.{k}", g[k]) for k in keys})
    except ParameterError as exc:
        raise ParameterError(f"geometry.{exc.name}".replace("geometry.geometry.", "geometry."),
                             exc.value, exc.allowed) from None


def _bbox(bb) -> dict:
    """bbox_mm: extents [dx, dy, dz] or [[xmin, ymin, zmin], [xmax, ymax, zmax]] (mm)."""
    if np.ndim(bb) == 2:  # [[xmin, ymin, zmin], [xmax, ymax, zmax]]
        lo, hi = _vec("bbox_mm", bb, n=6)[:3], _vec("bbox_mm", bb, n=6)[3:]
        if not all(b > a for a, b in zip(lo, hi)):
            raise ParameterError("bbox_mm", bb, "[[xmin, ymin, zmin], [xmax, ymax, zmax]] "
                                 "with max > min")
        return {"extents": [b - a for a, b in zip(lo, hi)], "min": lo, "max": hi}
    return {"extents": _vec("bbox_mm", bb, positive=True)}


def _port(port) -> dict:
    """port: axis point and direction, radius (mm) and the z (or s) range it spans."""
    if not isinstance(port, dict):
        raise ParameterError("port", port, "a dict with axis_point, axis_dir, radius, z_range")
    q = {"axis_point": _vec("port.axis_point", port.get("axis_point")),
         "axis_dir": _vec("port.axis_dir", port.get("axis_dir")),
         "radius": require("port.radius", port.get("radius"), gt=0, unit="mm")}
    d = q["axis_dir"]
    if np.linalg.norm(d) == 0:
        raise ParameterError("port.axis_dir", port.get("axis_dir"), "a non-zero vector")
    key = "s_range" if "s_range" in port else "z_range"
    rng = _vec(f"port.{key}", port.get(key), n=2)
    if rng[0] == rng[1]:
        raise ParameterError(f"port.{key}", port.get(key), "two different numbers")
    if key == "z_range" and abs(d[2]) < 1e-9 * np.linalg.norm(d):
        raise ParameterError("port.axis_dir", port.get("axis_dir"),
                             "a non-horizontal axis with z_range (use s_range)")
    q[key] = rng
    return q


def _vec(name, value, n=3, positive=False) -> list[float]:
    allowed = f"{n} finite numbers" + (" > 0" if positive else "")
    try:
        a = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ParameterError(name, value, allowed) from None
    if a.size != n or not np.all(np.isfinite(a)) or (positive and np.any(a <= 0)):
        raise ParameterError(name, value, allowed)
    return [float(x) for x in a]
