"""The membrane boundary-value problem discretised by a box (midpoint) scheme and solved by Newton.

Formulation (derived from eqs. 19–20, 25, 27–28, 30; replaces the garbled eq. 31)
--------------------------------------------------------------------------------
Independent variable: the arc length s of the undeformed meridian (mm), apex s = 0 to clamped
edge s = L. Unknowns at each node: deformed radius ρ, height η (mm), tangent angle φ below the
horizontal (rad) and meridional stretch λ1 = dS/ds. With λ2 = ρ/x(s) (eq. 20), tensions
T1, T2 (eqs. 22–23) and gauge pressure p (MPa), the free membrane obeys

    ρ' = λ1 cos φ,          η' = −λ1 sin φ                  (eqs. 19, 26 in s)
    (ρ T1)' = λ1 T2 cos φ                                   (eq. 27 with p_t = 0)
    T1 φ' = λ1 (p − T2 sin φ / ρ)                            (eq. 28, k1 = φ'/λ1, k2 = sin φ/ρ)

In x these give back the paper's system with δ = ρ_x = λ1 cos φ (1 + g²)^½ (eq. 25); on a
uniformly inflated sphere ρ = λx, so δ' = 0 (checked in the tests). In the contact region
η = H (the plate), φ = 0 (η' = 0, eq. 32) and only the first and third equations remain
(eq. 33); frictionless contact leaves the tangential balance unchanged.

Boundary conditions: ρ(0) = 0, φ(0) = 0 (symmetry, λ1 = λ2 at the apex); ρ(L) = w (λ2 = 1) and
η(L) = 0 at the clamped edge. Contact adds η(0) = H; its boundary s_Γ is an unknown placed on a
node, so λ1, λ2, ρ, φ are continuous there (the paper's continuity conditions); the gauge
pressure is an unknown closed by the gas law (eq. 34) over bladder plus reservoir:
(p + P_amb)(V + V_r)^n = (p_i + P_amb)(V_i + V_r)^n, V by eq. 37.

Tension field: a membrane carries no compression. The free membrane uses the relaxed law
(:func:`.tension.relaxed_tensions`: it wrinkles where the taut law would compress, e.g. the
lower bulge of Type D at GS1 size). On the plate, flattening the cap compresses it once the
inflation prestrain is used up; the solve then switches to *slack mode*: a core [0, s_0] lies
wrinkled and stress-free on the plate, the contact segment starts at s_0 with ρ = x(s_0),
λ1 = 1 (T1 = T2 = 0 there), and s_0 is one more unknown.

Discretisation: contact segment [0, s_Γ] and free segment [s_Γ, L] each on a fixed grid in the
normalised coordinate τ ∈ [0, 1]; midpoint rule per interval (second order). Jacobian by
finite differences with a two-colour grouping (each interval couples two nodes), the volume row
analytic; sparse LU; damped Newton.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.sparse import csc_matrix
from scipy.sparse.linalg import splu

from spsc.materials import Material
from .meridian import Meridian
from .tension import relaxed_tensions, tensions

__all__ = ["BoxScheme", "NewtonResult"]

#: Ambient pressure in MPa.


@dataclass
class NewtonResult:
    """Outcome of one Newton solve: the unknown vector, whether it converged, why, iterations."""

    v: np.ndarray
    converged: bool
    message: str
    iterations: int
    residual: float
    jacobians: int = 0


class BoxScheme:
    """Discrete membrane equations on ``nc`` contact and ``nf`` free intervals.

    ``nc = 0`` is the inflation problem (unknowns: nodal ρ, η, φ, λ1 at gauge pressure p);
    ``nc > 0`` the contact problem with a plate at height H (unknowns: nodal values, s_Γ, p).
    Lengths mm, pressures MPa, volumes mm³.
    """

    def __init__(self, meridian: Meridian, material: Material, nc: int, nf: int, *,
                 edge: str = "clamped",
                 slack: bool = False, wrinkling: bool = True):
        self.mer, self.mat = meridian, material
        g = meridian.geometry
        self.w, self.l, self.t0, self.L = g.w, g.l, g.t0, meridian.length
        self.nc, self.nf = int(nc), int(nf)
        self.N = self.nc + self.nf
        self.contact = self.nc > 0
        self.slack = bool(slack) and self.contact
        self.edge = edge
        self.wrinkling = bool(wrinkling)
        self.tau_c = np.linspace(0.0, 1.0, self.nc + 1)
        self.tau_f = np.linspace(0.0, 1.0, self.nf + 1)
        self.scale_T = material.shear_modulus * self.t0  # N/mm
        self.n_globals = (3 if self.slack else 2) if self.contact else 0
        self.n_unknowns = 4 * (self.N + 1) + self.n_globals
        self._pattern()

    # -- grid ---------------------------------------------------------------------------------
    def nodes(self, s_gamma: float = 0.0, s_slack: float = 0.0) -> np.ndarray:
        """Node arc lengths (mm): contact segment [s_0, s_Γ] then free segment [s_Γ, L];
        s_0 = 0, or the edge of the slack core in slack mode."""
        if not self.contact:
            return self.L * self.tau_f
        return np.concatenate([s_slack + (s_gamma - s_slack) * self.tau_c,
                               s_gamma + (self.L - s_gamma) * self.tau_f[1:]])

    def split(self, v):
        """(Z, s_Γ, p, s_0): nodal values (N+1, 4) and the global unknowns (None if absent)."""
        Z = v[: 4 * (self.N + 1)].reshape(self.N + 1, 4)
        if self.slack:
            return Z, v[-2], v[-1], v[-3]
        if self.contact:
            return Z, v[-2], v[-1], 0.0
        return Z, None, None, 0.0

    # -- equations ------------------------------------------------------------------------------
    def intervals(self, Z, s, p):
        """Scaled interval residuals, shape (N, 4); NaN where the stretches are not positive."""
        rho, eta, phi, l1 = Z[:, 0], Z[:, 1], Z[:, 2], Z[:, 3]
        h = np.diff(s)
        x, xm = self._radii(s)
        rm, pm, l1m = 0.5 * (rho[:-1] + rho[1:]), 0.5 * (phi[:-1] + phi[1:]), 0.5 * (l1[:-1] + l1[1:])
        l2m = rm / xm
        l2n = np.empty_like(rho)
        l2n[1:] = rho[1:] / x[1:]
        l2n[0] = rho[0] / x[0] if x[0] > 0 else l1[0]  # λ1 = λ2 at the apex (symmetry)
        with np.errstate(all="ignore"):
            # free membrane: relaxed law (wrinkles instead of compression); on the plate the
            # taut law, whose compression signals the slack core (handled in slack mode)
            k = self.nc
            law = relaxed_tensions if self.wrinkling else tensions  # taut: compression carried
            T1m, T2m = law(self.mat, self.t0, l1m, l2m)
            T1n, _ = law(self.mat, self.t0, l1, l2n)
            if k:
                T1m[:k], T2m[:k] = tensions(self.mat, self.t0, l1m[:k], l2m[:k])
                T1n[:k] = tensions(self.mat, self.t0, l1[:k], l2n[:k])[0]
        rT = rho * T1n
        c, sn = np.cos(pm), np.sin(pm)
        R = np.empty((self.N, 4))
        R[:, 0] = (rho[1:] - rho[:-1]) / h - l1m * c
        R[:, 1] = (eta[1:] - eta[:-1]) / h + l1m * sn
        R[:, 2] = ((rT[1:] - rT[:-1]) / h - l1m * T2m * c) / self.scale_T
        with np.errstate(all="ignore"):
            R[:, 3] = (T1m * (phi[1:] - phi[:-1]) / h - l1m * (p - T2m * sn / rm)) / self.scale_T
        if self.contact:  # flat and on the plate: η' = 0, φ' = 0 (eq. 32)
            k = self.nc
            R[:k, 1] = (eta[1:k + 1] - eta[:k]) / h[:k]
            R[:k, 3] = phi[1:k + 1] - phi[:k]
        bad = (l1m <= 0) | (l2m <= 0) | (l1[1:] <= 0)
        if np.any(bad):
            R[bad] = np.nan
        return R

    def _radii(self, s):
        """x at the nodes and the interval midpoints (cached: Jacobian columns reuse the grid)."""
        key = (s[1], s[self.nc], s[-2])
        if getattr(self, "_rkey", None) != key:
            self._rkey = key
            self._rval = (self.mer.x(s), self.mer.x(0.5 * (s[:-1] + s[1:])))
        return self._rval

    def volume(self, Z) -> float:
        """Cavity volume V = π∫ρ² dη + 2l∫ρ dη (eq. 37), midpoint rule, mm³."""
        rm = 0.5 * (Z[:-1, 0] + Z[1:, 0])
        return float(np.sum((math.pi * rm * rm + 2.0 * self.l * rm) * (Z[:-1, 1] - Z[1:, 1])))

    def volume_gradient(self, Z):
        """∂V/∂ρ_i and ∂V/∂η_i (mm², mm²) of :meth:`volume`."""
        rm = 0.5 * (Z[:-1, 0] + Z[1:, 0])
        de = Z[:-1, 1] - Z[1:, 1]
        q = (math.pi * rm + self.l) * de  # ½ ∂(πρm² + 2lρm)/∂ρm · Δη
        dr = np.zeros(self.N + 1)
        dr[:-1] += q
        dr[1:] += q
        a = math.pi * rm * rm + 2.0 * self.l * rm
        de_ = np.zeros(self.N + 1)
        de_[:-1] += a
        de_[1:] -= a
        return dr, de_

    def residual(self, v, *, p=None, H=None, gas=None):
        """Full scaled residual. Inflation: gauge pressure ``p`` (MPa) given. Contact: plate
        height ``H`` (mm) and the closed ``gas`` (:class:`~spsc.core.gaslaw.GasLaw`) given."""
        Z, sg, pc, s0 = self.split(v)
        if self.contact:
            p = pc
            if not (0.0 <= s0 < sg < self.L):
                return np.full(self.n_unknowns, np.nan)
        s = self.nodes(sg, s0)
        R = [self.intervals(Z, s, p).ravel(), self._bc(Z, s0)]
        if self.contact:
            R.append(np.array([(Z[0, 1] - H) / self.w, self._gas(Z, p, gas)]))
        if self.slack:  # T1 = T2 = 0 at the edge of the slack core: λ1 = 1 there (λ2 = 1 above)
            R.append(np.array([Z[0, 3] - 1.0]))
        return np.concatenate(R)

    def _bc(self, Z, s0=0.0):
        # apex: ρ = 0 (slack mode: ρ = x at the core's edge, λ2 = 1), φ = 0
        r0 = (Z[0, 0] - (float(self.mer.x(s0)) if self.slack else 0.0)) / self.w
        if self.edge == "symmetric":  # equator of a closed shell: used by the sphere check
            return np.array([r0, Z[0, 2], Z[-1, 2] - math.pi / 2, Z[-1, 1] / self.w])
        return np.array([r0, Z[0, 2], (Z[-1, 0] - self.w) / self.w, Z[-1, 1] / self.w])

    def _gas(self, Z, p, gas):
        # (p − p_gas(V)) / P_i: the gas law scaled by the absolute closing pressure
        return (p - gas.pressure(self.volume(Z))) / (gas.p_closed + gas.p_amb)

    # -- Jacobian -----------------------------------------------------------------------------
    def _pattern(self):
        N = self.N
        j, e, a, k = np.meshgrid(np.arange(N), np.arange(4), np.arange(2), np.arange(4), indexing="ij")
        self._rows_int = (4 * j + e).ravel()
        self._cols_int = (4 * (j + a) + k).ravel()
        self._a_of_color = [(np.arange(N) + c) % 2 for c in (0, 1)]  # a_j = (c − j) mod 2

    def jacobian(self, v, R0, *, p=None, H=None, gas=None):
        N, nn = self.N, 4 * (self.N + 1)
        Z, sg, pc, s0 = self.split(v)
        pp = pc if self.contact else p
        s = self.nodes(sg, s0)
        R0i = R0[: 4 * N].reshape(N, 4)
        D = np.zeros((N, 4, 2, 4))
        jj = np.arange(N)
        for c in (0, 1):
            nodes = np.arange(c, N + 1, 2)
            a = self._a_of_color[c]
            for k in range(4):
                Zp = Z.copy()
                eps = 1e-7 * (1.0 + np.abs(Z[nodes, k]))
                Zp[nodes, k] += eps
                dR = (self.intervals(Zp, s, pp) - R0i)
                epsn = np.empty(N + 1)
                epsn[nodes] = eps
                D[jj, :, a, k] = dR / epsn[jj + a][:, None]
        rows, cols, vals = [self._rows_int], [self._cols_int], [D.ravel()]
        r0 = 4 * N
        sym = self.edge == "symmetric"
        rows.append(np.arange(r0, r0 + 4))
        cols.append(np.array([0, 2, nn - 2 if sym else nn - 4, nn - 3]))
        vals.append(np.array([1 / self.w, 1.0, 1.0 if sym else 1 / self.w, 1 / self.w]))
        if self.contact:
            rows.append(np.array([r0 + 4]))  # η(0) = H
            cols.append(np.array([1]))
            vals.append(np.array([1 / self.w]))
            # gas law: analytic row in the nodal unknowns
            dRdV = -gas.dpressure(self.volume(Z)) / (gas.p_closed + gas.p_amb)
            dr, de = self.volume_gradient(Z)
            idx = np.arange(N + 1)
            rows.append(np.full(2 * (N + 1), r0 + 5))
            cols.append(np.concatenate([4 * idx, 4 * idx + 1]))
            vals.append(np.concatenate([dRdV * dr, dRdV * de]))
            if self.slack:
                rows.append(np.array([r0 + 6]))
                cols.append(np.array([3]))
                vals.append(np.array([1.0]))
            # global unknowns (s_0, s_Γ, p): one finite-difference column each, full residual
            for col in range(nn, self.n_unknowns):
                dv = 1e-7 * (1.0 + abs(v[col])) if col < self.n_unknowns - 1 else 1e-9
                vp = v.copy()
                vp[col] += dv
                dR = (self.residual(vp, p=p, H=H, gas=gas) - R0) / dv
                nz = np.nonzero(dR)[0]
                rows.append(nz)
                cols.append(np.full(nz.size, col))
                vals.append(dR[nz])
        n = self.n_unknowns
        return csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(n, n))

    # -- Newton --------------------------------------------------------------------------------
    def newton(self, v0, *, tol: float = 1e-9, max_iter: int = 30, **kw) -> NewtonResult:
        """Damped Newton from ``v0``; ``kw`` as for :meth:`residual`.

        The factorised Jacobian is reused while each step cuts the residual at least fivefold
        (chord steps cost one residual); otherwise it is recomputed.
        """
        v = np.array(v0, float)
        R = self.residual(v, **kw)
        if not np.all(np.isfinite(R)):
            return NewtonResult(v, False, "initial guess outside the admissible set", 0, np.inf)
        norm = np.linalg.norm(R)
        lu, fresh, jac = None, False, 0
        for it in range(1, max_iter + 1):
            if lu is None:
                J = self.jacobian(v, R, **kw)
                jac += 1
                try:
                    lu = splu(J)
                except RuntimeError:
                    return NewtonResult(v, False, "singular Jacobian (instability or bifurcation)",
                                        it, float(np.max(np.abs(R))))
                fresh = True
            dv = lu.solve(-R)
            if not np.all(np.isfinite(dv)):
                return NewtonResult(v, False, "singular Jacobian (instability or bifurcation)",
                                    it, float(np.max(np.abs(R))))
            t, ok = 1.0, False
            for _ in range(12 if fresh else 1):
                vt = v + t * dv
                Rt = self.residual(vt, **kw)
                nt = np.linalg.norm(Rt) if np.all(np.isfinite(Rt)) else np.inf
                if nt < (1.0 - 1e-4 * t) * norm or nt < 1e-12:
                    ok = True
                    break
                t *= 0.5
            if not ok:
                if fresh:
                    return NewtonResult(v, False, "line search failed (no descent)", it,
                                        float(np.max(np.abs(R))))
                lu = None  # chord step failed: refresh the Jacobian
                continue
            if nt > 0.2 * norm:
                lu = None
            v, R, norm, fresh = vt, Rt, nt, False
            if np.max(np.abs(R)) < tol:
                return NewtonResult(v, True, "", it, float(np.max(np.abs(R))), jac)
        return NewtonResult(v, False, f"no convergence in {max_iter} Newton iterations", max_iter,
                            float(np.max(np.abs(R))), jac)
