"""The figure of ``spsc fit-material``: one panel per test (uniaxial, equibiaxial, planar), the
data as markers and every fitted law as a line: solid over a test the user supplied, dashed
where it is the law's prediction of a test that was not (as Abaqus' material evaluation shows
them), so a law that fits one test and is absurd in another is seen at once."""

from __future__ import annotations

import numpy as np

__all__ = ["plot_fits"]

_TITLES = {"uniaxial": "uniaxial tension", "equibiaxial": "equibiaxial tension",
           "planar": "planar tension (pure shear)"}


def _panel(ax, test, fits, tests, lam_max, chosen) -> None:
    data = [d for d in tests if d.test == test]
    hi = max((float(d.stretch.max()) for d in data), default=lam_max)
    lam = np.linspace(1.0, hi, 200)
    ymax = max((float(d.stress_MPa.max()) for d in data), default=0.0)
    for d in data:
        ax.plot(d.stretch, d.stress_MPa, "ko", ms=4, mfc="none", label=f"data: {d.file_label}")
    tops = []
    for k, (name, f) in enumerate(fits.items()):
        if f is None:
            continue
        with np.errstate(over="ignore", invalid="ignore"):
            P = f.stress(test, lam)
        tops.append(float(np.max(P[np.isfinite(P)])) if np.any(np.isfinite(P)) else 0.0)
        label = name + (" → material file" if name == chosen else "")
        if data and test in f.r2:
            label += f" (R² {f.r2[test]:.3f})"
        if not f.drucker.stable:
            label += ", Drucker-unstable"
        ax.plot(lam, P, "-" if data else "--", color=f"C{k}", lw=2.0 if name == chosen else 1.2,
                label=label)
    top = 1.25 * ymax if data else 1.25 * float(np.median(tops)) if tops else 1.0
    top = top if np.isfinite(top) and top > 0 else 1.0
    ax.set_ylim(-0.05 * top, top)
    ax.set_xlim(1.0, hi)
    ax.set_xlabel("stretch λ")
    ax.set_ylabel("nominal stress (MPa)")
    ax.set_title(_TITLES[test] + ("" if data else "\n(not tested: predictions, dashed)"),
                 fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def plot_fits(fits: dict, tests, path, *, chosen: str | None = None, title: str = "") -> None:
    """Write the figure of ``fits`` (law name -> LawFit or None) against ``tests`` to ``path``
    (any format matplotlib writes, by suffix)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from spsc.materials.fit.laws import TESTS

    lam_max = max(float(d.stretch.max()) for d in tests)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), constrained_layout=True)
    for ax, test in zip(axes, TESTS):
        _panel(ax, test, fits, tests, lam_max, chosen)
    fig.suptitle(title or "spsc fit-material: data (markers), fits (solid), predictions "
                 "(dashed)", fontsize=11)
    fig.savefig(path, dpi=110)
    plt.close(fig)
