"""Mixed P2/P1 assembly: consistent tangent (differences), patch test, no locking."""

import numpy as np
import pytest

from spsc.cad.geometry import preset
from spsc.fem.solid.assembly import assemble, discretise
from spsc.fem.solid.element import TET_EDGES
from spsc.fem.solid.mesh import block, spsc_wall
from spsc.fem.solid.model import FEMModel, Load
from spsc.fem.engine import Settings, newton
from spsc.materials import material, yeoh


def test_tangent_matches_residual_differences():
    """K·v against central differences of r, with the follower cavity pressure included."""
    m = spsc_wall(preset("B"), 3.0, layers=1)
    model = FEMModel.build(m, yeoh(0.5056, 0.01, 0.002562), bulk_ratio=50.0)
    rng = np.random.default_rng(1)
    x = np.zeros(model.disc.n)
    x[: model.disc.n_u] = 0.05 * rng.standard_normal(model.disc.n_u)
    x[model.disc.n_u:] = 0.05 * rng.standard_normal(model.disc.n_p)
    v = rng.standard_normal(model.disc.n)
    load = Load(pressure=0.2)
    K = model.evaluate(x, load).K
    h = 1e-6
    fd = (model.evaluate(x + h * v, load, tangent=False).r
          - model.evaluate(x - h * v, load, tangent=False).r) / (2 * h)
    Kv = K @ v
    # O(h²) truncation and 1e-16/h round-off: 1e-6 of the largest entry is a sharp bound
    np.testing.assert_allclose(Kv, fd, rtol=0, atol=1e-6 * np.abs(Kv).max())


def test_compiled_element_loop_is_the_numpy_assembly(monkeypatch):
    """The Numba element loops (spsc.fem.solid.assembly_kernel: F, the residual alone, residual
    and tangent) against the NumPy assembly: the same integrals summed in another order, so
    equal to round-off (1e-13 of the largest; F is O(1))."""
    import spsc.fem.solid.assembly as assembly

    if not assembly.COMPILED:
        pytest.skip("Numba is not installed: the NumPy assembly is the assembly")
    m = spsc_wall(preset("B"), 3.0, layers=1)
    model = FEMModel.build(m, yeoh(0.5056, 0.01, 0.002562), bulk_ratio=50.0)
    d, rng = model.disc, np.random.default_rng(4)
    x = np.concatenate([0.05 * rng.standard_normal(d.n_u), 0.05 * rng.standard_normal(d.n_p)])
    r, K = assemble(d, model.law, x)
    r_alone = assemble(d, model.law, x, tangent=False)
    F = assembly.deformation_gradient(d, d.split(x)[0])
    monkeypatch.setattr(assembly, "COMPILED", False)
    r0, K0 = assemble(d, model.law, x)
    np.testing.assert_allclose(assembly.deformation_gradient(d, d.split(x)[0]), F, rtol=0,
                               atol=1e-14)
    np.testing.assert_allclose(r, r0, rtol=0, atol=1e-13 * np.abs(r0).max())
    np.testing.assert_allclose(r_alone, r0, rtol=0, atol=1e-13 * np.abs(r0).max())
    assert K.nnz == K0.nnz and np.array_equal(K.indices, K0.indices)
    np.testing.assert_allclose(K.data, K0.data, rtol=0, atol=1e-13 * np.abs(K0.data).max())


def test_node_pair_pattern_is_the_pattern_of_the_unknown_pairs():
    """The pattern found on node pairs (Pattern.from_element_dofs) against the plain one: every
    unknown pair of every element, sorted and made unique. Same CSR arrays, same slot of every
    element entry."""
    mesh = spsc_wall(preset("B"), 3.0, layers=1)
    d = discretise(mesh.nodes, mesh.tets)
    m = d.dofs.shape[1]
    pair = np.repeat(d.dofs, m, axis=1).astype(np.int64) * d.n + np.tile(d.dofs, (1, m))
    keys, inverse = np.unique(pair, return_inverse=True)
    p = d.pattern
    assert np.array_equal(p.keys, keys)
    assert np.array_equal(p.indptr, np.searchsorted(keys, np.arange(d.n + 1) * d.n))
    assert np.array_equal(p.indices, keys % d.n)
    assert np.array_equal(p.slots, inverse.reshape(p.slots.shape))


def _affine_patch(F0, law_mat, curved, seed=0):
    m = block((1.0, 1.2, 0.8), (2, 2, 2))
    X = m.nodes.copy()
    boundary = m.nodes_on(*m.facets)
    inner = np.setdiff1d(np.arange(len(X)), boundary)
    X[inner] += (0.02 if curved else 0.05) * np.random.default_rng(seed).standard_normal(
        (inner.size, 3))
    if not curved:  # straight-sided distorted tetrahedra: edge nodes back at the midpoints
        for e, (a, b) in enumerate(TET_EDGES):
            X[m.tets[:, 4 + e]] = 0.5 * (X[m.tets[:, a]] + X[m.tets[:, b]])
    m = type(m)(X, m.tets, m.facets, 1)
    # ∇N·det J is of degree 1 on straight tetrahedra (the default 4-point rule is exact) and of
    # degree 3 on curved ones (the 14-point degree-5 rule is)
    model = FEMModel.build(m, law_mat, supports={t: (0, 1, 2) for t in m.facets},
                           bulk_ratio=20.0, order=5 if curved else 2)
    x0 = np.zeros(model.disc.n)
    # start from the affine field, interior nodes disturbed: Newton must bring them back
    u0 = X @ (F0 - np.eye(3)).T
    u0[inner] += 0.02 * np.random.default_rng(seed + 1).standard_normal((inner.size, 3))
    x0[: model.disc.n_u] = u0.ravel()
    return m, model, x0


