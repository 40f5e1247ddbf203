"""The swept wall of a stadium chamber (l > 0): its geometry, consistent derivatives, and
agreement with the axisymmetric dome it must reduce to at l = 0 (an independent
discretisation: Cartesian 27-node hexahedra on the revolved quarter against the 2D section)."""

import numpy as np
import pytest

from spsc.cad.geometry import preset
from spsc.fem.material import NearlyIncompressible
from spsc.fem.wall.section import section_mesh
from spsc.fem.wall.swept import SweptWall, sweep_stations
from spsc.fem.wall import WallModel, WallSettings, wall_curve
from spsc.materials import material


def _swept(t="A", l=3.0, size=1.5, sweep=4.0, law="tpu60a"):
    g = preset(t, l=l)
    s = section_mesh(g, size=size, layers=1)
    return g, SweptWall(s, sweep_stations(g, sweep), NearlyIncompressible(material(law)))


@pytest.mark.parametrize("t, l", [("A", 0.0), ("B", 3.0), ("D", 10.0)])
def test_swept_wall_encloses_the_analytic_cavity(t, l):
    g, sw = _swept(t, l, size=0.5, sweep=2.0)
    # exact sweep geometry, quadratic section edges on the profile: the section's O(h⁴)
    # error (~1e-7), plus the 4-point ζ-rule on the half-dome's trigonometric integrand
    np.testing.assert_allclose(sw.volume(np.zeros(sw.n_dofs)), g.cavity_volume(), rtol=1e-6)


def test_swept_volume_gradient_and_hessian_are_derivatives():
    _, sw = _swept("C", 3.0)
    rng = np.random.default_rng(4)
    u = rng.normal(size=sw.n_dofs) * 0.05
    du = rng.normal(size=sw.n_dofs)
    g, H, d = sw.volume_gradient(u)
    eps = 1e-5
    fd = (sw.volume(u + eps * du) - sw.volume(u - eps * du)) / (2 * eps)
    # V is cubic in u: the central difference is exact up to eps² V''' and round-off
    np.testing.assert_allclose(g @ du, fd, rtol=1e-7)
    Hdu = np.zeros(sw.n_dofs)
    np.add.at(Hdu, d, np.einsum("pab,pb->pa", H, du[d]))
    fd = (sw.volume_gradient(u + eps * du, hessian=False)
          - sw.volume_gradient(u - eps * du, hessian=False)) / (2 * eps)
    np.testing.assert_allclose(Hdu, fd, rtol=0, atol=1e-7 * np.abs(fd).max())


@pytest.mark.parametrize("law", ["tpu60a", "elastic50a"])
def test_swept_tangent_is_the_derivative_of_the_residual(law):
    _, sw = _swept("D", 3.0, law=law)
    st = sw.solid
    rng = np.random.default_rng(6)
    U = rng.normal(size=sw.n_dofs) * 0.004  # rough: the wedges at the axis are short
    U[sw.fixed] = 0.0
    pc = rng.normal(size=st.zero_pressure().shape) * 0.01
    r, rp, K, G = st.residual_tangent(U, pc)
    dU = rng.normal(size=sw.n_dofs)
    dU[sw.fixed] = 0.0
    dp = st.recover(G, np.zeros_like(rp), dU)  # the p-variation slaved to dU (r_p fixed)
    eps = 1e-6
    fd = (st.residual(U + eps * dU, pc + eps * dp)[0]
          - st.residual(U - eps * dU, pc - eps * dp)[0]) / (2 * eps)
    fdp = (st.residual(U + eps * dU, pc + eps * dp)[1]
           - st.residual(U - eps * dU, pc - eps * dp)[1]) / (2 * eps)
    # central differences: O(eps²) truncation, round-off ~1e-16/eps relative
    np.testing.assert_allclose(K @ dU, fd, rtol=0, atol=1e-6 * np.abs(fd).max())
    assert abs(K - K.T).max() <= 1e-10 * abs(K).max()
    # r_p does not change along (dU, dp): δr_p = G dU − M dp/κ = 0 by construction
    np.testing.assert_allclose(fdp, 0.0, atol=1e-8 * np.abs(G).max())
    # the residual agrees with the one of the tangent call
    np.testing.assert_allclose(st.residual(U, pc)[0], r, rtol=0, atol=1e-12 * abs(r).max())


def test_rigid_motion_along_the_stadium_is_strain_free():
    # a translation along y is admissible away from the planes it would cut; its energy is
    # zero: F = I exactly, so the residual at zero pressure vanishes (the pole ties included)
    _, sw = _swept("A", 3.0)
    u = np.zeros((sw.n_nodes, 3))
    u[:, 1] = 0.1
    F = sw.solid.deformation(u.ravel())
    np.testing.assert_allclose(F, np.broadcast_to(np.eye(3), F.shape), atol=1e-12)


@pytest.mark.parametrize("t", ["A", "C"])
def test_swept_quarter_dome_is_the_axisymmetric_dome(t):
    # l = 0: the swept hexahedra on the revolved quarter (Cartesian displacements, pole nodes
    # merged) and the axisymmetric section are two discretisations of one problem; on the same
    # section mesh they differ only by the sweep's quadratic interpolation of an axisymmetric
    # field in θ: measured 2e-8 (volume), 4e-7 (force) with 3 mm sweep elements, 10x less
    # at 1.5 mm
    g = preset(t, l=0.0)
    mat = material("tpu60a")
    kw = dict(pressure_kPa=40, stroke_mm=1.0, points=3)
    settings = WallSettings(mesh_size_mm=1.5, sweep_size_mm=3.0)
    axi = wall_curve(g, mat, **kw, settings=settings)
    sw = wall_curve(g, mat, **kw, model=WallModel(g, mat, settings, stadium=True))
    assert axi.all_converged and sw.all_converged
    assert sw.solver.details["part"] == "swept" and axi.solver.details["part"] == "dome"
    np.testing.assert_allclose(sw.inflated_volume_mm3, axi.inflated_volume_mm3, rtol=1e-6)
    np.testing.assert_allclose(sw.force_N[1:], axi.force_N[1:], rtol=5e-6)
    np.testing.assert_allclose(sw.pressure_kPa, axi.pressure_kPa, rtol=1e-6)


@pytest.mark.slow
def test_type_c_snap_is_reported_and_followed():
    # Table 1 Type C at 10 kPa, high mode: the 3D FEM's contact area drops from 64 to 49 mm²
    # between y = 3.0 and 3.5 mm (the flank snaps); the swept wall finds the negative
    # eigenvalue there, follows the jump to the stable state and records it (it used to stop
    # there; on the default mesh: a 2 mm / 1-layer mesh is too stiff to buckle); every reported
    # point is a stable, converged one
    g = preset("C")
    c = wall_curve(g, material("tpu60a"), pressure_kPa=10, stroke_mm=4.0, points=9)
    assert c.solver.converged and c.all_converged and np.all(np.isfinite(c.force_N))
    (jump,) = c.solver.details["jumps"]
    assert 2.5 <= jump["y_mm"] <= 3.5, jump
    assert "snap-through at y = " in c.solver.instability and c.solver.notes
