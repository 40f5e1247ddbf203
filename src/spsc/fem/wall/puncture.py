"""The paper's puncture test on the wall model (sec. 3.2, Table 2): a conical probe pressed on
the dome of a Type B chamber at p_i = 50 kPa on its 40 cm³ reservoir, through the chamber's
height onto its base, until the membrane under the tip breaks.

The probe is :class:`~spsc.core.indenter.Cone` ``cone:angle=60,r=0.05`` (half-angle 30°,
tip Ø 0.1 mm; the paper's is Tough PLA on the elastomer: it grips, so the probe sticks where
it touches, ``friction="stick"``, :meth:`spsc.fem.engine.bodies.Plate.lean`; ``"none"`` is
the frictionless bound); the dome's cavity comes down onto the base it stands on
(:class:`~spsc.fem.engine.bodies.Floor`), where the membrane is pinched between tip and base.
The mesh is graded toward the apex (``apex_mm``: the elements' length under the tip,
:func:`~spsc.fem.solid.mesh.graded_fractions`), so the tip's rounding is resolved.

At each travel the largest principal stretch λ₁ of the wall away from its clamped base is
read (nodal, :func:`~.fields.nodal`) with its place; the predicted failure force is the probe's
force where λ₁ first reaches the material's stretch at break (eq. B1,
:mod:`spsc.materials.failure`), linear between the two travels around it. Where it is not
reached before the walk ends, the force reached is a lower bound.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from spsc.cad.geometry import SPSCGeometry
from spsc.core.errors import ParameterError, require
from spsc.core.indenter import parse_indenter
from spsc.materials import Material
from spsc.materials.failure import Failure

from ..engine import CloseValve, Inflate, Press, solve
from .fields import nodal, node_places, wall_fields
from .model import WallModel, WallSettings

__all__ = ["PAPER_PUNCTURE", "PunctureMesh", "MESHES", "Puncture", "puncture"]

#: the paper's puncture test (sec. 3.2, Table 2 note 1): probe, p_i, V_r
PAPER_PUNCTURE = {"probe": "cone:angle=60,r=0.05", "pressure_kPa": 50.0,
                  "reservoir_mm3": 40000.0}

#: the tip's approach to the base (mm left between the tip's first-contact height and the
#: base at each recorded travel near the end): the pinch, resolved
_APPROACH = (0.5, 0.3, 0.2, 0.15, 0.1, 0.08, 0.06, 0.05, 0.04, 0.03, 0.02, 0.015, 0.01,
             0.0075, 0.005, 0.004, 0.003, 0.0025, 0.002, 0.0015, 0.001)


@dataclass(frozen=True)
class PunctureMesh:
    """The wall's mesh under the probe: ``size_mm`` along the profile away from the apex,
    ``apex_mm`` under the tip (graded between), ``layers`` through the wall."""

    size_mm: float
    apex_mm: float
    layers: int

    @property
    def label(self) -> str:
        return f"{self.apex_mm:g} mm at the tip, {self.layers} layers"

    def settings(self) -> WallSettings:
        return WallSettings(mesh_size_mm=self.size_mm, layers=self.layers,
                            apex_size_mm=self.apex_mm)


#: three refinements, each halving the tip's elements and doubling the layers
MESHES = (PunctureMesh(0.25, 0.04, 4), PunctureMesh(0.25, 0.02, 8),
          PunctureMesh(0.25, 0.01, 16))


@dataclass(frozen=True)
class Puncture:
    """A puncture walk: per recorded travel (mm from first contact) the probe's force (N),
    the base's push on the cavity (N), the cavity pressure (kPa), the largest principal
    stretch λ₁ away from the clamped base and its node's reference radius (mm from the
    axis); ``clearance_mm`` the tip's height above the base at first contact (the travel
    that would close it); whether the walk reached its last travel and why not."""

    material: str
    mesh: PunctureMesh
    friction: str
    travel_mm: np.ndarray
    force_N: np.ndarray
    floor_N: np.ndarray
    pressure_kPa: np.ndarray
    stretch: np.ndarray
    radius_mm: np.ndarray
    clearance_mm: float
    converged: bool
    message: str
    seconds: float

    def failure(self, criterion: Failure) -> dict:
        """Where λ₁ first reaches the stretch at break of ``criterion`` (eq. B1):
        ``force_N`` and ``travel_mm`` there (linear in λ₁ between the recorded travels
        around it), ``reached`` True; else the last force and stretch, ``reached`` False
        (the failure force is above ``force_N``)."""
        lam = criterion.stretch
        if not len(self.stretch):  # the press stopped before its first travel
            return {"reached": False, "force_N": 0.0, "travel_mm": 0.0, "stretch": 1.0,
                    "stretch_at_break": lam}
        over = np.flatnonzero(self.stretch >= lam)
        if over.size == 0:
            k = len(self.stretch) - 1
            return {"reached": False, "force_N": float(self.force_N[k]),
                    "travel_mm": float(self.travel_mm[k]), "stretch": float(self.stretch[k]),
                    "stretch_at_break": lam}
        k = int(over[0])
        if k == 0:
            f, y = self.force_N[0], self.travel_mm[0]
        else:
            s0, s1 = self.stretch[k - 1], self.stretch[k]
            a = (lam - s0) / (s1 - s0)
            f = self.force_N[k - 1] + a * (self.force_N[k] - self.force_N[k - 1])
            y = self.travel_mm[k - 1] + a * (self.travel_mm[k] - self.travel_mm[k - 1])
        return {"reached": True, "force_N": float(f), "travel_mm": float(y),
                "stretch": lam, "stretch_at_break": lam}

    def rows(self) -> list[dict]:
        """One row per recorded travel (a table's)."""
        return [{"travel_mm": float(y), "force_N": float(f), "floor_N": float(b),
                 "pressure_kPa": float(p), "stretch": float(s), "radius_mm": float(r)}
                for y, f, b, p, s, r in zip(self.travel_mm, self.force_N, self.floor_N,
                                            self.pressure_kPa, self.stretch, self.radius_mm)]


def puncture(geometry: SPSCGeometry, material: Material, mesh: PunctureMesh = MESHES[0], *,
             probe: str = PAPER_PUNCTURE["probe"],
             pressure_kPa: float = PAPER_PUNCTURE["pressure_kPa"],
             reservoir_mm3: float = PAPER_PUNCTURE["reservoir_mm3"], friction: str = "stick",
             step_mm: float = 0.25, progress=None) -> Puncture:
    """The probe ``probe`` pressed on the dome of ``geometry`` (l = 0) inflated to
    ``pressure_kPa`` with ``reservoir_mm3`` on the closed valve, every ``step_mm`` of travel
    and through :data:`_APPROACH` to 1 µm above the base, on ``mesh``; ``friction``
    ``"stick"`` or ``"none"``."""
    if geometry.l > 0:
        raise ParameterError("l", geometry.l, "0 (the puncture probe presses a dome's apex)")
    if friction not in ("stick", "none"):
        raise ParameterError("friction", friction, "'stick' or 'none'")
    require("pressure", pressure_kPa, gt=0, le=200, unit="kPa")
    require("reservoir", reservoir_mm3, ge=0, unit="mm³")
    require("step", step_mm, gt=0, le=2, unit="mm")
    cone = parse_indenter(probe)
    t0 = time.perf_counter()
    model = WallModel(geometry, material, mesh.settings(), floor=True)
    rest = solve(model, [Inflate(pressure_kPa / 1000.0, model.settings.inflate_increments),
                         CloseValve(reservoir_mm3)])
    if not rest.converged:
        raise RuntimeError(f"the inflation to {pressure_kPa:g} kPa did not converge: "
                           f"{rest.message}")
    sec = model.part.section
    clearance = float(sec.positions(rest.records[-1].x[:model.n_u])[sec.outer[0], 1])
    travel = np.union1d(np.arange(step_mm, clearance - _APPROACH[0], step_mm),
                        clearance - np.asarray(_APPROACH)).round(9)
    res = solve(model, [Press.through(travel, indenter=cone, stick=friction == "stick")],
                start=rest, progress=progress)
    pressed = [r for r in res.records if r.kind == "press"]
    places = node_places(model)
    away = ~places["base"]
    stretch, radius = [], []
    for r in pressed:
        lam = nodal(model, wall_fields(model, r.x).stretch)
        k = int(np.flatnonzero(away)[np.argmax(lam[away])])
        stretch.append(lam[k])
        radius.append(places["radius"][k])
    return Puncture(getattr(material, "name", ""), mesh, friction, travel[:len(pressed)],
                    np.array([r.force for r in pressed]),
                    np.array([r.bodies.get("floor", 0.0) for r in pressed]),
                    np.array([r.pressure_kPa for r in pressed]), np.array(stretch),
                    np.array(radius), clearance, res.converged, res.message,
                    time.perf_counter() - t0)
