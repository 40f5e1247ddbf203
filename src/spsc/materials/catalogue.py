"""The material catalogue (each entry with its source and provenance) and :func:`material`,
which resolves a catalogue name or a material file written by ``spsc fit-material``."""

from __future__ import annotations

from spsc.core.errors import ParameterError
from .failure import Failure, failure_entry
from .file import load_material
from .law import Material, neo_hookean, yeoh
from .mullins import MullinsParams
from .prony import Prony

__all__ = ["CATALOGUE", "PRONY", "FATIGUE_TESTS", "FAILURE", "material", "viscosity",
           "failure"]


def _shore_a_to_youngs(shore_a: float) -> float:
    """Gent's (1958) empirical relation between Shore A hardness and Young's modulus (MPa)."""
    return 0.0981 * (56.0 + 7.62336 * shore_a) / (0.137505 * (254.0 - 2.54 * shore_a))


_E_40A = _shore_a_to_youngs(40.0)

CATALOGUE: dict[str, Material] = {
    "tpu60a": neo_hookean(
        5.0 / 3.0, name="tpu60a", provenance="datasheet",
        source="Recreus Filaflex 60A, linearised datasheet E = 5 MPa at 20 % elongation "
               "(paper sec. 3.1); neo-Hookean with mu = E/3"),
    "elastic50a": yeoh(
        0.5056, 0.0, 0.002562, name="elastic50a", provenance="literature",
        source="Formlabs Elastic 50A (cured), Yeoh fit of Xavier et al., "
               "Sensors and Actuators A, 2021 (paper ref. [40])"),
    "silicone40a": neo_hookean(
        _E_40A / 3.0, name="silicone40a", provenance="assumed",
        source=f"ASSUMED: Formlabs Silicone 40A, Shore 40A -> E = {_E_40A:.2f} MPa by Gent's "
               "relation; neo-Hookean mu = E/3. No published hyperelastic fit used."),
    "as40": neo_hookean(
        _E_40A / 3.0, name="as40", provenance="assumed",
        source=f"ASSUMED: Easy Composites AS40 silicone, Shore 40A -> E = {_E_40A:.2f} MPa by "
               "Gent's relation; neo-Hookean mu = E/3. No published hyperelastic fit used."),
}


#: how a solving law is read (its ``kind``): W(I1, I2) (:class:`~.law.Material`) or the
#: principal stretches (:class:`~.ogden.Ogden`)
LAW_KINDS = ("invariants", "stretches")


def material(name) -> Material:
    """The catalogue material ``name`` (case-insensitive), the material file ``name`` (a
    path ending in ``.json``, :func:`.file.load_material`), or ``name`` itself when it is
    already a solving law (its ``kind`` one of :data:`LAW_KINDS`); else a one-line error
    listing the catalogue."""
    if getattr(name, "kind", None) in LAW_KINDS:
        return name
    text = str(name).strip()
    if text.lower().endswith(".json"):
        return load_material(text)
    key = text.lower()
    if key not in CATALOGUE:
        raise ParameterError("material", name, "one of " + ", ".join(CATALOGUE)
                             + ", or a material file (.json) from spsc fit-material")
    return CATALOGUE[key]


#: Prony terms of the catalogue's materials, with where they come from (the hyperelastic law
#: above is the relaxed response)
PRONY: dict[str, tuple[Prony, str]] = {
    "tpu60a": (Prony(((0.646, 1.0),)), "CALIBRATED: one term, tau = 1 s assumed, beta fitted "
               "so the wall model's squeeze-release of the Table 1 Type B (6 mm at 1 mm/s, "
               "open chamber) dissipates the paper's measured 3.8 N hysteresis (sec. 3.1); "
               "bench/bench_hysteresis.py. No relaxation test of TPU 60A used."),
}


def viscosity(name) -> tuple[Prony | None, str]:
    """(the Prony terms of ``name``, where they come from): the catalogue's, or the ``prony``
    entry of a material file; (None, why) where the material has none (elastic)."""
    text = str(name).strip()
    if text.lower().endswith(".json"):
        from pathlib import Path

        from .file import read_material_file
        from .prony import prony_from_record

        record = read_material_file(text)
        if "prony" not in record:
            return None, f"{Path(text).name} has no prony entry (spsc fit-material --relaxation)"
        return prony_from_record(record["prony"], Path(text).name), \
            str(record["prony"].get("source", ""))
    material(text)  # a catalogue name, or the one-line error
    got = PRONY.get(text.lower())
    return (got[0], got[1]) if got else (None, f"the catalogue has no Prony terms for {text}")


