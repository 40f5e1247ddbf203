"""The chamber of a design file, for the verbs that take ``--design FILE``: a bladder's
``STEM.design.json`` (``spsc bladder``: its ``geometry``, the seven parameters) or the
``design.json`` of ``spsc design`` (its best design's parameters, material and setup pressure).
One-line errors naming ``design``."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from spsc.core.errors import ParameterError
from spsc.cad.geometry import PARAMS as _PARAMS

__all__ = ["DesignChamber", "design_chamber"]

_WHAT = "a bladder's .design.json (spsc bladder) or a design.json with a best design (spsc design)"


@dataclass(frozen=True)
class DesignChamber:
    """The chamber of a design file: its geometry, and the material and setup pressure (kPa)
    when the file names them (None otherwise)."""

    geometry: object
    material: str | None = None
    pressure_kPa: float | None = None


def design_chamber(path) -> DesignChamber:
    """Read the design file at ``path`` (see the module)."""
    from spsc.cad.checkdesign import parse_design
    from spsc.core.jsonio import read_json

    path = Path(path)
    if not path.is_file():
        raise ParameterError("design", str(path), "an existing file: " + _WHAT)
    try:
        doc = read_json(path)
    except (ValueError, UnicodeDecodeError) as exc:
        raise ParameterError("design", str(path), f"{_WHAT} ({str(exc)[:80]})") from None
    if not isinstance(doc, dict):
        raise ParameterError("design", str(path), _WHAT)
    if doc.get("schema") == "spsc.design":
        best = doc.get("best")
        if not isinstance(best, dict) or not isinstance(best.get("params"), dict):
            raise ParameterError("design", str(path), "a design.json whose run found a best "
                                 "design (this one has none: no design met the goal)")
        p = best["params"]
        missing = [k for k in _PARAMS if k not in p]
        if missing:
            raise ParameterError("design", str(path), "a best design with the seven "
                                 "parameters (missing " + ", ".join(missing) + ")")
        geometry = parse_design({"geometry": {k: p[k] for k in _PARAMS}})["geometry"]
        return DesignChamber(geometry, p.get("material"), p.get("pressure"))
    if "geometry" not in doc:
        raise ParameterError("design", str(path), _WHAT + " (it has no geometry)")
    return DesignChamber(parse_design({"geometry": doc["geometry"]})["geometry"])
