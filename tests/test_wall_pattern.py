"""The wall tangent's fixed pattern (spsc.fem.wall.pattern) against SciPy's own COO → CSR
sum, on random blocks over a small node-major mesh."""

import numpy as np
import pytest
import scipy.sparse as sp
from numpy.testing import assert_allclose, assert_array_equal

from spsc.fem.wall.pattern import Pattern


def _blocks(rng, n_nodes, k, n_el, nodes_per_el):
    nodes = np.stack([rng.choice(n_nodes, nodes_per_el, replace=False) for _ in range(n_el)])
    return (k * nodes[:, :, None] + np.arange(k)).reshape(n_el, -1)


@pytest.mark.parametrize("k", [2, 3])
def test_pattern_sums_blocks_as_scipy_does(k):
    rng = np.random.default_rng(k)
    n_nodes = 40
    elements = _blocks(rng, n_nodes, k, 30, 6)
    patches = _blocks(rng, n_nodes, k, 7, 3)
    pat = Pattern(k * n_nodes, elements, patches, per_node=k)
    Ke = rng.standard_normal(elements.shape + elements.shape[1:])
    He = rng.standard_normal(patches.shape + patches.shape[1:])
    for values, blocks in (((Ke, He), (elements, patches)), ((Ke, None), (elements,))):
        rows = np.concatenate([np.repeat(d, d.shape[1], axis=1).ravel() for d in blocks])
        cols = np.concatenate([np.tile(d, (1, d.shape[1])).ravel() for d in blocks])
        vals = np.concatenate([v.ravel() for v in values if v is not None])
        ref = sp.coo_matrix((vals, (rows, cols)), shape=(pat.n,) * 2).toarray()
        K = pat.matrix(*values)
        assert K.has_sorted_indices
        # the same sums in another order: a few ulps
        assert_allclose(K.toarray(), ref, rtol=0, atol=1e-13)
    # the pattern holds exactly the coupled entries: no structural zero, none missing
    rows = np.concatenate([np.repeat(d, d.shape[1], axis=1).ravel() for d in (elements, patches)])
    cols = np.concatenate([np.tile(d, (1, d.shape[1])).ravel() for d in (elements, patches)])
    coupled = sp.coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(pat.n,) * 2).tocsr()
    coupled.sum_duplicates()
    assert_array_equal(pat.indptr, coupled.indptr)
    assert_array_equal(pat.indices, coupled.indices)


def test_pattern_refuses_blocks_that_are_not_whole_nodes():
    d = np.array([[0, 1, 2, 4, 5, 6]])  # node 1's unknowns start at 3, not 4
    with pytest.raises(ValueError, match="per_node = 3"):
        Pattern(9, d, per_node=3)


def test_without_numba_bincount_sums_the_same(monkeypatch):
    """The fallback (no Numba) sums the same values in the same order: bit for bit."""
    from spsc.fem.wall import pattern as pattern_module

    rng = np.random.default_rng(7)
    elements = _blocks(rng, 30, 3, 20, 5)
    patches = _blocks(rng, 30, 3, 6, 3)
    pat = Pattern(90, elements, patches, per_node=3)
    Ke = rng.standard_normal(elements.shape + elements.shape[1:])
    He = rng.standard_normal(patches.shape + patches.shape[1:])
    compiled = [pat.matrix(Ke, He).data, pat.matrix(Ke, None).data]
    monkeypatch.setattr(pattern_module, "AVAILABLE", False)
    assert_array_equal(pat.matrix(Ke, He).data, compiled[0])
    assert_array_equal(pat.matrix(Ke, None).data, compiled[1])
