"""The surrogate check's figure: the error's distribution, and where in the domain it grows."""

from __future__ import annotations

import numpy as np

__all__ = ["check_figure", "worst_figure"]

_INPUTS = (("h", "w", "h/w"), ("t0", "w", "t0/w"), ("n1", None, "n1"), ("n2", None, "n2"),
           ("cy", None, "c_y"), ("pressure_kPa", None, "p_i (kPa)"))


def check_figure(result: dict, path) -> None:
    """Histograms of the per-point errors (force, pressure rise) and each curve's largest
    force error against each input, both modes; PNG at ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows, pts = result["rows"], result["points"]
    fig, axes = plt.subplots(2, 4, figsize=(14, 6.5), constrained_layout=True)
    ax = axes[0, 0]
    bins = np.logspace(-5, 0, 41)
    for key, label in (("force", "force"), ("pressure", "pressure rise")):
        ax.hist(np.clip(pts[key], 1e-5, 1), bins=bins, histtype="step", label=label)
    ax.set_xscale("log")
    ax.set_xlabel("|error| / curve max (per point)")
    ax.set_ylabel("points")
    ax.legend(frameon=False)
    ax.set_title("surrogate vs wall model")
    for k, (a, b, label) in enumerate(_INPUTS):
        ax = axes.flat[k + 1]
        for mode, marker in (("high", "o"), ("low", "^")):
            sel = [r for r in rows if r["mode"] == mode]
            x = [r[a] / r[b] if b else r[a] for r in sel]
            ax.scatter(x, [100 * r["force_err"] for r in sel], s=9, marker=marker,
                       alpha=0.6, label=f"{mode} mode")
        ax.set_yscale("log")
        ax.set_xlabel(label)
        ax.set_ylabel("largest force error (%)")
    axes.flat[1].legend(frameon=False, fontsize=8)
    ax = axes.flat[-1]
    for key, label in (("stiffness_err", "mean stiffness"), ("sensitivity_err",
                                                             "mean sensitivity")):
        # a curve whose end the surrogate does not answer has no metric (NaN): left out
        ax.hist([100 * r[key] for r in rows if np.isfinite(r[key])], bins=30,
                histtype="step", label=label)
    ax.set_xlabel("error per curve (%)")
    ax.set_ylabel("curves")
    ax.legend(frameon=False, fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def worst_figure(surrogate, results: list[dict], rows: list[dict], path, count: int = 4):
    """The ``count`` curves with the largest force error, the wall model's beside the
    surrogate's (force and pressure over the travel, the stated error as a band); PNG at
    ``path``. Returns the rows drawn."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from spsc.studies.surrogate.check import MODES, beside

    worst = sorted(rows, key=lambda r: -r["force_err"])[:count]
    fig, axes = plt.subplots(2, len(worst), figsize=(3.6 * len(worst), 6), squeeze=False,
                             constrained_layout=True)
    answers = {id(res): s for res, s in beside(surrogate, results)}
    for k, r in enumerate(worst):
        res = next(x for x in results if id(x) in answers and x["geometry"]["w"] == r["w"]
                   and x["geometry"]["h"] == r["h"] and x["pressure_kPa"] == r["pressure_kPa"])
        s, j = answers[id(res)], [m for m, _ in MODES].index(r["mode"])
        w = res[r["mode"]]
        for ax, key, wkey, err, label in (
                (axes[0, k], "force_N", "F", "force_err_N", "force (N)"),
                (axes[1, k], "pressure_kPa", "P", "pressure_err_kPa", "pressure (kPa)")):
            ax.plot(w["y"], w[wkey], "k-", label="wall model")
            ax.plot(w["y"], s[key][j], "C5:", label="surrogate")
            ax.fill_between(w["y"], s[key][j] - s[err][j], s[key][j] + s[err][j],
                            color="C5", alpha=0.2, label="stated error")
            ax.set_ylabel(label)
            ax.set_xlabel("plate travel (mm)")
        g = res["geometry"]
        axes[0, k].set_title(f"{r['mode']} mode, {res['pressure_kPa']:.0f} kPa, force "
                             f"{100 * r['force_err']:.1f} %\nh/w {g['h'] / g['w']:.2f}, t0/w "
                             f"{g['t0'] / g['w']:.3f}, n1 {g['n1']:.2f}, n2 {g['n2']:.2f}, "
                             f"c_y {g['cy']:.2f}" + (", flagged" if r["flagged"] else ""),
                             fontsize=8)
    axes[0, 0].legend(frameon=False, fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return worst
