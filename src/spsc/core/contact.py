"""What presses the chamber, as every model spells it: today the rigid plate, frictionless or
sticking (``--friction 0|stick``), checked in one place so the command line and the Python
API refuse the same values with the same one-line error.

``stick`` holds every node the plate touches from sliding on it (no tangential slip: the
limit of Coulomb friction as μ → ∞, :mod:`spsc.fem.engine.friction`); ``0`` is the
frictionless plate of the paper's models. A finite coefficient (Coulomb stick/slip) is not
built yet and is refused.
"""

from __future__ import annotations

import math

from .errors import ParameterError

__all__ = ["FRICTION_VALUES", "check_friction", "sticks"]

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
