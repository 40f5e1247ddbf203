"""The fast estimate of a fused multi-chamber part (the fingertip of sec. 4.1): the pressed
chamber by a fast model (wall or membrane), the others coupled to it through the shared gas.

All chambers, the channel and the reservoir hold one gas, P·Vⁿ = const (eq. 2) over their sum.
The chambers that are not pressed only breathe with the pressure: about the setup pressure
p_i their volume is V_k(p) ≈ V_k(p_i) + C_k (p − p_i), with the compliance C_k = dV_k/dp of
their own inflation (the same fast model, central difference over ± ``dp_kPa``). For the
isothermal gas (n = 1) the compliant chamber then holds the same gas as a rigid volume

    V_eq,k = V_k(p_i) + P_abs C_k,      P_abs = p_i + 101.325 kPa,

(d(P V_k)/dP = V_k + P C_k), so the pressed chamber is solved by the fast model with the
reservoir V_r + V_channel + Σ V_eq,k: seconds, where the fused part's FEM takes minutes. What
it leaves out: the body block under the chambers (each chamber is clamped on its base, as in
the fast models) and the pockets' pads; the closing note states its error against the FEM.
"""

from __future__ import annotations

from spsc.core.curve import Curve
from spsc.core.loadcase import LoadCase
from spsc.core.setup import Setup
from spsc.models import get

__all__ = ["fused_estimate", "compliance"]

AMBIENT_KPA = 101.325


def _curve(model: str, geometry, material, pressure_kPa, reservoir_mm3, stroke_mm, points,
           polytropic_n=1.0) -> Curve:
    m = get(model)
    load = LoadCase(float(pressure_kPa), float(reservoir_mm3), float(stroke_mm), int(points),
                    float(polytropic_n))
    return m.curve(Setup(geometry, material, load), m.Options()).curve


def compliance(model: str, geometry, material, pressure_kPa: float, dp_kPa: float = 2.0):
    """(V(p_i) mm³, dV/dp mm³/kPa) of a chamber's inflation by ``model``."""
    lo = _curve(model, geometry, material, pressure_kPa - dp_kPa, 0.0, 0.5, 2)
    mid = _curve(model, geometry, material, pressure_kPa, 0.0, 0.5, 2)
    hi = _curve(model, geometry, material, pressure_kPa + dp_kPa, 0.0, 0.5, 2)
    return mid.inflated_volume_mm3, (hi.inflated_volume_mm3 - lo.inflated_volume_mm3) / (2 * dp_kPa)


def fused_estimate(pressed, others, material, *, pressure_kPa: float, channel_mm3: float,
                   reservoir_mm3: float = 0.0, stroke_mm: float = 3.0, points: int = 7,
                   model: str = "wall") -> Curve:
    """The Curve of the pressed chamber (SPSCGeometry) sharing its gas with ``others``
    (SPSCGeometry list), a channel of ``channel_mm3`` and a reservoir (mm³), by ``model``
    (``wall`` or ``membrane``); its setup records the equivalent reservoir and its parts."""
    if model not in ("wall", "membrane"):
        from spsc.core.errors import ParameterError
        raise ParameterError("model", model, "wall or membrane (the fast models that inflate "
                             "a chamber)")
    p_abs = pressure_kPa + AMBIENT_KPA
    parts = []
    for g in others:
        v, c = compliance(model, g, material, pressure_kPa) if pressure_kPa > 2.0 else \
            (g.cavity_volume(), 0.0)
        parts.append({"volume_mm3": v, "compliance_mm3_per_kPa": c, "equivalent_mm3": v + p_abs * c})
    equivalent = reservoir_mm3 + channel_mm3 + sum(p["equivalent_mm3"] for p in parts)
    curve = _curve(model, pressed, material, pressure_kPa, equivalent, stroke_mm, points)
    setup = dict(curve.setup)
    setup.update({"fused": {"model": model, "channel_mm3": channel_mm3,
                            "reservoir_mm3": reservoir_mm3, "others": parts,
                            "equivalent_reservoir_mm3": equivalent}})
    return curve.replace(setup=setup, model=f"fused-{model}")
