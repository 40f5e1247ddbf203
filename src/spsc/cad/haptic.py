"""The haptic chamber of sec. 4.2 (PAL-HAND.Q): a Type D bladder holding an ERM vibration motor
against its inner top surface, made to print in one piece instead of being cut open and
re-joined by hand.

Inside the cavity, under the dome: a **pocket** (a ring around the motor, a ledge under its rim)
carried by a conical **support film** 0.8 mm thick (the paper's TPU 60A film, here printed with
the part) that runs down at 45° to the wall, self-supporting on an FDM printer, with windows so
the gas on both sides is one volume. Over the pocket the dome is solid down to a flat
**ceiling** at the motor's top (a cap filling the dome's crown inside the pocket's radius), so the
motor is held between ledge and ceiling without play, against the inner top surface as in the
paper. The print is paused when it reaches the motor's top (``design["print"]["pause_at_mm"]``):
the dome's opening there is the motor's diameter plus the clearance, the motor is dropped into
the pocket with its leads through the ledge's hole and the **wire exit** (a channel from the
cavity floor under the pocket out through the flange, opposite the inlet), and the print
resumes onto the motor's flat top, which carries the ceiling's first layer. The channel's
outer end is a funnel for the sealant (silicone or CA) that closes it around the leads; the
gate caps it as it caps the inlet.

The motor: DFRobot FIT0774 coin ERM, Ø10 mm × 2.7 mm (DFRobot product page, SKU FIT0774; the
same figures in the public bills of materials that use it), 1.5–4.2 V.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from spsc.core.errors import ParameterError, require

from .bladder import widest_outer_radius
from .mold.kernel import BrepKernel, MeshKernel
from .specs import BladderSpec

__all__ = ["MotorSpec", "HapticSpec", "Haptic", "build_haptic", "motor_top", "FIT0774"]


@dataclass(frozen=True)
class MotorSpec:
    """A coin vibration motor: diameter and height (mm), where the figures come from."""

    name: str
    diameter: float
    height: float
    source: str


FIT0774 = MotorSpec("FIT0774", 10.0, 2.7,
                    "DFRobot FIT0774 mini vibration motor, product page: Ø10 mm x 2.7 mm, "
                    "1.5-4.2 V")


@dataclass(frozen=True)
class HapticSpec:
    """The motor pocket and its support (mm): radial ``clearance`` of the motor in its ring,
    ``film`` the support film's thickness (the paper's 0.8 mm), ``ledge`` how far the ledge
    reaches under the motor's rim, ``ring`` the ring's wall, ``windows`` gas windows in the film
    of diameter ``window``, ``wire`` the wire channel's diameter (two leads)."""

    motor: MotorSpec = field(default_factory=lambda: FIT0774)
    clearance: float = 0.2
    film: float = 0.8
    ledge: float = 1.5
    ring: float = 0.8
    windows: int = 4
    window: float = 3.0
    wire: float = 1.6

    def __post_init__(self):
        require("haptic.clearance", self.clearance, ge=0.0, le=1.0, unit="mm")
        require("haptic.film", self.film, ge=0.4, le=2.0, unit="mm")
        require("haptic.ledge", self.ledge, gt=0.3, lt=self.motor.diameter / 2 - 1.0,
                unit="mm")
        require("haptic.ring", self.ring, ge=0.4, le=2.0, unit="mm")
        require("haptic.wire", self.wire, ge=0.8, le=3.0, unit="mm")
        if self.windows < 0 or int(self.windows) != self.windows:
            raise ParameterError("haptic.windows", self.windows, "an integer >= 0")


@dataclass(frozen=True)
class Haptic:
    """A built haptic chamber: the solid on the kernel it was built with, the motor's place
    (``motor_z`` = bottom, top; mm) and the design facts for the gate."""

    solid: object
    motor_z: tuple
    design: dict


