"""The setup of a curve as one value: the chamber, its material, the load case and what presses
it, checked once where it enters (the command line, a scenario or study file, the Python API)
and handed down whole to the models (:class:`~spsc.models.base.CurveModel`), which neither
unpack it into keywords for their callers nor check it again.

* :class:`Contact` — the body that presses (an :class:`~spsc.core.indenter.Indenter`), the
  plate's friction (``"0"``, a Coulomb μ, ``"stick"``) and the pressed object's stiffness
  (N/mm, None: rigid), checked together (:mod:`spsc.core.contact`);
* :class:`Setup` — the body (an :class:`~spsc.cad.geometry.SPSCGeometry`), the material (a
  :class:`~spsc.materials.Material`), the :class:`~spsc.core.loadcase.LoadCase` (setup
  pressure kPa gauge, reservoir mm³, stroke mm, plate positions, polytropic index) and the
  :class:`Contact`;
* :class:`SetupRecord` — what a :class:`~spsc.core.curve.Curve` records of its setup, typed
  (the load case, the contact complete, a part's record, how the model ran it), written as
  the flat ``setup`` object of the curve's JSON and CSV header.

The core holds these values without importing the layers that build them (``cad``,
``materials``): a setup is made from a built geometry and material.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from .contact import (check_body, check_combination, check_friction, check_object_stiffness,
                      coefficient)
from .indenter import Indenter, Plate
from .loadcase import LoadCase, check_load

__all__ = ["Contact", "Setup", "SetupRecord", "PLATE"]

#: the flat, level plate of the paper's models
PLATE = Plate()


@dataclass(frozen=True)
class Contact:
    """What presses the chamber: ``indenter`` the rigid body (its tip on the chamber's axis),
    ``friction`` the plate's (``"0"`` frictionless, a Coulomb coefficient as text such as
    ``"0.3"``, or ``"stick"``), ``object_stiffness`` the pressed object's spring (N/mm; None:
    a rigid object). Build it with :meth:`of`, which checks the three together."""

    indenter: Indenter = field(default=PLATE)
    friction: str = "0"
    object_stiffness: float | None = None

    @classmethod
    def of(cls, indenter: Any = "plate", friction: Any = "0",
           object_stiffness: float | None = None) -> "Contact":
        """The checked contact of the spellings the command line takes (``--indenter``,
        ``--friction``, ``--object-stiffness``); one-line ParameterError naming the first
        value refused: Coulomb friction on a curved body or with a spring-borne
        object (not built yet)."""
        text = check_friction(friction)
        spring = check_object_stiffness(object_stiffness)
        check_combination(coefficient(text), spring)
        return cls(check_body(indenter, text), text, spring)

    @property
    def default(self) -> bool:
        """The paper's contact: the frictionless, rigid, level plate."""
        return (self.indenter == PLATE and self.friction == "0"
                and self.object_stiffness is None)

    @property
    def mu(self) -> float | None:
        """The Coulomb coefficient; None for no friction or no slip."""
        return coefficient(self.friction)

    def record(self) -> dict:
        """The contact as the curve records it (its spellings)."""
        return {"indenter": self.indenter.spec, "friction": self.friction,
                "object_stiffness_N_per_mm": self.object_stiffness}


