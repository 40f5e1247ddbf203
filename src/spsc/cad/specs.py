"""The parameters of the printable parts, as frozen dataclasses validated on construction:
the bladder's port and flange, the fingertip's pockets, mount and chambers (mm, deg).

No CAD kernel here: a command checks every parameter in a fraction of a second, before the
seconds it takes to import OCCT and build (:mod:`spsc.cad.bladder`, :mod:`spsc.cad.fingertip`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from spsc.core.errors import ParameterError, require

from .geometry import SPSCGeometry

__all__ = ["PortSpec", "FlangeSpec", "BladderSpec", "PocketSpec", "MountSpec", "FingertipSpec",
           "bladder_spec"]


@dataclass(frozen=True)
class PortSpec:
    """Barbed nipple for a push-on tube (mm).

    ``tube_id`` is the tube's inner diameter: the shaft has that diameter and the barbs
    ``barb_ratio`` times it. ``bore`` is the air channel diameter.
    """

    tube_id: float = 3.0
    bore: float = 1.4
    length: float = 9.0
    barbs: int = 2
    barb_ratio: float = 1.25

    def __post_init__(self):
        require("port.tube_id", self.tube_id, gt=0, unit="mm")
        require("port.bore", self.bore, gt=0, lt=self.tube_id, unit="mm, < tube_id")
        require("port.length", self.length, gt=0, unit="mm")
        require("port.barb_ratio", self.barb_ratio, ge=1.0, le=2.0)
        if int(self.barbs) != self.barbs or self.barbs < 0:
            raise ParameterError("port.barbs", self.barbs, "an integer >= 0")

    @property
    def barb_diameter(self) -> float:
        return self.barb_ratio * self.tube_id

    @property
    def wall(self) -> float:
        """Radial wall of the nipple's shaft around the bore, (tube_id − bore) / 2 (mm): the
        thinnest air-tight wall of the port (the barbs only add to it)."""
        return (self.tube_id - self.bore) / 2


@dataclass(frozen=True)
class FlangeSpec:
    """Floor plate and clamping flange (mm): thickness, width beyond the widest wall, holes."""

    thickness: float = 3.5
    width: float = 6.0
    holes: int = 4
    hole_diameter: float = 3.4  # M3 clearance

    def __post_init__(self):
        require("flange.thickness", self.thickness, gt=0, unit="mm")
        require("flange.width", self.width, gt=0, unit="mm")
        require("flange.hole_diameter", self.hole_diameter, gt=0, lt=self.width,
                unit="mm, < flange.width")
        if self.holes not in (0, 2, 4):
            raise ParameterError("flange.holes", self.holes, "0, 2 or 4")

    @property
    def ligament(self) -> float:
        """Flange material on either side of a screw hole, (width − hole_diameter) / 2 (mm): the
        holes sit midway across the flange (:func:`spsc.cad.bladder.flange_hole_centres`)."""
        return (self.width - self.hole_diameter) / 2


@dataclass(frozen=True)
class BladderSpec:
    geometry: SPSCGeometry
    flange: FlangeSpec = field(default_factory=FlangeSpec)
    port: PortSpec = field(default_factory=PortSpec)

    def __post_init__(self):
        f, p = self.flange, self.port
        if self.port_axis_z + p.bore / 2 >= 0:
            widest = 2 * (f.thickness - p.bore / 2) / p.barb_ratio
            raise ParameterError("port.tube_id", p.tube_id,
                                 f"< {widest:.4g} mm for flange.thickness = {f.thickness:g} mm "
                                 "(the barbs rest on the build plane and the bore must pass "
                                 "under the cavity floor)")

    @property
    def port_axis_z(self) -> float:
        """Height of the port axis: the barbs touch the build plane z = −thickness."""
        return -self.flange.thickness + self.port.barb_diameter / 2

    @property
    def bore_roof(self) -> float:
        """Material over the horizontal bore up to the base plane z = 0 (mm): the cavity floor
        inside the wall and, between the wall and the flange edge, the only wall between the
        bore's air and the outside. Construction requires it > 0."""
        return -(self.port_axis_z + self.port.bore / 2)


