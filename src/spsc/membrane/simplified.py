"""Simplified model (the paper's baseline of Fig. 4(b–c), its ref. [6]): the nominal chamber cut
by the plate.

The cavity keeps its nominal shape; a plate at height z = h − y cuts it. The contact area is the
cut section A(y) = π r(z)² + 2 l r(z) and the volume change the cap above the plate,
ΔV(y) = ∫_{h−y}^{h} (π r² + 2 l r) dz. The air spring (eqs. 6–7) then gives P(y), F(y).
Units: mm, mm², mm³; pressures at the edge in kPa gauge.
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy import integrate

from spsc.core.loadcase import check_load
from spsc.cad.geometry import SPSCGeometry

from spsc.core.curve import Curve, SolveInfo
from .lumped import Setup, lumped_curve
from .solver import check_membrane_pressure

__all__ = ["cut_area", "cut_volume", "simplified_curve"]


def cut_area(geometry: SPSCGeometry, y_mm) -> np.ndarray:
    """Section of the nominal cavity at the plate, A(y) = π r² + 2 l r (mm²), r = r(h − y)."""
    r = geometry.radius_at(geometry.h - np.asarray(y_mm, float))
    return math.pi * r**2 + 2.0 * geometry.l * r


def cut_volume(geometry: SPSCGeometry, y_mm) -> np.ndarray:
    """Nominal cavity volume above the plate, ΔV(y) = ∫_{h−y}^{h} (π r² + 2 l r) dz (mm³)."""
    g = geometry

    def section(z):
        r = float(g.radius_at(z))
        return math.pi * r * r + 2.0 * g.l * r

    out = []
    for y in np.atleast_1d(np.asarray(y_mm, float)):
        z0 = g.h - y
        pts = [g.z_widest] if z0 < g.z_widest < g.h else None
        out.append(integrate.quad(section, z0, g.h, points=pts, limit=200,
                                  epsabs=1e-9, epsrel=1e-11)[0] if y > 0 else 0.0)
    return np.array(out)


def simplified_curve(geometry: SPSCGeometry, *, pressure_kPa: float, reservoir_mm3: float = 0.0,
                     stroke_mm: float = 6.0, points: int = 41, polytropic_n: float = 1.0,
                     material: str = "") -> Curve:
    """The simplified model's :class:`Curve` on ``points`` plate positions over [0, stroke] mm.

    Closed form plus quadrature: trivially converged; ``curve.solver`` carries the time taken."""
    t_start = time.perf_counter()
    load = check_load(geometry, pressure_kPa=pressure_kPa, reservoir_mm3=reservoir_mm3,
                      stroke_mm=stroke_mm, points=points, polytropic_n=polytropic_n)
    stroke, n = load.stroke_mm, load.points
    check_membrane_pressure(load.pressure_kPa, stroke)
    y = np.linspace(0.0, stroke, n)
    v0 = geometry.cavity_volume()
    setup = Setup(pressure_kPa, v0, reservoir_mm3, polytropic_n)
    curve = lumped_curve(y, cut_area(geometry, y), cut_volume(geometry, y), setup,
                         geometry=geometry.as_dict(), material=material, model="simplified",
                         inflated_height_mm=geometry.h, nominal_volume_mm3=v0)
    info = SolveInfo(converged=curve.all_converged, message="converged",
                     y_reached_mm=float(y[-1]), seconds=time.perf_counter() - t_start,
                     notes=("closed form: the nominal cavity cut by the plate (no solve)",))
    return curve.replace(solver=info)
