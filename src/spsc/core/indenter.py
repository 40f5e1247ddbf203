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

Spelling: ``plate``; ``plate:tilt=5,axis=y`` (the plate turned 5° about y, still lowered
along −z: a quarter model cannot carry it); ``FILE.stl|.3mf|.step`` (any rigid body, its lower
surface read as a height field, :mod:`spsc.cad.heightfield`); ``sphere:R=10``; ``cylinder:R=10,axis=x`` (the cylinder's axis along x:
it presses a line across y); ``wedge:angle=60,axis=x,r=0.5`` (included angle in degrees, the
edge along x, rounded with radius r, default 0.5 mm). Keys are case-insensitive.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .errors import ParameterError

__all__ = ["Indenter", "parse_indenter", "check_indenter", "INDENTER_KINDS"]

#: the bodies ``--indenter`` names
INDENTER_KINDS = ("plate", "sphere", "cylinder", "wedge")

_ALLOWED = ("plate[:tilt=DEG,axis=x|y], sphere:R=MM, cylinder:R=MM,axis=x|y, "
            "wedge:angle=DEG,axis=x|y[,r=MM] (|tilt| < 45, 0 < R <= 1e7, 0 < angle < 180, "
            "r >= 0) "
            "or a body's FILE.stl|.3mf|.step")

#: the files a rigid body is read from (:mod:`spsc.cad.heightfield`)
FILE_SUFFIXES = (".stl", ".3mf", ".step", ".stp")

#: the largest radius a sphere or a cylinder takes (mm): beyond, use the plate
MAX_RADIUS_MM = 1e7

#: the default rounding of a wedge's edge (mm): a printed or machined edge is never sharp
WEDGE_EDGE_MM = 0.5


@dataclass(frozen=True)
class Indenter:
    """A rigid body, its tip on the chamber's axis (or over ``at``). ``radius`` (mm): the
    sphere's or the cylinder's, the wedge's edge rounding; ``axis``: the cylinder's axis or
    the wedge's edge, or the tilted plate's turning axis (``"x"`` or ``"y"``); ``angle``
    (degrees): the wedge's included angle, or the plate's tilt (0: level)."""

    kind: str = "plate"
    radius: float = math.inf
    axis: str = "x"
    angle: float = 0.0
    #: the tip's lateral position (mm; x, y of the press frame): the chamber's axis, or where
    #: ``--plate-at`` puts it on a part
    at: tuple = (0.0, 0.0)
    #: a body from a file (kind ``"file"``: its lower surface is read by
    #: :func:`spsc.cad.heightfield.resolve`)
    path: str = ""

    def placed(self, at) -> "Indenter":
        """This body with its tip over the lateral point ``at`` (x, y in mm)."""
        return replace(self, at=(float(at[0]), float(at[1])))

    @property
    def curved(self) -> bool:
        """Whether the body is not the level plate (a curved body or a tilted plate: its
        contact follows the surface, :mod:`spsc.fem.engine.leaning`)."""
        return self.kind != "plate" or self.angle != 0.0

    @property
    def axisymmetric(self) -> bool:
        """Whether the body is symmetric about the chamber's axis (the level plate, the
        sphere)."""
        return self.kind == "sphere" or not self.curved

    @property
    def mirrored(self) -> bool:
        """Whether the body is symmetric about the planes x = 0 and y = 0 (a quarter model
        can carry it): all but a tilted plate, with their tip on the axis."""
        return (self.kind != "plate" or self.angle == 0.0) and self.at == (0.0, 0.0) \
            and self.kind != "file"

    @property
    def spec(self) -> str:
        """The canonical spelling (as ``--indenter`` takes it)."""
        if self.kind == "file":
            return self.path
        if self.kind == "plate":
            return "plate" if self.angle == 0.0 else \
                f"plate:tilt={_text(self.angle)},axis={self.axis}"
        if self.kind == "sphere":
            return f"sphere:R={_text(self.radius)}"
        if self.kind == "cylinder":
            return f"cylinder:R={_text(self.radius)},axis={self.axis}"
        return f"wedge:angle={_text(self.angle)},axis={self.axis},r={_text(self.radius)}"

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
        gap = np.broadcast_to(np.asarray(gap, float), (n,))
        if not self.curved:
            return np.zeros(n), np.zeros((k, n)), np.zeros((k, k, n))
        if self.kind == "file":
            raise ValueError(f"the body {self.path} is read first (spsc.cad.heightfield.resolve)")
        if self.kind == "sphere":
            return _round(lateral, self.radius + gap)
        if k != 2:
            raise ParameterError("indenter", self.spec, "plate or sphere:R=MM on an "
                                 "axisymmetric section")
        if self.kind == "plate":
            return _tilted(lateral, math.radians(self.angle), self.axis, gap)
        across = 1 if self.axis == "x" else 0  # the coordinate across the axis
        d = lateral[across:across + 1]
        S, dS, d2S = _round(d, self.radius + gap) if self.kind == "cylinder" \
            else _wedge(d[0], self.radius + gap, math.radians(self.angle) / 2)
        grad, hess = np.zeros((2, n)), np.zeros((2, 2, n))
        grad[across] = dS.reshape(n)
        hess[across, across] = d2S.reshape(n)
        return S, grad, hess


