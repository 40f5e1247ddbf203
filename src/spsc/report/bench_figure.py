"""The report's first figure: every model's headline mean beside the paper's bench mean, per
quantity and mode (the numbers of :func:`~.overview.bench_gap`). PNG, matplotlib (Agg)."""

from __future__ import annotations

from pathlib import Path

from spsc.report.overview import QUANTITIES

__all__ = ["bench_gap_figure"]


def bench_gap_figure(path, gap: dict, band: dict | None = None) -> Path | None:
    """Horizontal bars of each model's mean (model = bench × (1 + relative difference)), the
    bench's mean a dashed line, one panel per quantity and mode; the wall model's P5–P95 under
    the declared tolerances as a whisker with its median when ``band`` (the report's band
    section) has it. None when there is no gap to draw (the study's materials do not include
    the paper's)."""
    panels = [(q, mode, d) for q in QUANTITIES for mode, d in gap.get(q, {}).items()
              if d["models"]]
    if not panels:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(panels), figsize=(3.1 * len(panels), 3.2),
                             constrained_layout=True, squeeze=False)
    for ax, (q, mode, d) in zip(axes[0], panels):
        names = list(d["models"])
        values = [d["bench"] * (1.0 + d["models"][v]) for v in names]
        ax.barh(range(len(names)), values, color=["C3" if x < 0 else "C0"
                                                  for x in d["models"].values()])
        ax.axvline(d["bench"], color="k", ls="--", lw=1.2, label="paper bench")
        row = next((r for r in (band or {}).get("rows", []) if r["key"] == f"{q}_{mode}"), None)
        if row is not None and "wall" in names:
            k = names.index("wall")
            ax.errorbar([row["p50"]], [k], xerr=[[row["p50"] - row["p5"]],
                                                 [row["p95"] - row["p50"]]],
                        fmt="o", color="k", ms=3, capsize=3, lw=1.2,
                        label="wall: P5–P50–P95 of prints")
        ax.set_yticks(range(len(names)))
        ax.set_yticklabels([d["names"][v].removeprefix("the ") for v in names]
                           if ax is axes[0][0] else [""] * len(names), fontsize=8)
        ax.invert_yaxis()
        ax.set_title(f"{QUANTITIES[q].lower()}, {mode} mode", fontsize=9)
        ax.set_xlabel(d["unit"], fontsize=8)
        ax.grid(axis="x", alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=7, loc="outside lower center", ncol=len(labels))
    title = "Headline means against the paper's bench (dashed; red: below it, blue: above)"
    if band and band.get("rows"):
        title += "\nwhisker: the wall model's band under the declared print and material scatter"
    fig.suptitle(title, fontsize=10)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return Path(path)
