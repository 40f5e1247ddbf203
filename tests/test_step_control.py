"""Step control of a press (:mod:`spsc.fem.engine.walk`): the first increment from first
contact (``Settings.onset_fraction``) and the regrowth of the increment after a cut
(``Settings.regrow_after``), observed on the plate travels Newton is asked to solve. The
recorded curve does not depend on them (its points are the same targets)."""

from __future__ import annotations

import sys

import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.fem.engine.result import NewtonFailure
from spsc.fem.engine.settings import Settings
from spsc.fem.solid.chamber import chamber_run, run_chamber
from spsc.materials import material

_walk = sys.modules["spsc.fem.engine.walk"]


def _press(tmp_path, monkeypatch, settings, points, too_long=None):
    """(curve, plate travels from first contact asked of Newton in the press (mm)). With
    ``too_long`` (mm) an increment longer than it past the first point fails."""
    z0, travels, newton, first_contact = [], [], _walk.newton, _walk.first_contact

    def touching(*args, **kwargs):
        z0.append(first_contact(*args, **kwargs))
        return z0[-1]

    def watched(model, x0, load, *args, **kwargs):
        if load.plate is None:
            return newton(model, x0, load, *args, **kwargs)
        travel = round(z0[0] - load.plate, 9)
        last = max((t for t, solved in travels if solved), default=0.0)
        if too_long is not None and last >= 1.0 and travel - last > too_long:
            travels.append((travel, False))
            raise NewtonFailure("injected: the increment is too long")
        sol = newton(model, x0, load, *args, **kwargs)
        travels.append((travel, True))
        return sol

    monkeypatch.setattr(_walk, "first_contact", touching)
    monkeypatch.setattr(_walk, "newton", watched)
    run = chamber_run(preset("B"), material("tpu60a"), pressure_kPa=40.0, stroke_mm=2.0,
                      points=points, mesh_size_mm=3.0, layers=1)
    curve, result, _ = run_chamber(run, settings=settings, cache_dir=tmp_path)
    assert result.converged, result.message
    return curve, [t for t, _ in travels]


def test_onset_fraction_sets_the_first_increment(tmp_path, monkeypatch):
    base, travels = _press(tmp_path, monkeypatch, Settings(), 5)
    assert travels[0] == pytest.approx(0.5)
    curve, travels = _press(tmp_path, monkeypatch, Settings(onset_fraction=0.25), 5)
    assert travels[:3] == pytest.approx([0.125, 0.375, 0.5])  # 1/4, doubled, clipped at 0.5
    assert_allclose(curve.force_N, base.force_N, rtol=1e-7, atol=1e-9)


@pytest.mark.parametrize("regrow, expected", [
    (1, [1.0, 2.0, 1.5, 1.25, 1.75, 1.5, 2.0, 1.75, 2.0]),  # four failures
    (2, [1.0, 2.0, 1.5, 1.25, 1.5, 2.0, 1.75, 2.0])])       # three
def test_increment_regrows_after_solved_ones(tmp_path, monkeypatch, regrow, expected):
    """Past 1 mm an increment longer than 0.3 mm fails: the nominal 1 mm is cut to 0.25 mm;
    with ``regrow_after`` 1 each solved increment doubles the next one (and it fails again),
    with 2 the increment doubles after two solved at its length."""
    _, travels = _press(tmp_path, monkeypatch, Settings(regrow_after=regrow), 3, 0.3)
    assert travels == pytest.approx(expected)


@pytest.mark.parametrize("kw, name", [({"onset_fraction": 0.0}, "onset_fraction"),
                                      ({"onset_fraction": 1.5}, "onset_fraction"),
                                      ({"regrow_after": 0}, "regrow_after"),
                                      ({"low_rank": -1}, "low_rank"),
                                      ({"low_rank": 2.5}, "low_rank")])
def test_bad_step_control_settings_are_refused_by_name(kw, name):
    with pytest.raises(ValueError, match=f"^{name} = "):
        Settings(**kw)
