"""The fields of a design file (``.design.json``, written by ``spsc bladder`` and ``spsc
fingertip``) that a part FEM reads, checked before any work: one ParameterError naming the
field, its value and what is allowed, instead of a KeyError or a silently ignored field later.

Checked (lengths in mm; every other field is the gate's and left alone):

- ``port``: a table, or a list of tables, each with ``axis_point`` and ``axis_dir`` (3 numbers),
  ``radius`` > 0 and ``z_range`` (2 numbers);
- ``fem``: a table; ``mount`` a selector text; ``sites`` a table of name -> {``at``, ``normal``}
  (3 numbers each); ``contacts`` a list of {``name``, ``center``, ``normal`` (3 numbers),
  ``radius`` > 0, optional ``insert_mm`` >= 0};
- ``motor``: a table with ``diameter_mm`` > 0, ``height_mm`` > 0, ``z_bottom_mm`` and an
  optional ``name``.
"""

from __future__ import annotations

import math

from spsc.core.errors import ParameterError

__all__ = ["check_design"]


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _numbers(where: str, value, n: int) -> None:
    if not (isinstance(value, (list, tuple)) and len(value) == n
            and all(_is_number(x) for x in value)):
        raise ParameterError(where, value, f"{n} finite numbers")


def _positive(where: str, value, *, zero: bool = False) -> None:
    if not _is_number(value) or value < 0 or (value == 0 and not zero):
        raise ParameterError(where, value, "a number >= 0" if zero else "a number > 0")


def _table(where: str, value, fields: str) -> dict:
    if not isinstance(value, dict):
        raise ParameterError(where, value, f"a table (JSON object) with {fields}")
    return value


def _port(where: str, port) -> None:
    for k, p in enumerate(port if isinstance(port, list) else [port]):
        at = f"{where}[{k}]" if isinstance(port, list) else where
        p = _table(at, p, "axis_point, axis_dir, radius, z_range")
        _numbers(f"{at}.axis_point", p.get("axis_point"), 3)
        _numbers(f"{at}.axis_dir", p.get("axis_dir"), 3)
        _positive(f"{at}.radius", p.get("radius"))
        _numbers(f"{at}.z_range", p.get("z_range"), 2)


def _fem(where: str, fem) -> None:
    fem = _table(where, fem, "mount, sites, contacts")
    if "mount" in fem and not (isinstance(fem["mount"], str) and fem["mount"].strip()):
        raise ParameterError(f"{where}.mount", fem["mount"], "a selector text, e.g. 'z<=0'")
    sites = _table(f"{where}.sites", fem.get("sites", {}), "name -> {at, normal}")
    for name, site in sites.items():
        site = _table(f"{where}.sites.{name}", site, "at, normal")
        _numbers(f"{where}.sites.{name}.at", site.get("at"), 3)
        _numbers(f"{where}.sites.{name}.normal", site.get("normal"), 3)
    contacts = fem.get("contacts", [])
    if not isinstance(contacts, list):
        raise ParameterError(f"{where}.contacts", contacts, "a list of contact patches")
    for k, c in enumerate(contacts):
        at = f"{where}.contacts[{k}]"
        c = _table(at, c, "name, center, normal, radius")
        if not (isinstance(c.get("name"), str) and c["name"].strip()):
            raise ParameterError(f"{at}.name", c.get("name"), "a name")
        _numbers(f"{at}.center", c.get("center"), 3)
        _numbers(f"{at}.normal", c.get("normal"), 3)
        _positive(f"{at}.radius", c.get("radius"))
        _positive(f"{at}.insert_mm", c.get("insert_mm", 0.0), zero=True)


def _motor(where: str, motor) -> None:
    motor = _table(where, motor, "diameter_mm, height_mm, z_bottom_mm (spsc bladder --haptic "
                   "writes one)")
    _positive(f"{where}.diameter_mm", motor.get("diameter_mm"))
    _positive(f"{where}.height_mm", motor.get("height_mm"))
    if not _is_number(motor.get("z_bottom_mm")):
        raise ParameterError(f"{where}.z_bottom_mm", motor.get("z_bottom_mm"), "a number")
    if "name" in motor and not isinstance(motor["name"], str):
        raise ParameterError(f"{where}.name", motor["name"], "a text")


def check_design(design, source: str = "design file") -> dict:
    """``design`` (a design file's data) with the fields a part FEM reads checked (module
    docstring); ``source`` (the file's name) prefixes each field's name in the error."""
    if not isinstance(design, dict):
        kind = type(design).__name__
        raise ParameterError(f"design {source}", f"a JSON {kind}",
                             "a JSON object (a .design.json)")
    for key, check in (("port", _port), ("fem", _fem), ("motor", _motor)):
        if design.get(key) is not None:
            check(f"{source}: {key}", design[key])
    return design
