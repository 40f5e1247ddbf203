"""``spsc fatigue --png`` and the durability study: the wall's section coloured by the squeeze cycle's strain-energy
amplitude (the largest along the sweep), the hot spot marked, the life in the title."""

from __future__ import annotations

import numpy as np

__all__ = ["draw"]

#: each Q2 element (scikit-fem's local order: corners 0-3, edge midpoints 4-7, centre 8) in
#: eight triangles
_TRIANGLES = np.array([[0, 4, 8], [0, 8, 7], [4, 1, 5], [4, 5, 8], [8, 5, 2], [8, 2, 6],
                       [7, 8, 6], [7, 6, 3]])


def draw(cycle, geometry, law, life: float, path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.tri import Triangulation

    sec = cycle.section
    xy, elements = sec["nodes"], sec["elements"]
    tri = Triangulation(xy[:, 0], xy[:, 1], elements[:, _TRIANGLES].reshape(-1, 3))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.8), constrained_layout=True)
    for ax, (name, label) in zip(axes, (("energy_amplitude", "strain-energy amplitude (MPa)"),
                                        ("stretch_max", "largest principal stretch"))):
        values = cycle.on_section(name)
        art = ax.tripcolor(tri, values, shading="gouraud", cmap="magma")
        fig.colorbar(art, ax=ax, label=label, shrink=0.85)
        peak = cycle.fields.peak(name)
        ax.plot(peak["radius_mm"], peak["height_mm"], marker="o", mfc="none", mec="cyan",
                ms=12, mew=2, label=f"peak {peak['value']:.3g} ({peak['face']} face)")
        for line, style in ((sec["cavity"], ":"), (sec["outer"], "-")):
            ax.plot(xy[line, 0], xy[line, 1], style, color="0.5", lw=0.8)
        ax.axhspan(0.0, geometry.t0, color="0.85", zorder=0,
                   label="within t0 of the clamped base (singular corner, left out)")
        ax.set_aspect("equal")
        ax.set_xlabel("distance from the axis (mm)")
        ax.set_ylabel("height above the base (mm)")
        ax.legend(loc="lower left", fontsize=7)
    s = cycle.setup
    bound = "≥ " if law.runout else ""
    fig.suptitle(f"{s['material']}, {s['pressure_kPa']:g} kPa, V_r {s['reservoir_mm3']:g} mm³, "
                 f"squeeze 0 → {s['stroke_mm']:g} mm: life {bound}{life:.3g} cycles "
                 f"(F = {law.exponent:g}, calibrated on Table 2)", fontsize=10)
    fig.savefig(path, dpi=130)
    plt.close(fig)