@dataclass(frozen=True)
class PocketSpec:
    """FSR pocket (mm): diameter and depth of the recess, rim of the raised pad around it,
    clearance of the pocket floor above the wall's tangent plane, lead (tail) channel width."""

    diameter: float = 8.0      # FSR05 head Ø7.62 + 0.4 clearance
    depth: float = 0.5         # FSR05 thickness 0.325 + adhesive/clearance
    rim: float = 1.2
    clearance: float = 0.3
    lead_width: float = 6.75   # FSR05 tail 6.35 + 0.4

    def __post_init__(self):
        require("pocket.diameter", self.diameter, gt=0, unit="mm")
        require("pocket.depth", self.depth, gt=0, le=self.diameter / 2,
                unit="mm, at most half the pocket diameter: a recess for a flat sensor "
                "(FSR05: 0.325 mm)")
        require("pocket.rim", self.rim, gt=0, unit="mm")
        require("pocket.clearance", self.clearance, ge=0, unit="mm")
        require("pocket.lead_width", self.lead_width, gt=0, le=self.diameter,
                unit="mm, <= pocket.diameter")


@dataclass(frozen=True)
class MountSpec:
    """Rear mount (mm): block length behind the pulp, slot for the gripper finger on the
    underside (width × depth), cross screw holes (count, diameter)."""

    length: float = 12.0
    slot_width: float = 10.0
    slot_depth: float = 3.0
    screws: int = 2
    screw_diameter: float = 2.2  # M2 clearance

    def __post_init__(self):
        require("mount.length", self.length, gt=0, unit="mm")
        require("mount.slot_width", self.slot_width, ge=0, unit="mm")
        require("mount.slot_depth", self.slot_depth, ge=0, unit="mm")
        require("mount.screw_diameter", self.screw_diameter, gt=0, unit="mm")
        if self.screws not in (0, 1, 2):
            raise ParameterError("mount.screws", self.screws, "0, 1 or 2")


def _type_a(w, h, l, t0):
    return SPSCGeometry(w=w, h=h, l=l, t0=t0, n1=3.0, n2=4.0, cy=0.0)


@dataclass(frozen=True)
class FingertipSpec:
    """Fingertip for a ~20 mm wide gripper finger pad (defaults): pulp and distal Type A
    chambers, the angle (deg) between their axes, pockets, mount and port."""

    pulp: SPSCGeometry = field(default_factory=lambda: _type_a(8.0, 5.0, 12.0, 1.0))
    distal: SPSCGeometry = field(default_factory=lambda: _type_a(6.0, 4.0, 5.0, 1.0))
    angle: float = 45.0
    pocket_pitch: float = 9.0
    pocket: PocketSpec = field(default_factory=PocketSpec)
    mount: MountSpec = field(default_factory=MountSpec)
    port: PortSpec = field(default_factory=lambda: PortSpec(tube_id=3.0))
    channel_width: float = 4.0
    margin: float = 1.0

    def __post_init__(self):
        require("angle", self.angle, ge=30.0, le=90.0, unit="deg")
        require("pocket_pitch", self.pocket_pitch, ge=self.pocket.diameter + 0.8,
                unit="mm, >= pocket.diameter + 0.8")
        require("channel_width", self.channel_width, gt=0,
                lt=2 * min(self.pulp.w, self.distal.w), unit="mm, < 2 min(w)")
        for name, g in (("pulp", self.pulp), ("distal", self.distal)):
            if g.cy != 0 or g.n2 < 2:
                raise ParameterError(f"{name}.n2/cy", (g.n2, g.cy),
                                     "a chamber whose base is vertical (n2 >= 2, c_y = 0)")
        span = self.distal.l + 2 * (self.distal.w + self.distal.t0)
        if self.pocket_pitch + self.pocket.diameter > span:
            raise ParameterError("pocket_pitch", self.pocket_pitch,
                                 f"<= {span - self.pocket.diameter:g} mm so both distal pockets "
                                 "fit on the distal chamber")

    @property
    def width(self) -> float:
        """Body width across the finger (x), mm."""
        return max(2 * (self.pulp.w + self.pulp.t0),
                   self.distal.l + 2 * (self.distal.w + self.distal.t0)) + 2 * self.margin


def bladder_spec(geom, flange_holes, tube_id):
    """The :class:`BladderSpec` of a chamber with ``flange_holes`` screw holes (0, 2 or 4) and
    a port for a tube of ``tube_id`` mm inner diameter (validated: one-line ParameterError)."""
    return BladderSpec(geom, FlangeSpec(holes=flange_holes), PortSpec(tube_id=tube_id))
