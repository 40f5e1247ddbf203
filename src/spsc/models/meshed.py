"""The options every meshed model shares (mesh size, layers through the wall, --force) and the
command line's spelling of the contact (the body, the plate's friction, the object's
stiffness: :class:`ContactOptions`), declared once so that every verb spells and explains
them alike."""

from __future__ import annotations

from dataclasses import dataclass

from .base import option

__all__ = ["mesh_size_option", "layers_option", "force_option", "solver_option", "vtu_option", "friction_option",
           "object_stiffness_option", "indenter_option", "ContactOptions"]


def mesh_size_option(default: float | None):
    """Element edge along the wall (mm); None: the model's default for the chamber."""
    return option(default, "--mesh-size", "element edge along the wall, mm (default: fem 1.0, "
                  "wall 0.5 on a dome, 1.0 on a stadium)", kind="number",
                  group="discretisation", label="mesh size", unit="mm", metavar="MM")


def layers_option(default: int = 2):
    """Quadratic elements through the wall thickness."""
    return option(default, "--layers", "quadratic elements through the wall thickness "
                  "(default: fem 2, wall 2)", kind="integer", group="discretisation",
                  label="layers", metavar="N")


def force_option():
    """Run beyond the size limits."""
    return option(False, "--force", "run a model beyond the size limits (the estimate of "
                  "unknowns, memory and load steps is printed and checked before the run)",
                  kind="flag", group="discretisation")


def solver_option():
    """The sparse linear solver of the 3D FEM (:mod:`spsc.fem.engine.linsolve`)."""
    return option("auto", "--solver", "sparse linear solver (default auto: pardiso if "
                  "installed)", kind="choice", choices=("auto", "pardiso", "superlu", "superlu-mmd"))


def vtu_option():
    """A folder for one VTU per converged step."""
    return option(None, "--vtu", "write one VTU per converged step into this folder (for "
                  "ParaView)", kind="value", metavar="DIR")


def friction_option():
    """The plate's friction: 0 (frictionless), μ or stick (:mod:`spsc.core.contact`)."""
    return option("0", "--friction", "the plate's friction: 0 (frictionless, default), a "
                  "Coulomb coefficient such as 0.3 (stick or slip per node), or stick (no "
                  "slip: every node the plate touches is held where it touched)",
                  kind="value", group="contact", metavar="0|MU|stick")


def object_stiffness_option():
    """The pressing object's stiffness (N/mm), None: rigid (:mod:`spsc.core.contact`)."""
    return option(None, "--object-stiffness", "the pressing object's stiffness, N/mm: the "
                  "indenter rides on a spring whose far end follows the travel; the curve's "
                  "indenter_travel_mm is its own (default: a rigid object)", kind="number",
                  group="contact", label="object stiffness", unit="N/mm", metavar="N/MM")


def indenter_option():
    """The rigid body that presses, centred on the chamber's axis (:mod:`spsc.core.indenter`)."""
    return option("plate", "--indenter", "the body that presses, centred on the chamber's "
                  "axis: plate (default), plate:tilt=DEG,axis=x|y (fem --full), sphere:R=MM, "
                  "cylinder:R=MM,axis=x|y, wedge:angle=DEG,axis=x|y[,r=MM] (a rounded "
                  "edge, r default 0.5), cone:angle=DEG[,r=MM] (the included angle, its tip "
                  "rounded; the paper's puncture probe: cone:angle=60,r=0.05) or any body's "
                  "FILE.stl|.3mf|.step (fem --full); y is its tip's travel; all but the level "
                  "plate are frictionless; the wall model takes a sphere or a cone on a dome "
                  "and every symmetric body on a stadium", kind="value", group="contact", metavar="BODY")


@dataclass(frozen=True)
class ContactOptions:
    """The command line's spelling of a :class:`~spsc.core.setup.Contact` (``--friction``,
    ``--object-stiffness``, ``--indenter``), offered by the verbs whose models take it
    (``contact``); :meth:`~spsc.core.setup.Contact.of` checks it."""

    friction: str = friction_option()
    object_stiffness: float | None = object_stiffness_option()
    indenter: str = indenter_option()
