"""Several shipped surrogates, one per design family: a design goes to the first whose domain
holds it, a batch is split among them and put back in its order, and a design none holds is
refused naming the parameter and every family's domain.

The second family here is a stand-in: the domes' own file relabelled as the surrogate of
l/w = 0.5 (its maps are the domes', so every answer it gives is checkable against them)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

import spsc.models.surrogate.predict as predict
from spsc.cad.geometry import SPSCGeometry
from spsc.core.errors import ParameterError
from spsc.core.setup import Setup
from spsc.materials import material
from spsc.models import get


@pytest.fixture
def two_families(tmp_path, monkeypatch):
    with np.load(predict.SHIPPED, allow_pickle=False) as z:
        arrays = {k: z[k] for k in z.files}
    meta = json.loads(str(arrays.pop("meta")))
    meta.update(name="wall-halfl", fixed={"l/w": 0.5})
    path = tmp_path / "wall-halfl.npz"
    np.savez(path, meta=np.array(json.dumps(meta)), **arrays)
    monkeypatch.setattr(predict, "SHIPPED_FILES", {"dome": predict.SHIPPED, "halfl": path})
    predict.surrogates.cache_clear()  # the shipped set is read once per process
    yield predict.load(str(path))
    predict.surrogates.cache_clear()


def _setup(l, pressure=30.0, reservoir=0.0):
    g = SPSCGeometry(w=10.0, h=12.0, l=l, t0=0.9, n1=2.2, n2=2.0, cy=0.1)
    return Setup.of(g, material("tpu60a"), pressure_kPa=pressure, stroke_mm=4.0, points=9,
                    reservoir_mm3=reservoir)


def test_each_design_goes_to_the_family_that_holds_it(two_families):
    dome, half = predict.load(), two_families
    assert predict.choose(None, [1.2, 0.0, 0.09, 2.2, 2.0, 0.1]) == (dome, "")
    assert predict.choose(None, [1.2, 0.5, 0.09, 2.2, 2.0, 0.1]) == (half, "")
    # within the fixed ratio's tolerance (a chamber drawn to 0.01 mm), not beyond it
    assert predict.choose(None, [1.2, 0.5004, 0.09, 2.2, 2.0, 0.1])[0] is half
    sur, why = predict.choose(None, [1.2, 0.3, 0.09, 2.2, 2.0, 0.1])
    assert sur is dome and why.startswith("l: l/w = 0 ") and "wall-halfl: l/w = 0.5" in why
    # a file given by the user answers alone
    assert predict.surrogates(str(predict.SHIPPED)) == (predict.load(str(predict.SHIPPED)),)


def test_a_batch_of_mixed_families_is_answered_in_its_order(two_families):
    model = get("surrogate")
    options = model.Options()
    setups = [_setup(0.0), _setup(5.0), _setup(0.0, 40.0, 20_000.0), _setup(5.0, 20.0)]
    many = model.curves_many(setups, options)
    # one design's coefficients and a batch's differ by round-off of ~1e-7 of a force: the
    # GP's α is large and cancels, and BLAS sums a vector product and a matrix product in
    # different orders (far below the surrogate's error, ~1e-3)
    close = dict(rtol=1e-6, atol=1e-9)
    for s, c in zip(setups, many):
        one = model.curves_many([s], options)[0]
        assert_allclose(c.force_N, one.force_N, **close)
        assert_allclose(c.pressure_kPa, one.pressure_kPa, **close)
        assert c.geometry["l"] == s.body.l and c.setup.p_i_kPa == s.load.pressure_kPa
    # the stand-in holds the domes' maps: a stadium of l/w = 0.5 answers as its dome does
    # at the same pressure, every length the same (the file cannot tell them apart)
    assert_allclose(many[1].force_N, many[0].force_N, **close)
    assert not np.allclose(many[3].force_N, many[1].force_N, rtol=1e-3)


def test_a_design_no_family_holds_is_refused_naming_each_domain(two_families):
    model = get("surrogate")
    with pytest.raises(ParameterError) as err:
        model.check(_setup(3.0), model.Options(), verb="curve", quiet=True)
    text = str(err.value)
    assert text.startswith("l = 3.0 is invalid") and "\n" not in text
    assert "wall-halfl: l/w = 0.5" in text


def test_the_table1_family_samples_its_shape_and_trains_its_corners_and_types():
    from spsc.cad.geometry import TYPES
    from spsc.models.surrogate.domain import BOUNDS, RATIOS
    from spsc.studies.surrogate.sample import geometry_of
    from spsc.studies.surrogate.train import anchor_points, design_points

    pts = design_points(64, 0, "table1")
    g = geometry_of(pts[5])
    assert (g.w, g.h, g.l, g.t0) == (11.0, 13.0, 3.0, 1.0)  # Table 1's, exactly
    for k, name in enumerate(RATIOS):
        lo, hi = BOUNDS[name]
        if name in ("n1", "n2", "cy"):
            assert lo <= pts[:, k].min() < pts[:, k].max() <= hi
    shapes = {tuple(r[3:]) for r in anchor_points("table1")}
    assert len(shapes) == 10 and all(tuple(map(float, TYPES[t])) in shapes for t in "ABCD")
    # the domes' sample is as before the families (its 2048-design study resumes)
    assert anchor_points("dome").shape == (0, 6)
    assert np.all(design_points(8, 0, "dome")[:, 1] == 0.0)
