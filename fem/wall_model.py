"""The wall model's discretisation: its settings and its parts — the axisymmetric dome (l = 0),
or the stadium's half-domes with θ-harmonics and the straight middle in plane strain — with the
shared cavity volume, follower pressure and contact surface (:mod:`spsc.fem.wall` solves it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from spsc.cad.geometry import SPSCGeometry
from spsc.core.errors import require
from spsc.membrane.materials import Material

from .material import NearlyIncompressible
from .section import DOME, MIDDLE, section_mesh
from .section_solid import (_THETA, _THETA_W, half_domes, meridian_modes,
                            section_solid, theta_rule)

__all__ = ["WallSettings", "WallModel"]


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

