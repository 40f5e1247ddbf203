"""The puncture figure: the probe's force and the largest stretch under its tip against the
tip's height above the base (log: the press through the dome and the pinch on the base
both show), one line per mesh, the material's stretch at break and where it is reached."""

from __future__ import annotations

__all__ = ["draw"]


def draw(runs, criterion, path, title: str | None = None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (af, al) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for r in runs:
        gap = r.clearance_mm - r.travel_mm
        keep = gap > 0
        af.semilogx(gap[keep], r.force_N[keep], "-", label=r.mesh.label)
        al.semilogx(gap[keep], r.stretch[keep], "-", label=r.mesh.label)
        if criterion is not None:
            f = r.failure(criterion)
            if f["reached"]:
                g = r.clearance_mm - f["travel_mm"]
                af.semilogx([g], [f["force_N"]], "kx", ms=9)
                al.semilogx([g], [criterion.stretch], "kx", ms=9)
    if criterion is not None:
        al.axhline(criterion.stretch, color="k", ls="--", lw=1,
                   label=f"stretch at break {criterion.stretch:g}")
    for ax in (af, al):
        ax.invert_xaxis()
        ax.set_xlabel("tip above the base (mm)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    af.set_ylabel("probe force (N)")
    al.set_ylabel("largest principal stretch λ₁ (under the tip)")
    name = runs[0].material
    fig.suptitle(title or f"{name}: the paper's puncture probe through the dome onto the base"
                 f" (×: the criterion reached)", fontsize=10)
    fig.savefig(path, dpi=120)
    plt.close(fig)
