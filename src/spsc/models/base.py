"""What a curve model is: the one interface every model of a chamber's static response answers
through (:class:`CurveModel`), what it returns (:class:`Outcome`) and how a model declares its
own options (:func:`option`, read by the command line).

A model takes one :class:`~spsc.core.setup.Setup` — the chamber (an
:class:`~spsc.cad.geometry.SPSCGeometry`), a material (an :class:`~spsc.materials.Material`),
the load case every model shares (an :class:`~spsc.core.loadcase.LoadCase`: setup pressure kPa
gauge, reservoir mm³, stroke mm, plate positions, polytropic index) and what presses it (a
:class:`~spsc.core.setup.Contact`: the body, the plate's friction, the object's stiffness),
checked once where it entered — and its own options (a frozen dataclass), and returns a
:class:`~spsc.core.curve.Curve` F, p, A, ΔV over the plate travel y. ``spsc curve``, the
sweep, the inverse design, the calibration, the report's runner and the fused estimate reach
models only through :data:`spsc.models.MODELS`; adding a model is one module and one line
there.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any, Callable, ClassVar, Protocol, runtime_checkable

from spsc.core.errors import ParameterError

__all__ = ["CurveModel", "ModelBase", "Outcome", "Progress", "option", "cli_options",
           "options_from"]

#: ``progress(done, total)``: load steps done of the total so far (the total may grow).
Progress = Callable[[int, int], None]


@dataclass
class Outcome:
    """A model's result: the :class:`~spsc.core.curve.Curve` (its ``solver`` says how the solve
    went), model-specific JSON additions (``extra``) and what the model leaves for its writers
    and plots (``state``: the membrane's :class:`~spsc.membrane.solver.MembraneResult`, the
    FEM's ``(FEMModel, Result)``; None for the others)."""

    curve: Any
    extra: dict = field(default_factory=dict)
    state: Any = None


@runtime_checkable
class CurveModel(Protocol):
    """One model of the chamber's static response.

    Attributes
    ----------
    name, help : the ``--model`` value and its one-line description.
    module : the module computing it; its import closure is the model's code version (the
        cache key of every run and sweep row it computes).
    Options : its options, a frozen dataclass whose fields carry :func:`option` metadata (the
        command line's options come from them).
    stroke_mm, points : its default stroke (mm) and plate positions.
    bending : its force includes the wall's own structural force (False: p·A only).
    meshed : it takes a mesh size and layers (``Options`` has ``mesh_size`` and ``layers``).
    fast : seconds per curve, fit for sweeps and the inverse design's search.
    sweep : the report runs it at every setup pressure on the fine grid (False: the FEM's
        comparison pressure on its own grid, plus the open chamber).
    study : the report's validation study runs it (False: a model with its own section, e.g.
        the surrogate, checked against the model it learnt).
    color, style : how the report draws its curves (matplotlib colour and format).
    seconds_per_point : a rough compute time per plate position (s) at a 1 mm mesh with two
        layers, to start the longest runs of a study first.
    zero_stroke : it computes the inflation alone (stroke 0, one plate position).
    contact : it takes a contact other than the frictionless rigid plate (friction, a
        spring-borne object, another body: :class:`~spsc.core.setup.Contact`).
    parametric : its body is the parametric chamber (an
        :class:`~spsc.cad.geometry.SPSCGeometry`; False: a part file's
        :class:`~spsc.fem.part.Part`).
    """

    name: str
    help: str
    module: str
    Options: ClassVar[type]
    stroke_mm: float
    points: int
    bending: bool
    meshed: bool
    fast: bool
    sweep: bool
    study: bool
    color: str
    style: str
    seconds_per_point: float
    zero_stroke: bool
    contact: bool
    parametric: bool

    def load_steps(self, setup, options) -> int:
        """The load steps the solve reports through ``progress`` (0: it reports none)."""

    def check(self, setup, options, *, verb: str, quiet: bool) -> None:
        """The model's own limits on the (already checked) setup and what the run will cost,
        before any work (:class:`~spsc.core.errors.ParameterError`, one line, when
        refused)."""

    def curve(self, setup, options, *, progress: Progress | None = None,
              cache_dir=None) -> Outcome:
        """Solve ``setup`` (:class:`~spsc.core.setup.Setup`): the chamber inflated to the
        setup pressure, the valve state of the load case (reservoir 0: high stiffness), the
        body pressed over the stroke. ``cache_dir``: where a meshed model may keep its meshes.

        A model may also define ``curves(setup, reservoirs, options)``: the
        :class:`~spsc.core.curve.Curve` of ``setup`` with each reservoir volume of
        ``reservoirs`` (mm³), the modes of a design, sharing what they share (the wall model:
        one inflation). Sweeps and the inverse design use it where it exists, one ``curve``
        per reservoir otherwise (:func:`spsc.sweep.evaluate.design_curves`)."""


@dataclass(frozen=True)
class ModelBase:
    """What most models share, for a model to override: no bending, no mesh, fast, run at every
    setup pressure by the report, no stroke-0 inflation, no progress to report and no limits of
    its own beyond the load case's, and the paper's contact only (the frictionless rigid
    plate), and the parametric chamber as its body."""

    bending: bool = False
    meshed: bool = False
    fast: bool = True
    sweep: bool = True
    study: bool = True
    zero_stroke: bool = False
    contact: bool = False
    parametric: bool = True
    color: str = "C4"
    style: str = "-"
    seconds_per_point: float = 0.1

    def load_steps(self, setup, options) -> int:
        return 0

    def check(self, setup, options, *, verb: str, quiet: bool) -> None:
        self.check_contact(setup)

    def check_contact(self, setup) -> None:
        """A model without ``contact`` refuses any but the frictionless rigid plate, naming
        the first value that is not its."""
        c = setup.contact
        if self.contact or c.default:
            return
        name, value = next((n, v) for n, v, d in (
            ("friction", c.friction, c.friction == "0"),
            ("object_stiffness", c.object_stiffness, c.object_stiffness is None),
            ("indenter", c.indenter.spec, c.indenter.spec == "plate")) if not d)
        raise ParameterError(name, value, f"the frictionless rigid plate with the {self.name} "
                             "model (friction, a compliant object and other bodies: the wall "
                             "model or the 3D FEM)")


def option(default, flag: str, help: str, *, kind: str = "value", group: str = "model",
           label: str = "", unit: str = "", metavar: str | None = None, choices=None):
    """A field of a model's options dataclass that is also a command-line option.

    ``kind``: ``flag`` (present or not), ``number``, ``integer``, ``choice`` (one of
    ``choices``) or ``value`` (a string, e.g. a folder). ``group``: ``model`` (the model's own
    options), ``discretisation`` (mesh size, layers, --force) or ``contact`` (the plate's
    friction): the last two shared by the meshed models, which must declare them with the same
    flag and help. ``label``, ``unit``: how an invalid
    number is named in the one-line error."""
    cli = {"flag": flag, "help": help, "kind": kind, "group": group, "label": label or
           flag.lstrip("-").replace("-", " "), "unit": unit, "metavar": metavar,
           "choices": choices}
    return field(default=default, metadata={"cli": cli})


def cli_options(options_type) -> dict[str, dict]:
    """``{field name: option metadata}`` of an options dataclass (fields without metadata are
    not command-line options)."""
    return {f.name: f.metadata["cli"] for f in fields(options_type) if "cli" in f.metadata}


def options_from(options_type, values) -> Any:
    """``options_type`` with every option of ``values`` (a mapping or an object with
    attributes) that is given (not None); the others keep their defaults."""
    get = values.get if isinstance(values, dict) else (lambda k: getattr(values, k, None))
    given = {k: get(k) for k in cli_options(options_type)}
    return options_type(**{k: v for k, v in given.items() if v is not None})

