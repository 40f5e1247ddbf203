"""An independent discretisation of the same membrane problem, for verification only (lives in
the test tree, not in the installed package).

Linear axisymmetric membrane finite elements on the nominal profile polyline, equilibrium found
by minimising the total potential Π = U − p V_rev with a projected Newton method (analytic
gradient, sparse finite-difference Hessian, backtracking line search); the plate is a bound
η_i ≤ H on the nodal heights (active set); the gauge pressure of the closed gas is found by an
outer root solve on the invariant P(V + V_r)ⁿ = const of :class:`spsc.core.GasLaw`. Nothing else
is shared with the box-scheme solver than the material's W(I1, I2) and the gas law: the nodes
come from the CAD polyline (:meth:`SPSCGeometry.profile_points`), stretches from element chords,
the stress from the chain rule of W (not eqs. 22–23), the volume from exact frustums, and the
plate force from the nodal reactions (not p·A). Slow (seconds per point): tests only.

Units: mm, N, MPa, mm³.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, sparse
from scipy.sparse import linalg as splinalg

from spsc.cad.geometry import SPSCGeometry
from spsc.core import GasLaw
from spsc.materials import Material

__all__ = ["AxisymmetricFE", "FEState"]

_GAUSS = (0.5 - 0.5 / math.sqrt(3.0), 0.5 + 0.5 / math.sqrt(3.0))


@dataclass
class FEState:
    """Nodal ρ, η (mm), gauge pressure p (MPa), volume (mm³), plate force (N), contact radius (mm)."""

    rho: np.ndarray
    eta: np.ndarray
    p: float
    volume: float
    force: float = 0.0
    contact_radius: float = 0.0


class AxisymmetricFE:
    """Membrane FE model of the revolved part with ``n`` linear elements."""

    def __init__(self, geometry: SPSCGeometry, material: Material, n: int = 400):
        self.g, self.mat, self.n = geometry, material, n
        pts, _ = geometry.profile_points(n + 1)
        self.X, self.Y = pts[:, 0].copy(), pts[:, 1].copy()
        self.X[0], self.X[-1], self.Y[-1] = 0.0, geometry.w, 0.0
        self.S = np.hypot(np.diff(self.X), np.diff(self.Y))  # reference element lengths
        self.xg = [(1 - a) * self.X[:-1] + a * self.X[1:] for a in _GAUSS]

    # unknowns: ρ_1..ρ_{n-1}, η_0..η_{n-1}; ρ_0 = 0, ρ_n = w, η_n = 0
    def unpack(self, z):
        rho = np.concatenate([[0.0], z[: self.n - 1], [self.g.w]])
        eta = np.concatenate([z[self.n - 1:], [0.0]])
        return rho, eta

    def pack(self, rho, eta):
        return np.concatenate([rho[1:-1], eta[:-1]])

    def _dW_dl(self, l1, l2):
        """W (MPa) and ∂W/∂λ1, ∂W/∂λ2 of the relaxed (tension-field) energy: the hyperelastic
        W where both directions are taut, uniaxial W where one is wrinkled, 0 where slack."""
        n1, n2 = 1 / np.sqrt(l1), 1 / np.sqrt(l2)  # natural widths under uniaxial tension
        wr1 = (l2 <= n1) & (l1 > 1)  # tension along 1 only
        wr2 = (l1 <= n2) & (l2 > 1) & ~wr1
        slack = (l1 <= n2) & (l2 <= n1) & ~wr1 & ~wr2
        a = np.where(wr1, l1, np.where(wr2, n2, np.where(slack, 1.0, l1)))
        b = np.where(wr1, n1, np.where(wr2, l2, np.where(slack, 1.0, l2)))
        W, d1, d2 = self._w_taut(a, b)
        d1 = np.where(wr2 | slack, 0.0, d1)
        d2 = np.where(wr1 | slack, 0.0, d2)
        return np.where(slack, 0.0, W), d1, d2

    def _w_taut(self, l1, l2):
        """W and ∂W/∂λ1, ∂W/∂λ2 (MPa) by the chain rule through I1, I2 (incompressible)."""
        I1 = l1**2 + l2**2 + 1 / (l1 * l2) ** 2
        I2 = 1 / l1**2 + 1 / l2**2 + (l1 * l2) ** 2
        W1, W2 = self.mat.dW(I1, I2)
        d1 = W1 * (2 * l1 - 2 / (l1**3 * l2**2)) + W2 * (-2 / l1**3 + 2 * l1 * l2**2)
        d2 = W1 * (2 * l2 - 2 / (l2**3 * l1**2)) + W2 * (-2 / l2**3 + 2 * l2 * l1**2)
        return self.mat.energy(I1, I2), d1, d2

    def volumes(self, rho, eta):
        """(V_rev, V_total) in mm³: exact frustums plus the extruded trapezoids."""
        de = eta[:-1] - eta[1:]
        vrev = math.pi / 3 * np.sum((rho[:-1] ** 2 + rho[:-1] * rho[1:] + rho[1:] ** 2) * de)
        area = np.sum((rho[:-1] + rho[1:]) * de)  # 2 × half cross-section
        return vrev, vrev + self.g.l * area

    def potential(self, z, p):
        """Π = U − p V_rev (N·mm) and its gradient."""
        rho, eta = self.unpack(z)
        dr, de = np.diff(rho), np.diff(eta)
        ell = np.hypot(dr, de)
        l1 = ell / self.S
        t0 = self.g.t0
        U = 0.0
        gr, ge = np.zeros_like(rho), np.zeros_like(eta)
        for a, xg in zip(_GAUSS, self.xg):
            rg = (1 - a) * rho[:-1] + a * rho[1:]
            if np.any(rg <= 0):
                return np.inf, np.zeros_like(z)
            l2 = rg / xg
            W, d1, d2 = self._dW_dl(l1, l2)
            wgt = math.pi * xg * t0 * self.S  # 2π x t0 S × Gauss weight ½
            U += np.sum(wgt * W)
            # ∂λ1/∂(ρ_i, ρ_{i+1}) = ∓dr/(ℓS); ∂λ2/∂ρ = (1−a, a)/x_g
            c1 = wgt * d1 / (ell * self.S)
            gr[:-1] -= c1 * dr
            gr[1:] += c1 * dr
            ge[:-1] -= c1 * de
            ge[1:] += c1 * de
            c2 = wgt * d2 / xg
            gr[:-1] += c2 * (1 - a)
            gr[1:] += c2 * a
        de_ = eta[:-1] - eta[1:]
        q = rho[:-1] ** 2 + rho[:-1] * rho[1:] + rho[1:] ** 2
        V = math.pi / 3 * np.sum(q * de_)
        gr[:-1] -= p * math.pi / 3 * (2 * rho[:-1] + rho[1:]) * de_
        gr[1:] -= p * math.pi / 3 * (rho[:-1] + 2 * rho[1:]) * de_
        ge[:-1] -= p * math.pi / 3 * q
        ge[1:] += p * math.pi / 3 * q
        return U - p * V, np.concatenate([gr[1:-1], ge[:-1]])

    def _hessian(self, z, p):
        """Sparse Hessian of Π by finite differences of the analytic gradient: a node couples
        to its neighbours only, so three colours per field suffice."""
        nu = z.size
        g0 = self.potential(z, p)[1]
        # unknown index of (field, node): ρ nodes 1..n−1 -> 0..n−2; η nodes 0..n−1 -> n−1..2n−2
        idx = np.full((2, self.n + 1), -1)
        idx[0, 1:-1] = np.arange(self.n - 1)
        idx[1, :-1] = np.arange(self.n - 1, nu)
        rows, cols, vals = [], [], []
        nodes = np.arange(self.n + 1)
        for f in (0, 1):
            for c in range(3):
                ks = nodes[(nodes % 3 == c) & (idx[f] >= 0)]
                if ks.size == 0:
                    continue
                zp = z.copy()
                eps = 1e-7 * (1.0 + np.abs(z[idx[f, ks]]))
                zp[idx[f, ks]] += eps
                dg = self.potential(zp, p)[1] - g0
                epsn = np.zeros(self.n + 1)
                epsn[ks] = eps
                for fr in (0, 1):
                    j = nodes[idx[fr] >= 0]
                    k = j + np.array([0, 1, -1])[(c - j) % 3]
                    ok = (k >= 0) & (k <= self.n) & (idx[f, np.clip(k, 0, self.n)] >= 0)
                    ok &= epsn[np.clip(k, 0, self.n)] > 0
                    j, k = j[ok], k[ok]
                    rows.append(idx[fr, j])
                    cols.append(idx[f, k])
                    vals.append(dg[idx[fr, j]] / epsn[k])
        Hm = sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                               shape=(nu, nu))
        return 0.5 * (Hm + Hm.T)

    def _minimise(self, z0, p, H=None, *, tol=1e-9, max_iter=60):
        """Projected Newton with an active set for η_i ≤ H and a backtracking line search."""
        z = np.array(z0, float)
        eta_part = np.arange(z.size) >= self.n - 1
        if H is not None:
            z[eta_part] = np.minimum(z[eta_part], H)
        f, g = self.potential(z, p)
        for _ in range(max_iter):
            active = np.zeros(z.size, bool)
            if H is not None:
                active = eta_part & (z >= H - 1e-12) & (g < 0)
            free = ~active
            if np.max(np.abs(g[free])) < tol:
                break
            Hm = self._hessian(z, p).tocsc()[free][:, free]
            # a slack core has no stiffness (its nodes are indeterminate): a tiny shift fixes them
            shift = 1e-9 * abs(Hm.diagonal()).max()
            for _ in range(8):
                try:
                    dz_f = splinalg.spsolve((Hm + shift * sparse.eye(Hm.shape[0])).tocsc(), -g[free])
                except RuntimeError:
                    dz_f = np.full(free.sum(), np.nan)
                if np.all(np.isfinite(dz_f)) and np.dot(dz_f, g[free]) < 0:
                    break
                shift = max(10 * shift, 1e-6 * abs(Hm.diagonal()).max())
            dz = np.zeros_like(z)
            dz[free] = dz_f
            t = 1.0
            while t > 1e-10:
                zt = z + t * dz
                if H is not None:
                    zt[eta_part] = np.minimum(zt[eta_part], H)
                ft, gt = self.potential(zt, p)
                if ft <= f + 1e-4 * t * np.dot(g, zt - z) or abs(ft - f) < 1e-14 * abs(f):
                    break
                t *= 0.5
            z, f, g = zt, ft, gt
        return z

    def inflate(self, p: float) -> FEState:
        """Equilibrium at gauge pressure p (MPa), from the nominal shape."""
        z = self.pack(self.X, self.Y)
        for frac in (0.25, 0.5, 1.0):
            z = self._minimise(z, frac * p)
        rho, eta = self.unpack(z)
        return FEState(rho, eta, p, self.volumes(rho, eta)[1])

    def press(self, start: FEState, H: float, *, reservoir: float = 0.0, n_poly: float = 1.0,
              p_i: float | None = None, v_i: float | None = None,
              max_iter: int = 60) -> FEState:
        """Plate at height H (mm) on the gas closed at (p_i, v_i) (MPa gauge, mm³); ``start``
        is the previous equilibrium (the inflated one, or the last plate position)."""
        p_i = start.p if p_i is None else p_i
        v_i = start.volume if v_i is None else v_i
        law = GasLaw(p_i, v_i, reservoir, n_poly)
        z0 = self.pack(start.rho, np.minimum(start.eta, H))
        cache = {}

        def gas(p):
            z = self._minimise(z0 if not cache else cache["z"], p, H, max_iter=max_iter)
            rho, eta = self.unpack(z)
            V = self.volumes(rho, eta)[1]
            cache.update(z=z, p=p)
            return law.invariant(p, V) / law.constant - 1.0

        lo, hi = start.p, start.p * 1.05 + 2e-3
        while gas(hi) < 0:
            lo, hi = hi, hi + 2 * (hi - lo)
        p = optimize.brentq(gas, lo, hi, xtol=1e-10, rtol=1e-10)
        z = self._minimise(cache["z"], p, H, max_iter=4 * max_iter)
        rho, eta = self.unpack(z)
        _, grad = self.potential(z, p)
        ge = grad[self.n - 1:]
        active = eta[:-1] >= H - 1e-7
        force = float(-np.sum(ge[active]))  # plate reaction: Σ −∂Π/∂η_i at the active nodes
        k = int(np.nonzero(active)[0].max()) if active.any() else 0
        return FEState(rho, eta, p, self.volumes(rho, eta)[1], force, float(rho[k]))
