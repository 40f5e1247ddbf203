"""A chamber's squeeze cycle for its durability (the paper's sec. 3.2 fatigue test: a Type B
chamber on its 40 cm³ reservoir at p_i = 50 kPa, squeezed by a rigid plate from rest,
y = 0, to y_max and back, until the pressure falls below 0.95 p_i).

The wall model walks the cycle's loading half (inflate, close the valve onto the reservoir,
press; the release retraces it: the relaxed wall is elastic) and :mod:`.fields` gives, per
node, the largest principal stretch and the strain-energy density over the cycle and their
amplitudes; the hot spot is the largest energy amplitude away from the clamped base. A
:class:`~spsc.materials.fatigue.FatigueLaw` turns its amplitude into a life (eq. L1).
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass

import numpy as np

from spsc.cad.geometry import SPSCGeometry
from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import check_load
from spsc.materials import Material
from spsc.materials.fatigue import FatigueLaw

from ..engine import load_steps, solve
from .fields import CycleFields, cycle_fields
from .model import WallModel, WallSettings

__all__ = ["SqueezeCycle", "squeeze_cycle", "paper_fatigue_law", "PAPER_TEST"]

#: the paper's fatigue test (sec. 3.2, Table 2 note 1): p_i, V_r; its y_max is not stated,
#: the 6 mm of the static tests' stroke is taken (an assumption)
PAPER_TEST = {"pressure_kPa": 50.0, "reservoir_mm3": 40000.0, "stroke_mm": 6.0}

_FIELDS = ("stretch_max", "stretch_amplitude", "energy_max", "energy_amplitude")


@dataclass(frozen=True)
class SqueezeCycle:
    """One squeeze cycle's fields (:class:`~.fields.CycleFields`) with its setup, the plate
    force and cavity pressure at the deepest point, whether the walk reached it (and how far
    it got: ``reached_mm``) and its seconds."""

    setup: dict
    fields: CycleFields
    force_N: float
    pressure_kPa: float
    reached_mm: float
    converged: bool
    message: str
    seconds: float
    #: the wall's section to draw a field on: ``nodes`` (n_s, 2) reference (R, Z) mm,
    #: ``elements`` (ne_s, 9) Q2 quads (scikit-fem's local order), ``node_of`` (stations, n_s)
    #: the model's node of each section node at each sweep station (one station: the dome),
    #: ``cavity`` and ``outer`` its two faces' nodes (apex to base)
    section: dict | None = None

    def on_section(self, name: str):
        """The field ``name`` on the section's nodes: at each, the largest over the sweep's
        stations (the dome's own)."""
        values = getattr(self.fields, name)
        return values[self.section["node_of"]].max(axis=0)

    def peaks(self) -> dict:
        """Each field's peak away from the clamped base (:meth:`CycleFields.peak`), and the
        largest stretch anywhere (the base's corner included: a singular value, shown for
        what it is)."""
        out = {name: self.fields.peak(name) for name in _FIELDS}
        out["stretch_max_with_base"] = self.fields.peak("stretch_max", away_from_base=False)
        return out

    @property
    def energy_amplitude_MPa(self) -> float:
        """The hot spot's strain-energy amplitude W_a (MPa), the fatigue law's input."""
        return self.fields.peak("energy_amplitude")["value"]


def squeeze_cycle(geometry: SPSCGeometry, material: Material, *,
                  pressure_kPa: float = PAPER_TEST["pressure_kPa"],
                  reservoir_mm3: float = PAPER_TEST["reservoir_mm3"],
                  stroke_mm: float = PAPER_TEST["stroke_mm"], polytropic_n: float = 1.0,
                  points: int = 13, settings: WallSettings | None = None) -> SqueezeCycle:
    """The squeeze cycle of ``geometry`` in ``material`` at the setup ``pressure_kPa`` (kPa
    gauge; 0: the vented chamber) with ``reservoir_mm3`` on the closed valve, to
    ``stroke_mm`` from first contact in ``points`` plate positions (y = 0 included)."""
    lc = check_load(geometry, pressure_kPa=pressure_kPa, reservoir_mm3=reservoir_mm3,
                    stroke_mm=stroke_mm, points=points, polytropic_n=polytropic_n)
    require("points", lc.points, ge=3, unit="plate positions, y = 0 included")
    pressure_kPa, reservoir_mm3, stroke_mm, points = (lc.pressure_kPa, lc.reservoir_mm3,
                                                      lc.stroke_mm, lc.points)
    t0 = time.perf_counter()
    model = WallModel(geometry, material, settings)
    res = solve(model, load_steps(lc, model.settings.inflate_increments))
    rest = [r for r in res.records if r.kind != "press"][-1]
    pressed = [r for r in res.records if r.kind == "press"]
    fields = cycle_fields(model, [rest.x] + [r.x for r in pressed])
    last = pressed[-1] if pressed else rest
    reached = stroke_mm * len(pressed) / (points - 1)
    setup = {"material": getattr(material, "name", ""), "pressure_kPa": pressure_kPa,
             "reservoir_mm3": reservoir_mm3, "stroke_mm": stroke_mm,
             "polytropic_n": polytropic_n, "points": points,
             "mesh_size_mm": model.mesh_size_mm, "layers": model.settings.layers,
             "model": model.kind}
    sec = model.part.section
    node_of = model.part.node_of if model.stadium else np.arange(len(sec.nodes))[None, :]
    section = {"nodes": np.asarray(sec.nodes), "elements": np.asarray(sec.elements),
               "node_of": np.asarray(node_of), "cavity": np.asarray(sec.cavity),
               "outer": np.asarray(sec.outer)}
    return SqueezeCycle(setup, fields, float(last.force), float(last.pressure_kPa),
                        reached, res.converged, res.message, time.perf_counter() - t0, section)


def _file_test(name: str) -> dict:
    """The ``fatigue`` entry of the material file ``name`` (its own law, or a Type B test to
    calibrate on); one-line ParameterError when it has none."""
    from spsc.materials.catalogue import FATIGUE_TESTS
    from spsc.materials.fatigue import fatigue_entry
    from spsc.materials.file import read_material_file

    if not name.lower().endswith(".json"):
        raise ParameterError("material", name, "a catalogue material with a fatigue test ("
                             + ", ".join(FATIGUE_TESTS) + ") or a material file with a "
                             "fatigue entry")
    entry = fatigue_entry(read_material_file(name), name)
    if entry is None:
        raise ParameterError("material", name, "a material file with a fatigue entry "
                             "({exponent, cycles[, amplitude_MPa]}: docs/guides/durability.md)"
                             " or a catalogue material with a fatigue test")
    if not entry["source"]:
        entry["source"] = f"the fatigue entry of {name}: a Type B chamber's test"
    return entry


@functools.lru_cache(maxsize=16)
def paper_fatigue_law(name: str, exponent: float | None = None, settings=None) -> FatigueLaw:
    """The fatigue law (eq. L1) of the catalogue material ``name`` calibrated on its Table 2
    test (:data:`~spsc.materials.catalogue.FATIGUE_TESTS`): the wall model's Table 1 Type B
    squeeze cycle at :data:`PAPER_TEST` gives the hot spot's energy amplitude, which lasted the
    test's cycles. Or a material file's ``fatigue`` entry: its own law, or its own Type B test
    calibrated the same way. ``exponent``: F (default the catalogue's or the file's). One wall
    solve (seconds), kept for the process."""
    from spsc.cad.geometry import preset
    from spsc.materials import material
    from spsc.materials.catalogue import FATIGUE_TESTS

    key = str(name).strip().lower()
    test = FATIGUE_TESTS.get(key) or _file_test(str(name).strip())
    if "amplitude_MPa" in test:  # the file's own law: no calibration
        return FatigueLaw(test["exponent"] if exponent is None else float(exponent),
                          test["amplitude_MPa"], test["cycles"], test["runout"],
                          test["source"] or f"the fatigue entry of {name}")
    if key in FATIGUE_TESTS:
        name = key
    cycle = squeeze_cycle(preset("B"), material(name), settings=settings)
    if not cycle.converged:
        raise RuntimeError(f"the calibration cycle of {key} did not converge: "
                           f"{cycle.message}")
    f = test["exponent"] if exponent is None else float(exponent)
    return FatigueLaw(f, cycle.energy_amplitude_MPa, test["cycles"], test["runout"],
                      f"CALIBRATED on {test['source']}: the wall model's Type B squeeze "
                      f"cycle at 50 kPa, 40 cm³, 6 mm (W_a = "
                      f"{cycle.energy_amplitude_MPa:.4g} MPa); F = {f:g}")
