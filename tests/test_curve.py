"""The Curve result type: validation, JSON/CSV round trips, derivatives."""

import json

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.core.curve import CURVE_COLUMNS, SCHEMA, SCHEMA_VERSION, Curve, SolveInfo


def _curve(**kw):
    y = np.linspace(0.0, 6.0, 13)
    base = dict(y_mm=y, force_N=2.0 * y**2 + y, pressure_kPa=40.0 + 3.0 * y**2,
                contact_area_mm2=50.0 * y, volume_change_mm3=20.0 * y**2, model="membrane",
                geometry={"w": 11, "h": 13, "l": 3, "t0": 1, "n1": 2, "n2": 2.2, "cy": 0.6},
                material="tpu60a", setup={"p_i_kPa": 40, "reservoir_mm3": 0, "polytropic_n": 1},
                nominal_volume_mm3=6505.0, inflated_volume_mm3=7000.0, inflated_height_mm=14.9)
    base.update(kw)
    return Curve(**base)


def test_json_round_trip_keeps_everything(tmp_path):
    c = _curve()
    d = json.loads(c.to_json())
    assert list(d) == ["schema", "schema_version", "model", "geometry", "material", "setup",
                       "nominal_volume_mm3", "inflated_volume_mm3", "inflated_height_mm", "curve",
                       "solver", "metrics", "provenance"]
    assert (d["schema"], d["schema_version"]) == (SCHEMA, SCHEMA_VERSION)
    assert list(d["curve"]) == list(CURVE_COLUMNS) + ["converged", "message"]
    c2 = Curve.from_json(c.to_json(tmp_path / "c.json"))
    c3 = Curve.from_json(tmp_path / "c.json")
    for cc in (c2, c3):
        for k in CURVE_COLUMNS:
            np.testing.assert_array_equal(getattr(cc, k), getattr(c, k))
        assert cc.geometry == c.geometry and cc.setup == c.setup and cc.material == "tpu60a"
        assert cc.inflated_height_mm == 14.9


def test_nan_points_and_messages_round_trip(tmp_path):
    f = _curve().force_N.copy()
    f[-3:] = np.nan
    conv = np.isfinite(f)
    msg = tuple("" if ok else "no equilibrium" for ok in conv)
    c = _curve(force_N=f, converged=conv, message=msg)
    text = c.to_json()
    assert "NaN" not in text  # strict JSON: null, not NaN
    c2 = Curve.from_json(text)
    np.testing.assert_array_equal(c2.converged, conv)
    assert c2.message == msg and not c2.all_converged
    np.testing.assert_array_equal(np.isnan(c2.force_N), ~conv)
    c3 = Curve.from_csv(c.to_csv(tmp_path / "c.csv"))
    np.testing.assert_array_equal(c3.converged, conv)
    np.testing.assert_allclose(c3.force_N[conv], f[conv], rtol=0, atol=0)


def test_csv_round_trip_is_exact(tmp_path):
    c = _curve()
    c.to_csv(tmp_path / "x.csv")
    c2 = Curve.from_csv(tmp_path / "x.csv")
    for k in CURVE_COLUMNS:
        np.testing.assert_array_equal(getattr(c2, k), getattr(c, k))
    assert c2.model == "membrane" and c2.nominal_volume_mm3 == 6505.0


