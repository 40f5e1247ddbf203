"""The rigid insert (a coin motor inside the cavity) on a coarse Type B quarter wall: the
aliased Newton step equals the Lagrange-multiplier (KKT) solution of the same constraints, an
insert that never touches changes nothing but the gas volume, the gas law holds on the gas
volume, and once the wall comes down onto the insert its engaged nodes lie on its face and its
force balances its seat's."""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from spsc.cad.geometry import preset
from spsc.core.constants import KPA_PER_MPA, P_AMB
from spsc.core.gaslaw import GasLaw
from spsc.fem.solid.insert import RigidInsert, insert_constraints
from spsc.fem.solid.mesh import spsc_wall
from spsc.fem.solid.model import FEMModel, Load
from spsc.fem.engine import CloseValve, Inflate, Press, Settings, solve
from spsc.fem.engine.constraints import Constraints, Reduction
from spsc.fem.engine.linear import linear_step
from spsc.materials import material

G = preset("B")
MAT = material("tpu60a")


@pytest.fixture(scope="module")
def wall():
    return spsc_wall(G, 3.0, layers=1)


def _insert(mesh, *, gap=0.3, volume=300.0, seat_band=(2.0, 4.0), reach=0.3):
    """An insert standing in the cavity: seated on the inner wall's nodes in a band of heights
    (away from the supports), its top face ``gap`` below the inner apex; top candidates are
    the cavity nodes within ``reach`` of the inner apex."""
    X = mesh.nodes
    cav = mesh.nodes_on("cavity")
    on_sym = np.union1d(mesh.nodes_on("sym_x"), mesh.nodes_on("sym_y"))
    band = cav[(X[cav, 2] >= seat_band[0]) & (X[cav, 2] <= seat_band[1])]
    seat = np.setdiff1d(band, on_sym)
    apex = X[cav, 2].max()
    z0 = float(X[seat[0], 2])
    top = np.setdiff1d(cav[X[cav, 2] >= apex - reach], seat)
    return RigidInsert("motor", seat, top, z0, apex - gap - z0, volume)


def _kkt_step(model, ev, free, slaves, master, sjump):
    """The same Newton step by Lagrange multipliers: [K_ff Cᵀ; C 0] with C Δu = d for
    Δu_s − Δu_m = sjump_s (the gas's rank-one term added to K explicitly)."""
    n_u = model.disc.n_u
    live = free.copy()
    live[slaves] = True
    idx = np.flatnonzero(live)
    pos = -np.ones(model.disc.n, int)
    pos[idx] = np.arange(idx.size)
    g = np.zeros(model.disc.n)
    g[:n_u] = ev.g
    K = ev.K[idx][:, idx] + ev.c * sp.csr_matrix(np.outer(g[idx], g[idx]))
    rows = np.arange(slaves.size)
    C = sp.csr_matrix((np.r_[np.ones(slaves.size), -np.ones(slaves.size)],
                       (np.r_[rows, rows], np.r_[pos[slaves], np.full(slaves.size,
                                                                        pos[master])])),
                      shape=(slaves.size, idx.size))
    A = sp.bmat([[K, C.T], [C, None]]).tocsc()
    sol = spla.spsolve(A, np.r_[-ev.r[idx], sjump])
    step = np.zeros(model.disc.n)
    step[idx] = sol[: idx.size]
    return step


@pytest.mark.parametrize("gas", [False, True])
def test_aliased_step_equals_the_kkt_step(wall, gas):
    """The eliminated (aliased, PᵀKP) Newton step and the Lagrange-multiplier step of the same
    constraints are the same vector: an independent check of the reduction, the condensed
    right-hand side, the jumps and the Sherman–Morrison gas term."""
    ins = _insert(wall)
    model = FEMModel.build(wall, MAT, insert=ins)
    rng = np.random.default_rng(3)
    x = model.zero_state()
    free0 = ~model.fixed
    x[: model.disc.n_u][free0[: model.disc.n_u]] = 0.01 * rng.standard_normal(
        free0[: model.disc.n_u].sum())
    engaged = ins.top[X_top_order(model, ins)[:5]]
    load = Load(gas=GasLaw(0.04, model.volume(x))) if gas else Load(pressure=0.04)
    ev = model.evaluate(x, load)
    slaves, sjump = insert_constraints(ins, model.disc.X, x, engaged)
    assert np.abs(sjump).max() > 1e-3  # the random state violates them: the jumps are tested
    free = free0.copy()
    free[slaves] = False
    con = Constraints(model.disc.n, np.zeros(0, int), np.zeros(0), slaves, sjump, ins.master)
    red = Reduction(ev.K, free, slaves, ins.master)
    step = linear_step(model, ev, red, free, con, Settings()).dx
    ref = _kkt_step(model, ev, free, slaves, ins.master, sjump)
    assert (ev.c > 0) == gas
    # two direct solves of one well-conditioned system: agreement to ~1e-9 of the step
    np.testing.assert_allclose(step, ref, rtol=0, atol=1e-8 * np.abs(ref).max())
    # and the step does what the constraints ask
    np.testing.assert_allclose(x[slaves] + step[slaves],
                               x[ins.master] + step[ins.master]
                               + (x[slaves] - x[ins.master] + sjump), atol=1e-12)


