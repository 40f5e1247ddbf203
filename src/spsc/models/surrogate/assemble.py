"""From the learnt map to the curve: the gas law applied exactly (eqs. 2, 6–7).

The map of a design holds, at each dimensionless pressure level q_j (P = q μ t0/w) with the
pressure held, the outer top H(q) and free cavity volume V0(q) of the inflated chamber, and
over the travels δ from that level's own first contact the volume given up ΔV(δ, q), the plate
force F(δ, q) and the contact area A(δ, q). Between grid points it is a tensor-product cubic
spline (:class:`.spline.SplineGrid`).

A plate at travel y below the first contact at the setup pressure p_i meets the chamber at
pressure P after δ(y, P) = y + H(P) − H(p_i) of that level's travel. With the valve closed the
trapped gas fixes P (eq. 2): (P + P_atm) (V0(P) − ΔV(δ, P) + V_r)ⁿ = (p_i + P_atm)
(V0(p_i) + V_r)ⁿ, solved for P at every y by a safeguarded Newton iteration (the left side
grows with P: a higher pressure both compresses the gas less and inflates the wall). The
vented chamber (p_i = 0) stays at P = 0. The force, area and volume change then follow from
the map at (δ, P). Every array is (designs × travels): one call answers thousands of curves.

Units: mm, N, kPa gauge, mm³.
"""

from __future__ import annotations

import numpy as np

from spsc.core.constants import P_AMB_KPA
from .spline import SplineGrid

__all__ = ["Maps", "solve_curves", "CHUNK"]

#: designs solved together (their points' spline weights stay in the cache)
CHUNK = 256


class Maps:
    """The maps of m designs in real units: ``H`` (m × levels) mm, ``V0`` mm³, ``dV``, ``F``,
    ``A`` (m × travels × levels), the travels' scale ``h`` (m) mm (δ = travel · h), the
    pressure of q = 1 ``unit`` (m) kPa, and the splines of the map's grid: ``qgrid`` over its
    levels q, ``dgrid`` over its travels δ/h (:class:`.spline.SplineGrid`; the surrogate file's
    own grid)."""

    def __init__(self, H, V0, dV, F, A, h, unit, qgrid: SplineGrid, dgrid: SplineGrid):
        self.H, self.V0, self.dV, self.F, self.A = H, V0, dV, F, A
        self.h, self.unit = np.asarray(h, float), np.asarray(unit, float)
        self.qgrid, self.dgrid = qgrid, dgrid

    def at(self, name, q):
        """A per-level field (``H`` or ``V0``) at the levels q (m × k)."""
        return self.level(name, self.qgrid.weights(np.asarray(q, float), slope=False)[0])

    def level(self, name, Wq, rows=slice(None)):
        """A per-level field at the levels whose spline weights are ``Wq`` (m × k × levels),
        of the designs ``rows`` (all)."""
        return np.matmul(Wq, getattr(self, name)[rows, :, None])[..., 0]

    def grid(self, name, Wd, Wq, rows=slice(None)):
        """A map field at travels and levels of spline weights ``Wd`` (m × k × travels) and
        ``Wq`` (m × k × levels), of the designs ``rows`` (all)."""
        return (Wd * self.at_levels(name, Wq, rows)).sum(-1)

    def at_levels(self, name, Wq, rows=slice(None)):
        """A map field at the levels of spline weights ``Wq`` (m × k × levels), still over the
        travels (m × k × travels): :meth:`grid` before its travels' weights."""
        return np.matmul(Wq, np.swapaxes(getattr(self, name)[rows], 1, 2))


