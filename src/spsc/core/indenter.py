"""The rigid body that presses the chamber (``--indenter``): the flat plate of the paper's
models, a sphere, a cylinder or a wedge with a rounded edge, each centred on the chamber's
axis and lowered along −z.

A curved body is met where it is a graph over the plate's plane: its lower surface is
z = z_tip + S(x, y), S ≥ 0 and S(0) = 0, with z_tip the lowest point (the "plate height" of the
engine). A node whose contact point lies ``gap`` above it meets the body offset by the gap,
whose lower surface is the same kind of body with radii grown by the gap and its tip lowered
by it (the offset of a sphere is a sphere), so the node stays below

    z ≤ z_tip − gap + S_gap(x, y)

(the plate: S = 0, the paper's condition of eqs. 39–40). :meth:`Indenter.surface` gives
S_gap, its gradient and its Hessian at the nodes' current lateral positions; the engine
eliminates the node's height with them (:mod:`spsc.fem.engine.leaning`).

Each body is a class (:class:`Plate`, :class:`Sphere`, :class:`Cylinder`, :class:`Wedge`,
:class:`FileBody`) deriving from :class:`Indenter`: its ``kind`` (the name before the colon),
its ``keys`` and how they build it (:meth:`Indenter.of`), its surface, its spelling
(:attr:`Indenter.spec`) and its symmetries. :data:`INDENTERS` maps a kind to its class:
adding a body is one class and one line there.

Spelling: ``plate``; ``plate:tilt=5,axis=y`` (the plate turned 5° about y, still lowered
along −z: a quarter model cannot carry it); ``FILE.stl|.3mf|.step`` (any rigid body, its lower
surface read as a height field, :mod:`spsc.cad.heightfield`); ``sphere:R=10``; ``cylinder:R=10,axis=x`` (the cylinder's axis along x:
it presses a line across y); ``wedge:angle=60,axis=x,r=0.5`` (included angle in degrees, the
edge along x, rounded with radius r, default 0.5 mm). Keys are case-insensitive.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from .errors import ParameterError
from .surfaces import across, cone, round_, tilted, wedge

__all__ = ["Indenter", "Plate", "Sphere", "Cylinder", "Wedge", "Cone", "FileBody", "INDENTERS",
           "INDENTER_KINDS", "parse_indenter", "check_indenter"]

_ALLOWED = ("plate[:tilt=DEG,axis=x|y], sphere:R=MM, cylinder:R=MM,axis=x|y, "
            "wedge:angle=DEG,axis=x|y[,r=MM], cone:angle=DEG[,r=MM] (|tilt| < 45, "
            "0 < R <= 1e7, 0 < angle < 180, r >= 0) "
            "or a body's FILE.stl|.3mf|.step")



def _allowed() -> str:
    """What ``--indenter`` takes: the built-in spellings and every body registered in
    :data:`INDENTERS` since (its kind and keys)."""
    extra = [f"{k}:" + ",".join(f"{key}=…" for key in sorted(c.keys))
             for k, c in INDENTERS.items() if k not in INDENTER_KINDS]
    if not extra:
        return _ALLOWED
    return _ALLOWED.replace(" or a body's", ", " + ", ".join(extra) + " or a body's")


#: the files a rigid body is read from (:mod:`spsc.cad.heightfield`)
FILE_SUFFIXES = (".stl", ".3mf", ".step", ".stp")

#: the largest radius a sphere or a cylinder takes (mm): beyond, use the plate
MAX_RADIUS_MM = 1e7

#: the default rounding of a wedge's edge (mm): a printed or machined edge is never sharp
WEDGE_EDGE_MM = 0.5


@dataclass(frozen=True)
class Indenter:
    """A rigid body lowered along −z, its tip on the chamber's axis (or over ``at``, mm: x, y
    of the press frame, where ``--plate-at`` puts it on a part). A subclass gives ``kind``,
    ``keys`` (the spelling's keys, lower case), :meth:`of` (from those keys), :meth:`_surface`
    and :attr:`spec`; the base answers for the level plate's symmetries."""

    at: tuple = (0.0, 0.0)
    kind: ClassVar[str] = ""
    keys: ClassVar[frozenset] = frozenset()

    @classmethod
    def of(cls, keys: dict, text: str) -> "Indenter":
        """The body of the spelling's ``keys`` (text values); ParameterError naming
        ``indenter`` and the whole ``text`` when they do not make one."""
        raise NotImplementedError

    def placed(self, at) -> "Indenter":
        """This body with its tip over the lateral point ``at`` (x, y in mm)."""
        return replace(self, at=(float(at[0]), float(at[1])))

    @property
    def curved(self) -> bool:
        """Whether the body is not the level plate (a curved body or a tilted plate: its
        contact follows the surface, :mod:`spsc.fem.engine.leaning`)."""
        return True

    @property
    def axisymmetric(self) -> bool:
        """Whether the body is symmetric about the chamber's axis (the level plate, the
        sphere): an axisymmetric section (the wall model's dome) can carry it."""
        return not self.curved

    @property
    def mirrored(self) -> bool:
        """Whether the body is symmetric about the planes x = 0 and y = 0 (a quarter model
        can carry it), with its tip on the axis."""
        return self.at == (0.0, 0.0)

    @property
    def spec(self) -> str:
        """The canonical spelling (as ``--indenter`` takes it)."""
        raise NotImplementedError

    def surface(self, lateral, gap=0.0):
        """(S, ∇S, ∇²S) of the body offset by ``gap`` (mm, per node) at the lateral positions
        ``lateral`` (k, n) (mm; k = 2: x and y; k = 1: the radius of an axisymmetric
        section): S (n,) in mm, ∇S (k, n), ∇²S (k, k, n) in 1/mm. S is +inf where the
        body has no lower surface above the point (beyond a sphere's or a cylinder's
        equator)."""
        lateral = np.atleast_2d(np.asarray(lateral, float))
        k, n = lateral.shape
        if self.at != (0.0, 0.0):
            if k != 2:
                raise ParameterError("indenter", self.spec, "on the axis of an axisymmetric "
                                     "section")
            lateral = lateral - np.asarray(self.at, float)[:, None]
        if k != 2 and not self.axisymmetric:
            raise ParameterError("indenter", self.spec, "plate or sphere:R=MM on an "
                                 "axisymmetric section")
        return self._surface(lateral, np.broadcast_to(np.asarray(gap, float), (n,)))

    def _surface(self, lateral, gap):
        raise NotImplementedError


@dataclass(frozen=True)
class Plate(Indenter):
    """The flat plate of the paper's models; ``angle`` (degrees) turns it about the x or y
    ``axis`` (still lowered along −z: a quarter model cannot carry a tilt)."""

    angle: float = 0.0
    axis: str = "x"
    kind: ClassVar[str] = "plate"
    keys: ClassVar[frozenset] = frozenset({"tilt", "axis"})

    @classmethod
    def of(cls, keys, text):
        tilt = _number("tilt", keys.get("tilt", 0.0), text)
        if not -45.0 < tilt < 45.0:
            raise ParameterError("indenter", text, _allowed())
        return cls(angle=tilt, axis=_axis(keys, text)) if tilt else cls()

    @property
    def curved(self) -> bool:
        return self.angle != 0.0

    @property
    def mirrored(self) -> bool:
        return self.angle == 0.0 and self.at == (0.0, 0.0)

    @property
    def spec(self) -> str:
        return "plate" if self.angle == 0.0 else \
            f"plate:tilt={_text(self.angle)},axis={self.axis}"

    def _surface(self, lateral, gap):
        k, n = lateral.shape
        if not self.curved:
            return np.zeros(n), np.zeros((k, n)), np.zeros((k, k, n))
        return tilted(lateral, math.radians(self.angle), self.axis, gap)


@dataclass(frozen=True)
class Sphere(Indenter):
    """A sphere of ``radius`` (mm) on the chamber's axis."""

    radius: float = 10.0
    kind: ClassVar[str] = "sphere"
    keys: ClassVar[frozenset] = frozenset({"r"})

    @classmethod
    def of(cls, keys, text):
        return cls(radius=_radius(keys, text))

    @property
    def axisymmetric(self) -> bool:
        return True

    @property
    def spec(self) -> str:
        return f"sphere:R={_text(self.radius)}"

    def _surface(self, lateral, gap):
        return round_(lateral, self.radius + gap)


@dataclass(frozen=True)
class Cylinder(Indenter):
    """A cylinder of ``radius`` (mm) whose axis runs along x or y (``axis``): it presses a
    line across the other."""

    radius: float = 10.0
    axis: str = "x"
    kind: ClassVar[str] = "cylinder"
    keys: ClassVar[frozenset] = frozenset({"r", "axis"})

    @classmethod
    def of(cls, keys, text):
        return cls(radius=_radius(keys, text), axis=_axis(keys, text))

    @property
    def spec(self) -> str:
        return f"cylinder:R={_text(self.radius)},axis={self.axis}"

    def _surface(self, lateral, gap):
        return across(lateral, self.axis, lambda d: round_(d, self.radius + gap))


@dataclass(frozen=True)
class Wedge(Indenter):
    """A wedge of included ``angle`` (degrees) whose edge runs along x or y (``axis``),
    rounded with ``radius`` r (mm)."""

    angle: float = 60.0
    radius: float = WEDGE_EDGE_MM
    axis: str = "x"
    kind: ClassVar[str] = "wedge"
    keys: ClassVar[frozenset] = frozenset({"angle", "axis", "r"})

    @classmethod
    def of(cls, keys, text):
        angle, r = _angle_and_edge(keys, text)
        return cls(angle=angle, radius=r, axis=_axis(keys, text))

    @property
    def spec(self) -> str:
        return f"wedge:angle={_text(self.angle)},axis={self.axis},r={_text(self.radius)}"

    def _surface(self, lateral, gap):
        half = math.radians(self.angle) / 2
        return across(lateral, self.axis,
                       lambda d: wedge(d[0], self.radius + gap, half))


@dataclass(frozen=True)
class Cone(Indenter):
    """A cone of included ``angle`` (degrees) on the chamber's axis, its tip rounded with
    ``radius`` r (mm): the paper's puncture probe is ``cone:angle=60,r=0.05`` (sec. 3.2: half
    angle 30°, tip Ø 0.1 mm)."""

    angle: float = 60.0
    radius: float = WEDGE_EDGE_MM
    kind: ClassVar[str] = "cone"
    keys: ClassVar[frozenset] = frozenset({"angle", "r"})

    @classmethod
    def of(cls, keys, text):
        angle, r = _angle_and_edge(keys, text)
        return cls(angle=angle, radius=r)

    @property
    def axisymmetric(self) -> bool:
        return True

    @property
    def spec(self) -> str:
        return f"cone:angle={_text(self.angle)},r={_text(self.radius)}"

    def _surface(self, lateral, gap):
        return cone(lateral, self.radius + gap, math.radians(self.angle) / 2)


@dataclass(frozen=True)
class FileBody(Indenter):
    """Any rigid body of a file (``path``: STL, 3MF, STEP), its lower surface read as a
    height field by :func:`spsc.cad.heightfield.resolve` before a model uses it."""

    path: str = ""
    kind: ClassVar[str] = "file"

    @property
    def mirrored(self) -> bool:
        return False

    @property
    def spec(self) -> str:
        return self.path

    def _surface(self, lateral, gap):
        raise ValueError(f"the body {self.path} is read first (spsc.cad.heightfield.resolve)")


#: the bodies ``--indenter`` names, by the name before the colon: one line adds a body
INDENTERS: dict[str, type[Indenter]] = {c.kind: c for c in (Plate, Sphere, Cylinder, Wedge,
                                                             Cone)}
#: the names of :data:`INDENTERS` when this module was loaded
INDENTER_KINDS = tuple(INDENTERS)


def _axis(keys: dict, text: str) -> str:
    axis = keys.get("axis", "x").lower()
    if axis not in ("x", "y"):
        raise ParameterError("indenter", text, _allowed())
    return axis


def _angle_and_edge(keys: dict, text: str) -> tuple[float, float]:
    """(included angle, degrees in (0, 180); rounding radius r ≥ 0, mm, default
    :data:`WEDGE_EDGE_MM`) of a wedge's or a cone's spelling."""
    if "angle" not in keys:
        raise ParameterError("indenter", text, _allowed())
    angle = _number("angle", keys["angle"], text)
    r = _number("r", keys.get("r", WEDGE_EDGE_MM), text)
    if not 0 < angle < 180 or r < 0:
        raise ParameterError("indenter", text, _allowed())
    return angle, r


def _radius(keys: dict, text: str) -> float:
    if "r" not in keys:
        raise ParameterError("indenter", text, _allowed())
    R = _number("r", keys["r"], text)
    if not 0 < R <= MAX_RADIUS_MM:
        raise ParameterError("indenter", text, _allowed())
    return R




def _text(v: float) -> str:
    """The shortest spelling that reads back to ``v`` (``10`` for 10.0)."""
    s = repr(float(v))
    return s[:-2] if s.endswith(".0") else s










def _number(key, value, text) -> float:
    try:
        out = float(value)
    except ValueError:
        raise ParameterError("indenter", text, _allowed()) from None
    if not math.isfinite(out):
        raise ParameterError("indenter", text, _allowed())
    return out


def parse_indenter(value) -> Indenter:
    """The :class:`Indenter` of a spelling such as ``sphere:R=10`` (see the module; the kinds
    of :data:`INDENTERS`); ParameterError naming ``indenter`` otherwise. An
    :class:`Indenter` or None (the plate) passes through."""
    if value is None:
        return Plate()
    if isinstance(value, Indenter):
        return value
    text = str(value).strip()
    if text.lower().endswith(FILE_SUFFIXES):
        from pathlib import Path

        if not Path(text).is_file():
            raise ParameterError("indenter", value, "an existing .stl, .3mf or .step file, "
                                 "or " + _allowed())
        return FileBody(path=text)
    kind, _, rest = text.partition(":")
    cls = INDENTERS.get(kind.strip().lower())
    if cls is None:
        raise ParameterError("indenter", value, _allowed())
    keys = {}
    for item in filter(None, (s.strip() for s in rest.split(","))):
        key, eq, val = item.partition("=")
        if not eq:
            raise ParameterError("indenter", value, _allowed())
        if key.strip().lower() in keys:  # sphere:R=10,R=20 was the last one silently
            raise ParameterError("indenter", value, f"each key once ({key.strip()} is given "
                                 "twice): " + _allowed())
        keys[key.strip().lower()] = val.strip()
    if set(keys) - cls.keys:
        raise ParameterError("indenter", value, _allowed())
    return cls.of(keys, value)


def check_indenter(value) -> str:
    """The canonical spelling of ``value`` (see :func:`parse_indenter`)."""
    return parse_indenter(value).spec