@dataclass(frozen=True)
class Setup:
    """One curve's setup: ``body`` the chamber, ``material``, ``load`` the load case, and
    ``contact``. Build it with :meth:`of` (every value checked once) or from checked parts."""

    body: Any
    material: Any
    load: LoadCase
    contact: Contact = field(default_factory=Contact)

    @classmethod
    def of(cls, body, material, *, pressure_kPa: float, stroke_mm: float, points: int,
           reservoir_mm3: float = 0.0, polytropic_n: float = 1.0, indenter: Any = "plate",
           friction: Any = "0", object_stiffness: float | None = None,
           allow_zero_stroke: bool = False) -> "Setup":
        """The checked setup (:func:`~spsc.core.loadcase.check_load` on ``body``,
        :meth:`Contact.of`); ParameterError naming the first value refused."""
        load = check_load(body, pressure_kPa=pressure_kPa, reservoir_mm3=reservoir_mm3,
                          stroke_mm=stroke_mm, points=points, polytropic_n=polytropic_n,
                          allow_zero_stroke=allow_zero_stroke)
        return cls(body, material, load, Contact.of(indenter, friction, object_stiffness))

    def with_load(self, **changes) -> "Setup":
        """This setup with the load case's fields ``changes`` (e.g. ``reservoir_mm3``), not
        checked again: use it to vary a checked setup within what was checked."""
        return replace(self, load=replace(self.load, **changes))

    def record(self, **run) -> "SetupRecord":
        """What a curve of this setup records; ``run``: how the model ran it (mesh size,
        layers, unknowns, ...)."""
        c, load = self.contact, self.load
        return SetupRecord(load.pressure_kPa, load.reservoir_mm3, load.polytropic_n,
                           c.indenter.spec, c.friction, c.object_stiffness, run=dict(run))


_FIELDS = ("p_i_kPa", "reservoir_mm3", "polytropic_n", "indenter", "friction",
           "object_stiffness_N_per_mm", "part")


@dataclass(frozen=True, eq=False)
class SetupRecord(Mapping):
    """The setup a :class:`~spsc.core.curve.Curve` records: ``p_i_kPa`` the setup pressure
    (kPa gauge), ``reservoir_mm3``, ``polytropic_n``, the contact complete (``indenter`` the
    body's spelling, ``friction`` ``"0"``, μ or ``"stick"``, ``object_stiffness_N_per_mm``,
    None: rigid), ``part`` a part's record (the part FEM: its file, fixing, pockets, ...;
    None for the parametric chamber) and ``run`` how the model ran it (mesh size, layers,
    unknowns, the part it modelled, an instability).

    It reads as the flat mapping the curve's JSON holds (``setup["p_i_kPa"]``,
    :meth:`as_dict`); a mapping of those keys (a JSON file of any version) becomes one with
    :meth:`of`: a part's indenter is the record's, a missing contact the paper's plate."""

    p_i_kPa: Any = math.nan
    reservoir_mm3: Any = math.nan
    polytropic_n: Any = math.nan
    indenter: str = "plate"
    friction: str = "0"
    object_stiffness_N_per_mm: float | None = None
    part: dict | None = None
    run: dict = field(default_factory=dict)

    def __post_init__(self):
        # the flat mapping it reads as, made once (readers index it per point and per run)
        object.__setattr__(self, "_flat", self._flatten())

    @classmethod
    def of(cls, value) -> "SetupRecord":
        """The record of ``value``: a record, or a mapping of the JSON's flat keys."""
        if isinstance(value, SetupRecord):
            return value
        d = dict(value or {})
        known = {k: d.pop(k) for k in _FIELDS if k in d}
        part = known.get("part")
        if "indenter" not in known and isinstance(part, dict) and "indenter" in part:
            known["indenter"] = part["indenter"]
        return cls(**known, run=d)

    def as_dict(self) -> dict:
        """The flat JSON object: the load case, the contact, the part, then ``run``'s keys."""
        return dict(self._flat)

    def _flatten(self) -> dict:
        out = {"p_i_kPa": self.p_i_kPa, "reservoir_mm3": self.reservoir_mm3,
               "polytropic_n": self.polytropic_n, "indenter": self.indenter,
               "friction": self.friction}
        if self.object_stiffness_N_per_mm is not None:
            out["object_stiffness_N_per_mm"] = self.object_stiffness_N_per_mm
        if self.part is not None:
            out["part"] = self.part
        return out | self.run

    def __getitem__(self, key):
        return self._flat[key]

    def __iter__(self):
        return iter(self._flat)

    def __len__(self) -> int:
        return len(self._flat)

    @property
    def default_contact(self) -> bool:
        """The paper's contact: the frictionless, rigid, level plate."""
        return (self.indenter == "plate" and self.friction == "0"
                and self.object_stiffness_N_per_mm is None)
