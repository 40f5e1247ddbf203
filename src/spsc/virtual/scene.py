"""A scene file of ``spsc virtual`` (issue 50): a scenario of ``spsc simulate`` (its
``[chamber]``, ``[circuit]`` with the valve, gas and sensor, timed ``[[events]]``) with a
``[scene]`` table picking the MuJoCo scene, read and checked before anything runs; every
malformed entry a one-line :class:`~spsc.core.errors.ParameterError` naming it.

.. code-block:: toml

    [scene]
    kind = "gripper"          # or "plate": a plate pressing one pad along [press]

    [chamber]                 # as spsc simulate's; or design = "my.design.json" (a bladder's
    type = "D"                # design file or spsc design's design.json)
    model = "wall"            # the pads' map: "wall" (any chamber) or "surrogate" (domes)

    [object]                  # kind = "gripper": what the pads grasp
    shape = "box"             # "box" [x, y, z] | "cylinder" [diameter, height] | "sphere" [diameter]
    size_mm = [30, 30, 40]
    mass_g = 50
    stiffness_N_per_mm = 3    # the object's own stiffness at one pad; "rigid"
    friction = 0.8            # Coulomb μ of pad on object

    [grasp]                   # the jaws' faces apart and the hand's lift, [t_s, mm] knots
    opening_mm = [[0, 60], [0.5, 60], [1.0, 24]]
    lift_mm = [[0, 0], [1.2, 0], [1.7, 30]]
    duration_s = 3.0
    max_travel_mm = 4         # the pads' map's depth

    [output]
    dt = 0.001                # the physics step (s, at most 0.002), the trace's rows

The plate scene presses with ``[press] force = [[t_s, N], ...]`` (the plate's actuator) or
along ``[press] profile = [[t_s, y_mm], ...]`` (the plate on a stiff position servo).
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from spsc.core.errors import ParameterError, known_keys, require, table_of
from spsc.dynamics.profile import ForceProfile, PressProfile
from spsc.dynamics.scenario import Scenario, parse_scenario

from .contact import PadContact
from .gripper import Grasp
from .objects import GraspObject

__all__ = ["Scene", "SCENES", "read_scene", "parse_scene"]

#: the longest physics step a scene takes (s)
MAX_DT_S = 2e-3
#: the scenes there are
SCENES = ("plate", "gripper")
_OBJECT = {"shape", "size_mm", "mass_g", "stiffness_N_per_mm", "friction", "shear_N_per_mm",
           "damping_N_s_per_m"}
_GRASP = {"opening_mm", "lift_mm", "duration_s", "max_travel_mm", "jaw_kp_N_per_mm",
          "lift_kp_N_per_mm"}


@dataclass(frozen=True)
class Scene:
    """A checked scene: its ``kind``, the ``scenario`` (the chamber, its circuit and valve
    events; for the gripper its press is the grasp's duration at no force, the pads' map as
    deep as ``max_travel_mm``), and the gripper's ``obj`` and ``grasp``."""

    kind: str
    scenario: Scenario
    obj: GraspObject | None = None
    grasp: Grasp | None = None

    @property
    def duration_s(self) -> float:
        return self.grasp.duration_s if self.grasp else self.scenario.press.duration


def _table(doc, name, keys) -> dict:
    t = table_of(doc, name, of="the scene")
    known_keys(name, t, keys)
    return t


def _object(t: dict) -> GraspObject:
    k = t.get("stiffness_N_per_mm", "rigid")
    if k == "rigid":
        k = float("inf")
    elif isinstance(k, str):
        raise ParameterError("object.stiffness_N_per_mm", k, "a number (N/mm) or \"rigid\"")
    contact = PadContact(k, t.get("friction", PadContact.mu),
                         t.get("shear_N_per_mm", PadContact.shear_N_per_mm),
                         t.get("damping_N_s_per_m", PadContact.damping_N_s_per_m))
    size = t.get("size_mm", GraspObject.size_mm)
    return GraspObject(t.get("shape", "box"), size, t.get("mass_g", 50.0), contact)


