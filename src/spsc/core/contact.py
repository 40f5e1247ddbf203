"""What presses the chamber, as every model spells it: today the rigid plate, frictionless or
sticking (``--friction 0|stick``), rigid or on a spring (``--object-stiffness K``: a compliant
object), checked in one place so the command line and the Python API refuse the same values
with the same one-line error.

``stick`` holds every node the plate touches from sliding on it (no tangential slip: the
limit of Coulomb friction as μ → ∞, :mod:`spsc.fem.engine.friction`); ``0`` is the
frictionless plate of the paper's models. A finite coefficient (Coulomb stick/slip) is not
built yet and is refused.
"""

from __future__ import annotations

import math

from .errors import ParameterError, require

__all__ = ["FRICTION_VALUES", "check_friction", "sticks", "check_object_stiffness",
           "with_indenter"]

#: what ``--friction`` takes
FRICTION_VALUES = ("0", "stick")


def check_friction(value) -> str:
    """``"0"`` (frictionless) or ``"stick"``; ParameterError naming ``friction`` otherwise."""
    text = str(value).strip().lower()
    if text == "stick":
        return "stick"
    try:
        mu = float(text)
    except ValueError:
        mu = math.nan
    if mu == 0.0:
        return "0"
    allowed = "0 (frictionless) or stick (no slip)"
    if math.isfinite(mu) and mu > 0:
        allowed += "; a finite Coulomb coefficient is not built yet"
    raise ParameterError("friction", value, allowed)


def sticks(value) -> bool:
    """Whether the checked ``value`` holds what the plate touches."""
    return check_friction(value) == "stick"


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
