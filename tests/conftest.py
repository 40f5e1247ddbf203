"""Test-session switches.

``SPSC_SKIP_MESH_LUCK=1`` (set by ``.ci/run``) skips the cases marked ``mesh_luck``: they pass
or fail with the unstructured mesh fTetWild happens to produce on a run, which differs from
run to run and from machine to machine. They stay in ``make test-slow`` / ``make test-all``.
"""

from __future__ import annotations

import os

import pytest


def pytest_collection_modifyitems(config, items):
    if os.environ.get("SPSC_SKIP_MESH_LUCK") != "1":
        return
    skip = pytest.mark.skip(reason="mesh_luck: converges on some fTetWild meshes only "
                            "(SPSC_SKIP_MESH_LUCK=1)")
    for item in items:
        if "mesh_luck" in item.keywords:
            item.add_marker(skip)


@pytest.fixture
def counted_chamber(tmp_path, monkeypatch):
    """settings -> (curve, factorisations) of a coarse Type B chamber curve (40 kPa, 3 mm in 6
    points, 3 mm × 1 layer): the 3D engine's factorisations counted where its Newton step
    makes them."""
    import sys

    from spsc.cad.geometry import preset
    from spsc.fem.engine.linsolve import factorize
    from spsc.fem.solid.chamber import chamber_run, run_chamber
    from spsc.materials import material

    count = [0]

    def counting(*args, **kwargs):
        count[0] += 1
        return factorize(*args, **kwargs)

    monkeypatch.setattr(sys.modules["spsc.fem.engine.linear"], "factorize", counting)
    run = chamber_run(preset("B"), material("tpu60a"), pressure_kPa=40.0, stroke_mm=3.0,
                      points=7, mesh_size_mm=3.0, layers=1)

    def curve(settings):
        count[0] = 0
        out, result, _ = run_chamber(run, settings=settings, cache_dir=tmp_path)
        assert result.converged, result.message
        return out, count[0]

    return curve
