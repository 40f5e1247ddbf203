"""The wall model (the thick wall as a nearly incompressible solid: axisymmetric on a dome,
swept along a stadium; with the gas and the plate) as a :class:`~spsc.models.base.CurveModel`."""

from __future__ import annotations

import itertools
from dataclasses import dataclass

from .base import ModelBase, Outcome
from .meshed import force_option, layers_option, mesh_size_option

__all__ = ["WallCurveModel", "WallOptions", "wall_size_check"]


@dataclass(frozen=True)
class WallOptions:
    """``mesh_size`` (mm; None: 0.5 on a dome, 1.0 on a stadium), ``layers`` through the wall,
    ``force``: run beyond the size limits. What presses the chamber is the setup's
    :class:`~spsc.core.setup.Contact`."""

    mesh_size: float | None = mesh_size_option(None)
    layers: int = layers_option(2)
    force: bool = force_option()


def wall_size_check(verb: str, geometry, mesh_size, layers, steps: int, *, force: bool,
                    quiet: bool, points: int) -> None:
    """The wall model's discretisation checked and its size estimated before any work
    (ParameterError beyond the limits unless ``force``; the estimate on stderr unless
    ``quiet``). ``mesh_size`` None: the model's default for the chamber."""
    from spsc.fem.solid.mesh import check_mesh_size
    from spsc.fem.wall.model import WallSettings

    from .resources import WALL_MAX_UNKNOWNS, check_size, wall_counts

    size = mesh_size if mesh_size is not None else \
        WallSettings().profile_size(geometry.l > 0)
    size, layers = check_mesh_size(geometry, size, layers)
    counts = wall_counts(geometry, size, layers, WallSettings().sweep_size_mm)
    check_size(verb, counts, steps, limit=WALL_MAX_UNKNOWNS, gib=None, force=force,
               quiet=quiet, mesh_size=size, points=points)


@dataclass(frozen=True)
class WallCurveModel(ModelBase):
    """Pressure and bending in one solve: the wall's own structural force F_el(y) of the vented
    chamber as well as the pressurised one (seconds per curve)."""

    name: str = "wall"
    help: str = ("the thick wall as a solid (axisymmetric dome; swept stadium) with gas and "
                 "plate: pressure and bending in one solve (seconds)")
    module: str = "spsc.models.wall"
    Options = WallOptions
    stroke_mm: float = 6.0
    points: int = 25
    bending: bool = True
    meshed: bool = True
    contact: bool = True
    color: str = "C1"
    style: str = "-."
    seconds_per_point: float = 0.9

    def load_steps(self, setup, options) -> int:
        from spsc.fem.wall import WallSettings

        load = setup.load
        inflate = WallSettings().inflate_increments if load.pressure_kPa > 0 else 0
        return load.points - 1 + inflate

    def check(self, setup, options, *, verb: str, quiet: bool) -> None:
        from spsc.core.contact import check_body

        geometry, load, c = setup.body, setup.load, setup.contact
        check_body(c.indenter, c.friction, axisymmetric=not geometry.l > 0, quarter=True)
        wall_size_check(verb, geometry, options.mesh_size, options.layers,
                        load.points - 1 + (2 if load.pressure_kPa > 0 else 0),
                        force=bool(options.force), quiet=quiet, points=load.points)

    def curve(self, setup, options, *, progress=None, cache_dir=None):
        total = self.load_steps(setup, options)
        done = itertools.count(1)
        step = None if progress is None else (lambda: progress(next(done), total))
        return Outcome(self.curves(setup, [setup.load.reservoir_mm3], options,
                                   progress=step)[0])

    def curves(self, setup, reservoirs, options, *, progress=None) -> list:
        """One model and one inflation for every reservoir (:func:`~spsc.fem.wall.curve.setup_curves`:
        the curves of separate solves, bit for bit); ``progress()`` once per point. The setup
        goes down whole."""
        from spsc.fem.wall import WallSettings
        from spsc.fem.wall.curve import setup_curves

        ws = WallSettings(mesh_size_mm=options.mesh_size, layers=options.layers)
        return setup_curves(setup, reservoirs, settings=ws, progress=progress)