def motor_top(bladder: BladderSpec, spec: "HapticSpec | None" = None) -> float:
    """Highest z (mm) where the cavity is still as wide as the motor's pocket (the x half-width
    of its stadium section): the motor's top rim touches the dome there. ParameterError when
    the cavity is nowhere that wide."""
    spec = spec or HapticSpec()
    radius = spec.motor.diameter / 2 + spec.clearance
    g = bladder.geometry
    z = np.linspace(g.z_widest, g.h, 4001)
    r = np.array([g.radius_at(float(zz)) for zz in z])
    ok = np.nonzero(r >= radius)[0]
    if not len(ok):
        raise ParameterError("haptic", f"a cavity {2 * r.max():.3g} mm wide",
                             f"a cavity at least {2 * radius:.3g} mm wide for the "
                             f"{spec.motor.name} ({spec.motor.diameter:g} mm and "
                             f"{spec.clearance:g} mm clearance): a larger w")
    top = float(z[ok[-1]])
    # the motor hangs below its rim's contact with the dome, its film 45° under it: both must
    # stay above the cavity's base plane (an h of 3 mm built a part the gate failed)
    need = spec.motor.height + spec.film * math.sqrt(2.0)
    if top < need:
        raise ParameterError("haptic", f"h = {g.h:g} mm (the motor's rim meets the dome "
                             f"{top:.3g} mm up)", f"a dome that meets the {spec.motor.name}'s "
                             f"rim at least {need:.3g} mm above the base (its {spec.motor.height:g}"
                             f" mm and the film under it): a larger h or a smaller w")
    return top


def _wire_exit(K, bladder: BladderSpec, spec: HapticSpec):
    """The wire exit (its solid, and its start at the floor under the pocket, mm): down from the
    floor, two 45° turns, then level through the flange's middle to its +y edge, ending in a
    funnel for the sealant."""
    g, f = bladder.geometry, bladder.flange
    r_flange = widest_outer_radius(g) + f.width
    z_c = -f.thickness / 2
    rw = spec.wire / 2
    p0 = np.array([0.0, g.l / 2, 0.3])
    p1 = np.array([0.0, g.l / 2, z_c + 1.0])
    p2 = np.array([0.0, g.l / 2 + 1.0, z_c])
    p3 = np.array([0.0, g.l / 2 + r_flange + 0.5, z_c])
    legs = []
    for q0, q1 in ((p0, p1), (p1, p2), (p2, p3)):
        dq = q1 - q0
        legs.append(K.cylinder(rw, float(np.linalg.norm(dq)) + 1e-3, q0,
                               dq / np.linalg.norm(dq)))
        legs.append(K.sphere(rw, q1) if q1 is not p3 else None)
    funnel = 3.0
    legs.append(K.cylinder(rw, funnel + 0.01, p3 - np.array([0, funnel + 0.5, 0]),
                           [0.0, 1.0, 0.0], r_top=spec.wire))
    return K.union(legs), p0


