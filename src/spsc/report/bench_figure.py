"""The report's first figure: every model's headline mean beside the paper's bench mean, per
quantity and mode (the numbers of :func:`~.overview.bench_gap`). PNG, matplotlib (Agg)."""

from __future__ import annotations

from pathlib import Path

from spsc.report.overview import QUANTITIES

__all__ = ["bench_gap_figure"]


def bench_gap_figure(path, gap: dict) -> Path | None:
    """Horizontal bars of each model's mean (model = bench × (1 + relative difference)), the
    bench's mean a dashed line, one panel per quantity and mode; None when there is no gap
    to draw (the study's materials do not include the paper's)."""
    panels = [(q, mode, d) for q in QUANTITIES for mode, d in gap.get(q, {}).items()
              if d["models"]]
    if not panels:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(panels), figsize=(3.1 * len(panels), 2.9),
                             constrained_layout=True, squeeze=False)
    for ax, (q, mode, d) in zip(axes[0], panels):
        names = list(d["models"])
        values = [d["bench"] * (1.0 + d["models"][v]) for v in names]
        ax.barh(range(len(names)), values, color=["C3" if x < 0 else "C0"
                                                  for x in d["models"].values()])
        ax.axvline(d["bench"], color="k", ls="--", lw=1.2, label="paper bench")
        ax.set_yticks(range(len(names)))
        ax.set_yticklabels([d["names"][v].removeprefix("the ") for v in names]
                           if ax is axes[0][0] else [""] * len(names), fontsize=8)
        ax.invert_yaxis()
        ax.set_title(f"{QUANTITIES[q].lower()}, {mode} mode", fontsize=9)
        ax.set_xlabel(d["unit"], fontsize=8)
        ax.grid(axis="x", alpha=0.3)
    axes[0][0].legend(fontsize=7, loc="lower right")
    fig.suptitle("Headline means against the paper's bench (dashed; red: below it, blue: above)",
                 fontsize=10)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return Path(path)