def X_top_order(model, ins):
    return np.argsort(-model.disc.X[ins.top, 2])


def _steps(stroke=2.0, points=5, reservoir=0.0):
    return [Inflate(0.04, 2), CloseValve(reservoir), Press(stroke, points - 1)]


def test_an_insert_that_never_touches_changes_only_the_gas_volume(wall):
    """Seated on one node (no constraint) with its face far below the wall: the states are
    those of the chamber without it; the closed gas is the cavity less the insert, so with a
    reservoir equal to the insert's volume the pressures are the plain chamber's too."""
    plain = solve(FEMModel.build(wall, MAT), _steps())
    ins = _insert(wall, gap=20.0, volume=500.0)
    one = RigidInsert("motor", ins.seat[:1], ins.top, ins.z_bottom, ins.height, 500.0)
    held = solve(FEMModel.build(wall, MAT, insert=one), _steps(reservoir=500.0))
    assert plain.converged and held.converged, (plain.message, held.message)
    for a, b in zip(plain.records, held.records):
        np.testing.assert_allclose(b.x, a.x, rtol=0, atol=1e-9)
        np.testing.assert_allclose(b.pressure, a.pressure, rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose(b.force, a.force, rtol=1e-7, atol=1e-9)
        assert b.insert_force == 0.0
        np.testing.assert_allclose(b.volume, a.volume - 500.0, rtol=1e-12)


def test_the_wall_comes_down_onto_the_insert(wall):
    """Pressed 2 mm with the insert's face 0.3 mm below the inner apex: no insert force until
    the apex meets it, then a positive one; the engaged nodes lie on its face, the others above
    it; its force equals its seat's (its own equilibrium); the plate force exceeds the plain
    chamber's; P·V_gas is constant with V_gas the measured cavity less the insert."""
    ins = _insert(wall, gap=0.3, volume=300.0)
    model = FEMModel.build(wall, MAT, insert=ins)
    res = solve(model, _steps(points=9))
    plain = solve(FEMModel.build(wall, MAT), _steps(points=9))
    assert res.converged and plain.converged, (res.message, plain.message)
    X = model.disc.X
    press = res.of("press")
    held = np.array([r.insert_force for r in press])
    assert held[0] == 0.0 and held[-1] > 0.5, held
    assert np.all(np.diff(held) >= -1e-9)
    inflated = res.of("inflate")[-1]
    gas = GasLaw(inflated.pressure, model.volume(inflated.x))
    for rec, base in zip(press, plain.of("press")):
        w = rec.x[ins.master]
        face = ins.z_top + w
        zt = X[ins.top, 2] + rec.x[3 * ins.top + 2]
        assert np.all(zt >= face - 1e-5)  # none inside the insert beyond the contact tolerance
        on = np.isclose(zt, face, atol=1e-9)
        if rec.insert_force > 0:
            assert on.any()
            ev = model.evaluate(rec.x, Load(gas=gas))
            seat = -ev.r[3 * ins.seat + 2].sum() * model.symmetry
            # the insert's equilibrium holds to the Newton tolerance (1e-8 of the force scale)
            np.testing.assert_allclose(rec.insert_force, seat, rtol=1e-6)
            assert rec.force > base.force
        # seat nodes moved as one
        np.testing.assert_allclose(rec.x[3 * ins.seat + 2], w, rtol=0, atol=1e-12)
        v_gas = model.cavity.volume(X, model.displacement(rec.x)) - ins.volume
        P = rec.pressure + P_AMB
        np.testing.assert_allclose(P * v_gas, (gas.p_closed + P_AMB) * gas.v_closed,
                                   rtol=1e-12)
    assert press[-1].pressure * KPA_PER_MPA > plain.of("press")[-1].pressure * KPA_PER_MPA


def test_an_insert_on_a_support_or_inside_the_wall_is_refused(wall):
    base = wall.nodes_on("base")
    ins = RigidInsert("motor", base[:3], base[3:6], 0.0, 1.0, 10.0)
    with pytest.raises(ValueError, match="insert motor: a seat or top node is supported"):
        FEMModel.build(wall, MAT, insert=ins)
    ok = _insert(wall)
    low = RigidInsert("motor", ok.seat, ok.top, ok.z_bottom, ok.height + 0.5, 10.0)
    with pytest.raises(ValueError, match="insert motor: .* top node.* below its face"):
        FEMModel.build(wall, MAT, insert=low)
    with pytest.raises(ValueError, match="no seat node"):
        RigidInsert("motor", [], base[3:6], 0.0, 1.0, 10.0)
