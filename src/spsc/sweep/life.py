"""A design's life in a sweep or a design search (issue 51): its chamber squeezed in the wall
model at its own setup (its pressure, its reservoir on the closed valve) to a stroke, the hot
spot's strain-energy amplitude turned into cycles by its material's fatigue law calibrated on
the paper's Table 2 (:mod:`spsc.fem.wall.durability`). One wall solve a design: about 0.3 s a
dome, 3 s a stadium.
"""

from __future__ import annotations

from spsc.core.errors import ParameterError

__all__ = ["LIFE_COLUMNS", "life_columns", "life_row", "check_life_materials"]

#: the columns a row gains (cycles, the hot spot's energy amplitude, the largest principal
#: stretch away from the base, whether the life is a lower bound, what went wrong)
LIFE_COLUMNS = ("life_cycles", "energy_amplitude_MPa", "peak_stretch", "life_lower_bound",
                "life_message")


def life_columns(design: dict, stroke_mm: float, exponent: float | None = None) -> dict:
    """The life columns of ``design`` squeezed to ``stroke_mm`` at its own setup."""
    from spsc.fem.wall.durability import paper_fatigue_law, squeeze_cycle
    from spsc.sweep.evaluate import resolve_design

    out = dict.fromkeys(LIFE_COLUMNS)
    try:
        geometry, mat, setup = resolve_design(design)
        law = paper_fatigue_law(str(design.get("material", "tpu60a")), exponent)
        cycle = squeeze_cycle(geometry, mat, pressure_kPa=setup["p_i_kPa"],
                              reservoir_mm3=setup["reservoir_mm3"], stroke_mm=stroke_mm)
    except (ParameterError, RuntimeError, ValueError, ArithmeticError) as exc:
        out["life_message"] = f"{type(exc).__name__}: {str(exc).splitlines()[0][:200]}"
        return out
    if not cycle.converged:
        out["life_message"] = f"the squeeze stopped at {cycle.reached_mm:.3g} mm: " \
            f"{cycle.message[:160]}"
        return out
    w = cycle.energy_amplitude_MPa
    out.update(life_cycles=law.life(w), energy_amplitude_MPa=w,
               peak_stretch=cycle.fields.peak("stretch_max")["value"],
               life_lower_bound=law.runout, life_message="")
    return out


def life_row(design: dict, model: str, process: str, points=None, stroke_mm=None, *,
             base, life_stroke_mm: float, exponent: float | None = None) -> dict:
    """``base``'s row of the design (a sweep row, or a design search's robust one) with its
    life columns, its key that of a row with a life (:func:`~.evaluate.design_key`); a row
    the base refused keeps none."""
    from spsc.sweep.evaluate import design_key

    row = base(design, model, process, points, stroke_mm)
    if row.get("status") == "ok":
        row.update(life_columns(design, life_stroke_mm, exponent))
    if row.get("key"):
        row["key"] = design_key(design, model, process, points, stroke_mm,
                                life_stroke_mm=life_stroke_mm)
    return row




def check_life_materials(materials, option: str = "--life") -> None:
    """Every material of ``materials`` one with a fatigue law: a catalogue material with a
    fatigue test (Table 2 calibrates it) or a material file with a ``fatigue`` entry; one
    ParameterError naming the first that is not."""
    from spsc.materials.catalogue import FATIGUE_TESTS
    from spsc.materials.fatigue import fatigue_entry
    from spsc.materials.file import read_material_file

    for m in materials:
        text = str(m).strip()
        if text.lower() in FATIGUE_TESTS:
            continue
        if text.lower().endswith(".json") and \
                fatigue_entry(read_material_file(text), text) is not None:
            continue
        raise ParameterError("material", m, f"with {option}, a catalogue material with a "
                             "fatigue test (" + ", ".join(FATIGUE_TESTS) + ") or a material "
                             "file with a fatigue entry")
