"""The one error type for invalid user input, shared by every layer."""

from __future__ import annotations

import math

__all__ = ["ParameterError", "require"]


class ParameterError(ValueError):
    """An input parameter is outside its allowed range.

    The message is one line: ``name = value is invalid: allowed ...``. The CLI prints it as is.
    """

    def __init__(self, name: str, value: object, allowed: str):
        self.name, self.value, self.allowed = name, value, allowed
        super().__init__(f"{name} = {value!r} is invalid: allowed {allowed}")


def require(name: str, value: float, *, gt: float | None = None, ge: float | None = None,
            le: float | None = None, lt: float | None = None, unit: str = "") -> float:
    """Return ``float(value)`` or raise :class:`ParameterError` naming the bound it breaks."""
    bounds = []
    if gt is not None:
        bounds.append(f"> {gt:g}")
    if ge is not None:
        bounds.append(f">= {ge:g}")
    if lt is not None:
        bounds.append(f"< {lt:g}")
    if le is not None:
        bounds.append(f"<= {le:g}")
    allowed = " and ".join(bounds) if bounds else "a finite number"
    if unit:
        allowed += f" ({unit})"
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, allowed) from None
    ok = math.isfinite(v)
    ok = ok and (gt is None or v > gt) and (ge is None or v >= ge)
    ok = ok and (lt is None or v < lt) and (le is None or v <= le)
    if not ok:
        raise ParameterError(name, value, allowed)
    return v
