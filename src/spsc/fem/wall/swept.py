"""The stadium chamber's wall (l > 0) as a swept solid: the wall section extruded along the
straight middle and revolved about each half-dome's axis, meshed with 27-node hexahedra
(the section's 9-node quadrilateral × a quadratic element along the sweep) on the quarter
x ≥ 0, y ≥ 0 — the 3D model's own sweep (:func:`spsc.fem.solid.mesh.spsc_wall`), with the exact
geometry of the sweep and Cartesian displacements.

Sweep coordinate s: the middle y ∈ [0, a] (a = l/2), then the half-dome θ ∈ [0, π/2] about the
axis x = 0, y = a (θ = 0: the junction plane with the middle, π/2: the tip meridian):

    middle:     X = (R, y, Z),                      dV = dA dy
    half-dome:  X = (R cos θ, a + R sin θ, Z),      dV = R dA dθ

with (R, Z) the section's coordinates (:mod:`spsc.fem.wall.section`). The displacement is Cartesian,
u = Σ N_a(R, Z) φ_k(s) u_ak, so the half-dome's axis (R = 0) is one node per section node, shared
by every θ-station: ∂u/∂θ vanishes there identically and the 1/R of the gradient

    ∂/∂x = cos θ ∂/∂R − (sin θ / R) ∂/∂θ,   ∂/∂y = sin θ ∂/∂R + (cos θ / R) ∂/∂θ

stays bounded (the quadrature points are off the axis). Unlike harmonics in θ, nothing ties the
half-dome to be symmetric about the junction plane or the middle to be uniform along y: the
middle bends along y and moves along it, and lifts the half-domes' crown, as the 3D model shows.

The solid is the package's mixed u–p :class:`~spsc.fem.wall.section_solid.MixedSolid` (pressure
discontinuous and linear in each hexahedron, (1, R, Z, s): the Q2/P1ᵈ hexahedron, inf–sup
stable). Integrals are taken over the whole chamber (the quarter × 4): residuals are forces
in N, as in the dome. The cavity volume is the surface integral V = ∮ z n_z dS over the cavity
wall (the base plane has z = 0 and the symmetry planes n_z = 0), exact for any displacement,
with its gradient and Hessian for the follower pressure.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spsc.cad.geometry import SPSCGeometry

from ..material import NearlyIncompressible
from .section import Section, _GAUSS_T, _GAUSS_W, _edge_shape
from .cartesian_solid import CartesianSolid
from .section_solid import _pressure_basis

__all__ = ["Sweep", "sweep_stations", "SweptWall"]

# quadratic Lagrange on ζ ∈ [−1, 1] (nodes −1, 0, 1) and a 3-point Gauss rule there
_ZG, _ZW = np.polynomial.legendre.leggauss(3)
_ZG4, _ZW4 = np.polynomial.legendre.leggauss(4)


def _phi(z):
    z = np.asarray(z, float)
    return (np.stack([0.5 * z * (z - 1.0), 1.0 - z * z, 0.5 * z * (z + 1.0)], -1),
            np.stack([z - 0.5, -2.0 * z, z + 0.5], -1))


@dataclass(frozen=True)
class Sweep:
    """The stations of the sweep: ``kinds`` (per element, "y" or "theta"), the element ends
    ``ends`` (per element, (s0, s1) in mm for y and rad for θ) and a = l/2 (mm)."""

    a: float
    kinds: tuple
    ends: tuple

    @property
    def n_elements(self) -> int:
        return len(self.kinds)

    @property
    def n_stations(self) -> int:
        return 2 * self.n_elements + 1


def sweep_stations(g: SPSCGeometry, size: float) -> Sweep:
    """Quadratic sweep elements of about ``size`` mm: along the middle's half-length and along
    the half-dome's outer quarter arc π/2 (w + t0) (at least one, resp. two)."""
    a = 0.5 * g.l
    n_y = math.ceil(a / size - 1e-9) if a > 0 else 0
    n_t = max(2, math.ceil(0.5 * math.pi * (g.w + g.t0) / size - 1e-9))
    ys = np.linspace(0.0, a, n_y + 1)
    ts = np.linspace(0.0, 0.5 * math.pi, n_t + 1)
    kinds = ("y",) * n_y + ("theta",) * n_t
    ends = tuple(zip(ys[:-1], ys[1:])) + tuple(zip(ts[:-1], ts[1:]))
    return Sweep(a, kinds, tuple((float(s0), float(s1)) for s0, s1 in ends))