def build_haptic(bladder: BladderSpec, spec: HapticSpec = HapticSpec(), *,
                 kernel: str = "mesh") -> Haptic:
    """The haptic chamber of ``bladder`` (see the module docstring) on ``kernel`` (``mesh``:
    manifold3d, ``brep``: cadquery)."""
    K = {"mesh": MeshKernel, "brep": BrepKernel}[kernel]()
    g = bladder.geometry
    m = spec.motor
    r_p = m.diameter / 2 + spec.clearance          # pocket radius
    r_s = r_p + spec.ring                           # ring's outside
    z_top = motor_top(bladder, spec)
    z_bot = z_top - m.height
    raw = K.bladder(bladder)
    up = [0.0, 0.0, 1.0]
    reach = widest_outer_radius(g) + g.l + 5.0      # far enough to cross the wall
    drop = spec.film * math.sqrt(2.0)               # the 45° film's vertical thickness
    # the ring from the ledge up into the dome; the ledge and the 45° film down through the
    # wall (the support is only kept where it is inside the cavity: see below)
    ring = K.cut(K.cylinder(r_s, z_top + 5.0 - (z_bot - drop), [0, 0, z_bot - drop], up),
                 [K.cylinder(r_p, z_top + 6.0 - z_bot, [0, 0, z_bot], up)])
    cone = K.cylinder(r_s + reach, reach, [0, 0, z_bot - reach], up, r_top=r_s)
    lower = K.cylinder(r_s + reach, reach, [0, 0, z_bot - reach - drop], up, r_top=r_s)
    # the hole in the ledge for the leads: through the ledge, not up into the ceiling
    seat = K.cylinder(m.diameter / 2 - spec.ledge, 5.0 + m.height / 2, [0, 0, z_bot - 5.0], up)
    cuts = [lower, seat]
    r_meet = _film_meets_wall(bladder, r_s, z_bot)
    r_w = (r_s + r_meet) / 2                        # gas windows half way down the film
    z_w = z_bot - (r_w - r_s) - drop / 2
    for k in range(int(spec.windows)):
        a = 2 * math.pi * (k + 0.5) / spec.windows
        d = [math.cos(a), math.sin(a), 0.0]
        cuts.append(K.cylinder(spec.window / 2, reach, [r_s * d[0], r_s * d[1], z_w], d))
    # the ceiling: the crown of the dome inside the pocket's radius is solid down to the
    # motor's top (above it the cavity is narrower than the pocket in x; a stadium's straight
    # part beyond the ring stays gas)
    cap = K.cylinder(r_p, 10.0, [0, 0, z_top], up)
    support = K.cut(K.union([ring, cone, cap]), cuts)
    wire, p0 = _wire_exit(K, bladder, spec)
    # the cavity less the support is cut from the body: the support's faces then never lie on
    # the cavity's (a union of touching solids leaves slivers)
    gas = K.cut(raw["cavity"], [support])
    cut = [gas, raw["bore"], wire]
    if raw["holes"] is not None:
        cut.append(raw["holes"])
    solid = K.cut(raw["body"], cut)
    v_support = K.volume(raw["cavity"]) - K.volume(gas)
    design = _design(bladder, spec, z_bot, z_top, p0, v_support)
    return Haptic(solid, (z_bot, z_top), design)


def _film_meets_wall(bladder, r_s, z_bot) -> float:
    """Radius (mm) where the 45° film from (r_s, z_bot) meets the cavity's wall (x half-width)."""
    g = bladder.geometry
    z = np.linspace(z_bot, 0.0, 2001)
    r_film = r_s + (z_bot - z)
    r_wall = np.array([g.radius_at(float(zz)) for zz in z])
    hit = np.nonzero(r_film >= r_wall)[0]
    return float(r_film[hit[0]]) if len(hit) else float(r_wall[-1])


def _design(bladder, spec, z_bot, z_top, a, v_support) -> dict:
    from .bladder import bladder_design

    design = bladder_design(bladder)
    # the gate plugs the wire exit's first leg, as it plugs the inlet's riser
    cap = {"axis_point": [float(a[0]), float(a[1]), 0.0], "axis_dir": [0.0, 0.0, 1.0],
           "radius": spec.wire / 2 + 0.02, "z_range": [-0.6, 0.0]}
    # handles: the flange's holes, the wire exit (a second way out of the cavity), every gas
    # window but the first, and the pocket's way round the ring into the dome
    design["genus"] = bladder.flange.holes + 1 + int(spec.windows)
    design["kind"] = "haptic"
    design["cavity_volume_mm3"] = design["cavity_volume_mm3"] - v_support
    design["support_volume_mm3"] = v_support
    design["port"] = [design["port"], cap]
    design["exclude"] = design["exclude"] + [{"center": [float(x) for x in a],
                                              "radius": spec.wire / 2 + 0.8}]
    design["motor"] = {"name": spec.motor.name, "diameter_mm": spec.motor.diameter,
                       "height_mm": spec.motor.height, "source": spec.motor.source,
                       "z_bottom_mm": z_bot, "z_top_mm": z_top}
    design["print"] = dict(design["print"], pause_at_mm=z_top,
                           pause="insert the motor (leads down through the ledge's hole and "
                                 "out of the wire exit), then resume")
    return design
