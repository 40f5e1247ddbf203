"""The one error type for invalid user input, shared by every layer."""

from __future__ import annotations

import math

__all__ = ["ParameterError", "require", "require_integer", "table_of", "known_keys"]


class ParameterError(ValueError):
    """An input parameter is outside its allowed range.

    The message is one line: ``name = value is invalid: allowed ...``. The CLI prints it as is.
    """

    def __init__(self, name: str, value: object, allowed: str):
        self.name, self.value, self.allowed = name, value, allowed
        super().__init__(f"{name} = {_shown(value)!r} is invalid: allowed {allowed}")


def _shown(value: object) -> object:
    """A value as the user wrote it: a numpy scalar as its Python number (not
    ``np.float64(0.4)``), binary cut to its first 80 bytes, a text to its first 240
    characters (a file's header echoed back was 4–25 KB)."""
    item = getattr(value, "item", None)
    if callable(item) and getattr(value, "ndim", None) == 0:
        value = item()
    if isinstance(value, (bytes, bytearray)):
        value = bytes(value[:80]) + (b"..." if len(value) > 80 else b"")
    elif isinstance(value, str) and len(value) > 240:  # a path stays whole
        value = value[:240] + "..."
    return value


def require(name: str, value: float, *, gt: float | None = None, ge: float | None = None,
            le: float | None = None, lt: float | None = None, unit: str = "") -> float:
    """Return ``float(value)`` or raise :class:`ParameterError` naming the bound it breaks.
    A boolean is refused, not taken for 0 or 1 (a scenario's ``setup_kPa = true`` ran at
    1 kPa); text is converted (the command line's), so a typed input (TOML, JSON) refuses
    its quoted numbers where it is read (:func:`spsc.dynamics.scenario.parse_scenario`)."""
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
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        raise ParameterError(name, value, "a number: " + allowed)
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


def require_integer(name: str, value, *, ge: int | None = None, le: int | None = None,
                    unit: str = "") -> int:
    """Return ``int(value)`` for a whole number within the bounds, or raise
    :class:`ParameterError`: ``2.5`` is not rounded to 2, ``true`` is not 1."""
    v = require(name, value, ge=ge, le=le, unit=unit)
    if v != int(v):
        bounds = " and ".join(b for b in ((f">= {ge}" if ge is not None else ""),
                                          (f"<= {le}" if le is not None else "")) if b)
        raise ParameterError(name, value, "a whole number" + (f" {bounds}" if bounds else "")
                             + (f" ({unit})" if unit else ""))
    return int(v)


def table_of(doc: dict, name: str, *, required: bool = False, of: str = "the file") -> dict:
    """The TOML table ``[name]`` of ``doc`` ({} when absent and not ``required``), or a
    one-line :class:`ParameterError` naming ``[name]``: missing (``of``: whose table it is)
    or not a table."""
    t = doc.get(name, None if required else {})
    if t is None:
        raise ParameterError(f"[{name}]", "missing", f"a table of {of}")
    if not isinstance(t, dict):
        raise ParameterError(f"[{name}]", t, "a table")
    return t


def known_keys(where: str, table: dict, allowed) -> None:
    """A one-line :class:`ParameterError` naming ``where.key`` for the first key of ``table``
    outside ``allowed`` (a misspelt key is refused, never ignored)."""
    extra = sorted(set(table) - set(allowed))
    if extra:
        raise ParameterError(f"{where}.{extra[0]}", table[extra[0]],
                             "one of the keys " + ", ".join(sorted(allowed)))
