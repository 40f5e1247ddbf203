"""The wall tangent's fixed sparsity: every element block (and the cavity's volume-Hessian
blocks, which lie inside them) summed into one CSR pattern, found once per model.

The pattern is found on the nodes (a node pair couples all their unknowns, ``per_node`` of
them, node-major): the swept wall's 92k node pairs sorted instead of its 830k unknown pairs
(75 → 22 ms a Table 1 stadium model; each design of a sweep builds two). Each iteration's
values are summed into it in the blocks' order by one compiled loop (:func:`_scatter`;
``np.bincount`` with weights where Numba is absent, the same sums in the same order):
2.2 → 0.8 ms a stadium tangent (issue 26's profile).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..material_kernel import AVAILABLE, njit

__all__ = ["Pattern"]


@njit(cache=True)
def _scatter(data, positions, values):
    for i in range(positions.size):
        data[positions[i]] += values[i]


def _node_pairs(n_nodes, blocks, per_node):
    """(node-pair CSR indptr, its column nodes, each block entry's node-pair index)."""
    nodes = [d[:, ::per_node] // per_node for d in blocks]
    keys = [(np.repeat(e, e.shape[1], axis=1) * n_nodes + np.tile(e, (1, e.shape[1]))).ravel()
            for e in nodes]
    uniq, inv = np.unique(np.concatenate(keys), return_inverse=True)
    ptr = np.searchsorted(uniq, np.arange(n_nodes + 1) * n_nodes)
    return ptr, uniq % n_nodes, np.split(inv.ravel(), np.cumsum([k.size for k in keys])[:-1])


class Pattern:
    """The CSR pattern of ``n`` unknowns, ``per_node`` to a node (node-major: unknown
    ``per_node · node + c``), coupled by the dense ``blocks`` (each an array of element
    unknowns whose node groups are complete and in order)."""

    def __init__(self, n: int, *blocks, per_node: int):
        k = per_node
        for d in blocks:
            groups = d.reshape(len(d), -1, k)
            if n % k or np.any(groups != groups[:, :, :1] + np.arange(k)) \
                    or np.any(groups[:, :, 0] % k):
                raise ValueError(f"per_node = {k}: the blocks' unknowns are not whole nodes")
        n_nodes = n // k
        ptr, cols, pairs = _node_pairs(n_nodes, blocks, k)
        degree = np.diff(ptr)
        # unknown row k·a + c holds k·degree(a) entries: node b's columns k·b … k·b + k − 1
        row_start = (k * k * ptr[:-1])[:, None] + k * degree[:, None] * np.arange(k)
        self.n, self.nnz = n, int(k * k * ptr[-1])
        self.indptr = np.append(row_start.ravel(), self.nnz).astype(np.int32)
        # entry j of row k·a + c is column k·cols[ptr[a] + j // k] + j % k
        row = np.repeat(np.arange(n), np.diff(self.indptr))
        j = np.arange(self.nnz) - self.indptr[row]
        self.indices = (k * cols[ptr[row // k] + j // k] + j % k).astype(np.int32)
        self.positions = []
        for d, p in zip(blocks, pairs):
            ne, m = d.shape
            a, c = (d // k)[:, :, None], (d % k)[:, :, None]
            first = k * k * ptr[a] + c * k * degree[a]  # where each entry's row starts
            pair = p.reshape(ne, m // k, 1, m // k, 1) - ptr[d[:, ::k] // k][:, :, None, None,
                                                                                 None]
            pair = np.broadcast_to(pair, (ne, m // k, k, m // k, k)).reshape(ne, m, m)
            self.positions.append((first + k * pair + (d % k)[:, None, :]).ravel())
        self._joined = {}  # the bincount fallback's positions of the blocks present, joined

    def matrix(self, *values) -> sp.csr_matrix:
        """The CSR matrix of the blocks' ``values`` (each the size of its block array; None:
        that block absent)."""
        data = np.zeros(self.nnz)
        if AVAILABLE:
            for v, pos in zip(values, self.positions):
                if v is not None:
                    _scatter(data, pos, np.ascontiguousarray(v).ravel())
        else:  # no Numba: the same sums in the same order (tested by forcing it)
            present = tuple(v is not None for v in values)
            pos = self._joined.get(present)
            if pos is None:
                pos = self._joined[present] = np.concatenate(
                    [p for p, there in zip(self.positions, present) if there])
            data = np.bincount(pos, weights=np.concatenate(
                [v.ravel() for v in values if v is not None]), minlength=self.nnz)
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))
