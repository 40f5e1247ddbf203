"""The fatigue life of an elastomer from the strain-energy density it is cycled through.

The crack-growth view of rubber fatigue (Gent, Lindley & Thomas, J. Appl. Polym. Sci. 8,
1964; Lake & Lindley, 1965; surveyed by Mars & Fatemi, Int. J. Fatigue 24, 2002, 949–961,
sec. 3): a flaw of size c₀ grows at dc/dN = B T^F under the tearing energy T = 2 k W c, W
the strain-energy density around it, so the cycles to grow it to failure are

    N_f = 1 / ((F − 1) B (2 k W)^F c₀^(F−1)) ∝ W^(−F),

a power law in the energy amplitude with the crack-growth exponent F: about 2 for a
strain-crystallising natural rubber, about 4 for a non-crystallising one such as SBR (Lake
& Lindley, as surveyed there). With F given, one constant remains — the energy amplitude
W_c of a one-cycle life:

    N_f = (W_a / W_c)^(−F).                                                          (L1)

Where no fatigue data of a material exists, W_c is calibrated on one test (the paper's
Table 2: a Type B chamber at 50 kPa, cycles to failure) and every other chamber, stroke and
pressure is a prediction from W_a alone. A test that did not fail (a run-out) gives only a
bound: W_c at most the calibrated value, the lives at least the predicted ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from spsc.core.errors import ParameterError, require

__all__ = ["FatigueLaw", "EXPONENTS", "fatigue_entry"]

#: crack-growth exponents F of the two classes of Lake & Lindley (Mars & Fatemi 2002, sec. 3)
EXPONENTS = {"crystallising": 2.0, "non-crystallising": 4.0}


@dataclass(frozen=True)
class FatigueLaw:
    """Eq. L1 through one point: a life of ``cycles`` at the energy amplitude
    ``amplitude_MPa`` (MPa = mJ/mm³), and the crack-growth ``exponent`` F; ``runout``: the
    point is a test that did not fail (W_c is an upper bound, the lives lower bounds);
    ``source`` where the point and F come from."""

    exponent: float
    amplitude_MPa: float
    cycles: float
    runout: bool = False
    source: str = ""

    def __post_init__(self):
        require("fatigue exponent", self.exponent, gt=1, le=20)
        require("fatigue amplitude_MPa", self.amplitude_MPa, gt=0, unit="MPa")
        require("fatigue cycles", self.cycles, ge=1)

    @property
    def energy_MPa(self) -> float:
        """W_c (MPa): the amplitude of a one-cycle life, W_a N^(1/F)."""
        return self.amplitude_MPa * self.cycles ** (1.0 / self.exponent)

    def life(self, amplitude_MPa: float) -> float:
        """N_f (cycles) at the energy amplitude W_a (MPa); inf at W_a = 0."""
        if not (amplitude_MPa >= 0 and math.isfinite(amplitude_MPa)):
            raise ParameterError("energy amplitude", amplitude_MPa, ">= 0 (MPa)")
        if amplitude_MPa == 0:
            return math.inf
        return self.cycles * (amplitude_MPa / self.amplitude_MPa) ** (-self.exponent)

    def amplitude_for(self, cycles: float) -> float:
        """The energy amplitude W_a (MPa) of a life of ``cycles``."""
        require("cycles", cycles, ge=1)
        return self.amplitude_MPa * (cycles / self.cycles) ** (-1.0 / self.exponent)

    def with_exponent(self, exponent: float) -> "FatigueLaw":
        """The same calibration point under another exponent F (the sensitivity of a
        prediction to F)."""
        return FatigueLaw(exponent, self.amplitude_MPa, self.cycles, self.runout, self.source)


def fatigue_entry(record: dict, fname: str = "") -> dict | None:
    """The checked ``fatigue`` entry of a material file (None without one): ``exponent`` F,
    ``cycles`` a life N, and either ``amplitude_MPa`` (the energy amplitude that lasted N: the
    law itself) or none (N is a Type B chamber's life at the paper's fatigue test, which
    calibrates it as Table 2 does the catalogue's); ``runout`` (the test did not fail) and
    ``source``. One-line ParameterError naming the key otherwise."""
    entry = record.get("fatigue")
    if entry is None:
        return None
    where = f"material {fname}: fatigue" if fname else "fatigue"
    if not isinstance(entry, dict):
        raise ParameterError(where, entry, "a table {exponent, cycles[, amplitude_MPa, "
                             "runout, source]}")
    extra = sorted(set(entry) - {"exponent", "cycles", "amplitude_MPa", "runout", "source"})
    if extra:
        raise ParameterError(f"{where}.{extra[0]}", entry[extra[0]], "one of exponent, "
                             "cycles, amplitude_MPa, runout, source")
    out = {"exponent": require(f"{where}.exponent", entry.get("exponent"), gt=1, le=20),
           "cycles": require(f"{where}.cycles", entry.get("cycles"), ge=1, le=1e12),
           "runout": bool(entry.get("runout", False)),
           "source": str(entry.get("source", ""))}
    if "amplitude_MPa" in entry:
        out["amplitude_MPa"] = require(f"{where}.amplitude_MPa", entry["amplitude_MPa"],
                                       gt=0, unit="MPa")
    return out
