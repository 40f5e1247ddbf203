"""The surrogate's fit: the wall maps of a training study (:mod:`.train`) turned into the
arrays of a :class:`~spsc.models.surrogate.gp.FieldModel`.

Each field of the map — the volume given up ΔV = V0(q) − V(δ, q), the plate force F(δ, q) and
the contact area A(δ, q) on the travels × levels grid, and the inflated top H(q) and free volume
V0(q) per level — is made dimensionless by the exact similarities of
:mod:`spsc.models.surrogate.domain` (F / (μ t0 w), V / w³, A / w², H / w), standardised and
compressed by a principal component analysis (the modes that hold all but 1e-6 of its
variance). Each mode is then a Gaussian process of the design ratios (a Matérn 5/2 kernel with one
length per ratio and a white-noise term for the mesh's own scatter between neighbouring
designs, its hyperparameters found by scikit-learn): by default every mode of every block shares
the kernel found on the leading mode of the force (``shared="F"``: one kernel, one Cholesky
factor, and at prediction one kernel row per design for all 300-odd modes); with
``shared=None`` the leading ``own_kernels`` modes of each block have their own and the rest
share the first's. The shared kernel was the better on the held-out wall curves (design
decisions, "The surrogate") and 35 × less work to evaluate. Each mode's leave-one-out residuals
at the training designs are kept: the model's error estimate reads its neighbours'.

The levels below :data:`SPLIT_Q` (0.12) are learnt apart from the others: every field in two parts,
each with its own components and its own kernel (found on its force's leading mode). At low
q a thin wall's bending gives way to its tension and the maps change fastest between
designs: their leave-one-out errors were ten to a hundred times those of the higher levels,
under the one kernel whose lengths the smooth high levels set (design decisions, "The
surrogate").

Designs the wall model could not mesh or press over the whole grid are left out and counted;
designs that snap through stay in (their jump is the map's) and are kept as a flag the model
reads back for its neighbours.
"""

from __future__ import annotations

import numpy as np

from spsc.models.surrogate.domain import MU_REF_MPA, TRAVELS, W_REF_MM
from spsc.models.surrogate.inputs import unit_inputs

__all__ = ["fields_of", "fit_study", "BLOCKS", "SPLIT_Q"]

#: the map's blocks, in the order a FieldModel stores them
BLOCKS = ("dV", "F", "A", "H", "V0")


def fields_of(run: dict) -> dict[str, np.ndarray] | None:
    """The dimensionless blocks of one training run (each flattened, travels fastest), or
    None if the run is incomplete."""
    if "error" in run or not np.all(np.isfinite(run["force_N"])):
        return None
    r = run["ratios"]
    w, t0 = W_REF_MM, r[2] * W_REF_MM
    V0 = run["free_volume_mm3"]
    return {"dV": ((V0[None, :] - run["volume_mm3"]) / w**3).ravel(order="F"),
            "F": (run["force_N"] / (MU_REF_MPA * t0 * w)).ravel(order="F"),
            "A": (run["area_mm2"] / w**2).ravel(order="F"),
            "H": run["top_mm"] / w, "V0": V0 / w**3}


def _pca(Y: np.ndarray, keep: float):
    mean, scale = Y.mean(axis=0), Y.std(axis=0)
    scale = np.where(scale > 1e-12 * max(scale.max(), 1e-300), scale, 1.0)
    Z = (Y - mean) / scale
    _, s, vt = np.linalg.svd(Z, full_matrices=False)
    energy = np.cumsum(s**2) / np.sum(s**2)
    k = int(np.searchsorted(energy, 1.0 - keep) + 1)
    return mean, scale, vt[:k], Z @ vt[:k].T


def _kernel_fit(X, y, seed, hyper_points: int):
    """(length scales, signal variance, noise variance) of a Matérn 5/2 + white GP on the
    leading mode, found by scikit-learn on at most ``hyper_points`` designs."""
    import warnings

    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import ConstantKernel, Matern, WhiteKernel

    rng = np.random.default_rng(seed)
    pick = rng.permutation(len(X))[:hyper_points]
    kernel = ConstantKernel(1.0, (1e-3, 1e3)) * Matern(
        np.full(X.shape[1], 0.5), (1e-2, 1e2), nu=2.5) + WhiteKernel(1e-4, (1e-9, 1e-1))
    s = y.std()
    with warnings.catch_warnings():
        # a bound reached (a length at its top: the mode ignores that input) is an answer
        warnings.simplefilter("ignore", ConvergenceWarning)
        gp = GaussianProcessRegressor(kernel, normalize_y=False, n_restarts_optimizer=1,
                                      random_state=seed).fit(X[pick], y[pick] / s)
    k = gp.kernel_
    return np.asarray(k.k1.k2.length_scale, float), float(k.k1.k1.constant_value), \
        float(k.k2.noise_level)


#: the levels below this q are learnt apart from the rest (their own components and kernel):
#: chosen among 0.12, 0.16 and 0.2 (and no split) on the calibration designs, not the check's
SPLIT_Q = 0.12


