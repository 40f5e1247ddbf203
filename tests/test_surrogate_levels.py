"""The surrogate's pressure levels: a training run extended by the levels it lacks is the run
computed on the whole grid, bit for bit; a study of mixed grids is not fitted; a surrogate
file answers on its own grid (a file that does not state one: the sixteen even levels)."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_array_equal

from spsc.models.surrogate.domain import Q_LEVELS, Q_UNIFORM_16, TRAVELS
from spsc.studies.surrogate.sample import extend_run, levels_of, run_design

#: a dome of the trained hull (h/w, l/w, t0/w, n1, n2, c_y)
RATIOS = np.array([1.2, 0.0, 0.09, 2.0, 2.2, 0.0])
KEYS = ("top_mm", "free_volume_mm3", "volume_mm3", "force_N", "area_mm2", "pressure_kPa")


@pytest.fixture(scope="module")
def whole():
    return run_design(RATIOS, levels=[0.0, 0.1, 0.3])


def test_an_extended_run_is_the_run_of_the_whole_grid(whole):
    part = run_design(RATIOS, levels=[0.0, 0.3])
    grown = extend_run(part, levels=[0.0, 0.1, 0.3])
    for key in KEYS:
        assert_array_equal(grown[key], whole[key], err_msg=key)
    assert_array_equal(grown["q_levels"], [0.0, 0.1, 0.3])
    assert list(grown["messages"]) == list(whole["messages"])
    assert grown["seconds"] > part["seconds"]
    # nothing to add: the run itself
    again = extend_run(grown, levels=[0.0, 0.1, 0.3])
    for key in KEYS:
        assert_array_equal(again[key], whole[key], err_msg=key)


def test_a_run_of_a_study_before_the_levels_were_stored_has_them_from_its_pressures(whole):
    old = {k: v for k, v in whole.items() if k != "q_levels"}
    assert np.allclose(levels_of(old), [0.0, 0.1, 0.3], rtol=0, atol=1e-12)


def test_a_study_of_mixed_grids_is_refused(whole):
    from spsc.studies.surrogate.fit import fit_study

    other = run_design(RATIOS * [1.1, 1, 1, 1, 1, 1], levels=[0.0, 0.3])
    with pytest.raises(ValueError, match="different pressure levels"):
        fit_study([whole, other], free=["h/w", "t0/w", "n1", "n2", "cy"])


def test_the_grid_adds_low_levels_to_the_sixteen_even_ones():
    assert Q_LEVELS.size == 21 and np.all(np.diff(Q_LEVELS) > 0)
    assert np.all(np.isin(Q_UNIFORM_16, Q_LEVELS))
    assert Q_LEVELS[-1] == Q_UNIFORM_16[-1] and (Q_LEVELS < Q_UNIFORM_16[4]).sum() == 4 + 5


def test_a_surrogate_answers_on_its_files_grid():
    from spsc.models.surrogate.predict import Surrogate, load

    shipped = load()
    assert_array_equal(shipped.q_levels, Q_LEVELS)
    assert shipped.fields.risk.shape[1] == Q_LEVELS.size
    maps, _ = shipped.maps(np.array([[11.0, 13.0, 0.0, 1.0, 2.0, 2.2, 0.0]]), 5.0 / 3.0)
    assert maps.F.shape == (1, TRAVELS.size, Q_LEVELS.size) and maps.qgrid.x.size == 21
    # a file of an earlier version, which does not state its grid: the sixteen even levels
    arrays = {k: v for k, v in _arrays(shipped).items() if k not in ("q_levels", "travels")}
    legacy = Surrogate(arrays, shipped.meta)
    assert_array_equal(legacy.q_levels, Q_UNIFORM_16)
    assert_array_equal(legacy.travels, TRAVELS)


def _arrays(sur) -> dict:
    from spsc.models.surrogate.predict import SHIPPED

    with np.load(SHIPPED, allow_pickle=False) as z:
        return {k: z[k] for k in z.files if k != "meta"}


def _synthetic_runs(n: int, seed: int = 0) -> list[dict]:
    """Runs whose maps are smooth functions of the design (no wall model): ΔV, F, A over the
    travels × 21 levels, a different law below q = 0.2 than above."""
    from spsc.models.surrogate.domain import BOUNDS, RATIOS

    rng = np.random.default_rng(seed)
    runs = []
    for _ in range(n):
        r = np.array([rng.uniform(*BOUNDS[k]) if k != "l/w" else 0.0 for k in RATIOS])
        q, d = Q_LEVELS[None, :], TRAVELS[:, None]
        soft = np.where(q < 0.2, 1.0 + 3.0 * q * r[2] / 0.2, 1.6 + q * r[3])
        F = d * soft * (1.0 + 0.3 * r[0] + 0.1 * r[4])
        runs.append({"ratios": r, "q_levels": Q_LEVELS, "top_mm": 11 * (r[0] + 0.1 * Q_LEVELS),
                     "free_volume_mm3": 1000 * (1 + Q_LEVELS * r[5] + r[0]),
                     "volume_mm3": 1000 * (1 + q * r[5] + r[0]) - 100 * d * soft,
                     "force_N": F, "area_mm2": 50 * d * (1 + r[3] * q), "jumps": np.zeros((0, 3))})
    return runs


@pytest.mark.parametrize("split_q", [None, 0.2])
def test_a_field_learnt_in_parts_is_put_together_in_its_places(split_q):
    from spsc.models.surrogate.gp import FieldModel
    from spsc.models.surrogate.inputs import unit_inputs
    from spsc.studies.surrogate.fit import fields_of, fit_study

    free = ["h/w", "t0/w", "n1", "n2", "cy"]
    runs = _synthetic_runs(60)
    arrays = fit_study(runs, free=free, hyper_points=60, split_q=split_q)
    names = [str(b) for b in arrays["blocks"]]
    assert len(names) == (5 if split_q is None else 10)
    fm = FieldModel(arrays)
    x = unit_inputs(np.array([r["ratios"] for r in runs]), free)
    got = fm.fields(x, draws=2)
    for b in ("dV", "F", "A", "H", "V0"):
        want = np.array([fields_of(r)[b] for r in runs])
        # the GP interpolates its training designs up to its fitted noise: 1e-3 of the range
        assert np.abs(got[b] - want).max() <= 1e-3 * np.ptp(want), b
        assert got[b + ".draws"].shape == (2,) + want.shape


def test_a_press_that_runs_off_the_map_says_so_not_that_the_gas_law_failed():
    """A closed dome whose last travels need more travel than the map holds at the pressure
    they reach (a sweep row of 100 000): those points are the map's limit, named as such."""
    from spsc.cad.geometry import SPSCGeometry
    from spsc.core.setup import Setup
    from spsc.materials import material
    from spsc.models import get

    g = SPSCGeometry(w=9.25976294186, h=11.6508517933, l=0.0, t0=0.873834130774,
                     n1=2.30862849189, n2=3.5891785049, cy=0.00452865563331)
    setup = Setup.of(g, material("tpu60a"), pressure_kPa=17.5368825473, stroke_mm=6.0,
                     points=25)
    entry = get("surrogate")
    curve = entry.curve(setup, entry.Options()).curve
    off = ~np.asarray(curve.converged)
    assert off.any() and not off[:20].any()
    assert all("beyond the surrogate's map" in m for m, o in zip(curve.message, off) if o)
    assert all("did not converge" not in m for m in curve.message)


