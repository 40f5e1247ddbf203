"""The failure criterion of a material: the largest principal stretch at break.

A tension test to rupture gives the elongation at break ε_b (%) and the tensile strength; the
criterion used here is the maximum principal stretch (the oldest and simplest of the rubber
failure criteria, surveyed with its limits by Mars & Fatemi, Rubber Chem. Technol. 75, 2002,
1–17): the wall fails where its largest principal stretch λ₁ first reaches

    λ_b = 1 + ε_b / 100.                                                             (B1)

The tensile strength is carried with it, as the datasheet gives it, but not used: a law fitted
at small strain (the catalogue's TPU 60A is linearised at 20 %) does not know the stress at
ten times the length, while the stretch it is asked about is the model's own kinematics. A
uniaxial ε_b also does not know the state under a probe (closer to equibiaxial, where
elastomers break at a lower λ₁): a limit of the criterion, said where it is used.
"""

from __future__ import annotations

from dataclasses import dataclass

from spsc.core.errors import ParameterError, require

__all__ = ["Failure", "failure_entry"]


@dataclass(frozen=True)
class Failure:
    """A material's tension test to rupture: ``elongation_pct`` ε_b (%), ``strength_MPa``
    (engineering tensile strength, MPa; None if not given) and ``source``."""

    elongation_pct: float
    strength_MPa: float | None = None
    source: str = ""

    def __post_init__(self):
        require("elongation at break", self.elongation_pct, gt=0, le=5000, unit="%")
        if self.strength_MPa is not None:
            require("tensile strength", self.strength_MPa, gt=0, le=1000, unit="MPa")

    @property
    def stretch(self) -> float:
        """λ_b (eq. B1)."""
        return 1.0 + self.elongation_pct / 100.0


def failure_entry(record: dict, fname: str = "") -> Failure | None:
    """The checked ``failure`` entry of a material file (None without one):
    ``{elongation_pct, strength_MPa?, source?}``. One-line ParameterError naming the key
    otherwise."""
    entry = record.get("failure")
    if entry is None:
        return None
    where = f"material {fname}: failure" if fname else "failure"
    if not isinstance(entry, dict) or "elongation_pct" not in entry:
        raise ParameterError(where, entry, "a table {elongation_pct[, strength_MPa, source]}")
    extra = sorted(set(entry) - {"elongation_pct", "strength_MPa", "source"})
    if extra:
        raise ParameterError(f"{where}.{extra[0]}", entry[extra[0]],
                             "one of elongation_pct, strength_MPa, source")
    e = require(f"{where}.elongation_pct", entry["elongation_pct"], gt=0, le=5000, unit="%")
    s = entry.get("strength_MPa")
    if s is not None:
        s = require(f"{where}.strength_MPa", s, gt=0, le=1000, unit="MPa")
    return Failure(e, s, str(entry.get("source", "")))
