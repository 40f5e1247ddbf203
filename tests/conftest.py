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
