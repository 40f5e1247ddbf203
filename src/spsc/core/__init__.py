"""What every layer shares: physical constants, the gas law, the one result type and its
JSON, and the one error type for invalid input (imports go down: core → cad → membrane → fem →
pipeline)."""

from .constants import KPA_PER_MPA, P_AMB
from .curve import CURVE_COLUMNS, SCHEMA, SCHEMA_VERSION, Curve, SolveInfo
from .errors import ParameterError, require
from .gaslaw import GasLaw
from .jsonio import read_json, to_jsonable, write_json

__all__ = [
    "CURVE_COLUMNS",
    "Curve",
    "GasLaw",
    "KPA_PER_MPA",
    "P_AMB",
    "ParameterError",
    "SCHEMA",
    "SCHEMA_VERSION",
    "SolveInfo",
    "read_json",
    "require",
    "to_jsonable",
    "write_json",
]
