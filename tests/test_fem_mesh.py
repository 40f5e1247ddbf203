"""Structured P2 meshes: exact planes, tags, volumes, isoparametric convergence, cache."""

import math

import numpy as np
import pytest

from spsc.cad.geometry import preset
from spsc.fem.solid.assembly import discretise
from spsc.fem.solid.mesh import TetMesh, block, cached_mesh, sphere_shell, spsc_wall
from spsc.fem.solid.pressure import CavitySurface


def test_sphere_volume_converges_at_isoparametric_rate():
    """Shell volume error of the P2 geometry falls like h⁴ (a straight-sided mesh: h²)."""
    exact = 4 / 3 * math.pi * (1.5**3 - 1.0)
    errs = []
    for n in (4, 8):
        m = sphere_shell(1.0, 1.5, n_theta=n, layers=1)
        errs.append(abs(8 * discretise(m.nodes, m.tets).volume() / exact - 1))
    order = math.log2(errs[0] / errs[1])
    assert order > 3.5, (errs, order)


@pytest.mark.parametrize("kind", "ABCD")
def test_spsc_wall_tags_and_cavity_volume(kind):
    g = preset(kind)
    m = spsc_wall(g, 1.5, layers=1)
    assert m.symmetry == 4
    X = m.nodes
    np.testing.assert_array_equal(X[m.nodes_on("base"), 2], 0.0)  # exact planes, no tolerance
    np.testing.assert_array_equal(X[m.nodes_on("sym_x"), 0], 0.0)
    np.testing.assert_array_equal(X[m.nodes_on("sym_y"), 1], 0.0)
    assert X[:, 0].min() >= 0 and X[:, 1].min() >= 0 and X[:, 2].min() >= 0
    # cavity nodes lie on the profile: r(z) in the revolved end / x(z) in the middle
    c = X[m.nodes_on("cavity")]
    rad = np.where(c[:, 1] > g.l / 2, np.hypot(c[:, 0], c[:, 1] - g.l / 2), c[:, 0])
    np.testing.assert_allclose(rad, g.radius_at(c[:, 2]), rtol=0, atol=2e-3 * g.w)
    # enclosed volume of the P2 cavity surface vs the analytic V_b,i (Table 1): the
    # isoparametric surface is accurate to ~1e-5 at this size
    vol = CavitySurface(m.facets["cavity"], 4).volume(X, np.zeros_like(X))
    np.testing.assert_allclose(vol, g.cavity_volume(), rtol=2e-4, atol=0)
    # wall volume: between cavity and outer surface, ≈ t0 × mean surface area
    wall = 4 * discretise(X, m.tets).volume()
    outer = CavitySurface(m.facets["outer"], 4).volume(X, np.zeros_like(X))
    np.testing.assert_allclose(wall, -outer - vol, rtol=1e-6, atol=0)


def test_full_model_is_four_quarters():
    g = preset("B")
    q, f = spsc_wall(g, 2.0, layers=1), spsc_wall(g, 2.0, layers=1, full=True)
    assert f.n_tets == 4 * q.n_tets and f.symmetry == 1
    assert set(f.facets) == {"base", "cavity", "outer"}
    vq = CavitySurface(q.facets["cavity"], 4).volume(q.nodes, 0 * q.nodes)
    vf = CavitySurface(f.facets["cavity"], 1).volume(f.nodes, 0 * f.nodes)
    np.testing.assert_allclose(vf, vq, rtol=1e-12, atol=0)


def test_block_tags():
    m = block((2.0, 1.0, 1.0), (2, 1, 1))
    assert m.n_tets == 12
    assert all(len(m.facets[t]) == 4 for t in ("y0", "y1", "z0", "z1"))
    np.testing.assert_allclose(discretise(m.nodes, m.tets).volume(), 2.0, rtol=1e-13)


def test_mesh_cache(tmp_path):
    calls = []

    def builder(g, size):
        calls.append(size)
        return spsc_wall(g, size, layers=1)

    a = cached_mesh(builder, cache_dir=tmp_path, g=preset("C"), size=3.0)
    b = cached_mesh(builder, cache_dir=tmp_path, g=preset("C"), size=3.0)
    cached_mesh(builder, cache_dir=tmp_path, g=preset("C"), size=2.5)
    assert calls == [3.0, 2.5]
    assert isinstance(b, TetMesh)
    np.testing.assert_array_equal(a.tets, b.tets)
    np.testing.assert_array_equal(a.facets["cavity"], b.facets["cavity"])


def test_mesh_save_is_atomic_and_a_damaged_cache_file_is_rebuilt(tmp_path, monkeypatch):
    """Workers share the mesh cache: a write that fails half-way leaves the old file whole and
    no debris (temporary file renamed over it); a damaged file is built again, not loaded."""
    old, new = block((1.0, 1.0, 1.0), (1, 1, 1)), block((2.0, 1.0, 1.0), (2, 1, 1))
    path = tmp_path / "m.npz"
    old.save(path)

    def half_written(f, **arrays):
        if not hasattr(f, "write"):  # given a path: writing in place
            with open(f, "wb") as g:
                g.write(b"PK\x03\x04 half a zip")
        else:
            f.write(b"PK\x03\x04 half a zip")
        raise OSError("disk full")

    monkeypatch.setattr(np, "savez_compressed", half_written)
    with pytest.raises(OSError, match="disk full"):
        new.save(path)
    monkeypatch.undo()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.npz"]
    np.testing.assert_array_equal(TetMesh.load(path).tets, old.tets)
    new.save(path)
    np.testing.assert_array_equal(TetMesh.load(path).tets, new.tets)

    calls = []

    def builder(cells):
        calls.append(cells)
        return block((1.0, 1.0, 1.0), (cells, 1, 1))

    cached_mesh(builder, cache_dir=tmp_path, cells=2)
    (cached,) = tmp_path.glob("builder-*.npz")
    cached.write_bytes(b"PK\x03\x04 truncated")
    m = cached_mesh(builder, cache_dir=tmp_path, cells=2)
    assert calls == [2, 2] and m.n_tets == 12
    np.testing.assert_array_equal(TetMesh.load(cached).tets, m.tets)
