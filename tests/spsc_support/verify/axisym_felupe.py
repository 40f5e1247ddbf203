"""Independent axisymmetric solid model of an l = 0 chamber (a dome), for checking the 3D FEM
(verification only: lives in the test tree, not in the installed package).

Built on FElupe (a test-only dependency, imported lazily), not on this package's FEM: 9-node
biquadratic quadrilaterals of the meridional section of the wall with FElupe's three-field
(u, p, J̄) nearly incompressible formulation, the same law as the 3D model (neo-Hookean,
W = μ/2 (Ī1 − 3), U = κ/2 (J̄ − 1)², κ = bulk_ratio · μ), follower pressure on the cavity,
clamped base (z = 0) and u_r = 0 on the axis. On top of FElupe's assembled residual and
tangent, this module adds the two things FElupe does not have in this form:

* a closed isothermal/polytropic gas cavity (:class:`spsc.core.GasLaw`, P(V + V_r)ⁿ = const),
  whose rank-one stiffness −(dp/dV) g gᵀ is added over the cavity dofs (g = ∂V/∂u, the
  pressure load per unit pressure);
* a frictionless rigid plate, exactly enforced on the outer-surface nodes by an active set (an
  active node's z is prescribed at the plate; it is released when its reaction pulls).

The mesh is the wall section of the 3D model (:func:`spsc.fem.solid.mesh.wall_section`), so both
discretise the same wall; the cavity volume is this module's own (Gauss quadrature on the P2
cavity profile), independent of the 3D model's.

Units: mm, MPa, N, mm³. FElupe's axisymmetric integrals carry 2πR, so nodal reactions are the
forces of whole rings and the plate force is their sum.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from spsc.cad.geometry import SPSCGeometry
from spsc.core import GasLaw
from spsc.fem.solid.mesh import wall_section
from spsc.materials import Material

__all__ = ["AxisymmetricDome", "AxiRecord"]


def _quad9(shape):
    """quad9 cells (VTK order) of a fine grid of shape (2a+1, 2b+1), flat indices."""
    m, k = shape
    idx = np.arange(m * k).reshape(m, k)
    cells = []
    for i in range(0, m - 1, 2):
        for j in range(0, k - 1, 2):
            cells.append([idx[i, j], idx[i + 2, j], idx[i + 2, j + 2], idx[i, j + 2],
                          idx[i + 1, j], idx[i + 2, j + 1], idx[i + 1, j + 2], idx[i, j + 1],
                          idx[i + 1, j + 1]])
    return np.array(cells)


@dataclass(frozen=True)
class AxiRecord:
    """One converged state: gauge pressure (MPa), cavity volume (mm³), plate height (mm, None),
    plate force (N), apex height of the cavity (mm)."""

    pressure: float
    volume: float
    plate: float | None
    force: float
    apex: float


class AxisymmetricDome:
    """Meridional-section model of the l = 0 chamber ``g`` (``g.l`` must be 0).

    ``n_profile`` elements along the profile, ``layers`` through the thickness; ``base``
    ``"clamped"`` (the chamber, docs/design.md) or ``"symmetry"`` (u_z = 0 only: with n1 = n2 = 2,
    c_y = 0 and w = h the wall is half of a thick sphere, for the exact solution).
    """

    def __init__(self, g: SPSCGeometry, material: Material, *, n_profile: int = 40,
                 layers: int = 4, bulk_ratio: float = 2000.0, base: str = "clamped"):
        import felupe as fem

        if g.l != 0:
            raise ValueError(f"l = {g.l} mm: the axisymmetric model needs l = 0")
        self.fem, self.g = fem, g
        grid = wall_section(g, n_profile, layers)  # (r, z), apex first
        shape = grid.shape[:2]
        pts = grid.reshape(-1, 2)[:, ::-1].copy()  # FElupe's order: (axial z, radial r)
        cells = _quad9(shape)
        # orient cells counter-clockwise in (z, r)
        a, b, d = pts[cells[:, 0]], pts[cells[:, 1]], pts[cells[:, 3]]
        cross = (b - a)[:, 0] * (d - a)[:, 1] - (b - a)[:, 1] * (d - a)[:, 0]
        flip = cross < 0
        cells[flip] = cells[flip][:, [0, 3, 2, 1, 7, 6, 5, 4, 8]]
        self.mesh = fem.Mesh(pts, cells, "quad9")
        self.region = fem.RegionBiQuadraticQuad(self.mesh)
        self.field = fem.FieldsMixed(self.region, n=3, axisymmetric=True)
        mu = material.shear_modulus
        if {(i, j) for i, j, _ in material.coefficients} != {(1, 0)}:
            raise ValueError("the axisymmetric check implements the neo-Hookean law only")
        self.kappa = bulk_ratio * mu
        self.solid = fem.SolidBody(fem.NearlyIncompressible(fem.NeoHooke(mu=mu), self.kappa),
                                   self.field)
        layer = np.broadcast_to(np.arange(shape[1])[None, :], shape).ravel()
        self.grid_shape = shape
        self.cavity_points = np.nonzero(layer == 0)[0]  # apex first
        self.outer_points = np.nonzero(layer == shape[1] - 1)[0]
        self.boundary = fem.RegionBiQuadraticQuadBoundary(
            self.mesh, only_surface=True, mask=(layer == 0), ensure_3d=True)
        self.pfield = fem.FieldContainer([fem.FieldAxisymmetric(self.boundary, dim=2)])
        self.pressure_item = fem.SolidBodyPressure(self.pfield)
        n_u = 2 * len(pts)
        self.n_u = n_u
        self.n = int(sum(f.values.size for f in self.field.fields))
        fixed = np.zeros(self.n, bool)
        tol = 1e-9 * max(g.w, g.h)
        fixed[2 * np.nonzero(np.abs(pts[:, 1]) < tol)[0] + 1] = True  # u_r = 0 on the axis
        base_kind = base
        if base_kind not in ("clamped", "symmetry"):
            raise ValueError(f"base = {base!r}: 'clamped' or 'symmetry'")
        base = np.nonzero(np.abs(pts[:, 0]) < tol)[0]
        fixed[2 * base] = True
        if base_kind == "clamped":
            fixed[2 * base + 1] = True
        self.fixed = fixed
        self.contact_points = self.outer_points[~fixed[2 * self.outer_points]]

    # -- state ----------------------------------------------------------------------------------
    def state(self) -> np.ndarray:
        """The unknowns (u, p, J̄ of FElupe's fields, flattened) of the current state."""
        return np.concatenate([f.values.ravel() for f in self.field.fields])

    def _set(self, x):
        off = 0
        for f in self.field.fields:
            f.values[:] = x[off: off + f.values.size].reshape(f.values.shape)
            off += f.values.size
        self.pfield[0].values[:] = self.field[0].values

    def positions(self, x) -> np.ndarray:
        """Deformed (r, z) of every point (mm)."""
        return (self.mesh.points + x[: self.n_u].reshape(-1, 2))[:, ::-1]

    def volume(self, x) -> float:
        """Cavity volume (mm³): π∫ r² dz along the deformed P2 cavity profile, closed by the
        axis and the base plane (3-point Gauss per quadratic segment, exact for r² z')."""
        c = self.positions(x)[self.cavity_points]
        c0, c1, c2 = c[0:-2:2], c[1:-1:2], c[2::2]
        vol = 0.0
        for xi, w in zip((-math.sqrt(0.6), 0.0, math.sqrt(0.6)), (5 / 9, 8 / 9, 5 / 9)):
            N = (0.5 * xi * (xi - 1), 1 - xi * xi, 0.5 * xi * (xi + 1))
            dN = (xi - 0.5, -2 * xi, xi + 0.5)
            r = N[0] * c0[:, 0] + N[1] * c1[:, 0] + N[2] * c2[:, 0]
            dz = dN[0] * c0[:, 1] + dN[1] * c1[:, 1] + dN[2] * c2[:, 1]
            vol += w * np.sum(math.pi * r * r * dz)
        return -vol  # the profile runs from the apex down to the base

    def apex(self, x) -> float:
        return float(self.positions(x)[self.cavity_points[0], 1])

    # -- residual and tangent -------------------------------------------------------------------
    def assemble(self, x, p, tangent=True):
        """Residual r (N), tangent K (None unless ``tangent``) and the pressure load per unit
        pressure g = ∂V/∂u (mm², on the displacement dofs) at state ``x`` under the follower
        gauge pressure ``p`` (MPa) on the cavity."""
        self._set(x)
        r = np.asarray(self.solid.assemble.vector(self.field).todense()).ravel()
        self.pressure_item.update(1.0)
        # FElupe's pressure vector at unit pressure, with its sign here, is ∂V/∂u
        g = np.asarray(self.pressure_item.assemble.vector(self.pfield).todense()).ravel()
        r = r.copy()
        r[: self.n_u] -= p * g
        if not tangent:
            return r, None, g
        K = self.solid.assemble.matrix(self.field).tocsr()
        Kp = self.pressure_item.assemble.matrix(self.pfield).tocsr()
        Kp = Kp.tocoo()
        Kp.resize(K.shape)
        return r, (K - p * Kp).tocsr(), g

    def _newton(self, x, load, active, *, tol=1e-9, max_it=30):
        """Solve for the load ``(p, gas, plate)``; gas: None (``p`` prescribed) or the
        :class:`~spsc.core.GasLaw` of the closed cavity. Returns x, the active contact points,
        the gauge pressure (MPa) and the residual (whose −z components at active points are
        their ring forces)."""
        p_pres, gas, plate = load
        x = x.copy()
        active = np.asarray(active, int)
        scale = None
        changes = 0
        for it in range(max_it):
            V = self.volume(x)
            if gas is not None:
                p, dpdV = float(gas.pressure(V)), float(gas.dpressure(V))
            else:
                p, dpdV = p_pres, 0.0
            r, K, g = self.assemble(x, p)
            presc = 2 * active  # the axial (z) component
            free = ~self.fixed
            free[presc] = False
            jump = np.zeros(self.n)
            if plate is not None and active.size:
                jump[presc] = plate - self.mesh.points[active, 0] - x[presc]
            res = np.linalg.norm(r[free])
            if scale is None:
                scale = max(np.linalg.norm(p * g), np.linalg.norm(r[free]),
                            np.linalg.norm(r[self.fixed]), 1e-8)
            settled = np.max(np.abs(jump), initial=0.0) < 1e-12
            if plate is not None and settled and it > 0 and res < 1e-1 * scale:
                reac = -r[presc]
                keep = reac >= -tol * scale
                others = np.setdiff1d(self.contact_points, active)
                z = self.positions(x)[others, 1]
                new = others[z > plate + 1e-6]
                if new.size or not np.all(keep):
                    active = np.union1d(active[keep], new)
                    changes += 1
                    if changes > 40:
                        raise RuntimeError("active set does not settle")
                    continue
            if settled and it > 0 and res < tol * scale:
                return x, active, p, r
            gfull = np.zeros(self.n)
            gfull[: self.n_u] = g
            if dpdV != 0.0:
                cav = np.nonzero(gfull)[0]
                rank1 = sp.coo_matrix((-dpdV * np.outer(gfull[cav], gfull[cav]).ravel(),
                                       (np.repeat(cav, cav.size), np.tile(cav, cav.size))),
                                      shape=K.shape).tocsr()
                K = K + rank1
            rhs = -r[free] - (K @ jump)[free]
            dx = np.zeros(self.n)
            dx[free] = spla.spsolve(K[free][:, free].tocsc(), rhs)
            dx[presc] = jump[presc]
            x = x + dx
        raise RuntimeError(f"no convergence (residual {res:.3g} N against {tol * scale:.3g} N)")

    # -- load path ------------------------------------------------------------------------------
    def inflate(self, pressure: float, increments: int = 4):
        """Inflate to gauge ``pressure`` (MPa); returns (x, [AxiRecord per increment])."""
        x = self.state()
        recs = [AxiRecord(0.0, self.volume(x), None, 0.0, self.apex(x))]
        for k in range(1, increments + 1):
            p = pressure * k / increments
            x, _, p, _ = self._newton(x, (p, None, None), [])
            recs.append(AxiRecord(p, self.volume(x), None, 0.0, self.apex(x)))
        self._set(x)
        return x, recs

    def press(self, x, pressure: float, stroke: float, increments: int, *,
              reservoir: float = 0.0, polytropic_index: float = 1.0, gas: bool = True,
              substeps: int = 2):
        """From the state ``x`` inflated at ``pressure`` (MPa): close the valve (``gas``, else
        the pressure stays prescribed) and lower the plate from first contact by ``stroke`` mm;
        returns one AxiRecord per increment."""
        V0 = self.volume(x)
        gas_law = GasLaw(pressure, V0, reservoir, polytropic_index) if gas else None
        z0 = float(self.positions(x)[self.contact_points, 1].max())
        active = np.zeros(0, int)
        out = []
        for k in range(1, increments * substeps + 1):
            plate = z0 - stroke * k / (increments * substeps)
            x, active, p, r = self._newton(x, (pressure, gas_law, plate), active)
            if k % substeps == 0:
                force = float(np.sum(-r[2 * active]))
                out.append(AxiRecord(p, self.volume(x), plate, force, self.apex(x)))
        self._set(x)
        return out
