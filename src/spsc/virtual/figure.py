"""The figure of a virtual scene's trace (``spsc virtual``'s trace.png): what the scene did,
each pad's force, its pressure as the sensor read it; the valve's switches as dashed lines and
the object's slips shaded."""

from __future__ import annotations

import numpy as np

__all__ = ["scene_figure"]


def _switches(ax, t, valve):
    v = np.asarray(valve, bool)
    for x in t[1:][v[1:] != v[:-1]]:
        ax.axvline(x, color="C3", lw=0.8, ls="--")


def scene_figure(kind: str, trace: dict, path) -> None:
    """Draw ``trace`` (of :func:`~spsc.virtual.plate.press_plate` or
    :func:`~spsc.virtual.gripper.run_gripper`) to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = trace["t_s"]
    pads = sorted(int(k.rsplit("_", 1)[1]) for k in trace if k.startswith("force_N_"))
    fig, ax = plt.subplots(3, 1, figsize=(8.5, 7.5), sharex=True, constrained_layout=True)
    if kind == "gripper":
        ax[0].plot(t, trace["opening_mm"], label="jaws' faces apart")
        ax[0].plot(t, trace["lift_mm"], label="hand lifted")
        ax[0].plot(t, trace["object_z_mm"], label="object lifted")
        ax[0].set_ylabel("mm")
        ax[0].legend(frameon=False, fontsize=8, loc="upper right")
    else:
        ax[0].plot(t, trace["travel_mm_1"])
        ax[0].set_ylabel("plate travel (mm)")
    for i in pads:
        ax[1].plot(t, trace[f"force_N_{i}"], label=f"pad {i}")
        ax[2].plot(t, trace[f"sensor_kPa_{i}"], ".", ms=1.2, color=f"C{i - 1}", alpha=0.4)
        ax[2].plot(t, trace[f"pressure_kPa_{i}"], color=f"C{i - 1}", label=f"pad {i} (true; "
                   "dots: as read)")
        slip = np.asarray(trace.get(f"slipping_{i}", np.zeros(t.size)), bool)
        if slip.any():
            ax[1].fill_between(t, 0, 1, where=slip, transform=ax[1].get_xaxis_transform(),
                               color=f"C{i - 1}", alpha=0.12, lw=0,
                               label=f"pad {i}: the object slips")
    ax[1].set_ylabel("contact force (N)")
    ax[2].set_ylabel("pressure (kPa gauge)")
    ax[2].set_xlabel("time (s)")
    for a in ax[1:]:
        a.legend(frameon=False, fontsize=8)
    for a in ax:
        a.grid(alpha=0.3)
        _switches(a, t, trace["valve_open"])
    ax[0].set_title(f"spsc virtual: {kind} scene (dashed: the valve switched)", fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
