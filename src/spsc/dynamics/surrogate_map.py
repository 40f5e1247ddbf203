"""The time domain's chamber map from the wall model's surrogate
(:mod:`spsc.models.surrogate`): the same :class:`~.chamber_map.ChamberMap` V(y, P), F(y, P),
A(y, P) that :func:`~.chamber_map.build_map` computes with a wall solve per pressure level,
read from the surrogate's learnt map in milliseconds.

The surrogate holds, per held pressure P, the travel δ from that pressure's own first contact;
the map's y is the travel from first contact at the setup pressure, so δ = y + H(P) − H(p_i)
with H the inflated top: where δ ≤ 0 the plate has not reached the chamber (V = V0(P),
F = A = 0), beyond it V = V0(P) − ΔV(δ, P). Outside the surrogate's domain (a stadium, a law
that is not neo-Hookean, a pressure or a travel beyond its map) a one-line ParameterError
says which, and ``[chamber] model = "wall"`` maps it with the wall model.
"""

from __future__ import annotations

import numpy as np

from spsc.core.errors import ParameterError
from .chamber_map import ChamberMap, pressure_levels, travel_grid

__all__ = ["surrogate_map"]


def surrogate_map(geometry, material, *, setup_kPa: float, top_kPa: float, y_max_mm: float,
                  y_step_mm: float = 0.25, levels: int = 17, surrogate=None) -> ChamberMap:
    """The map of the chamber for gauge pressures 0 … ``top_kPa`` (``levels`` of them, the
    setup pressure among them) and travels from the highest level's first contact to
    ``y_max_mm`` every ``y_step_mm``, from the surrogate (``surrogate``: its file, None: the
    shipped one)."""
    from spsc.models.surrogate.domain import ratios_of
    from spsc.models.surrogate.model import check_material
    from spsc.models.surrogate.predict import choose

    sur, why = choose(surrogate, ratios_of(geometry))
    if why:
        name, text = why.split(": ", 1)
        raise ParameterError(f"chamber.{name}", getattr(geometry, name), text + " (the "
                             "surrogate's domain; [chamber] model = \"wall\" maps it)")
    check_material(material, False)
    g = geometry
    maps, _ = sur.maps(np.array([[g.w, g.h, g.l, g.t0, g.n1, g.n2, g.cy]]),
                       material.shear_modulus)
    unit, h = float(maps.unit[0]), float(maps.h[0])
    q_top, d_top = sur.q_levels[-1], sur.travels[-1]
    if top_kPa > q_top * unit:
        raise ParameterError("pressure", f"{top_kPa:.4g} kPa", f"at most "
                             f"{q_top * unit:.4g} kPa in the chamber for the surrogate's "
                             "map of this wall (the press reaches it); [chamber] model = "
                             "\"wall\" maps it")
    ps = pressure_levels(setup_kPa, top_kPa, levels)
    q = ps / unit
    H = maps.at("H", q[None, :])[0]
    H_i = float(maps.at("H", np.array([[setup_kPa / unit]]))[0, 0])
    V0 = maps.at("V0", q[None, :])[0]
    y = travel_grid(-(H.max() - H_i), y_max_mm, y_step_mm)
    delta = y[:, None] + H[None, :] - H_i
    if delta.max() > d_top * h * (1 + 1e-9):
        raise ParameterError("press", f"{y_max_mm:g} mm", f"a travel the surrogate maps: at "
                             f"most {d_top * h - (H.max() - H_i):.3g} mm here "
                             f"({d_top:g} h from each pressure's first contact)")
    d = np.maximum(delta, 0.0).ravel()
    Wd, _ = maps.dgrid.weights(d / h, slope=False)
    Wq, _ = maps.qgrid.weights(np.broadcast_to(q, delta.shape).ravel(), slope=False)
    dV, F, A = (maps.grid(k, Wd[None], Wq[None])[0].reshape(delta.shape)
                for k in ("dV", "F", "A"))
    touching = delta > 1e-9
    return ChamberMap(y, ps, np.where(touching, V0[None, :] - dV, V0[None, :]),
                      np.where(touching, np.maximum(F, 0.0), 0.0),
                      np.where(touching, np.maximum(A, 0.0), 0.0), float(setup_kPa))