def test_derivatives_are_second_order_exact_on_quadratics():
    c = _curve()
    # np.gradient with edge_order=2 is exact for quadratics: tolerance is round-off only
    np.testing.assert_allclose(c.stiffness(), 4.0 * c.y_mm + 1.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(c.sensitivity(), 6.0 * c.y_mm, rtol=0, atol=1e-12)


@pytest.mark.parametrize("change, name", [
    (dict(force_N=np.zeros(3)), "len(force_N)"),
    (dict(y_mm=np.r_[0.0, 1.0, 1.0, *np.arange(2.0, 12.0)]), "y_mm[2]"),
])
def test_invalid_curves_are_one_line_errors(change, name):
    with pytest.raises(ParameterError) as e:
        _curve(**change)
    assert name in str(e.value) and "\n" not in str(e.value)


def test_solver_info_round_trips_and_is_derived_when_absent():
    info = SolveInfo(converged=False, message="press at y = 3 mm: no convergence",
                     y_reached_mm=2.5, instability="limit point near y = 2.7 mm", seconds=0.25,
                     iterations=42, notes=("slack core at y = 1 mm",), details={"dofs": 812})
    c = _curve(solver=info)
    c2 = Curve.from_json(c.to_json())
    assert c2.solver == info
    f = _curve().force_N.copy()
    f[5:] = np.nan
    derived = _curve(force_N=f, converged=np.isfinite(f),
                     message=tuple("" if np.isfinite(v) else "stalled" for v in f)).solver
    assert not derived.converged and derived.message == "stalled"
    assert derived.y_reached_mm == pytest.approx(2.0, abs=0)


def test_version_1_files_load_and_future_versions_fail_in_one_line():
    d = _curve().to_dict()
    v1 = {k: v for k, v in d.items() if k not in ("schema", "schema_version", "solver",
                                                  "metrics", "provenance")}
    c = Curve.from_dict(v1)
    assert c.all_converged and c.solver.converged
    with pytest.raises(ParameterError) as e:
        Curve.from_dict(d | {"schema_version": SCHEMA_VERSION + 1})
    assert "upgrade spsc" in str(e.value) and "\n" not in str(e.value)


def test_metrics_in_json_are_the_mean_slopes_and_null_when_not_converged():
    d = _curve().to_dict()
    # dF/dy = 4y + 1 on [0, 6]: its mean over the stroke is 4·3 + 1 = 13
    assert d["metrics"]["mean_stiffness_N_per_mm"] == pytest.approx(13.0, rel=1e-12)
    f = _curve().force_N.copy()
    f[-1] = np.nan
    d = _curve(force_N=f, converged=np.isfinite(f)).to_dict()
    assert d["metrics"]["mean_stiffness_N_per_mm"] is None


def test_mean_slopes_do_not_depend_on_the_sampling():
    # a stiffening curve F = y³ on [0, 6]: the mean of dF/dy over the stroke is 36 N/mm on any
    # grid (the mean of sampled slopes was 37.6 on 13 points and 36.8 on 25); a model run on
    # 25 points and the FEM on 13 compare without a grid bias
    for n in (13, 25, 7):
        y = np.linspace(0.0, 6.0, n)
        c = _curve(y_mm=y, force_N=y**3, pressure_kPa=40 + y**2, contact_area_mm2=0 * y,
                   volume_change_mm3=0 * y)
        assert c.mean_stiffness() == pytest.approx(36.0, rel=1e-12)
        assert c.mean_sensitivity() == pytest.approx(6.0, rel=1e-12)
    # reached=True: over the converged points from the start (a solve stopped at y = 3)
    f = y**3
    conv = y <= 3.0
    c = _curve(y_mm=y, force_N=np.where(conv, f, np.nan), pressure_kPa=40 + y**2,
               contact_area_mm2=0 * y, volume_change_mm3=0 * y, converged=conv)
    assert np.isnan(c.mean_stiffness())
    assert c.mean_stiffness(reached=True) == pytest.approx(9.0, rel=1e-12)


def test_an_even_y_grid_is_held_as_decimals_and_any_other_kept():
    # an even grid (np.linspace's rounding) becomes the decimals k * step, in JSON and CSV
    c = _grid_curve(np.linspace(0.0, 3.0, 21))
    assert c.y_mm[3] == 0.45 and Curve.from_json(c.to_json()).y_mm[3] == 0.45
    assert "0.45," in c.to_csv()
    # a non-terminating step keeps the correctly rounded float (not a 15-digit decimal)
    assert _grid_curve(np.linspace(0.0, 2.0, 4)).y_mm[2] == 4.0 / 3.0
    # an uneven grid (a bench's measured positions) is kept bit for bit
    y = np.array([0.0, 0.1, 0.44999999999999996, 0.7])
    assert np.array_equal(_grid_curve(y).y_mm, y)


def _grid_curve(y):
    z = np.zeros_like(y)
    return Curve(y_mm=y, force_N=z, pressure_kPa=z, contact_area_mm2=z, volume_change_mm3=z)
