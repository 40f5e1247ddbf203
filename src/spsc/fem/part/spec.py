"""What a part run is asked: the part file and its design, the mount's selector, the plate's
direction and first touch, the load case every model shares, the mesh size, named contact
patches and the motor (:class:`PartRun`, built from keywords by :func:`part_run`, or from a
:class:`~spsc.core.setup.Setup` whose body is a :class:`Part` by :meth:`PartRun.of`: the
registry's ``part`` model, :mod:`spsc.models.part`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import LoadCase, WithLoadCase, check_load
from spsc.materials import Material

from ..engine import load_steps
from .selector import parse_selector

__all__ = ["ContactPatch", "Part", "PartRun", "part_run"]


@dataclass(frozen=True)
class ContactPatch:
    """A named disc of the outer surface (mm): centre, outward unit normal, radius; the plate
    meets it through a rigid insert ``thickness`` thick (an FSR05 is 0.325 mm)."""

    name: str
    center: tuple
    normal: tuple
    radius: float
    thickness: float = 0.0

    def select(self, nodes, tol: float) -> np.ndarray:
        """Mask of the points on the disc (within ``tol`` of its plane)."""
        c, n = np.asarray(self.center, float), np.asarray(self.normal, float)
        n = n / np.linalg.norm(n)
        d = np.asarray(nodes) - c
        h = d @ n
        rho = np.linalg.norm(d - h[:, None] * n, axis=1)
        return (np.abs(h) <= tol) & (rho <= self.radius + tol)


@dataclass(frozen=True)
class Part:
    """A part as the body of a :class:`~spsc.core.setup.Setup`: the file (.stl, .3mf, .step),
    the mount's selector ``fix``, the plate's direction of travel and the point it first
    touches (None: wherever it first touches), the design dict (plugs the port, names sites,
    pockets and the motor), the named contact patches and whether the motor is held. Checked
    with the load case and the mesh size where the model builds its :class:`PartRun`."""

    path: str
    fix: str
    plate_normal: tuple = (0.0, 0.0, -1.0)
    plate_at: tuple | None = None
    design: dict | None = field(default=None, compare=False)
    contacts: tuple = ()
    motor: bool = False


@dataclass(frozen=True)
class PartRun(WithLoadCase):
    """Inputs of a part run (mm, kPa, mm³): the part file, its design dict (plugs the port,
    names sites), the support selector, the plate's direction of travel and the point it first
    touches (None: wherever it first touches), the load case as for a chamber
    (:class:`~spsc.core.loadcase.LoadCase`, the same limits; the stroke against the part's own
    room is checked where the plate is placed), the mesh size. :func:`part_run` builds one
    from keywords."""

    part: str
    material: Material
    fix: str
    load: LoadCase
    plate_normal: tuple = (0.0, 0.0, -1.0)
    plate_at: tuple | None = None
    mesh_size_mm: float = 1.0
    inflate_increments: int = 4
    bulk_ratio: float = 2000.0
    design: dict | None = field(default=None, compare=False)
    contacts: tuple = ()
    motor: bool = False
    #: the body that presses (:mod:`spsc.core.indenter`): its tip at ``plate_at`` (or where
    #: the plate first touches), moving along ``plate_normal``
    indenter: str = "plate"

    def __post_init__(self):
        if not isinstance(self.load, LoadCase):
            raise ParameterError("load", type(self.load).__name__,
                                 "a LoadCase (spsc.core.loadcase.check_load)")
        check_load(None, **self.load.as_dict())
        require("mesh size", self.mesh_size_mm, gt=0, unit="mm")
        n = np.asarray(self.plate_normal, float)
        if n.shape != (3,) or not np.all(np.isfinite(n)) or np.linalg.norm(n) < 1e-12:
            raise ParameterError("plate-normal", self.plate_normal,
                                 "three numbers nx,ny,nz, not all zero (the plate's direction "
                                 "of travel)")
        object.__setattr__(self, "plate_normal", tuple(float(v) for v in n / np.linalg.norm(n)))
        if self.plate_at is not None:
            a = np.asarray(self.plate_at, float)
            if a.shape != (3,) or not np.all(np.isfinite(a)):
                raise ParameterError("plate-at", self.plate_at, "three numbers x,y,z (mm)")
            object.__setattr__(self, "plate_at", tuple(float(v) for v in a))
        parse_selector(self.fix)
        from spsc.core.indenter import check_indenter

        object.__setattr__(self, "indenter", check_indenter(self.indenter))
        if self.design is not None:
            from .design import check_design

            check_design(self.design)
        if self.motor:
            if not (self.design or {}).get("motor"):
                raise ParameterError("motor", True, "a part whose design file names a motor "
                                     "(spsc bladder --haptic writes one)")
            if not np.allclose(self.plate_normal, (0.0, 0.0, -1.0), atol=1e-9):
                raise ParameterError("plate-normal", self.plate_normal,
                                     "0,0,-1 with --motor (the motor translates along its own "
                                     "axis, z: a press along it)")

    @classmethod
    def of(cls, setup, mesh_size_mm: float = 1.0) -> "PartRun":
        """The run of ``setup`` (its body a :class:`Part`, its contact's body the indenter)
        meshed at ``mesh_size_mm``; checked as :class:`PartRun` is."""
        part = setup.body
        if not isinstance(part, Part):
            raise ParameterError("body", type(part).__name__, "a part (spsc.fem.part.Part: "
                                 "spsc fem --part FILE); the parametric chamber is the fem "
                                 "model's")
        return cls(str(part.path), setup.material, part.fix, setup.load,
                   plate_normal=part.plate_normal, plate_at=part.plate_at,
                   mesh_size_mm=mesh_size_mm, design=part.design, contacts=part.contacts,
                   motor=part.motor, indenter=setup.contact.indenter.spec)

    def body(self, model, R):
        """The :class:`~spsc.core.indenter.Indenter` placed in the press frame of ``model``
        (turned by ``R``): its tip over ``plate_at``, or over the contact node a plate first
        touches; None for the plate."""
        from spsc.cad.heightfield import resolve
        from spsc.core.indenter import parse_indenter

        body = resolve(parse_indenter(self.indenter))
        if not body.curved:
            return None
        if self.plate_at is not None:
            return body.placed((np.asarray(R) @ np.asarray(self.plate_at))[:2])
        on = model.surface
        top = on.dofs[np.argmax(on.height[on.dofs] + on.gap[on.dofs])] // 3
        return body.placed(model.disc.X[top, :2])

    def steps(self, body=None) -> list:
        """The load path; ``body``: the placed curved indenter (:meth:`body`), None: the
        plate."""
        return load_steps(self.load, self.inflate_increments, indenter=body)


def part_run(part, material: Material, fix: str, *, pressure_kPa: float = 40.0,
             reservoir_mm3: float = 0.0, stroke_mm: float = 4.0, points: int = 11,
             polytropic_n: float = 1.0, **rest) -> PartRun:
    """A :class:`PartRun` from the load case's keywords (checked by
    :func:`~spsc.core.loadcase.check_load`) and the part's (``plate_normal``, ``plate_at``,
    ``mesh_size_mm``, ``design``, ``contacts``, ``motor``, ...)."""
    load = check_load(None, pressure_kPa=pressure_kPa, reservoir_mm3=reservoir_mm3,
                      stroke_mm=stroke_mm, points=points, polytropic_n=polytropic_n)
    return PartRun(str(part), material, fix, load, **rest)
