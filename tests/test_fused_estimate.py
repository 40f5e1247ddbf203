"""The fused fingertip's fast estimate (issue 14): the pressed chamber by a fast model with the
other chambers' gas as an equivalent reservoir."""

from __future__ import annotations

import pytest
from numpy.testing import assert_allclose

from spsc.cad.specs import FingertipSpec
from spsc.core.errors import ParameterError
from spsc.materials import material
from spsc.studies.fused import AMBIENT_KPA, _curve, compliance, fused_estimate

SPEC = FingertipSpec()
MAT = material("silicone40a")


def test_without_other_chambers_it_is_the_model_with_the_channel_as_reservoir():
    c = fused_estimate(SPEC.pulp, [], MAT, pressure_kPa=40, channel_mm3=500.0, model="membrane")
    ref = _curve("membrane", SPEC.pulp, MAT, 40, 500.0, 3.0, 7)
    assert_allclose(c.force_N, ref.force_N, rtol=1e-12)
    assert_allclose(c.pressure_kPa, ref.pressure_kPa, rtol=1e-12)
    assert c.setup["fused"]["equivalent_reservoir_mm3"] == 500.0


def test_a_compliant_chamber_counts_as_its_volume_plus_p_times_its_compliance():
    v, cmp = compliance("membrane", SPEC.distal, MAT, 40.0)
    assert v > SPEC.distal.cavity_volume() and cmp > 0  # it inflates, and more with pressure
    c = fused_estimate(SPEC.pulp, [SPEC.distal], MAT, pressure_kPa=40, channel_mm3=100.0,
                       model="membrane")
    eq = c.setup["fused"]["equivalent_reservoir_mm3"]
    assert_allclose(eq, 100.0 + v + (40 + AMBIENT_KPA) * cmp, rtol=1e-12)
    stiff = fused_estimate(SPEC.pulp, [], MAT, pressure_kPa=40, channel_mm3=100.0 + v,
                           model="membrane")
    # the breathing chamber softens the gas spring: less pressure rise than a rigid one
    assert c.pressure_kPa[-1] < stiff.pressure_kPa[-1]


def test_only_fast_models():
    with pytest.raises(ParameterError, match="^model = 'fem' is invalid: allowed wall or membrane"):
        fused_estimate(SPEC.pulp, [], MAT, pressure_kPa=40, channel_mm3=0.0, model="fem")