def fit_study(runs: list[dict], *, free: list[str], keep: float = 1e-6, seed: int = 0,
              hyper_points: int = 400, shared: str | None = "F", own_kernels: int = 8,
              split_q: float | None = SPLIT_Q) -> dict:
    """The arrays of a FieldModel fitted to ``runs`` (:func:`.train.load_runs`): one kernel
    for every mode, found on the leading mode of block ``shared``, or (``shared=None``) own
    kernels for the ``own_kernels`` leading modes of each block. With ``split_q``, the
    levels below it and the others are two parts of every field (``F@0``, ``F@1``), each with
    its own components and kernels (None: one part, the fields whole)."""
    from .sample import levels_of

    usable = [(r, f) for r in runs if (f := fields_of(r)) is not None]
    X = unit_inputs(np.array([r["ratios"] for r, _ in usable]), free)
    grid = levels_of(usable[0][0])
    for r, _ in usable:
        lv = levels_of(r)
        if lv.shape != grid.shape or not np.allclose(lv, grid, atol=1e-9):
            raise ValueError(f"runs of different pressure levels ({lv.size} and "
                             f"{grid.size}): extend the study first (spsc surrogate train)")
    if shared is not None and shared not in BLOCKS:
        raise ValueError(f"shared: one of {', '.join(BLOCKS)}, or None ({shared!r} here)")
    out = {"free": np.array(free), "X": X, "excluded": np.array(len(runs) - len(usable)),
           "q_levels": grid, "travels": np.asarray(TRAVELS, float),
           "risk_X": unit_inputs(np.array([r["ratios"] for r in runs]), free),
           "risk": _risk(runs, grid.size)}
    if split_q is None or not 0 < np.sum(grid < split_q) < grid.size:
        parts = [("", None)]
    else:
        parts = [("@0", grid < split_q), ("@1", grid >= split_q)]
    nt = len(TRAVELS)
    for suffix, low in parts:
        cols = {b: None if low is None else np.flatnonzero(
            np.repeat(low, nt) if b in ("dV", "F", "A") else low) for b in BLOCKS}
        data = {b: np.array([f[b] if cols[b] is None else f[b][cols[b]] for _, f in usable])
                for b in BLOCKS}
        _fit_part(out, X, data, suffix, cols, keep=keep, seed=seed, hyper_points=hyper_points,
                  shared=shared, own_kernels=own_kernels)
    out["blocks"] = np.array([b + suffix for suffix, _ in parts for b in BLOCKS])
    return out


def _risk(runs, levels: int) -> np.ndarray:
    """Where the wall model snapped or could not press: every design, per level (1 for all
    levels of a design it could not mesh or press over the whole grid: it is left out of the
    fit, a hole in the training designs at every level; marking only its failed levels
    unflagged a check curve 42 % off)."""
    risk = np.zeros((len(runs), levels))
    for i, r in enumerate(runs):
        if fields_of(r) is None:
            risk[i] = 1.0
            continue
        for level, _, _ in r.get("jumps", np.zeros((0, 3))):
            risk[i, int(level)] = 1.0
    return risk


def _fit_part(out, X, data, suffix, cols, *, keep, seed, hyper_points, shared, own_kernels):
    """The components and Gaussian processes of every block of one part (``data``: block ->
    designs × its outputs), into ``out`` under the names block + ``suffix``."""
    pcs = {b: _pca(data[b], keep) for b in BLOCKS}
    if shared is not None:
        common = _Factor(X, *_kernel_fit(X, pcs[shared][3][:, 0], seed, hyper_points))
    for b in BLOCKS:
        name = b + suffix
        mean, scale, modes, C = pcs[b]
        s = C.std(axis=0)
        out.update({f"{name}.mean": mean, f"{name}.scale": scale, f"{name}.modes": modes,
                    f"{name}.s": s})
        if cols[b] is not None:
            out[f"{name}.outputs"] = cols[b]
        if shared is not None:
            groups = [list(range(C.shape[1]))]
        else:
            groups = [[k] for k in range(min(own_kernels, C.shape[1]))]
            if C.shape[1] > own_kernels:
                groups.append(list(range(own_kernels, C.shape[1])))
        loo = np.empty_like(C)
        for g, gcols in enumerate(groups):
            f = common if shared is not None else _Factor(
                X, *_kernel_fit(X, C[:, gcols[0]], seed, hyper_points))
            alpha, loo[:, gcols] = f.solve(C[:, gcols] / s[gcols])
            out.update({f"{name}.{g}.cols": np.array(gcols), f"{name}.{g}.ell": f.ell,
                        f"{name}.{g}.amp": np.array(f.amp),
                        f"{name}.{g}.noise": np.array(f.noise), f"{name}.{g}.alpha": alpha})
        out[f"{name}.groups"] = np.array(len(groups))
        out[f"{name}.loo"] = loo.astype(np.float32)


class _Factor:
    """The Cholesky factor of a kernel's matrix on the training designs, and its solves."""

    def __init__(self, X, ell, amp, noise):
        from spsc.models.surrogate.gp import matern52

        self.ell, self.amp, self.noise = ell, amp, noise
        self.L = np.linalg.cholesky(amp * matern52(X, X, ell) + noise * np.eye(len(X)))
        # the diagonal of K⁻¹, for the leave-one-out residuals
        self.kinv_diag = (np.linalg.solve(self.L, np.eye(len(X))) ** 2).sum(axis=0)

    def solve(self, Y):
        """(α = K⁻¹ Y, the leave-one-out residuals α_i / (K⁻¹)_ii, R&W 2006, eq. 5.12)."""
        alpha = np.linalg.solve(self.L.T, np.linalg.solve(self.L, Y))
        return alpha, alpha / self.kinv_diag[:, None]
