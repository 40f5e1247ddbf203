"""Invalid invocations of ``spsc fatigue``: the chamber, the cycle's setup, the exponent, the
material (a catalogue material with a fatigue test) and the outputs, each refused in one line
naming the option before the calibration's wall solve."""

from __future__ import annotations

from .fuzz_base import GEOMETRY, Case, numbers, outputs

__all__ = ["fatigue_cases"]


def fatigue_cases(f, tmp) -> list[Case]:
    """``f``: the fixtures (:func:`~.fuzz_fixtures.fixtures`)."""
    base = ("fatigue", "--type", "B", "--quiet")
    cases = numbers(base, GEOMETRY)
    cases += numbers(base, ("pressure", "reservoir", "stroke", "points", "exponent"))
    cases += [Case(base + ("--type", "E"), "unknown type", "type"),
              Case(base + ("--material", "rubber"), "unknown material", "material"),
              Case(base + ("--material", ""), "empty material", "material"),
              Case(base + ("--material", str(f["file"]) + ".json"),
                   "a material file (no fatigue test calibrates it)", "material"),
              Case(base + ("--stroke", "20"), "stroke above the chamber's height", "stroke"),
              Case(base + ("--h", "4", "--stroke", "5"), "stroke above h", "stroke"),
              Case(base + ("--exponent", "1"), "an exponent of 1 (no power law)", "exponent"),
              Case(base + ("--exponent", "50"), "an exponent of 50", "exponent"),
              Case(base + ("--pressure", "5000"), "5000 kPa", "pressure"),
              Case(base + ("--points", "2"), "two plate positions", "points"),
              Case(base + ("--reservoir", "-1"), "a negative reservoir", "reservoir")]
    cases += outputs(base, "--json", f, tmp)
    cases += outputs(base, "--png", f, tmp, ".png")
    return cases