def test_the_check_scores_what_the_surrogate_answers_and_counts_the_rest():
    """A point the surrogate marks past its map (NaN in its curve) is counted, not scored;
    a curve whose end it does not answer has no mean stiffness or sensitivity to compare."""
    from spsc.studies.surrogate.check import compare, summary

    y = np.linspace(0.0, 4.0, 5)
    wall = {"y": y, "F": 2.0 * y, "P": 40.0 + y, "converged": np.ones(5, bool), "jumps": 0,
            "instability": "", "seconds": 1.0}
    case = {"geometry": {"w": 11.0, "h": 13.0, "l": 0.0, "t0": 1.0, "n1": 2.0, "n2": 2.2,
                         "cy": 0.0}, "pressure_kPa": 40.0, "polytropic_n": 1.0,
            "stroke_mm": 4.0, "points": 5, "high": wall, "low": wall}

    class Stub:
        def curves(self, params, mu, y, p_i, reservoir, n, draws=0, rng=None):
            F, P = np.array([2.0 * y[0] * 1.01] * 2), np.array([40.0 + y[0]] * 2)
            F[:, -1] = 1e9  # the last point ran off the map: a value no user sees
            inside = np.ones((2, 5), bool)
            inside[:, -1] = False
            return {"force_N": F, "pressure_kPa": P, "force_err_N": np.ones((2, 5)),
                    "pressure_err_kPa": np.ones((2, 5)), "converged": np.ones((2, 5), bool),
                    "inside": inside, "snap_risk": np.zeros(2)}

    result = compare(Stub(), [case])
    s = summary(result)
    assert s["unanswered_points"] == 2
    assert result["points"]["force"].size == 8  # 4 answered points of each mode
    # the largest answered error: 1 % of F = 6 N at y = 3 mm, over the wall's largest 8 N
    assert s["force"]["max"] == pytest.approx(0.01 * 6.0 / 8.0, rel=1e-12)
    assert all(np.isnan(r["stiffness_err"]) for r in result["rows"])
