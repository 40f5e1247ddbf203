"""Identical parts give identical files: STL and 3MF in a canonical triangle order with fixed
3MF UUIDs, STEP with a fixed header time stamp (a user can diff and cache their outputs)."""

import time

import numpy as np
import pytest
import trimesh

from spsc.cad.export import TriMesh, read_3mf, write_3mf, write_stl


def _shuffled(mesh: TriMesh, seed: int) -> TriMesh:
    """The same surface with vertices and triangles renumbered and each triangle's start
    rotated (orientation kept): what a parallel mesher may emit on another run."""
    rng = np.random.default_rng(seed)
    perm = rng.permutation(len(mesh.vertices))
    inv = np.empty_like(perm)
    inv[perm] = np.arange(len(perm))
    f = inv[mesh.faces][rng.permutation(len(mesh.faces))]
    roll = rng.integers(0, 3, len(f))
    f = np.stack([np.roll(row, r) for row, r in zip(f, roll)])
    return TriMesh(mesh.vertices[perm], f)


@pytest.fixture(scope="module")
def sphere() -> TriMesh:
    s = trimesh.creation.icosphere(subdivisions=3, radius=5.0)
    return TriMesh(np.asarray(s.vertices, float), np.asarray(s.faces, np.int64))


@pytest.mark.parametrize("write", [write_stl, write_3mf])
def test_same_surface_in_any_order_gives_the_same_bytes(sphere, write, tmp_path):
    a, b = _shuffled(sphere, 1), _shuffled(sphere, 2)
    assert not np.array_equal(a.faces, b.faces)
    suffix = ".stl" if write is write_stl else ".3mf"
    pa, pb = write(a, tmp_path / f"a{suffix}"), write(b, tmp_path / f"b{suffix}")
    assert pa.read_bytes() == pb.read_bytes()


def test_canonical_order_keeps_the_surface_and_its_orientation(sphere, tmp_path):
    c = _shuffled(sphere, 3).canonical()
    tm = trimesh.Trimesh(c.vertices, c.faces, process=False)
    assert tm.is_watertight and tm.is_winding_consistent
    np.testing.assert_allclose(tm.volume, trimesh.Trimesh(sphere.vertices, sphere.faces).volume,
                               rtol=1e-12)  # positive: still outward
    back = read_3mf(write_3mf(c, tmp_path / "c.3mf"))
    np.testing.assert_array_equal(back.faces, c.faces)
    # lib3mf keeps float32 coordinates and writes 6 decimals of a mm: ~1e-6 mm (measured
    # 1.01e-6 at most here)
    np.testing.assert_allclose(back.vertices, c.vertices, rtol=0, atol=2e-6)


@pytest.mark.slow
def test_step_of_two_runs_is_the_same(tmp_path):
    """Two processes (as two `spsc bladder` runs) a second apart write the same STEP bytes:
    OCCT would stamp each header with its wall-clock time."""
    import subprocess
    import sys

    script = ("import sys, cadquery as cq; from spsc.cad.export import write_step; "
              "write_step(cq.Solid.makeBox(1.0, 2.0, 3.0), sys.argv[1])")
    paths = [tmp_path / "a.step", tmp_path / "b.step"]
    for k, p in enumerate(paths):
        if k:
            time.sleep(1.1)
        subprocess.run([sys.executable, "-c", script, str(p)], check=True)
    assert paths[0].read_bytes() == paths[1].read_bytes()
    assert b"2000-01-01T00:00:00" in paths[0].read_bytes()


def test_a_3mf_written_and_read_leaves_the_locale_and_the_text_encoding(sphere, tmp_path):
    """lib3mf sets the C locale to "C" on write and read; after both, Python still writes and
    reads UTF-8 text by default (it fell to ASCII: a JSON with a "Δ" then failed)."""
    import locale

    from spsc.cad.meshload import load_mesh

    before = locale.setlocale(locale.LC_ALL), locale.getpreferredencoding(False)
    path = write_3mf(sphere, tmp_path / "s.3mf")
    read_3mf(path)
    load_mesh(path)
    assert (locale.setlocale(locale.LC_ALL), locale.getpreferredencoding(False)) == before
    (tmp_path / "t.txt").write_text("Δp ≤ 1 kPa")
    assert (tmp_path / "t.txt").read_text() == "Δp ≤ 1 kPa"
