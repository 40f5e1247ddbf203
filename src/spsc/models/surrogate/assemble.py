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
    own grid).

    Held stacked, as the solve reads them: ``levels`` (m × levels × 2: H, V0) and ``fields``
    (m × levels × 3 × travels: ΔV, F, A, in :data:`FIELDS`' order); ``H`` … ``A`` are views
    of them."""

    FIELDS = ("dV", "F", "A")

    def __init__(self, levels, fields, h, unit, qgrid: SplineGrid, dgrid: SplineGrid):
        self.levels, self.fields = levels, fields
        self.h, self.unit = np.asarray(h, float), np.asarray(unit, float)
        self.qgrid, self.dgrid = qgrid, dgrid

    H = property(lambda self: self.levels[..., 0])
    V0 = property(lambda self: self.levels[..., 1])
    dV = property(lambda self: np.swapaxes(self.fields[:, :, 0], 1, 2))
    F = property(lambda self: np.swapaxes(self.fields[:, :, 1], 1, 2))
    A = property(lambda self: np.swapaxes(self.fields[:, :, 2], 1, 2))

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
        return np.matmul(Wq, self.fields[rows, :, self.FIELDS.index(name)])


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
    _Q, _D = maps.qgrid, maps.dgrid
    levels, fields = maps.levels[sel], maps.fields[sel]
    unit, h = maps.unit[sel, None], maps.h[sel, None]
    m, nt = y.shape[0], maps.dgrid.x.size
    qi = (p_i / maps.unit[sel])[:, None] * np.ones_like(y)
    Wi, _ = _Q.weights(qi[:, :1], slope=False)
    H_i, V0_i = np.matmul(Wi, levels)[:, 0].T[:, :, None]  # each m × 1
    C = (p_i[:, None] + P_AMB_KPA) * np.maximum(V0_i + Vr[:, None], 1e-9) ** n[:, None]
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
        if a.size == m:
            a = slice(None)  # every design: views, not copies
        qa, ya, k = q[a], y[a], y.shape[1]
        Wq, Dq = _Q.weights(qa)
        WD = np.concatenate([Wq, Dq], axis=1)  # value and q-slope weights, one product each
        r = np.matmul(WD, levels[a])
        H, V0, dH, dV0 = r[:, :k, 0], r[:, :k, 1], r[:, k:, 0], r[:, k:, 1]
        ha_ = h[a]
        Wd, Dd = _D.weights((ya + H - H_i[a]) / ha_)
        fq = np.matmul(WD, fields[a][:, :, 0])  # ΔV over the travels at q, and its q-slope
        f0, f1 = fq[:, :k], fq[:, k:]
        dV, dV_dd, dV_dq = (Wd * f0).sum(-1), (Dd * f0).sum(-1) / ha_, (Wd * f1).sum(-1)
        # a Newton step far out may read the map's cubic continued into negative volumes
        na, Ca = n[a, None], C[a]
        gas = np.maximum(V0 - dV + Vr[a, None], 1e-9)
        gn = gas ** na
        P = qa * unit[a] + P_AMB_KPA
        G = P * gn - Ca
        dG = unit[a] * gn + P * na * (gn / gas) * (dV0 - dV_dd * dH - dV_dq)
        da = done[a] | (np.abs(G) <= tol * Ca)
        la = np.where(G < 0, qa, lo[a])
        ha = np.where(G > 0, qa, hi[a])
        step = np.where(dG > 0, qa - G / np.where(dG > 0, dG, 1.0), np.nan)
        inside = (step > la) & (step < ha)
        q[a] = np.where(da, qa, np.where(inside, step, 0.5 * (la + ha)))
        done[a], lo[a], hi[a] = da, la, ha
    Wq, _ = _Q.weights(q, slope=False)
    H, V0 = np.moveaxis(np.matmul(Wq, levels), 2, 0)
    delta = y + H - H_i
    Wd, _ = _D.weights(delta / h, slope=False)
    k = y.shape[1]
    dV, F, A = np.moveaxis((np.matmul(Wq, fields.reshape(m, -1, 3 * nt)).reshape(m, k, 3, nt)
                            * Wd[:, :, None, :]).sum(-1), 2, 0)
    return {"pressure_kPa": q * unit, "force_N": F, "contact_area_mm2": A,
            "volume_change_mm3": V0_i - V0 + dV, "delta_mm": delta, "q": q,
            "converged": done, "top_mm": H_i[:, 0], "inflated_volume_mm3": V0_i[:, 0]}
