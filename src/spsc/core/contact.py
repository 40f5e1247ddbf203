"""What presses the chamber, as every model spells it: today the rigid plate, frictionless or
sticking (``--friction 0|stick``), rigid or on a spring (``--object-stiffness K``: a compliant
object), checked in one place so the command line and the Python API refuse the same values
with the same one-line error.

``stick`` holds every node the plate touches from sliding on it (no tangential slip: the
limit of Coulomb friction as μ → ∞, :mod:`spsc.fem.engine.friction`); a number μ > 0 is
Coulomb friction, stick or slip per node (:mod:`spsc.fem.engine.coulomb`); ``0`` is the
frictionless plate of the paper's models.
"""

from __future__ import annotations

import math

from .errors import ParameterError, require

__all__ = ["FRICTION_VALUES", "check_friction", "sticks", "coefficient", "check_combination",
           "check_object_stiffness", "check_friction_on", "check_body",
           "with_indenter"]

#: what ``--friction`` takes (besides a coefficient μ > 0)
FRICTION_VALUES = ("0", "stick")


def check_friction(value) -> str:
    """``"0"`` (frictionless), ``"stick"`` or the coefficient μ > 0 as text (``"0.3"``);
    ParameterError naming ``friction`` otherwise."""
    text = str(value).strip().lower()
    if text == "stick":
        return "stick"
    try:
        mu = float(text)
    except ValueError:
        mu = math.nan
    if mu == 0.0:
        return "0"
    if math.isfinite(mu) and mu > 0:
        return f"{mu:g}"
    raise ParameterError("friction", value, "0 (frictionless), a Coulomb coefficient > 0 "
                         "(e.g. 0.3) or stick (no slip)")


def sticks(value) -> bool:
    """Whether the plate of the checked ``value`` holds what it touches (stick, or Coulomb
    friction within its cone)."""
    return check_friction(value) != "0"


def coefficient(value) -> float | None:
    """The Coulomb coefficient μ of the checked ``value``; None for no slip or no friction."""
    text = check_friction(value)
    return None if text in ("0", "stick") else float(text)


def check_combination(mu: float | None, spring: float | None) -> None:
    """Coulomb friction and a spring-borne object are not built together."""
    if mu is not None and spring is not None:
        raise ParameterError("object_stiffness", spring, "only with friction 0 or stick (a "
                             "compliant object under Coulomb friction is not built yet)")


def check_friction_on(indenter, friction) -> None:
    """Coulomb friction is built on the plate only: a curved ``indenter``
    (:class:`~spsc.core.indenter.Indenter`) is frictionless or sticks."""
    if indenter.curved and check_friction(friction) not in ("0", "stick"):
        raise ParameterError("friction", friction, f"0 or stick with the indenter "
                             f"{indenter.spec} (Coulomb friction on a curved body is not "
                             "built yet; the plate takes 0, MU or stick)")


def check_body(indenter, friction, *, axisymmetric: bool = False, quarter: bool = False):
    """The :class:`~spsc.core.indenter.Indenter` of ``indenter`` (a spelling), checked with
    ``friction`` (:func:`check_friction_on`); on an ``axisymmetric`` section (the wall
    model's dome) refused unless it is the plate or a sphere, on a ``quarter`` model unless
    it is symmetric about both planes (not a tilted plate)."""
    from .indenter import parse_indenter

    body = parse_indenter(indenter)
    check_friction_on(body, friction)
    if axisymmetric and not body.axisymmetric:
        raise ParameterError("indenter", body.spec, "plate or sphere:R=MM on a dome (l = 0) "
                             "in the wall model (its axisymmetric section); the 3D FEM takes "
                             "every body")
    if quarter and not body.mirrored:
        raise ParameterError("indenter", body.spec, "a body symmetric about x = 0 and y = 0 "
                             "on a quarter model (a tilted plate or a body from a file needs "
                             "the 3D FEM's --full)")
    return body


def check_object_stiffness(value) -> float | None:
    """The object's stiffness k (N/mm, > 0), or None for a rigid object: the indenter rides on
    a linear spring whose far end follows the prescribed travel
    (:mod:`spsc.fem.engine.spring`)."""
    if value is None:
        return None
    return require("object_stiffness", value, gt=0, unit="N/mm, the object's spring; leave "
                   "it out for a rigid object")


def with_indenter(curve, spring: float | None, travels):
    """``curve`` (a :class:`~spsc.core.curve.Curve`) with a spring-borne indenter's own travel
    per pressed point, ``travels`` (mm, from y's second point on), as the series
    ``indenter_travel_mm`` (0 at first contact, NaN where not reached) and the spring in its
    setup; unchanged for a rigid object (``spring`` None)."""
    import numpy as np

    if spring is None:
        return curve
    travel = np.full(curve.y_mm.size, np.nan)
    travel[0] = 0.0
    travel[1:len(travels) + 1] = list(travels)
    setup = {**curve.setup, "object_stiffness_N_per_mm": spring}
    return curve.replace(series={**curve.series, "indenter_travel_mm": travel}, setup=setup)
