"""What ``spsc simulate`` writes: the trace (Parquet, CSV on request), the scenario echoed with
the code that ran it and how the run went, and a figure of the trace."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

__all__ = ["write", "figure"]


def _echo(sim) -> dict:
    from importlib.metadata import PackageNotFoundError, version

    from spsc.study.provenance import provenance

    try:
        release = version("spsc")
    except PackageNotFoundError:  # pragma: no cover - run from a bare checkout
        release = "unknown"

    m = sim.chamber_map
    return {"scenario": sim.scenario.source, "spsc": release,
            "code": provenance().describe(), "complete": sim.complete,
            "message": sim.message, "seconds": {k: round(v, 3) for k, v in sim.seconds.items()},
            "samples": int(len(sim.trace)),
            "valve_switches": [{"t_s": t, "valve": "open" if o else "closed", "why": why}
                               for t, o, why in sim.switches],
            "chamber_map": None if m is None else {
                "model": sim.scenario.chamber.model, "travel_mm": list(m.y_range),
                "pressure_kPa": list(m.pressure_range),
                "levels_kPa": [float(p) for p in m.pressure_kPa], "travels": int(m.y_mm.size)},
            "wall": {"viscous": sim.scenario.chamber.viscous,
                     "friction": sim.scenario.chamber.friction,
                     "vented": sim.scenario.vented, "stepped_in_time": m is None},
            "valve": {"C_dm3_s_bar": sim.scenario.valve.C, "b": sim.scenario.valve.b,
                      "m": sim.scenario.valve.m},
            **({"stiffness_steps": sim.stiffness_steps} if sim.stiffness_steps else {})}


def write(sim, out: Path, *, csv: bool = False, png: bool = True) -> list[Path]:
    """The files of a run in ``out`` (created): trace.parquet [trace.csv] scenario.json
    trace.png."""
    out.mkdir(parents=True, exist_ok=True)
    files = [out / "trace.parquet"]
    sim.trace.to_parquet(files[0], index=False)
    if csv:
        files.append(out / "trace.csv")
        sim.trace.to_csv(files[-1], index=False, float_format="%.9g")
    files.append(out / "scenario.json")
    files[-1].write_text(json.dumps(_echo(sim), indent=2, default=float) + "\n",
                         encoding="utf-8")
    if png and len(sim.trace):
        files.append(out / "trace.png")
        figure(sim, files[-1])
    return files


def _valve_shading(ax, t, is_open) -> None:
    edges = np.flatnonzero(np.diff(np.r_[0, is_open, 0]))
    for a, b in zip(edges[::2], edges[1::2]):
        ax.axvspan(t[a], t[min(b, len(t) - 1)], color="0.9", lw=0)


def _stiffness_panel(ax, t, d) -> None:
    ax.step(t, d.target_N_per_mm, "k--", where="post", lw=1, label="target")
    ax.plot(t, d.stiffness_N_per_mm, "C0", label="stiffness (quasi-static)")
    ax.set_ylabel("stiffness (N/mm)")
    ax.legend(loc="upper left")
    av = ax.twinx()
    av.plot(t, d.reservoir_volume_mm3 / 1e3, "C7:", label="reservoir")
    av.set_ylabel("reservoir volume (cm³)")
    av.legend(loc="lower right")


def figure(sim, path) -> None:
    """Travel and force, chamber and reservoir pressure (and the sensor's reading), the gas
    temperatures against time; the valve's open spans shaded."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = sim.trace
    t = d.t_s.to_numpy()
    control = "stiffness_N_per_mm" in d
    fig, axes = plt.subplots(3 + control, 1, figsize=(8, 7.5 + 2.5 * control), sharex=True,
                             constrained_layout=True)
    for ax in axes:
        _valve_shading(ax, t, d.valve_open.to_numpy())
    ax = axes[0]
    ax.plot(t, d.force_N, "C0", label="force")
    ax.set_ylabel("plate force (N)")
    ay = ax.twinx()
    ay.plot(t, d.y_mm, "C7--", label="travel")
    ay.set_ylabel("plate travel y (mm)")
    ax.legend(loc="upper left")
    ay.legend(loc="upper right")
    ax = axes[1]
    if "pressure_measured_kPa" in d:
        ax.plot(t, d.pressure_measured_kPa, color="C1", alpha=0.35, lw=0.8, label="sensor")
    ax.plot(t, d.pressure_kPa, "C1", label="chamber")
    if np.isfinite(d.reservoir_kPa).any():
        ax.plot(t, d.reservoir_kPa, "C2", label="reservoir")
    ax.set_ylabel("gauge pressure (kPa)")
    ax.legend(loc="best")
    if control:
        _stiffness_panel(axes[3], t, d)
    ax = axes[2]
    ax.plot(t, d.chamber_K - 273.15, "C3", label="chamber gas")
    if np.isfinite(d.reservoir_kPa).any():
        ax.plot(t, d.reservoir_K - 273.15, "C4", label="reservoir gas")
    ax.set_ylabel("temperature (°C)")
    axes[-1].set_xlabel("time (s); valve open: shaded")
    ax.legend(loc="best")
    title = "spsc simulate" + ("" if sim.complete else f" (stopped: {sim.message})")
    axes[0].set_title(title, fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_bode(table, summary, scenario, out: Path) -> list[Path]:
    """bode.parquet, bode.json (the summary and the scenario) and bode.png in ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    files = [out / "bode.parquet", out / "bode.json", out / "bode.png"]
    table.to_parquet(files[0], index=False)
    files[1].write_text(json.dumps({"summary": summary, "scenario": scenario.source}, indent=2,
                                   default=float) + "\n", encoding="utf-8")
    bode_figure(table, summary, files[2])
    return files


def bode_figure(table, summary, path) -> None:
    """Magnitude and phase of the dynamic stiffness and sensitivity against frequency."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f = table.f_Hz
    fig, axes = plt.subplots(2, 2, figsize=(9, 6), sharex=True, constrained_layout=True)
    for col, (mag, ph, label) in enumerate((
            ("stiffness_N_per_mm", "stiffness_phase_deg", "stiffness F̂/ŷ (N/mm)"),
            ("sensitivity_kPa_per_mm", "sensitivity_phase_deg", "sensitivity P̂/ŷ (kPa/mm)"))):
        style = "o-" if summary.get("wall") else "-"  # the stepped wall: few frequencies
        axes[0, col].semilogx(f, table[mag], style, color="C0", ms=4)
        axes[0, col].set_ylabel(label)
        axes[1, col].semilogx(f, table[ph], style, color="C1", ms=4)
        axes[1, col].set_ylabel("phase (°)")
        axes[1, col].set_xlabel("frequency (Hz)")
        if summary.get("sensitivity_halfway_Hz"):
            for r in range(2):
                axes[r, col].axvline(summary["sensitivity_halfway_Hz"], color="0.6", ls=":")
    valve = "open" if summary["valve_open"] else "closed"
    wall = f"; the wall {summary['wall']}" if summary.get("wall") else ""
    if "vented" in wall:
        valve = "none (vented)"
    fig.suptitle(f"small press about y = {summary['y_mm']:.3g} mm, valve {valve}, "
                 f"{summary['pressure_kPa']:.4g} kPa{wall}", fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
