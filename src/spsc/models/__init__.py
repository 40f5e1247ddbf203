"""The curve models, one interface and one registry: every model of a chamber's static
response — membrane, simplified, wall, fem, surrogate — is a :class:`~.base.CurveModel` in
:data:`MODELS`, and the command line, sweeps, inverse design, calibration, the report and the
fused estimate reach models only through it.

Adding a model is one module (its class and its options dataclass) and one line of
:data:`MODELS`. :func:`parametric` gives the models of the parametric chamber (Types A–D), the
ones ``spsc curve`` offers; the ``part`` model takes a part file (``spsc fem --part``).
"""

from spsc.core.errors import ParameterError
from .base import CurveModel, ModelBase, Outcome, cli_options, option, options_from
from .fem import FEMCurveModel
from .membrane import MembraneModel
from .part import PartCurveModel
from .simplified import SimplifiedModel
from .surrogate.model import SurrogateCurveModel
from .wall import WallCurveModel

__all__ = ["MODELS", "parametric", "CurveModel", "ModelBase", "Outcome", "cli_options", "get", "option", "options_from"]

#: Every model, in the order the report shows them.
MODELS: dict[str, CurveModel] = {m.name: m for m in (
    MembraneModel(),
    SimplifiedModel(),
    WallCurveModel(),
    FEMCurveModel(),
    SurrogateCurveModel(),
    PartCurveModel(),
)}


def parametric() -> tuple[str, ...]:
    """The models of the parametric chamber (``parametric``), in :data:`MODELS`' order, as
    the registry holds them now (a model registered later is among them)."""
    return tuple(n for n, m in MODELS.items() if m.parametric)


def get(name: str) -> CurveModel:
    """The model called ``name``; a one-line ParameterError naming the models otherwise."""
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        raise ParameterError("model", name, "one of " + ", ".join(MODELS)) from None
