"""The parameters of a mold (``spsc mold``): the moulding process, the silicone and its
shrinkage, the mold's walls, keys, bolts and feed system, as one frozen dataclass validated on
construction. Lengths in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

from spsc.core.errors import ParameterError, require

__all__ = ["MoldSpec", "Silicone", "SILICONES", "silicone", "PROCESSES", "PARTINGS"]

PROCESSES = ("casting", "compression")
PARTINGS = ("auto", "z", "x")


@dataclass(frozen=True)
class Silicone:
    """A moulding silicone: linear shrinkage on cure (%) and where that figure comes from."""

    name: str
    shrinkage_pct: float
    source: str


#: The catalogue. Easy Composites' AS40 datasheet is not reachable from here; its shrinkage is
#: the bound that platinum (addition) cure silicones are sold with, stated as such.
SILICONES: dict[str, Silicone] = {
    s.name: s
    for s in (
        Silicone("as40", 0.1,
                 "Easy Composites AS40 (addition cure, Shore 40A, the paper's moulded chambers, "
                 "sec. 3.4): shrinkage not taken from its datasheet (not available offline); "
                 "0.1 % is the upper bound addition-cure silicones are specified with, e.g. "
                 "Smooth-On Dragon Skin technical bulletin: < 0.001 in/in (ASTM D2566). "
                 "Give --shrinkage from your batch's datasheet to replace it"),
        Silicone("dragonskin", 0.1,
                 "Smooth-On Dragon Skin series technical bulletin: shrinkage < 0.001 in/in "
                 "(ASTM D2566)"),
    )
}


def silicone(name: str) -> Silicone:
    """The :class:`Silicone` called ``name`` (case-insensitive); ParameterError if unknown."""
    key = str(name).strip().lower()
    if key not in SILICONES:
        raise ParameterError("material", name, "one of " + ", ".join(SILICONES))
    return SILICONES[key]


@dataclass(frozen=True)
class MoldSpec:
    """A mold for a bladder's wall.

    ``process``: ``casting`` (poured into the closed mold: sprue, risers and vents) or
    ``compression`` (the open mold overfilled and pressed shut: flash grooves take the excess).
    ``parting``: ``auto`` (the split with the least undercut, :func:`spsc.cad.mold.build_mold`),
    ``z`` (a horizontal plane through the port axis, halves pulled up and down) or ``x`` (the
    vertical plane x = 0, halves pulled sideways, the flange holes formed by pins pulled down).
    ``shrinkage_pct``: linear cure shrinkage (%, default the silicone's); the cavity is the part
    scaled by 1 / (1 − s). ``clearance``: gap of the registration keys in their sockets.
    ``wall``: least mold material between the part (or a key) and the mold's outside.
    """

    process: str = "casting"
    material: str = "as40"
    shrinkage_pct: float | None = None
    clearance: float = 0.2
    wall: float = 5.0
    parting: str = "auto"
    key_radius: float = 3.0
    key_height: float = 3.0
    key_draft_deg: float = 15.0
    bolt_diameter: float = 4.5       # M4 clearance
    side: float = 14.0               # mold beyond the part in the parting plane (keys, bolts)
    stem_length: float = 4.0         # the core's stem beyond the port tip
    core_print: float = 5.0          # square section of the core's print (its seat)
    sprue_radius: tuple = (4.0, 1.5)  # top, bottom
    vent_radius: float = 0.75
    groove_land: float = 1.5
    groove_width: float = 2.0
    groove_depth: float = 1.0

    def __post_init__(self):
        if self.process not in PROCESSES:
            raise ParameterError("process", self.process, "one of " + ", ".join(PROCESSES))
        if self.parting not in PARTINGS:
            raise ParameterError("parting", self.parting, "one of " + ", ".join(PARTINGS))
        silicone(self.material)
        if self.shrinkage_pct is not None:
            require("shrinkage", self.shrinkage_pct, ge=0.0, le=5.0, unit="%")
        require("clearance", self.clearance, ge=0.05, le=1.0, unit="mm")
        require("wall", self.wall, ge=2.0, le=30.0, unit="mm")
        require("key_radius", self.key_radius, ge=1.0, le=10.0, unit="mm")
        require("key_height", self.key_height, ge=1.0, le=10.0, unit="mm")
        require("key_draft_deg", self.key_draft_deg, ge=3.0, le=45.0, unit="deg")
        require("side", self.side, ge=2 * self.key_radius + self.bolt_diameter + 2.0,
                unit="mm (room for a key and a bolt)")

    @property
    def shrinkage(self) -> float:
        """Linear shrinkage as a fraction."""
        pct = silicone(self.material).shrinkage_pct if self.shrinkage_pct is None \
            else self.shrinkage_pct
        return pct / 100.0

    @property
    def scale(self) -> float:
        """Cavity scale 1 / (1 − s): the part shrinks back to its nominal size on cure."""
        return 1.0 / (1.0 - self.shrinkage)