@pytest.mark.parametrize("curved", [False, True], ids=["straight", "curved"])
@pytest.mark.parametrize("mat", [material("tpu60a"), yeoh(0.5056, 0.05, 0.002562)],
                         ids=lambda m: m.name)
def test_patch_test_homogeneous_deformation(mat, curved):
    """Prescribed affine boundary motion on a distorted P2 patch: the interior follows the
    affine field and the pressure is uniform, to solver precision."""
    F0 = np.array([[1.2, 0.1, 0.0], [0.05, 0.9, 0.1], [0.0, -0.1, 1.05]])
    m, model, x0 = _affine_patch(F0, mat, curved)
    x = newton(model, x0, Load(), Settings(rtol=1e-11)).x
    u = model.displacement(x)
    np.testing.assert_allclose(u, m.nodes @ (F0 - np.eye(3)).T, rtol=0, atol=1e-10)
    p = x[model.disc.n_u:]
    J = np.linalg.det(F0)
    # p = κ(J − 1) exactly for the discrete mixed form under uniform J
    np.testing.assert_allclose(p, model.law.kappa * (J - 1.0), rtol=1e-9, atol=1e-12)


def test_assembled_volume_residual_is_incompressibility():
    """r_p = ∫(J − 1 − p/κ) N dV: zero for a volume-preserving motion at p = 0."""
    m = block((1.0, 1.0, 1.0), (1, 1, 1))
    d = discretise(m.nodes, m.tets)
    F0 = np.diag([2.0, 0.5, 1.0])
    x = np.zeros(d.n)
    x[: d.n_u] = (m.nodes @ (F0 - np.eye(3)).T).ravel()
    from spsc.fem.material import NearlyIncompressible

    r = assemble(d, NearlyIncompressible(material("tpu60a")), x, tangent=False)
    np.testing.assert_allclose(r[d.n_u:], 0.0, rtol=0, atol=1e-14)


def test_linearised_tangent_matches_scikit_fem_forms():
    """At the undeformed state the vectorised tangent is the mixed linear-elasticity system;
    its quadratic form on smooth fields equals the one assembled by plain scikit-fem forms
    (λ = −2μ/3 in the displacement block: the volumetric stiffness lives in the p-field)."""
    from skfem import Basis, BilinearForm, ElementTetP1, ElementTetP2, ElementVector, MeshTet
    from skfem.helpers import ddot, div, sym_grad, trace

    from spsc.fem.material import NearlyIncompressible

    m = block((1.0, 1.2, 0.8), (2, 2, 1))
    law = NearlyIncompressible(material("tpu60a"), bulk_ratio=7.0)
    d = discretise(m.nodes, m.tets)
    _, K = assemble(d, law, np.zeros(d.n))
    rng = np.random.default_rng(4)
    cu, cp = rng.standard_normal((3, 10)), rng.standard_normal(4)

    def u_field(X):  # a quadratic vector field, exactly represented by P2
        x, y, z = X
        mono = np.array([np.ones_like(x), x, y, z, x * x, y * y, z * z, x * y, y * z, z * x])
        return np.einsum("cm,m...->c...", cu, mono)

    def p_field(X):  # a linear scalar field, exactly represented by P1
        return cp[0] + cp[1] * X[0] + cp[2] * X[1] + cp[3] * X[2]

    x = np.zeros(d.n)
    x[: d.n_u] = u_field(m.nodes.T).T.ravel()
    corner = d.pressure_dof >= 0
    x[d.n_u + d.pressure_dof[corner]] = p_field(m.nodes[corner].T)
    ours = x @ (K @ x)

    mesh = MeshTet(m.nodes[corner].T, np.searchsorted(np.nonzero(corner)[0], m.tets[:, :4]).T)
    ub = Basis(mesh, ElementVector(ElementTetP2()), intorder=2)
    pb = ub.with_element(ElementTetP1())
    mu, kappa = law.mu, law.kappa

    @BilinearForm
    def elastic(u, v, w):
        return 2 * mu * ddot(sym_grad(u), sym_grad(v)) - 2 * mu / 3 * trace(sym_grad(u)) * \
            trace(sym_grad(v))

    @BilinearForm
    def coupling(p, v, w):
        return div(v) * p

    @BilinearForm
    def compliance(p, q, w):
        return -p * q / kappa

    # L2 projections with a rule exact for the P2 mass matrix: they reproduce the fields
    uu = Basis(mesh, ElementVector(ElementTetP2()), intorder=4).project(u_field)
    pp = Basis(mesh, ElementTetP1(), intorder=4).project(p_field)
    theirs = (uu @ (elastic.assemble(ub) @ uu) + 2 * uu @ (coupling.assemble(pb, ub) @ pp)
              + pp @ (compliance.assemble(pb) @ pp))
    # both are exact quadratures of the same polynomial integrals: round-off only
    np.testing.assert_allclose(ours, theirs, rtol=1e-11, atol=0)
