"""Identification of the geometric curves from one bench test (sec. 3.1, eqs. 39–40), and
prediction at other setups through the lumped model (eqs. 6–7).

The bench test (:class:`~spsc.core.bench.BenchData`) is read by :func:`~spsc.core.bench.read_bench`.
A(y) = (F − F_el)/(P − P_amb) (eq. 39), ΔV(y) = ξV_b,i [1 − (P_i/P)^(1/n)] (eq. 40).
"""

from __future__ import annotations

import numpy as np

from spsc.core.bench import OPTIONAL, REQUIRED, BenchData, read_bench
from spsc.core.constants import to_MPa
from spsc.core.curve import Curve
from spsc.core.errors import ParameterError, require
from .lumped import Setup, lumped_curve

__all__ = ["BenchData", "read_bench", "identify", "predict", "REQUIRED", "OPTIONAL"]


def identify(bench: BenchData, *, pressure_kPa: float, bladder_volume_mm3: float,
             reservoir_mm3: float = 0.0, polytropic_n: float = 1.0,
             geometry: dict | None = None, material: str = "") -> Curve:
    """A(y) (eq. 39) and ΔV(y) (eq. 40) from a bench test at setup ``pressure_kPa`` (kPa gauge)
    with bladder volume V_b,i and reservoir V_r (mm³). Returns the bench :class:`Curve`
    (model ``identified``) carrying the measured F, p and the identified A, ΔV."""
    setup = Setup(pressure_kPa, bladder_volume_mm3, reservoir_mm3, polytropic_n)
    if bench.pressure_kPa is None:
        raise ParameterError("missing column", "pressure_kPa", "the cavity pressure of the test")
    p = np.asarray(bench.pressure_kPa, float)
    tol = max(1.0, 0.2 * setup.p_i_kPa)
    if abs(p[0] - setup.p_i_kPa) > tol:
        raise ParameterError("pressure_kPa (first row)", float(p[0]),
                             f"within {tol:g} kPa of the setup pressure {setup.p_i_kPa:g} kPa "
                             "(check the units: kPa gauge, not Pa, bar or absolute)")
    if np.any(p <= 0):
        k = int(np.argmax(p <= 0))
        raise ParameterError(f"pressure_kPa (row {k + 2})", float(p[k]), "> 0 kPa gauge")
    f_el = np.zeros_like(p) if bench.elastic_force_N is None else bench.elastic_force_N
    area = 1e3 * (bench.force_N - f_el) / p  # N / kPa = 1e3 mm²
    # eq. 40: ΔV = ξ V_b,i (1 − (P_i/P)^(1/n)), the gas law solved for the volume
    dv = setup.bladder_volume_mm3 - setup.gas().volume(to_MPa(p))
    return Curve(bench.y_mm, bench.force_N, p, area, dv, model="identified",
                 geometry=geometry or {}, material=material, setup=setup.as_dict(),
                 nominal_volume_mm3=bladder_volume_mm3, inflated_volume_mm3=bladder_volume_mm3)


def predict(identified: Curve, *, pressure_kPa: float, reservoir_mm3: float,
            bladder_volume_mm3: float, polytropic_n: float = 1.0, elastic_force_N=None) -> Curve:
    """The lumped model (eqs. 6–7) on the identified A(y), ΔV(y) at another setup pressure
    (kPa gauge) and reservoir (mm³); F_el(y) (N) is added if given."""
    require("pressure", pressure_kPa, ge=0, unit="kPa gauge")
    setup = Setup(pressure_kPa, bladder_volume_mm3, reservoir_mm3, polytropic_n)
    return lumped_curve(identified.y_mm, np.maximum(identified.contact_area_mm2, 0.0),
                        identified.volume_change_mm3, setup, elastic_force_N=elastic_force_N,
                        geometry=identified.geometry, material=identified.material,
                        model="predicted", nominal_volume_mm3=identified.nominal_volume_mm3)