def _frame(kind, a, R, s):
    """Reference position X (…, 3) and the rows ∂(R, Z, s)/∂X … as coefficients:
    (cR, cS) such that ∂/∂x_j = cR_j ∂/∂R + δ_j2 ∂/∂Z + cS_j ∂/∂s."""
    R, s = np.broadcast_arrays(np.asarray(R, float), np.asarray(s, float))
    zero, one = np.zeros_like(R), np.ones_like(R)
    if kind == "y":
        X = np.stack([R, s, zero], -1)
        cR = np.stack([one, zero, zero], -1)
        cS = np.stack([zero, one, zero], -1)
    else:
        c, sn = np.cos(s), np.sin(s)
        X = np.stack([R * c, a + R * sn, zero], -1)
        cR = np.stack([c, sn, zero], -1)
        with np.errstate(divide="ignore", invalid="ignore"):
            cS = np.stack([-sn / R, c / R, zero], -1)
    return X, cR, cS


class SweptWall:
    """The swept wall of a stadium quarter on ``section`` (its nodes, Q2 elements, basis,
    cavity and outer node lines; the measure of its ``dV`` is divided out) along ``sweep``.

    Unknowns: u (n_nodes, 3) Cartesian, flattened node-major. Node numbering: station k
    (0 … 2·n_elements) × section node, the θ-stations' axis nodes merged into the junction's
    (a = 0, l = 0: the θ = 0 station's)."""

    def __init__(self, section: Section, sweep: Sweep, law: NearlyIncompressible, *,
                 base: str = "clamped"):
        self.section, self.sweep = section, sweep
        ns = len(section.nodes)
        S = sweep.n_stations
        R0, Z0 = section.nodes[:, 0], section.nodes[:, 1]
        tol = 1e-9 * max(1.0, float(np.max(np.abs(section.nodes))))
        on_axis = R0 < tol
        # the station and coordinate of every station
        kind_st, s_st = [], []
        for e, (kind, (s0, s1)) in enumerate(zip(sweep.kinds, sweep.ends)):
            for j, s in enumerate((s0, 0.5 * (s0 + s1), s1)):
                if e > 0 and j == 0:
                    continue
                kind_st.append(kind)
                s_st.append(s)
        kind_st = np.array(kind_st)
        s_st = np.array(s_st)
        # the junction station (first θ-station): the axis nodes of later θ-stations are its own
        first_t = int(np.argmax(kind_st == "theta"))
        idx = np.arange(S * ns).reshape(S, ns)
        idx[first_t + 1:, on_axis] = idx[first_t, on_axis]
        used, inv = np.unique(idx, return_inverse=True)
        self.node_of = inv.reshape(S, ns)  # (station, section node) -> node
        n = len(used)
        self.n_nodes = n
        # reference coordinates of every node
        X = np.zeros((n, 3))
        for k in range(S):
            Xk, _, _ = _frame(kind_st[k], sweep.a, R0, s_st[k])
            Xk[:, 2] = Z0
            X[self.node_of[k]] = Xk
        self.X = X
        # boundary conditions: clamped base; x = 0 plane; y = 0 plane
        fixed = np.zeros((n, 3), bool)
        on_base = np.abs(X[:, 2]) < tol
        fixed[on_base, 2] = True
        if base == "clamped":
            fixed[on_base, :] = True
        fixed[np.abs(X[:, 0]) < tol, 0] = True
        fixed[np.abs(X[:, 1]) < tol, 1] = True
        self.fixed = fixed.ravel()
        self.reference = X.ravel()
        self.n_dofs = 3 * n
        self.dofs = np.arange(self.n_dofs)
        # the solid
        self.solid = self._solid(law)
        # cavity and outer surfaces: (patch, 9 local nodes) with their kind and station ends
        self._cavity = self._patches(section.cavity)
        self._outer = self._patches(section.outer)
        self.zdofs = np.unique(3 * self._outer[0].ravel() + 2)
        self._sign = 1.0
        self._sign = math.copysign(1.0, self.volume(np.zeros(self.n_dofs)))

    # -- the solid ---------------------------------------------------------------------------
    def _solid(self, law):
        s, sw = self.section, self.sweep
        ne, nq = s.dV.shape
        Rq = s.Xq[..., 0]
        dA = s.dV / s.measure(Rq)  # (ne, nq) plain area weights
        phi, dphi = _phi(_ZG)  # (3, 3): Gauss point g, local station k
        dR, dZ = s.dNdX[..., 0], s.dNdX[..., 1]  # (ne, nq, 9)
        grads, dVs, qs, edofs = [], [], [], []
        q_sec = _pressure_basis(s.dV, s.Xq, s.measure)  # (ne, nq, 3)
        for e, (kind, (s0, s1)) in enumerate(zip(sw.kinds, sw.ends)):
            half = 0.5 * (s1 - s0)
            st = np.arange(3) + 2 * e
            nodes = self.node_of[st][:, s.elements]  # (3, ne, 9)
            nodes = np.transpose(nodes, (1, 2, 0)).reshape(ne, 27)  # local b = 3a + k
            edofs.append((3 * nodes[:, :, None] + np.arange(3)).reshape(ne, 81))
            grad_e, dV_e, q_e = [], [], []
            for g in range(3):
                sg = 0.5 * (s0 + s1) + half * _ZG[g]
                _, cR, cS = _frame(kind, sw.a, Rq, sg)  # (ne, nq, 3)
                # ∂N_b/∂x_j = (dN_a/dR cR_j + dN_a/dZ δ_j2) φ_k + N_a φ_k' / half · cS_j
                G = (np.einsum("eqa,eqj->eqaj", dR, cR)[..., None, :] * phi[g][:, None]
                     + (dZ[..., None] * phi[g])[..., None] * np.array([0.0, 0.0, 1.0])
                     + np.einsum("eqa,k,eqj->eqakj", s.N, dphi[g] / half, cS))
                grad_e.append(G.reshape(ne, nq, 27, 3))
                meas = 1.0 if kind == "y" else Rq
                dV_e.append(4.0 * dA * meas * half * _ZW[g])
                q_e.append(np.concatenate([q_sec, np.full((ne, nq, 1), _ZG[g])], -1))
            grads.append(np.concatenate(grad_e, 1))
            dVs.append(np.concatenate(dV_e, 1))
            qs.append(np.concatenate(q_e, 1))
        return CartesianSolid(law, None, np.concatenate(dVs), np.concatenate(qs),
                              np.concatenate(edofs), 3 * self.n_nodes, grad=np.concatenate(grads))

    # -- surfaces ----------------------------------------------------------------------------
    def _patches(self, line):
        """Patches (section edge × sweep element) of a node ``line``: (nodes (np, 9) with local
        order 3·edge-node + station, kinds, s0, s1)."""
        edges = np.stack([line[0:-2:2], line[1:-1:2], line[2::2]], axis=1)  # (ned, 3)
        nodes, kinds, s0s, s1s, sec = [], [], [], [], []
        for e, (kind, (s0, s1)) in enumerate(zip(self.sweep.kinds, self.sweep.ends)):
            st = np.arange(3) + 2 * e
            nd = self.node_of[st][:, edges]  # (3, ned, 3)
            nodes.append(np.transpose(nd, (1, 2, 0)).reshape(len(edges), 9))
            kinds += [kind] * len(edges)
            s0s += [s0] * len(edges)
            s1s += [s1] * len(edges)
            sec.append(edges)
        return (np.concatenate(nodes), np.array(kinds), np.array(s0s), np.array(s1s),
                np.concatenate(sec))

    def _surface(self, patches, u):
        """At the patch points (t Gauss × ζ): positions P, ∂P/∂t, ∂P/∂ζ (np, nt, nz, 3) and
        the linear maps of each from the patch unknowns (nt, nz, 9) (shape value, t- and
        ζ-derivative of each local node; the same for the three components)."""
        P0, Pt0, Pz0, Lv, Lt, Lz = self._surface_reference(patches)
        ue = np.asarray(u).reshape(-1, 3)[patches[0]]  # (np, 9, 3)
        P = P0 + np.einsum("tzb,pbi->ptzi", Lv, ue)
        Pt = Pt0 + np.einsum("tzb,pbi->ptzi", Lt, ue)
        Pz = Pz0 + np.einsum("tzb,pbi->ptzi", Lz, ue)
        return P, Pt, Pz, Lv, Lt, Lz

    def _surface_reference(self, patches, zeta=_ZG4):
        """The undeformed part of :meth:`_surface` and its linear maps, made once per patch
        set (every volume, gradient and contact area evaluates them)."""
        cache = self.__dict__.setdefault("_references", {})
        key = id(patches[0])
        if key in cache:
            return cache[key][1]
        nodes, kinds, s0, s1, edges = patches
        Nt, dNt = _edge_shape(_GAUSS_T)  # (nt, 3)
        ph, dph = _phi(zeta)  # (nz, 3)
        Rn = self.section.nodes[edges, 0]  # (np, 3)
        Zn = self.section.nodes[edges, 1]
        R = Rn @ Nt.T  # (np, nt)
        Rt = Rn @ dNt.T
        Zt = Zn @ dNt.T
        Z = Zn @ Nt.T
        half = 0.5 * (s1 - s0)
        s = 0.5 * (s0 + s1)[:, None] + half[:, None] * zeta[None, :]  # (np, nz)
        P = np.zeros((len(nodes), len(_GAUSS_T), len(zeta), 3))
        Pt, Pz = P.copy(), P.copy()
        y = kinds == "y"
        th = ~y
        a = self.sweep.a
        # middle: (R, s, Z)
        P[y, :, :, 0] = R[y][:, :, None]
        P[y, :, :, 1] = s[y][:, None, :]
        Pt[y, :, :, 0] = Rt[y][:, :, None]
        Pz[y, :, :, 1] = half[y][:, None, None]
        # half-dome: (R cos θ, a + R sin θ, Z)
        c, sn = np.cos(s[th])[:, None, :], np.sin(s[th])[:, None, :]
        P[th, :, :, 0] = R[th][:, :, None] * c
        P[th, :, :, 1] = a + R[th][:, :, None] * sn
        Pt[th, :, :, 0] = Rt[th][:, :, None] * c
        Pt[th, :, :, 1] = Rt[th][:, :, None] * sn
        Pz[th, :, :, 0] = -R[th][:, :, None] * sn * half[th][:, None, None]
        Pz[th, :, :, 1] = R[th][:, :, None] * c * half[th][:, None, None]
        P[..., 2] = Z[:, :, None]
        Pt[..., 2] = Zt[:, :, None]
        # local node b = 3·(edge node) + station
        Lv = np.einsum("ta,zk->tzak", Nt, ph).reshape(len(_GAUSS_T), len(zeta), 9)
        Lt = np.einsum("ta,zk->tzak", dNt, ph).reshape(len(_GAUSS_T), len(zeta), 9)
        Lz = np.einsum("ta,zk->tzak", Nt, dph).reshape(len(_GAUSS_T), len(zeta), 9)
        # the Hessian's bilinear maps: O[(t z), (a b)] = L1_a L2_b at each point
        O = {name: np.einsum("tza,tzb->tzab", L1, L2).reshape(-1, 81)
             for name, (L1, L2) in {"vt": (Lv, Lt), "vz": (Lv, Lz), "tz": (Lt, Lz)}.items()}
        cache[key] = (patches, (P, Pt, Pz, Lv, Lt, Lz), O)  # the patches held: id stays theirs
        return cache[key][1]

    def _weights(self, zeta_w=_ZW4):
        return 4.0 * np.einsum("t,z->tz", _GAUSS_W, zeta_w)

    def volume(self, u) -> float:
        """Cavity volume of the whole chamber (mm³): 4 ∫ z (x_t y_ζ − x_ζ y_t) dt dζ."""
        P, Pt, Pz, *_ = self._surface(self._cavity, u)
        f = P[..., 2] * (Pt[..., 0] * Pz[..., 1] - Pz[..., 0] * Pt[..., 1])
        return self._sign * float(np.einsum("ptz,tz->", f, self._weights()))

    def volume_gradient(self, u, hessian=True):
        """g = ∂V/∂u (mm²) and, with ``hessian``, the patch blocks (np, 27, 27) of ∂²V/∂u² on
        the patch unknowns (np, 27) (node-major, x y z)."""
        P, Pt, Pz, Lv, Lt, Lz = self._surface(self._cavity, u)
        w = self._sign * self._weights()
        z, xt, yt, xz, yz = P[..., 2], Pt[..., 0], Pt[..., 1], Pz[..., 0], Pz[..., 1]
        cross = xt * yz - xz * yt
        npatch = len(P)
        ge = np.zeros((npatch, 9, 3))
        ge[..., 2] = np.einsum("ptz,tzb,tz->pb", cross, Lv, w)
        ge[..., 0] = np.einsum("ptz,tzb,tz->pb", z * yz, Lt, w) \
            - np.einsum("ptz,tzb,tz->pb", z * yt, Lz, w)
        ge[..., 1] = np.einsum("ptz,tzb,tz->pb", z * xt, Lz, w) \
            - np.einsum("ptz,tzb,tz->pb", z * xz, Lt, w)
        nodes = self._cavity[0]
        d = (3 * nodes[:, :, None] + np.arange(3)).reshape(npatch, 27)
        g = np.bincount(d.ravel(), weights=ge.ravel(), minlength=self.n_dofs)
        if not hessian:
            return g
        H = np.zeros((npatch, 9, 3, 9, 3))
        # z with x: ∂²/∂z_a∂x_b = Lv_a (yz Lt_b − yt Lz_b), as (point values) @ (basis pairs)
        O = self.__dict__["_references"][id(self._cavity[0])][2]
        wz = (w * z).reshape(npatch, -1)
        zx = ((w * yz).reshape(npatch, -1) @ O["vt"]
              - (w * yt).reshape(npatch, -1) @ O["vz"]).reshape(npatch, 9, 9)
        zy = ((w * xt).reshape(npatch, -1) @ O["vz"]
              - (w * xz).reshape(npatch, -1) @ O["vt"]).reshape(npatch, 9, 9)
        xy = (wz @ O["tz"]).reshape(npatch, 9, 9)
        xy = xy - np.swapaxes(xy, 1, 2)  # Lt_a Lz_b − Lz_a Lt_b
        H[:, :, 2, :, 0] = zx
        H[:, :, 0, :, 2] = np.swapaxes(zx, 1, 2)
        H[:, :, 2, :, 1] = zy
        H[:, :, 1, :, 2] = np.swapaxes(zy, 1, 2)
        H[:, :, 0, :, 1] = xy
        H[:, :, 1, :, 0] = np.swapaxes(xy, 1, 2)
        return g, H.reshape(npatch, 27, 27), d

    def contact_area(self, u, plate: float, tol: float = 1e-3, indenter=None) -> float:
        """Area (mm²) of the outer surface within ``tol`` of the plate (or of the curved
        ``indenter`` with its tip at ``plate``), whole chamber."""
        P, Pt, Pz, *_ = self._surface(self._outer, u)
        dA = np.linalg.norm(np.cross(Pt, Pz), axis=-1)
        z = P[..., 2]
        if indenter is not None and indenter.curved:
            z = z - indenter.surface(P[..., :2].reshape(-1, 2).T)[0].reshape(z.shape)
        on = z >= plate - tol
        return float(np.sum((dA * self._weights())[on]))

    def apex(self, u) -> float:
        """Height of the cavity's top at the centre x = y = 0 (mm)."""
        k = self.node_of[0, self.section.cavity[0]]
        return float(self.X[k, 2] + np.asarray(u).reshape(-1, 3)[k, 2])