def solve_curves(maps: Maps, y, p_i, reservoir, n_poly, *, iterations: int = 30,
                 tol: float = 1e-10, chunk: int = CHUNK) -> dict:
    """The curves of the m designs at travels ``y`` (m × k, mm from first contact at the setup
    pressure), setup pressures ``p_i`` (m, kPa gauge; 0: vented), reservoirs (m, mm³) and
    polytropic indices (m): ``pressure_kPa``, ``force_N``, ``contact_area_mm2``,
    ``volume_change_mm3``, the map coordinates ``delta_mm`` and ``q`` each point used, and
    ``converged`` (m × k), whether the gas law's residual fell below ``tol`` (relative); the
    inflated chamber's outer ``top_mm`` and cavity ``inflated_volume_mm3`` (m). Solved
    ``chunk`` designs at a time."""
    y = np.atleast_2d(np.asarray(y, float))
    m = y.shape[0]
    p_i, Vr, n = (np.broadcast_to(np.asarray(v, float), (m,)) for v in (p_i, reservoir, n_poly))
    parts = [_solve(maps, slice(a, a + chunk), y[a:a + chunk], p_i[a:a + chunk],
                    Vr[a:a + chunk], n[a:a + chunk], iterations, tol)
             for a in range(0, m, chunk)]
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def _solve(maps, sel, y, p_i, Vr, n, iterations, tol) -> dict:
    rows = np.arange(maps.h.size)[sel]
    _Q, _D = maps.qgrid, maps.dgrid
    unit, h = maps.unit[rows, None], maps.h[rows, None]
    n2, Vr2 = n[:, None], Vr[:, None]
    qi = (p_i / maps.unit[rows])[:, None] * np.ones_like(y)
    Wi, _ = _Q.weights(qi[:, :1], slope=False)
    H_i, V0_i = maps.level("H", Wi, rows), maps.level("V0", Wi, rows)
    C = (p_i[:, None] + P_AMB_KPA) * np.maximum(V0_i + Vr2, 1e-9) ** n2
    q = qi.copy()
    lo, hi = qi.copy(), np.full_like(y, _Q.x[-1] * 4.0)
    done = np.zeros(y.shape, bool)
    done[p_i <= 0] = True  # the vented chamber stays at P = 0
    for _ in range(iterations):
        # only the designs with a point still to converge (one slow point must not keep
        # thousands of converged ones iterating)
        a = np.flatnonzero(~done.all(axis=1))
        if a.size == 0:
            break
        qa, ya = q[a], y[a]
        Wq, Dq = _Q.weights(qa)
        H, dH = maps.level("H", Wq, rows[a]), maps.level("H", Dq, rows[a])
        V0, dV0 = maps.level("V0", Wq, rows[a]), maps.level("V0", Dq, rows[a])
        Wd, Dd = _D.weights((ya + H - H_i[a]) / h[a])
        fq = maps.at_levels("dV", Wq, rows[a])  # shared by the value and its travel slope
        dV, dV_dd = (Wd * fq).sum(-1), (Dd * fq).sum(-1) / h[a]
        dV_dq = maps.grid("dV", Wd, Dq, rows[a])
        # a Newton step far out may read the map's cubic continued into negative volumes
        gas = np.maximum(V0 - dV + Vr2[a], 1e-9)
        P = qa * unit[a] + P_AMB_KPA
        G = P * gas ** n2[a] - C[a]
        dG = unit[a] * gas ** n2[a] + P * n2[a] * gas ** (n2[a] - 1) * (
            dV0 - dV_dd * dH - dV_dq)
        da = done[a] | (np.abs(G) <= tol * C[a])
        la = np.where(G < 0, qa, lo[a])
        ha = np.where(G > 0, qa, hi[a])
        step = np.where(dG > 0, qa - G / np.where(dG > 0, dG, 1.0), np.nan)
        inside = (step > la) & (step < ha)
        q[a] = np.where(da, qa, np.where(inside, step, 0.5 * (la + ha)))
        done[a], lo[a], hi[a] = da, la, ha
    Wq, _ = _Q.weights(q, slope=False)
    H, V0 = maps.level("H", Wq, rows), maps.level("V0", Wq, rows)
    delta = y + H - H_i
    Wd, _ = _D.weights(delta / h, slope=False)
    dV, F, A = (maps.grid(k, Wd, Wq, rows) for k in ("dV", "F", "A"))
    return {"pressure_kPa": q * unit, "force_N": F, "contact_area_mm2": A,
            "volume_change_mm3": V0_i - V0 + dV, "delta_mm": delta, "q": q,
            "converged": done, "top_mm": H_i[:, 0], "inflated_volume_mm3": V0_i[:, 0]}
