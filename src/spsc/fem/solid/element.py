"""Quadratic (10-node) tetrahedron and 6-node triangle on whole arrays, with scikit-fem's rules.

Node order is VTK's (VTK_QUADRATIC_TETRA, VTK_QUADRATIC_TRIANGLE), so meshes go to ParaView as
they are: tetrahedron vertices 0–3, then edge midpoints (0,1), (1,2), (2,0), (0,3), (1,3), (2,3);
triangle vertices 0–2, then (0,1), (1,2), (2,0). Geometry is isoparametric: the edge nodes sit on
the curved surfaces.
"""

from __future__ import annotations

import numpy as np
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTet, RefTri

__all__ = ["TET_EDGES", "TRI_EDGES", "tet_rule", "tri_rule", "tet_p2", "tet_p1", "tri_p2"]

TET_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))
TRI_EDGES = ((0, 1), (1, 2), (2, 0))
#: the four faces of a tetrahedron as (vertex triple, its three edge numbers), each opposite the
#: vertex not in it
TET_FACES = (((1, 2, 3), (1, 5, 4)), ((0, 3, 2), (3, 5, 2)), ((0, 1, 3), (0, 4, 3)),
             ((0, 2, 1), (2, 1, 0)))


def tet_rule(order: int = 2):
    """Quadrature points (nq, 3) and weights (nq,) on the unit tetrahedron (scikit-fem)."""
    X, W = get_quadrature(RefTet, order)
    return X.T.copy(), W


def tri_rule(order: int = 4):
    """Quadrature points (nq, 2) and weights (nq,) on the unit triangle (scikit-fem)."""
    X, W = get_quadrature(RefTri, order)
    return X.T.copy(), W


def _quadratic(L, dL, edges):
    """Values (nq, n) and reference gradients (nq, n, d) of the Lagrange P2 basis from
    barycentric coordinates L (nq, m) with constant gradients dL (m, d)."""
    nq, m = L.shape
    N = [L[:, i] * (2 * L[:, i] - 1) for i in range(m)]
    dN = [np.outer(4 * L[:, i] - 1, dL[i]) for i in range(m)]
    for i, j in edges:
        N.append(4 * L[:, i] * L[:, j])
        dN.append(4 * (np.outer(L[:, j], dL[i]) + np.outer(L[:, i], dL[j])))
    return np.stack(N, axis=1), np.stack(dN, axis=1)


def _bary(X):
    L = np.column_stack([1.0 - X.sum(axis=1), X])
    d = X.shape[1]
    dL = np.vstack([-np.ones(d), np.eye(d)])
    return L, dL


def tet_p2(X):
    """P2 tetrahedron at reference points X (nq, 3): N (nq, 10), dN/dξ (nq, 10, 3)."""
    return _quadratic(*_bary(X), TET_EDGES)


def tet_p1(X):
    """P1 tetrahedron at reference points X (nq, 3): N (nq, 4) (for the pressure field)."""
    return _bary(X)[0]


def tri_p2(X):
    """P2 triangle at reference points X (nq, 2): N (nq, 6), dN/dξ (nq, 6, 2)."""
    return _quadratic(*_bary(X), TRI_EDGES)
