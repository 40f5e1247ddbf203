"""A life the design must reach (``spsc design --min-life N``, issue 51): each trial's chamber
squeezed in the wall model at its own setup (its pressure, its reservoir on the closed valve)
to the life's stroke, its hot spot's strain-energy amplitude turned into cycles by its
material's fatigue law calibrated on the paper's Table 2 (:mod:`spsc.fem.wall.durability`).

The life is an Optuna constraint, log₁₀ N_min − log₁₀ N ≤ 0, beside the printability: a
chamber that would not last is never the best. It costs one wall solve a trial (about 0.3 s a
dome, 3 s a stadium), on the workers with the trial's own evaluation.
"""

from __future__ import annotations

import math

from spsc.sweep.life import LIFE_COLUMNS, check_life_materials, life_columns, life_row

__all__ = ["life_columns", "life_row", "life_constraint", "check_life", "LIFE_COLUMNS"]


def life_constraint(row: dict, min_cycles: float) -> float:
    """log₁₀ N_min − log₁₀ N: ≤ 0 when the row's life reaches ``min_cycles``; 1 (infeasible)
    when its life could not be computed."""
    life = row.get("life_cycles")
    if not isinstance(life, (int, float)) or not life > 0:
        return 1.0
    if math.isinf(life):
        return -10.0  # no energy cycled at the hot spot: finite, for Optuna's sums
    return math.log10(min_cycles) - math.log10(life)


def check_life(min_cycles, stroke_mm, exponent, materials, lowest_h: float) -> dict:
    """The ``--min-life`` settings, checked before any work: ``min_cycles`` from 1 to 1e9, the
    life's stroke below the smallest h of the space, an exponent above 1, and every material
    of the space one with a fatigue test (its law is calibrated on it)."""
    from spsc.core.errors import require

    n = require("min-life", min_cycles, ge=1, le=1e9, unit="cycles")
    s = require("life-stroke", stroke_mm, gt=0, lt=lowest_h,
                unit=f"mm, below the smallest h of the search space ({lowest_h:g} mm)")
    if exponent is not None:
        require("fatigue exponent", exponent, gt=1, le=20)
    check_life_materials(materials, "--min-life")
    return {"cycles": n, "stroke_mm": s, "exponent": exponent}