def _text(v: float) -> str:
    """The shortest spelling that reads back to ``v`` (``10`` for 10.0)."""
    s = repr(float(v))
    return s[:-2] if s.endswith(".0") else s


def _round(p, R):
    """A sphere (k = 2 or 1) or a cylinder (one coordinate) of radius R (n,) about p = 0:
    S = R − √(R² − |p|²), evaluated as |p|² / (R + √(R² − |p|²)) (no cancellation for a
    large R)."""
    rho2 = np.sum(p * p, axis=0)
    inside = rho2 < R * R
    s = np.sqrt(np.where(inside, R * R - rho2, 1.0))
    S = np.where(inside, rho2 / (R + s), np.inf)
    grad = p / s
    k = p.shape[0]
    hess = np.eye(k)[:, :, None] / s + p[:, None, :] * p[None, :, :] / s ** 3
    return S, grad, hess


def _tilted(p, tilt, axis, gap):
    """A plate turned by ``tilt`` (rad) about the x or y ``axis``: z = tip + tan(tilt) times
    the coordinate across the axis; offset by the gap along its normal, g / cos(tilt) below."""
    across = 1 if axis == "x" else 0
    n = p.shape[1]
    S = math.tan(tilt) * p[across] - gap * (1.0 / math.cos(tilt) - 1.0)
    grad = np.zeros((2, n))
    grad[across] = math.tan(tilt)
    return S, grad, np.zeros((2, 2, n))


def _wedge(d, r, half):
    """A wedge of half-angle ``half`` (rad) whose edge is rounded with radius r (n,): the
    arc r − √(r² − d²) out to |d| = r cos(half), where it meets the flanks of slope
    cot(half) tangentially."""
    cot = 1.0 / math.tan(half)
    dt = r * math.cos(half)
    a = np.abs(d)
    arc = a < dt
    s = np.sqrt(np.where(arc, r * r - d * d, 1.0))
    S = np.where(arc, r - s, r * (1 - math.sin(half)) + (a - dt) * cot)
    grad = np.where(arc, d / s, np.sign(d) * cot)
    hess = np.where(arc, r * r / s ** 3, 0.0)
    return S, grad[None], hess[None, None]


def _number(key, value, text) -> float:
    try:
        out = float(value)
    except ValueError:
        raise ParameterError("indenter", text, _ALLOWED) from None
    if not math.isfinite(out):
        raise ParameterError("indenter", text, _ALLOWED)
    return out


def parse_indenter(value) -> Indenter:
    """The :class:`Indenter` of a spelling such as ``sphere:R=10`` (see the module);
    ParameterError naming ``indenter`` otherwise. An :class:`Indenter` or None (the plate)
    passes through."""
    if value is None:
        return Indenter()
    if isinstance(value, Indenter):
        return value
    text = str(value).strip()
    if text.lower().endswith(FILE_SUFFIXES):
        from pathlib import Path

        if not Path(text).is_file():
            raise ParameterError("indenter", value, "an existing .stl, .3mf or .step file, "
                                 "or " + _ALLOWED)
        return Indenter("file", path=text)
    kind, _, rest = text.partition(":")
    kind = kind.strip().lower()
    if kind not in INDENTER_KINDS:
        raise ParameterError("indenter", value, _ALLOWED)
    keys = {}
    for item in filter(None, (s.strip() for s in rest.split(","))):
        key, eq, val = item.partition("=")
        if not eq:
            raise ParameterError("indenter", value, _ALLOWED)
        if key.strip().lower() in keys:  # sphere:R=10,R=20 was the last one silently
            raise ParameterError("indenter", value, f"each key once ({key.strip()} is given "
                                 "twice): " + _ALLOWED)
        keys[key.strip().lower()] = val.strip()
    wanted = {"plate": {"tilt", "axis"}, "sphere": {"r"}, "cylinder": {"r", "axis"},
              "wedge": {"angle", "axis", "r"}}[kind]
    if set(keys) - wanted:
        raise ParameterError("indenter", value, _ALLOWED)
    axis = keys.get("axis", "x").lower()
    if axis not in ("x", "y"):
        raise ParameterError("indenter", value, _ALLOWED)
    if kind == "plate":
        tilt = _number("tilt", keys.get("tilt", 0.0), value)
        if not -45.0 < tilt < 45.0:
            raise ParameterError("indenter", value, _ALLOWED)
        return Indenter(axis=axis, angle=tilt) if tilt else Indenter()
    if kind == "wedge":
        if "angle" not in keys:
            raise ParameterError("indenter", value, _ALLOWED)
        angle = _number("angle", keys["angle"], value)
        r = _number("r", keys.get("r", WEDGE_EDGE_MM), value)
        if not 0 < angle < 180 or r < 0:
            raise ParameterError("indenter", value, _ALLOWED)
        return Indenter("wedge", r, axis, angle)
    if "r" not in keys:
        raise ParameterError("indenter", value, _ALLOWED)
    R = _number("r", keys["r"], value)
    if not 0 < R <= MAX_RADIUS_MM:
        raise ParameterError("indenter", value, _ALLOWED)
    return Indenter(kind, R, axis)


def check_indenter(value) -> str:
    """The canonical spelling of ``value`` (see :func:`parse_indenter`)."""
    return parse_indenter(value).spec
