"""The surrogate's learnt maps in NumPy: Gaussian processes on principal components
(fitted by :mod:`spsc.studies.surrogate.fit`), evaluated for many designs at once.

A block (one field of the map, or a part of one: a file may learn the low pressure levels of
every field apart from the others, ``F@0`` beside ``F@1``, each part holding the indices of the
field's outputs it predicts) is ``mean + scale · (c @ modes)`` with its mode coefficients
c(x) = k(x, X) α, the posterior mean of a Gaussian process with the Matérn 5/2 kernel
k = a (1 + √5 r + 5r²/3) e^{−√5 r}, r the distance scaled per ratio by the lengths ℓ (Rasmussen
& Williams 2006, eq. 4.17): by default one kernel serves every mode (:mod:`spsc.studies.
surrogate.fit`), evaluated once per design.
Its error scale is read from the neighbours: the root mean square of the leave-one-out
residuals (R&W eq. 5.12) of the training designs nearest the query — the GP's own error where
it had to predict a design it did not hold. (The posterior variance on a subset of the
training designs, tried first, was the prior's almost everywhere in five inputs: its samples
were maps with negative volumes.)
"""

from __future__ import annotations

import numpy as np

__all__ = ["matern52", "Block", "FieldModel", "NEIGHBOURS", "RISK_FLAG"]

#: training designs whose leave-one-out residuals make a query's error scale
NEIGHBOURS = 8
#: training designs whose snap-throughs make a query's snap risk, and the risk flagged
RISK_NEIGHBOURS, RISK_FLAG = 5, 0.45
#: designs evaluated together (bounds the m × n temporaries to a few MB each)
CHUNK = 512


def matern52(A: np.ndarray, B: np.ndarray, ell: np.ndarray) -> np.ndarray:
    """The unit Matérn 5/2 kernel between the rows of A and B, lengths ``ell``."""
    a, b = A / ell, B / ell
    d2 = (a * a).sum(1)[:, None] + (b * b).sum(1)[None, :] - 2.0 * a @ b.T
    r = np.sqrt(np.maximum(d2, 0.0)) * np.sqrt(5.0)
    return (1.0 + r + r * r / 3.0) * np.exp(-r)


class _Kernel:
    """One GP of a block: the mode columns ``cols`` it predicts, its ``ell``, ``amp`` and
    ``alpha`` (n × len(cols))."""

    def __init__(self, arrays: dict, key: str):
        g = lambda k: arrays[f"{key}.{k}"]  # noqa: E731
        self.cols, self.ell, self.amp = g("cols"), g("ell"), float(g("amp"))
        self.alpha = g("alpha")


class Block:
    """One field or part of one: ``mean``, ``scale`` (outputs), ``modes`` (k × outputs), each
    mode's standard deviation ``s`` (k), the GPs of its modes, the ``field`` it belongs to and
    the indices of that field's ``outputs`` it predicts (None: all)."""

    def __init__(self, arrays: dict, name: str, X: np.ndarray):
        g = lambda k: arrays[f"{name}.{k}"]  # noqa: E731
        self.mean, self.scale, self.modes, self.s = g("mean"), g("scale"), g("modes"), g("s")
        self.name, self.field_name = name, name.split("@")[0]
        self.outputs = arrays.get(f"{name}.outputs")
        self.kernels = [_Kernel(arrays, f"{name}.{j}") for j in range(int(g("groups")))]
        self.loo = g("loo").astype(float)
        self.X = X
        self._tree = None

    def std(self, x: np.ndarray, near: int = NEIGHBOURS) -> np.ndarray:
        """The modes' error scale (m × k): the root mean square of the leave-one-out
        residuals of the ``near`` training designs nearest ``x`` (distances scaled by the
        leading mode's lengths)."""
        ell = self.kernels[0].ell
        if self._tree is None:
            self._tree = _kdtree(self.X / ell)
        _, idx = self._tree.query(x / ell, k=near)
        return np.sqrt((self.loo[idx] ** 2).mean(axis=1)) * self.s

    def field(self, c: np.ndarray) -> np.ndarray:
        """The field (… × outputs) of mode coefficients ``c`` (… × k)."""
        return self.mean + self.scale * (c @ self.modes)


