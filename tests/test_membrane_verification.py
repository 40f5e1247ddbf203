"""The box-scheme solver against an independent discretisation of the same membrane problem
(``tests/verify/membrane_fe.py``: linear finite elements on the CAD polyline, total-potential
minimisation with the relaxed (tension-field) energy, plate as a bound, nodal reactions)."""

import math

import numpy as np
import pytest

from spsc.cad.geometry import preset
from verify.membrane_fe import AxisymmetricFE
from spsc.membrane.materials import material, mooney_rivlin
from spsc.membrane.solver import solve

TPU = material("tpu60a")


def _compare(g, mat, p_kPa, ys, vr=0.0, n=200, max_iter=60):
    r = solve(g, mat, pressure_kPa=p_kPa, reservoir_mm3=vr, stroke_mm=max(ys), points=len(ys) + 1)
    assert r.converged, r.message
    fe = AxisymmetricFE(g, mat, n)
    st = fe.inflate(1e-3 * p_kPa)
    out, prev = [], st
    for k, y in enumerate(r.curve.y_mm[1:], start=1):
        sh = r.shapes[k]
        # the FE walks the stroke too (warm start from its previous position)
        s = prev = fe.press(prev, st.eta[0] - y, reservoir=vr, p_i=st.p, v_i=st.volume,
                            max_iter=max_iter)
        f_box = 1e-3 * sh.pressure_kPa * math.pi * sh.contact_radius**2  # revolved part
        out.append((y, sh.pressure_kPa, 1e3 * s.p, f_box, s.force))
    return r, st, np.array(out)


@pytest.mark.parametrize("t, size, mat, p", [("A", "table1", TPU, 40), ("B", "table1", TPU, 40),
                                             ("C", "table1", TPU, 40), ("D", "table1", TPU, 40),
                                             ("B", "GS1", material("elastic50a"), 10),
                                             ("D", "GS1", mooney_rivlin(0.3, 0.1), 20)])
def test_inflated_volume_matches_the_fe_model(t, size, mat, p):
    g = preset(t, size)
    r = solve(g, mat, pressure_kPa=p, stroke_mm=0.0)
    fe = AxisymmetricFE(g, mat, 200).inflate(1e-3 * p)
    v_box, v_fe = r.curve.inflated_volume_mm3, fe.volume
    # the issue asks 0.5 % on the volume; both are O(h²) (FE: 200 elements, box: 192
    # intervals) so they agree far better, and the volume *increase* is held to 1 %
    np.testing.assert_allclose(v_box, v_fe, rtol=5e-3)
    v0 = g.cavity_volume()
    np.testing.assert_allclose(v_box - v0, v_fe - v0, rtol=1e-2)
    np.testing.assert_allclose(r.curve.inflated_height_mm, fe.eta[0], rtol=1e-3)


def test_contact_matches_the_fe_model_at_small_stroke():
    _, _, out = _compare(preset("B"), TPU, 40, [1.5])
    y, p_box, p_fe, f_box, f_fe = out.T
    # 1 % asked; observed ~1e-5 (p) and ~1e-4 (F, nodal reaction vs p·A)
    np.testing.assert_allclose(p_box, p_fe, rtol=1e-2)
    np.testing.assert_allclose(f_box, f_fe, rtol=1e-2)


def test_pure_dome_curve_matches_the_fe_model():
    """With l = 0 the Curve itself (F = p·A with the deformed contact radius) is compared."""
    g = preset("B", l=0.0)
    r = solve(g, TPU, pressure_kPa=40, stroke_mm=1.0, points=2)
    fe = AxisymmetricFE(g, TPU, 200)
    s = fe.press(fe.inflate(0.04), r.curve.inflated_height_mm - 1.0)
    c = r.curve
    # 1 % asked; observed < 1e-3 (nodal reactions vs p·πρ_Γ²)
    np.testing.assert_allclose(c.force_N[-1], s.force, rtol=1e-2)
    np.testing.assert_allclose(c.pressure_kPa[-1], 1e3 * s.p, rtol=1e-2)
    np.testing.assert_allclose(c.volume_change_mm3[-1], fe.inflate(0.04).volume - s.volume, rtol=1e-2)


@pytest.mark.slow
@pytest.mark.parametrize("t, vr", [("A", 0.0), ("B", 0.0), ("C", 0.0), ("D", 0.0), ("D", 40000.0)])
def test_contact_over_the_stroke_matches_the_fe_model(t, vr):
    """Over the stroke the cap flattens into a slack core (tension-field theory); both models
    must agree there too: force and pressure within 1 %."""
    _, _, out = _compare(preset(t), TPU, 40, [2.0, 4.0, 6.0], vr=vr)
    y, p_box, p_fe, f_box, f_fe = out.T
    np.testing.assert_allclose(p_box, p_fe, rtol=1e-2)
    np.testing.assert_allclose(f_box, f_fe, rtol=1e-2)
