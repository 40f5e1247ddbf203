"""The time domain's chamber map from the surrogate against the wall model's own map, as the
surrogate tests compare them."""

from __future__ import annotations

import numpy as np
from numpy.testing import assert_allclose


def assert_maps_agree(geometry, travels, pressures, *, force_share: float,
                      setup_kPa: float = 40.0, top_kPa: float = 80.0) -> None:
    """:func:`~spsc.dynamics.surrogate_map.surrogate_map` and
    :func:`~spsc.dynamics.chamber_map.build_map` of ``geometry`` in TPU 60A, up to the last
    of ``travels`` (mm): at each travel and each of ``pressures`` (kPa), volumes within 0.5 %
    and forces within ``force_share`` of the wall map's largest."""
    from spsc.dynamics.chamber_map import build_map
    from spsc.dynamics.surrogate_map import surrogate_map
    from spsc.materials import material

    m = material("tpu60a")
    kw = dict(setup_kPa=setup_kPa, top_kPa=top_kPa, y_max_mm=max(travels))
    s, w = surrogate_map(geometry, m, **kw), build_map(geometry, m, **kw)
    p = np.asarray(pressures, float)
    for y in travels:
        a, b = s.at(y), w.at(y)
        assert_allclose(a.volume(p), b.volume(p), rtol=5e-3)
        assert_allclose(a.force(p), b.force(p), rtol=0, atol=force_share * w.force_N.max())