class FieldModel:
    """Every block of a fitted surrogate: the fields of :data:`BLOCKS`, or their parts named
    in the file's ``blocks``."""

    BLOCKS = ("dV", "F", "A", "H", "V0")

    def __init__(self, arrays: dict):
        self.free = [str(v) for v in arrays["free"]]
        self.X = arrays["X"]
        self.risk_X, self.risk = arrays["risk_X"], arrays["risk"]
        self._risk_tree = None
        names = [str(v) for v in arrays["blocks"]] if "blocks" in arrays else self.BLOCKS
        self.blocks = {b: Block(arrays, b, self.X) for b in names}
        self._sizes = {}  # a field's outputs, over its parts
        for b in self.blocks.values():
            self._sizes[b.field_name] = self._sizes.get(b.field_name, 0) + b.mean.size

        # the distinct kernels (a shared kernel is evaluated once for every block), each with
        # the mode coefficients of every block it serves side by side
        self._kernels, self._serves = [], []
        for name, b in self.blocks.items():
            for kn in b.kernels:
                j = next((i for i, k in enumerate(self._kernels)
                          if k.amp == kn.amp and np.array_equal(k.ell, kn.ell)), None)
                if j is None:
                    self._kernels.append(kn)
                    self._serves.append([])
                    j = len(self._kernels) - 1
                self._serves[j].append((name, kn.cols, kn.alpha))
        self._alpha = [np.hstack([a for _, _, a in serves]) for serves in self._serves]
        # each kernel's training designs scaled by its lengths (√5 folded in), and their
        # squared norms: r² = |x̃|² + |X̃|² − 2 x̃·X̃ is one matrix product per chunk
        # (centred on the training designs' mean: the expansion cancels less)
        self._centre = self.X.mean(axis=0)
        self._scaled = [(self.X - self._centre) * (np.sqrt(5.0) / kn.ell)
                        for kn in self._kernels]
        self._norms = [(Xs * Xs).sum(axis=1) for Xs in self._scaled]

    def coefficients(self, x: np.ndarray, chunk: int = CHUNK) -> dict:
        """{block: mode coefficients (m × k)} at the unit inputs ``x`` (m × d): every distinct
        kernel from one squared difference per chunk of ``chunk`` designs (the kernels differ
        only in their lengths), each times the coefficients of all the modes it serves."""
        out = {name: np.empty((x.shape[0], b.s.size)) for name, b in self.blocks.items()}
        for a in range(0, x.shape[0], chunk):
            xs = x[a:a + chunk]
            for j, serves in enumerate(self._serves):
                kn, Xs = self._kernels[j], self._scaled[j]
                q = (xs - self._centre) * (np.sqrt(5.0) / kn.ell)
                r = q @ Xs.T  # m × n: −2 x̃·X̃ + |x̃|² + |X̃|² in place, then √ (≥ 0)
                r *= -2.0
                r += (q * q).sum(axis=1)[:, None]
                r += self._norms[j][None, :]
                np.maximum(r, 0.0, out=r)
                np.sqrt(r, out=r)
                k = np.exp(-r)
                k *= 1.0 + r * (1.0 + r / 3.0)
                k *= kn.amp
                c = k @ self._alpha[j]
                start = 0
                for name, cols, alpha in serves:
                    out[name][a:a + chunk, cols] = c[:, start:start + alpha.shape[1]]
                    start += alpha.shape[1]
        return {name: c * self.blocks[name].s for name, c in out.items()}

    def fields(self, x: np.ndarray, draws: int = 0, rng=None) -> dict:
        """{field: (m, outputs)} at the unit inputs ``x`` (m × d), a field's parts put in
        their places; with ``draws`` > 0 also ``draws`` posterior samples of each,
        (draws, m, outputs)."""
        out = {}
        for name, c in self.coefficients(x).items():
            blk = self.blocks[name]
            values = [(blk.field_name, blk.field(c))]
            if draws:
                z = (rng or np.random.default_rng(0)).standard_normal((draws,) + c.shape)
                values.append((blk.field_name + ".draws", blk.field(c + z * blk.std(x))))
            for key, v in values:
                if blk.outputs is None:
                    out[key] = v
                else:
                    size = self._sizes[blk.field_name]
                    out.setdefault(key, np.empty(v.shape[:-1] + (size,)))[..., blk.outputs] = v
        return out

    def snap_risk(self, x: np.ndarray, levels: np.ndarray, k: int = RISK_NEIGHBOURS):
        """The share of the ``k`` training designs nearest each ``x`` (m × d) that snapped
        through, or could not be pressed over the map, at one of the pressure ``levels``
        (a boolean mask of the surrogate's levels, m × levels): (m,)."""
        if self._risk_tree is None:
            self._risk_tree = _kdtree(self.risk_X)
        _, near = self._risk_tree.query(x, k=k)
        return (self.risk[near] * levels[:, None, :]).max(axis=2).mean(axis=1)



def _kdtree(points: np.ndarray):
    """A k-d tree of ``points`` (scipy's: the nearest designs of thousands of queries at once
    without the queries × training distance matrix)."""
    from scipy.spatial import cKDTree

    return cKDTree(points)