#: Ogden–Roxburgh constants of the first loading's softening (:mod:`.mullins`), with where
#: they come from
MULLINS: dict[str, tuple[MullinsParams, str]] = {
    "tpu60a": (MullinsParams(2.0, 0.02, 0.0), "ASSUMED: r = 2, m = 0.02 MPa (a third of the "
               "Table 1 walls' largest energy density at 6 mm), beta = 0; no cyclic test of "
               "printed TPU 60A with these constants used (bench/bench_mullins.py shows what "
               "they give)"),
}


def softening(name) -> tuple[MullinsParams | None, str]:
    """(the Mullins constants of ``name``, where they come from): the catalogue's, or the
    ``mullins`` entry ``{r, m, beta, source}`` of a material file; (None, why) without."""
    text = str(name).strip()
    if text.lower().endswith(".json"):
        from pathlib import Path

        from spsc.core.errors import ParameterError

        from .file import read_material_file

        record = read_material_file(text)
        if "mullins" not in record:
            return None, f"{Path(text).name} has no mullins entry"
        m = record["mullins"]
        if not isinstance(m, dict) or not {"r", "m"} <= set(m) or \
                set(m) - {"r", "m", "beta", "source"}:
            raise ParameterError(f"{Path(text).name}: mullins", m, "{r, m[, beta, source]}")
        return MullinsParams(m["r"], m["m"], m.get("beta", 0.0)), str(m.get("source", ""))
    material(text)
    got = MULLINS.get(text.lower())
    return (got[0], got[1]) if got else (None, f"the catalogue has no Mullins constants for "
                                               f"{text}")


#: The paper's fatigue test of each catalogue material (Table 2: a Type B chamber at
#: p_i = 50 kPa on its 40 cm³ reservoir, cycles to failure; ``runout``: passed without
#: failing) and the crack-growth exponent F assumed for it (:mod:`.fatigue`): the four are
#: non-crystallising elastomers (silicones, a TPU, an acrylate resin), F = 4 by analogy with
#: Lake & Lindley's non-crystallising SBR (Mars & Fatemi 2002) — ASSUMED, no crack-growth
#: test of these materials used. The fatigue law's constant is CALIBRATED on this test
#: (:func:`spsc.fem.wall.durability.paper_fatigue_law`).
FATIGUE_TESTS: dict[str, dict] = {
    "tpu60a": {"cycles": 4100.0, "runout": False, "exponent": 4.0,
               "source": "Table 2: Recreus TPU 60A, FDM, 4100 cycles to failure"},
    "elastic50a": {"cycles": 1330.0, "runout": False, "exponent": 4.0,
                   "source": "Table 2: Formlabs Elastic 50A (cured), SLA, 1330 cycles"},
    "silicone40a": {"cycles": 2075.0, "runout": False, "exponent": 4.0,
                    "source": "Table 2: Formlabs Silicone 40A (cured), SLA, 2075 cycles"},
    "as40": {"cycles": 5000.0, "runout": True, "exponent": 4.0,
             "source": "Table 2: Easy Composites AS40, compression molded, > 5000 cycles "
                       "(passed without failing: a run-out, the lives are lower bounds)"},
}


#: Each catalogue material's tension test to rupture (:mod:`.failure`), from the
#: manufacturer's datasheet; absent where no datasheet value is at hand (a material file's
#: ``failure`` entry supplies one).
_MANUFACTURER = ("the manufacturer's value as tabulated in PubMed Central article "
                 "PMC10406103, Table 2 (\"mechanical properties according to manufacturer\")")
FAILURE: dict[str, Failure] = {
    "tpu60a": Failure(950.0, 26.0, "Recreus Filaflex 60A Pro (DIN 53504-S2), "
                      + _MANUFACTURER),
    "elastic50a": Failure(160.0, 3.23, "Formlabs Elastic 50A, post-cured (ASTM D412-06 A), "
                          + _MANUFACTURER),
}


def failure(name) -> tuple[Failure | None, str]:
    """(the failure criterion of ``name``, where it comes from): the catalogue's, or the
    ``failure`` entry of a material file; (None, why) where there is none."""
    text = str(name).strip()
    if text.lower().endswith(".json"):
        from pathlib import Path

        from .file import read_material_file

        got = failure_entry(read_material_file(text), Path(text).name)
        if got is None:
            return None, f"{Path(text).name} has no failure entry {{elongation_pct, " \
                         f"strength_MPa, source}}"
        return got, got.source
    material(text)
    got = FAILURE.get(text.lower())
    return (got, got.source) if got else (
        None, f"no datasheet elongation at break of {text} is at hand (a material file's "
              "failure entry gives one)")