def _design(chamber: dict, base: Path) -> dict:
    """[chamber] with its ``design = FILE`` replaced by the file's seven parameters (and its
    material, unless the table names one)."""
    from spsc.cad.design_file import design_chamber
    from spsc.cad.geometry import PARAMS

    if "design" not in chamber:
        return chamber
    given = sorted(set(chamber) & (set(PARAMS) | {"type", "footprint"}))
    if given:
        raise ParameterError(f"chamber.{given[0]}", chamber[given[0]], "not with design = "
                             "FILE (the design file gives the chamber)")
    path = Path(chamber["design"])
    d = design_chamber(path if path.is_absolute() else base / path)
    out = {k: v for k, v in chamber.items() if k != "design"}
    out.update({k: getattr(d.geometry, k) for k in PARAMS})
    if d.material and "material" not in out:
        out["material"] = d.material
    return out


def parse_scene(doc: dict, base: Path = Path(".")) -> Scene:
    """The scene of a parsed TOML document (``base``: the folder design files are read
    from)."""
    doc = dict(doc)
    scene = doc.pop("scene", None)
    if not isinstance(scene, dict):
        raise ParameterError("scene", "missing", "a [scene] table with kind = "
                             + " | ".join(f'"{s}"' for s in SCENES))
    if scene.get("kind") not in SCENES:
        raise ParameterError("scene.kind", scene.get("kind"), " | ".join(SCENES))
    _table({"scene": scene}, "scene", {"kind"})
    if isinstance(doc.get("chamber"), dict):
        doc["chamber"] = _design(doc["chamber"], base)
    obj = grasp = None
    if scene["kind"] == "gripper":
        for name in ("press", "stiffness", "bode"):
            if name in doc:
                raise ParameterError(f"[{name}]", "in a gripper scene", "none: the jaws' "
                                     "[grasp] moves the pads")
        obj = _object(_table(doc, "object", _OBJECT))
        g = _table(doc, "grasp", _GRASP)
        doc.pop("object", None), doc.pop("grasp", None)
        if "opening_mm" not in g:
            raise ParameterError("grasp.opening_mm", "missing", "[[t_s, mm], ...] knots of the "
                                 "pads' faces apart")
        grasp = Grasp(g["opening_mm"], g.get("lift_mm", ((0.0, 0.0),)),
                      g.get("duration_s", 3.0), g.get("jaw_kp_N_per_mm", 100.0),
                      g.get("lift_kp_N_per_mm", 20.0))
        depth = require("grasp.max_travel_mm", g.get("max_travel_mm", 4.0), gt=0, le=50,
                        unit="mm")
        for i, e in enumerate(doc.get("events", []) if isinstance(doc.get("events"), list)
                              else []):
            t = e.get("t") if isinstance(e, dict) else None
            if isinstance(t, (int, float)) and not isinstance(t, bool) and \
                    t > grasp.duration_s:
                raise ParameterError(f"events[{i}].t", t, f"<= {grasp.duration_s:g} s (the "
                                     "grasp's duration_s)")
        doc["press"] = {"force": [[0.0, 0.0], [grasp.duration_s, 0.0]], "max_travel_mm": depth}
    else:
        for name in ("object", "grasp"):
            if name in doc:
                raise ParameterError(f"[{name}]", "in a plate scene", "only in kind = "
                                     "\"gripper\"")
    sc = parse_scenario(doc)
    if sc.dt > MAX_DT_S:
        raise ParameterError("output.dt", sc.dt, f"<= {MAX_DT_S:g} s in a scene (the physics "
                             "step: the jaws' and the plate's servos ring at 100-120 Hz)")
    if scene["kind"] == "plate" and not isinstance(sc.press, (ForceProfile, PressProfile)):
        raise ParameterError("press.object_N_per_mm", "in a plate scene", "a rigid plate: "
                             "force = [[t_s, N], ...] or profile = [[t_s, y_mm], ...]")
    if sc.triggers or sc.stiffness is not None:
        raise ParameterError("events", "pressure triggers or [stiffness]", "timed valve events "
                             "only in a scene")
    return Scene(scene["kind"], sc, obj, grasp)


def read_scene(path) -> Scene:
    """Read and check the scene file at ``path``."""
    p = Path(path)
    try:
        doc = tomllib.loads(p.read_text(encoding="utf-8-sig"))
    except OSError as exc:
        raise ParameterError("scene", str(path), f"a readable TOML file ({exc.strerror})") \
            from None
    except (UnicodeDecodeError, tomllib.TOMLDecodeError, RecursionError) as exc:
        raise ParameterError("scene", p.name, f"valid TOML ({str(exc)[:80]})") from None
    return parse_scene(doc, p.parent)
