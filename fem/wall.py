"""The ``wall`` model: the chamber wall as a thick, nearly incompressible hyperelastic solid,
coupled in one Newton solve to the cavity pressure, the trapped gas and a rigid plate.

The chamber is the axisymmetric **dome** (the body of revolution of the wall section: the two
half-domes of the stadium together) plus, when l > 0, the straight **middle** of length l in
plane strain (:mod:`spsc.fem.section`). Both sections share one cavity pressure and one plate:

* cavity volume V = V_dome(u₁) + V_middle(u₂) (the middle: l × cross-section area, eq. 37's
  2l∫ρ dη term), follower pressure p ∂V/∂u with its consistent stiffness p ∂²V/∂u²;
* after inflation the valve closes: p = p(V) of :class:`~spsc.core.gaslaw.GasLaw`
  (P (V + V_r)ⁿ = const, eqs. 2, 6–7), adding the rank-one stiffness −(dp/dV) g gᵀ, solved by
  Sherman–Morrison;
* the plate is a frictionless rigid plane z = z_p lowered from first contact: exact
  enforcement on the outer-surface nodes by a primal–dual active set (an active node's height is
  prescribed at the plate and released when its reaction pulls), so the answer does not depend
  on a penalty factor and contact can open and close anywhere along the outer surface (the
  vented flat-topped chambers invert: the apex lifts off and the contact becomes a ring);
* plate force F = Σ reactions of the active nodes (the section measures make them whole-ring
  and whole-length forces, N), pressure and wall together; contact area as the 3D model
  measures it (outer surface on the plate).

``pressure_kPa = 0`` is the vented chamber: gauge pressure held at zero, no gas; its force is
the structural F_el(y) of the paper's open-chamber bench test (Fig. 5b).

Stability: every recorded point's tangent (with the active constraints and the gas) is
factorised with its inertia; a negative eigenvalue is an unstable equilibrium (limit point,
snap-through or buckling of the wall). It is reported, and the solve stops there: no point past
it is reported as converged (DESIGN.md).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from spsc.cad.geometry import SPSCGeometry
from spsc.core.constants import KPA_PER_MPA
from spsc.core.curve import Curve, SolveInfo
from spsc.core.errors import require
from spsc.core.gaslaw import GasLaw
from spsc.membrane.materials import Material

from .linsolve import solve_rank_one
from .material import NearlyIncompressible
from .section import DOME, MIDDLE, section_mesh
from .section_solid import (_THETA, _THETA_W, InvertedSection, half_domes, meridian_modes,
                            section_solid, theta_rule)

__all__ = ["WallSettings", "WallModel", "WallState", "wall_curve", "inflate", "WallFailure"]


@dataclass(frozen=True)
class WallSettings:
    """Discretisation and solver controls of the wall model.

    mesh_size_mm : element length along the profile (mm); layers : quadratic elements through
    the wall; bulk_ratio : κ/μ0; rtol : residual against the load's force scale;
    max_iterations : Newton iterations per increment; min_fraction : smallest increment as a
    fraction of the nominal one; contact_tolerance : penetration that activates a node (mm);
    inflate_increments : pressure increments of the inflation; harmonics : K, the stadium
    half-domes' θ-harmonics cos 2mθ, m ≤ K (K + 1 meridians; l > 0 only; measured against the
    3D FEM of Table 1 Type A at 40 kPa, y = 1 mm: K = 1 +31 %, 2 +19 %, 3 +16 %, 5 +14 % in F).
    """

    mesh_size_mm: float = 0.5
    layers: int = 2
    bulk_ratio: float = 2000.0
    rtol: float = 1e-9
    max_iterations: int = 25
    min_fraction: float = 1.0 / 64
    contact_tolerance: float = 1e-7
    inflate_increments: int = 2
    harmonics: int = 3

    def __post_init__(self):
        require("mesh_size", self.mesh_size_mm, gt=0, le=5, unit="mm")
        require("layers", self.layers, ge=1, le=16)
        require("bulk_ratio", self.bulk_ratio, ge=10)
        require("rtol", self.rtol, gt=0, lt=1)
        require("max_iterations", self.max_iterations, ge=2)
        require("min_fraction", self.min_fraction, gt=0, le=1)
        require("inflate_increments", self.inflate_increments, ge=1)
        require("harmonics", self.harmonics, ge=1, le=8)


class WallFailure(RuntimeError):
    """Newton did not converge for one increment (the reason is the message)."""


@dataclass(frozen=True, eq=False)
class WallState:
    """A converged state: unknowns, gauge pressure (MPa), cavity volume (mm³), plate height
    (mm or None), plate force (N), contact area (mm²), active contact unknowns, iterations,
    negative eigenvalues of the constrained tangent (None: not computed)."""

    x: np.ndarray = field(repr=False)
    pressure: float
    volume: float
    plate: float | None
    force: float
    area: float
    active: np.ndarray = field(repr=False)
    iterations: int = 0
    negative: int | None = None


class _Dome:
    """The axisymmetric dome of an l = 0 chamber: the body of revolution of the section."""

    def __init__(self, section, law):
        self.section, self.solid = section, section_solid(section, law)
        self.dofs = np.arange(section.n_dofs)
        self.fixed = section.fixed
        self.reference = section.nodes.ravel()
        self.zdofs = 2 * section.outer + 1

    def volume(self, u) -> float:
        return self.section.volume(u)

    def volume_gradient(self, u, hessian=True):
        if not hessian:
            return self.section.volume_gradient(u, hessian=False)
        g, H = self.section.volume_gradient(u)
        return g, H, self.section.cavity_edge_dofs

    def contact_area(self, u, plate) -> float:
        return self.section.contact_area(u, plate)

    def apex(self, u) -> float:
        return float(self.section.positions(u)[self.section.cavity[0], 1])


class _StadiumDome(_Dome):
    """The two half-domes of a stadium (:func:`~spsc.fem.section_solid.half_domes`): local
    unknowns [u_0 (tip), …, u_K (junction), v_1, …, v_K]; u_K is the junction meridian, shared
    with the straight middle; every meridian's pole height is the tip's (one pole). The cavity
    volume is ∫dθ ½∮ r² dz over the meridians: the hoop displacements are tangent to the
    surface and change it only at second order, which is neglected."""

    def __init__(self, section, law, junction, K=1, n_theta=None):
        nd, nn = section.n_dofs, len(section.nodes)
        self.section, self.K = section, K
        self.thetas, self.weights = theta_rule(n_theta or 2 * K + 2)
        if K == 1 and n_theta is None:
            self.thetas, self.weights = _THETA, _THETA_W
        pole = 2 * np.nonzero(np.abs(section.nodes[:, 0]) < 1e-12)[0] + 1
        merid = []
        for k in range(K):
            d = k * nd + np.arange(nd)
            d[pole] = pole  # one pole: every meridian's pole height is the tip's
            merid.append(d)
        self.dofs = np.concatenate(merid + [junction, (K + 1) * nd + np.arange(K * nn)])
        local = section.element_dofs
        self.solid = half_domes(section, law, [local + k * nd for k in range(K + 1)],
                                [(K + 1) * nd + m * nn + section.elements for m in range(K)],
                                (K + 1) * nd + K * nn, len(self.thetas))
        hoop_fixed = section.fixed[1::2] | (np.abs(section.nodes[:, 0]) < 1e-12)
        self.fixed = np.concatenate([section.fixed] * (K + 1) + [hoop_fixed] * K)
        self.reference = np.concatenate([section.nodes.ravel()] * (K + 1)
                                        + [np.zeros(K * nn)])
        self.zdofs = np.concatenate([k * nd + 2 * section.outer + 1 for k in range(K + 1)])

    def _meridians(self, u):
        nd = self.section.n_dofs
        return u[:(self.K + 1) * nd].reshape(self.K + 1, nd)

    def _at(self, u, theta):
        L, _ = meridian_modes(theta, self.K)
        return L @ self._meridians(u)

    def volume(self, u) -> float:
        return float(sum(w * self.section.volume(self._at(u, th))
                         for th, w in zip(self.thetas, self.weights)))

    def volume_gradient(self, u, hessian=True):
        nd, K = self.section.n_dofs, self.K
        g = np.zeros(u.size)
        d = self.section.cavity_edge_dofs
        H = np.zeros((len(d), 6 * (K + 1), 6 * (K + 1)))
        for th, w in zip(self.thetas, self.weights):
            coef, _ = meridian_modes(th, K)
            if hessian:
                gk, Hk = self.section.volume_gradient(self._at(u, th))
                H += w * np.einsum("a,b,eij->eaibj", coef, coef,
                                   Hk.reshape(len(d), 6, 6)).reshape(H.shape)
            else:
                gk = self.section.volume_gradient(self._at(u, th), hessian=False)
            g[:(K + 1) * nd] += w * np.outer(coef, gk).ravel()
        if not hessian:
            return g
        return g, H, np.concatenate([d + k * nd for k in range(K + 1)], axis=1)

    def contact_area(self, u, plate) -> float:
        thetas = 0.25 * np.pi * (np.arange(8) + 0.5) / 4.0  # midpoints of 8 sectors
        return float(np.mean([self.section.contact_area(self._at(u, th), plate)
                              for th in thetas]))

    def apex(self, u) -> float:
        return float(self.section.positions(u[:self.section.n_dofs])[self.section.cavity[0], 1])


class _Middle:
    """The straight middle of length l, plane strain on the junction meridian u_j (both
    x-halves, whole length: measure 2l)."""

    def __init__(self, section, law, junction):
        self.section, self.solid = section, section_solid(section, law)
        self.dofs = junction
        self.fixed = section.fixed
        self.reference = section.nodes.ravel()
        self.zdofs = 2 * section.outer + 1

    volume = _Dome.volume
    volume_gradient = _Dome.volume_gradient
    contact_area = _Dome.contact_area


class WallModel:
    """The parts of one chamber and their shared loads. l = 0: the axisymmetric dome. l > 0:
    the two half-domes (meridian varying from the tip to the junction) and the straight
    middle in plane strain on the junction meridian. ``base``: ``"clamped"`` (the chamber)
    or ``"sliding"`` (u_z = 0 only, for the exact thick-sphere check)."""

    def __init__(self, geometry: SPSCGeometry, material: Material,
                 settings: WallSettings | None = None, *, base: str = "clamped"):
        self.geometry, self.material = geometry, material
        self.settings = settings = settings or WallSettings()
        law = NearlyIncompressible(material, settings.bulk_ratio)
        mesh = dict(size=settings.mesh_size_mm, layers=settings.layers, base=base)
        axi = section_mesh(geometry, DOME, **mesh)
        nd = axi.n_dofs
        if geometry.l > 0:
            K = settings.harmonics
            junction = np.arange(nd) + K * nd
            pole = 2 * np.nonzero(np.abs(axi.nodes[:, 0]) < 1e-12)[0] + 1
            junction[pole] = pole  # one pole: the junction meridian's is the tip's
            self.parts_ = [_StadiumDome(axi, law, junction, K),
                           _Middle(section_mesh(geometry, MIDDLE, **mesh), law, junction)]
            self.n_u = (K + 1) * nd + K * len(axi.nodes)
        else:
            self.parts_ = [_Dome(axi, law)]
            self.n_u = nd
        self.solids = [pt.solid for pt in self.parts_]
        psizes = [s.n_pressure for s in self.solids]
        self.p_offsets = self.n_u + np.concatenate([[0], np.cumsum(psizes)])
        self.n = int(self.p_offsets[-1])
        used = np.zeros(self.n_u, bool)
        self.fixed = np.zeros(self.n_u, bool)
        self.reference = np.zeros(self.n_u)
        for pt in self.parts_:
            used[pt.dofs] = True
            self.fixed[pt.dofs[pt.fixed]] = True
            self.reference[pt.dofs] = pt.reference
        self.fixed |= ~used  # aliased slots carry no unknown
        zdofs = np.unique(np.concatenate([pt.dofs[pt.zdofs] for pt in self.parts_]))
        self.contact_dofs = zdofs[~self.fixed[zdofs]]
        self.mu = law.mu

    def parts(self, x):
        """The local unknowns of each part."""
        return [x[pt.dofs] for pt in self.parts_]

    def _gather(self, vectors) -> np.ndarray:
        out = np.zeros(self.n_u)
        for pt, v in zip(self.parts_, vectors):
            np.add.at(out, pt.dofs, v)
        return out

    def pressures(self, x):
        """Hydrostatic pressure coefficients (ne_s, 3) of each part (MPa)."""
        return [x[a:b].reshape(len(s.element_dofs), -1)
                for s, a, b in zip(self.solids, self.p_offsets[:-1], self.p_offsets[1:])]

    def zero_state(self) -> np.ndarray:
        return np.zeros(self.n)

    def volume(self, x) -> float:
        """Cavity volume (mm³)."""
        return sum(pt.volume(u) for pt, u in zip(self.parts_, self.parts(x)))

    def contact_area(self, x, plate: float) -> float:
        """Outer surface on the plate (mm²)."""
        return sum(pt.contact_area(u, plate) for pt, u in zip(self.parts_, self.parts(x)))

    def apex(self, x) -> float:
        """Height of the cavity apex (mm)."""
        return self.parts_[0].apex(x[self.parts_[0].dofs])

    def top(self, x) -> float:
        """Highest point of the outer surface (mm): where the plate first touches."""
        return float(np.max(self.reference[self.contact_dofs] + x[self.contact_dofs]))

    def evaluate(self, x, pressure: float, *, tangent: bool = True) -> "_Evaluation":
        """Residuals at gauge cavity ``pressure`` (MPa): r_u = r_int − p g (N), the pressure
        residuals, and with ``tangent`` the condensed K_int − p H (N/mm) and the blocks G;
        g = ∂V/∂u (mm²)."""
        rs, rps, Gs, gs = [], [], [], []
        rows, cols, vals = [], [], []
        for pt, u, pc in zip(self.parts_, self.parts(x), self.pressures(x)):
            if tangent:
                r, rp, K, G = pt.solid.residual_tangent(u, pc)
                g, H, d = pt.volume_gradient(u)
                K = K.tocoo()
                rows += [pt.dofs[K.row]]
                cols += [pt.dofs[K.col]]
                vals += [K.data]
                if pressure != 0.0:
                    nd = d.shape[1]
                    rows += [pt.dofs[np.repeat(d, nd, axis=1).ravel()]]
                    cols += [pt.dofs[np.tile(d, (1, nd)).ravel()]]
                    vals += [-pressure * H.ravel()]
                Gs.append(G)
            else:
                r, rp = pt.solid.residual(u, pc)
                g = pt.volume_gradient(u, hessian=False)
            rs.append(r - pressure * g)
            rps.append(rp)
            gs.append(g)
        K = None
        if tangent:
            K = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                      np.concatenate(cols))),
                              shape=(self.n_u, self.n_u))
        return _Evaluation(self._gather(rs), rps, K, Gs, self._gather(gs))

    def pressure_error(self, ev: "_Evaluation") -> float:
        return max(s.pressure_error(rp) for s, rp in zip(self.solids, ev.rp))

    def condensed(self, ev: "_Evaluation") -> np.ndarray:
        """r_u + κ Gᵀ M⁻¹ r_p: the right-hand side of the condensed Newton system (N)."""
        return ev.r + self._gather([s.condensed_rhs(G, rp)
                                    for s, G, rp in zip(self.solids, ev.G, ev.rp)])

    def recover(self, ev: "_Evaluation", du) -> np.ndarray:
        """Δp of every section (flattened, MPa) from the displacement step ``du``."""
        return np.concatenate([s.recover(G, rp, d).ravel() for s, G, rp, d in
                               zip(self.solids, ev.G, ev.rp, self.parts(du))])


@dataclass(frozen=True, eq=False)
class _Evaluation:
    r: np.ndarray
    rp: list
    K: object
    G: list
    g: np.ndarray


def _factor(A):
    """LDLᵀ-like LU without off-diagonal pivoting (symmetric mode): its U diagonal carries the
    inertia (Sylvester). Falls back to pivoted LU (inertia unknown) if a pivot vanishes."""
    A = A.tocsc()
    try:
        lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
        d = lu.U.diagonal()
        if np.all(np.isfinite(d)) and np.min(np.abs(d)) > 1e-13 * np.max(np.abs(d)):
            return lu.solve, int(np.sum(d < 0))
    except RuntimeError:
        pass
    return spla.splu(A).solve, None


def _inertia(Kff, c, gf) -> int | None:
    """Negative eigenvalues of Kff + c g gᵀ (None if the factorisation cannot tell)."""
    solve, negative = _factor(Kff)
    if negative is not None and c > 0.0:
        negative -= int(1.0 + c * float(gf @ solve(gf)) < 0.0)
    return negative


def _newton(model: WallModel, x0, *, pressure=0.0, gas: GasLaw | None = None, plate=None,
            active=None, settings: WallSettings):
    """Solve one load (prescribed gauge ``pressure`` MPa, or the closed ``gas``; plate height
    ``plate`` mm or None) from ``x0``. Returns a :class:`WallState`."""
    x = x0.copy()
    n_u = model.n_u
    active = np.zeros(0, int) if active is None or plate is None else np.asarray(active, int)
    if plate is not None:  # start from every node the plate has passed
        z = model.reference[model.contact_dofs] + x[model.contact_dofs]
        active = np.union1d(active, model.contact_dofs[z > plate + settings.contact_tolerance])
    scale, changes, negative, factored, res, lam = None, 0, None, None, np.inf, None
    for it in range(1, settings.max_iterations + 1):
        V = model.volume(x)
        p = float(gas.pressure(V)) if gas is not None else float(pressure)
        c = -float(gas.dpressure(V)) if gas is not None else 0.0
        ev = model.evaluate(x, p)
        r = ev.r
        if not np.all(np.isfinite(r)):
            raise WallFailure("non-finite residual")
        jump = (plate - model.reference[active] - x[active]) if plate is not None \
            else np.zeros(0)
        free = ~model.fixed
        free[active] = False
        res = float(np.linalg.norm(r[free]))
        # the load's force scale: pressure load, support and plate reactions (displacement
        # control of a vented chamber has no other)
        scale = max(scale or 0.0, np.linalg.norm(p * ev.g), np.linalg.norm(r[model.fixed]),
                    np.linalg.norm(r[active]), 1e-9 * model.mu * model.geometry.t0 ** 2)
        settled = jump.size == 0 or float(np.max(np.abs(jump))) <= 1e-12
        small = settled and it > 1 and model.pressure_error(ev) <= 1e-3 * settings.rtol
        # semi-smooth Newton on the contact: the active set is updated after every linear
        # step from its linearised reactions (the multipliers of that step) and the gaps;
        # if it keeps changing, only at near-equilibrium from the true reactions (plain PDAS)
        changed = False
        if plate is not None and settled and it > 1 and (lam is not None
                                                          or res <= 1e-2 * scale):
            reaction = lam if lam is not None else -r[active]
            new = _update_active(model, x, reaction, plate, active, settings.rtol * scale,
                                 settings.contact_tolerance)
            if new is not None:
                changes += 1
                if changes > 40:
                    raise WallFailure("the contact active set does not settle")
                active, changed = new, True
                jump = plate - model.reference[active] - x[active]
                free = ~model.fixed
                free[active] = False
                res = float(np.linalg.norm(r[free]))
        lam = None
        if not changed and small and res <= settings.rtol * scale:
            if factored != free.tobytes():  # the inertia must be that of this free set
                negative = _inertia(ev.K[free][:, free], c, ev.g[free])
            force = float(-np.sum(r[active])) if plate is not None else 0.0
            area = model.contact_area(x, plate) if plate is not None and active.size else 0.0
            return WallState(x, p, V, plate, force, area, active, it, negative)
        K = ev.K
        solve, negative = _factor(K[free][:, free])
        factored = free.tobytes()
        rc = model.condensed(ev)
        rhs = -rc[free]
        g = ev.g
        if jump.size:
            dj = np.zeros(n_u)
            dj[active] = jump
            rhs -= (K @ dj)[free]
            if c > 0.0:
                rhs -= c * g[free] * (g[active] @ jump)
        if c > 0.0:
            du_f = solve_rank_one(solve, c, g[free], rhs)
            if negative is not None:
                # K + c g gᵀ loses one negative eigenvalue iff 1 + c gᵀK⁻¹g < 0
                negative -= int(1.0 + c * float(g[free] @ solve(g[free])) < 0.0)
        else:
            du_f = solve(rhs)
        du = np.zeros(n_u)
        du[free] = du_f
        if jump.size:
            du[active] = jump
        if active.size and changes < 10:
            r_lin = rc + K @ du + (c * g * (g @ du) if c > 0.0 else 0.0)
            lam = -r_lin[active]
        step = np.concatenate([du, model.recover(ev, du)])
        x = _admissible(model, x, step)
    raise WallFailure(f"no convergence in {settings.max_iterations} iterations (residual "
                      f"{res:.3g} N against {settings.rtol * scale:.3g} N)")


def _update_active(model, x, reaction, plate, active, force_tol, gap_tol):
    """The new active set (contact z-unknowns) or None if unchanged (the PDAS fixed point):
    active nodes whose ``reaction`` (N, pushing > 0) does not pull, and the nodes above the
    plate."""
    keep = reaction >= -force_tol
    inactive = np.setdiff1d(model.contact_dofs, active)
    z = model.reference[inactive] + x[inactive]
    new = inactive[z > plate + gap_tol]
    if new.size == 0 and np.all(keep):
        return None
    return np.union1d(active[keep], new)


def _admissible(model, x, step, trials=8):
    """x + α step with the largest α = 1, ½, … that inverts no element (full Newton steps
    otherwise: the mixed form's residual is no merit function to descend on)."""
    alpha = 1.0
    for _ in range(trials):
        xt = x + alpha * step
        F_ok = all(np.all(np.linalg.det(s.deformation(u)) > 0)
                   for s, u in zip(model.solids, model.parts(xt)))
        if F_ok:
            return xt
        alpha *= 0.5
    raise WallFailure("every trial step inverts an element")


@dataclass
class _Path:
    """The load path walked so far (converged states) and what stopped it."""

    states: list = field(default_factory=list)
    message: str = "converged"
    instability: str = ""
    iterations: int = 0
    converged: bool = True


def _ramp(model, path, x, settings, load_at, targets, label, progress=None):
    """Walk a load parameter t through ``targets`` with step halving; ``load_at(t)`` gives the
    keyword load. Appends one state per target; returns the last x or None on failure."""
    state = path.states[-1] if path.states else None
    t, dt = 0.0, targets[0]
    nominal = targets[0]
    hist = []  # (t, x) for the secant predictor
    k = 0
    while k < len(targets):
        t_new = min(t + dt, targets[k])
        guess = x
        if len(hist) >= 2:
            (t0, x0), (t1, x1) = hist[-2], hist[-1]
            guess = x1 + (x1 - x0) * (t_new - t1) / (t1 - t0)
        try:
            try:
                st = _newton(model, guess, active=state.active if state else None,
                             settings=settings, **load_at(t_new))
            except (WallFailure, InvertedSection, RuntimeError, np.linalg.LinAlgError):
                if guess is x:
                    raise
                st = _newton(model, x, active=state.active if state else None,
                             settings=settings, **load_at(t_new))
        except (WallFailure, InvertedSection, RuntimeError, np.linalg.LinAlgError) as exc:
            dt *= 0.5
            if dt < settings.min_fraction * nominal:
                path.converged = False
                path.message = f"{label(t_new)}: {exc}"
                return None
            continue
        path.iterations += st.iterations
        x, t, state = st.x, t_new, st
        hist.append((t, x))
        dt = min(nominal, 2.0 * dt)
        if math.isclose(t, targets[k], rel_tol=1e-12, abs_tol=1e-15):
            path.states.append(st)
            k += 1
            if progress is not None:
                progress()
            if st.negative:
                path.instability = (f"the tangent has {st.negative} negative eigenvalue(s) at "
                                    f"{label(t)}: unstable equilibrium (limit point, buckling "
                                    "or snap-through of the wall)")
                path.converged = False
                path.message = f"stopped: {path.instability}"
                return None
    return x


def inflate(model: WallModel, pressure_kPa: float, increments: int = 4) -> WallState:
    """Inflate ``model`` to gauge ``pressure_kPa`` (kPa) in ``increments``; the last state.
    Raises :class:`WallFailure` with the reason if it does not converge."""
    path = _Path()
    p = pressure_kPa / KPA_PER_MPA
    x = _ramp(model, path, model.zero_state(), model.settings, lambda t: {"pressure": p * t},
              [(k + 1) / increments for k in range(increments)],
              lambda t: f"inflation at p = {pressure_kPa * t:.4g} kPa")
    if x is None:
        raise WallFailure(path.message)
    return path.states[-1]


def wall_curve(geometry: SPSCGeometry, material: Material, **kwargs) -> Curve:
    """Inflate to ``pressure_kPa`` (kPa gauge), close the valve (gas with ``reservoir_mm3``,
    polytropic index ``polytropic_n``), lower the plate from first contact by ``stroke_mm`` in
    ``points`` − 1 equal increments. ``pressure_kPa = 0``: vented chamber (F_el). Returns the
    :class:`Curve` (model ``wall``); points not reached hold NaN and the reason.

    Keyword arguments: ``pressure_kPa`` (40), ``reservoir_mm3`` (0), ``stroke_mm`` (6),
    ``points`` (25), ``polytropic_n`` (1), ``settings`` (:class:`WallSettings`), ``model`` (a
    :class:`WallModel` to reuse), ``progress`` (called once per converged point).
    """
    from threadpoolctl import threadpool_limits

    # small dense blocks: one BLAS thread (threads spin on them, 100x slower when loaded)
    with threadpool_limits(limits=1, user_api="blas"):
        return _wall_curve(geometry, material, **kwargs)


def _wall_curve(geometry: SPSCGeometry, material: Material, *, pressure_kPa: float = 40.0,
               reservoir_mm3: float = 0.0, stroke_mm: float = 6.0, points: int = 25,
               polytropic_n: float = 1.0, settings: WallSettings | None = None,
               model: WallModel | None = None, progress=None) -> Curve:
    t_start = time.perf_counter()
    require("pressure", pressure_kPa, ge=0, le=1000, unit="kPa gauge")
    require("reservoir", reservoir_mm3, ge=0, unit="mm³")
    require("stroke", stroke_mm, gt=0, unit="mm")
    points = int(require("points", points, ge=2, le=10001))
    settings = settings or (model.settings if model is not None else WallSettings())
    model = model or WallModel(geometry, material, settings)
    if stroke_mm >= geometry.h + geometry.t0:
        require("stroke", stroke_mm, lt=geometry.h + geometry.t0, unit="mm: less than the "
                "chamber's height h + t0, the plate would reach the base")
    p_i = pressure_kPa / KPA_PER_MPA
    path = _Path()
    x = model.zero_state()
    v_nominal = model.volume(x)
    tick = (lambda: progress()) if progress is not None else None
    if p_i > 0:
        n_inf = settings.inflate_increments
        x = _ramp(model, path, x, settings, lambda t: {"pressure": p_i * t},
                  [(k + 1) / n_inf for k in range(n_inf)],
                  lambda t: f"inflation at p = {pressure_kPa * t:.4g} kPa", tick)
    inflated = path.states[-1] if path.states else None
    gas = None
    if x is not None and p_i > 0:
        gas = GasLaw(p_i, inflated.volume, reservoir_mm3, polytropic_n)
    y = np.linspace(0.0, stroke_mm, points)
    if x is not None:
        z0 = model.top(x)
        n_press = len(path.states)
        load = (lambda t: {"gas": gas, "plate": z0 - t}) if gas is not None else \
            (lambda t: {"pressure": 0.0, "plate": z0 - t})
        _ramp(model, path, x, settings, load, list(y[1:]),
              lambda t: f"press at y = {t:.4g} mm", tick)
        pressed = path.states[n_press:]
    else:
        pressed = []
    return _to_curve(model, path, inflated, pressed, y, v_nominal, pressure_kPa,
                     reservoir_mm3, polytropic_n, time.perf_counter() - t_start)


def _to_curve(model, path, inflated, pressed, y, v_nominal, pressure_kPa, reservoir,
              n_poly, seconds) -> Curve:
    n = y.size
    F, P, A, dV = (np.full(n, np.nan) for _ in range(4))
    conv = np.zeros(n, bool)
    msg = [""] * n
    ok_start = inflated is not None or pressure_kPa == 0
    v_inf = inflated.volume if inflated is not None else v_nominal
    x_inf = inflated.x if inflated is not None else model.zero_state()
    if ok_start:
        F[0], P[0], A[0], dV[0], conv[0] = 0.0, pressure_kPa, 0.0, 0.0, True
    for k, st in enumerate(pressed, start=1):
        F[k], P[k], A[k] = st.force, st.pressure * KPA_PER_MPA, st.area
        dV[k], conv[k] = v_inf - st.volume, True
    for k in range(len(pressed) + 1 if ok_start else 0, n):
        msg[k] = path.message
    s = model.settings
    info = SolveInfo(converged=path.converged, message=path.message,
                     y_reached_mm=y[conv][-1] if conv.any() else float("nan"),
                     instability=path.instability, seconds=seconds,
                     iterations=path.iterations,
                     details={"unknowns": model.n, "displacement_unknowns": model.n_u,
                              "parts": [type(pt).__name__.strip("_").lower()
                                        for pt in model.parts_],
                              "elements": len(model.parts_[0].section.elements),
                              "mesh_size_mm": s.mesh_size_mm, "layers": s.layers,
                              "bulk_ratio": s.bulk_ratio})
    setup = {"p_i_kPa": pressure_kPa, "reservoir_mm3": reservoir, "polytropic_n": n_poly}
    return Curve(y, F, P, A, dV, model="wall", geometry=model.geometry.as_dict(),
                 material=model.material.name, setup=setup, nominal_volume_mm3=v_nominal,
                 inflated_volume_mm3=v_inf, inflated_height_mm=model.apex(x_inf),
                 converged=conv, message=tuple(msg), solver=info)
