"""Figures of the fingertip study (:mod:`.fingertip_fem`): the curves, the pocket forces, whether
pressure or pockets tell a pulp press from a distal one, and renders of the pressed part."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from spsc.studies.fingertip import RENDERED, case_name

__all__ = ["curves_figure", "pockets_figure", "discrimination_figure", "render_part",
           "draw_all"]

_MODE_STYLE = {"high": "-", "low": "--"}
_P_COLOR = {10.0: "C0", 40.0: "C3"}


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _arr(v):
    return np.array([np.nan if x is None else x for x in v], float)


def curves_figure(summary: dict, path) -> Path:
    """P(y) and F(y) of the pulp and distal presses: FEM (markers), the fast estimate (thin)
    and the single Type A chamber (dotted), both modes, both setup pressures."""
    plt = _plt()
    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5), constrained_layout=True)
    for j, site in enumerate(("pulp", "distal")):
        for row in summary["cases"].values():
            if row["site"] != site:
                continue
            c, ls = _P_COLOR.get(row["pressure_kPa"], "k"), _MODE_STYLE[row["mode"]]
            lab = f"{row['mode']}, {row['pressure_kPa']:g} kPa"
            for i, key in enumerate(("pressure_kPa", "force_N")):
                a = ax[i, j]
                fem = row["fem"]
                y = np.array(fem["y_mm"])
                a.plot(y, _arr(fem[key]), ls, color=c, marker="o", ms=3, label=f"FEM {lab}")
                if "fast" in row:
                    a.plot(y, _arr(row["fast"][key]), ls, color=c, lw=0.8, alpha=0.7)
                if "single" in row:
                    a.plot(y, _arr(row["single"][key]), ":", color=c, lw=1.2)
        ax[0, j].set_title(f"{site} press (markers: fused FEM; thin: fast estimate; "
                           "dotted: single Type A)", fontsize=9)
        ax[0, j].set_ylabel("gauge pressure (kPa)")
        ax[1, j].set_ylabel("plate force (N)")
        for a in ax[:, j]:
            a.set_xlabel("plate travel y (mm)")
            a.grid(alpha=0.3)
        if ax[0, j].get_legend_handles_labels()[0]:  # a site with no case has nothing to name
            ax[0, j].legend(fontsize=7)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def pockets_figure(summary: dict, path) -> Path:
    """The force each FSR pocket transmits against plate travel, pulp and distal press (high
    mode, 40 kPa), with the plate force for scale."""
    plt = _plt()
    fig, ax = plt.subplots(1, 2, figsize=(11, 4), constrained_layout=True)
    for a, site in zip(ax, ("pulp", "distal")):
        row = summary["cases"].get(case_name(site, "high", 40.0))
        if row is None:
            a.axis("off")
            continue
        fem = row["fem"]
        y = np.array(fem["y_mm"])
        a.plot(y, _arr(fem["force_N"]), "k-", lw=2, label="plate")
        for k, (name, v) in enumerate(fem["pockets_N"].items()):
            a.plot(y, _arr(v), "o-", ms=3, color=f"C{k}", label=name)
        a.set_title(f"{site} press, high mode, 40 kPa: force through each FSR pocket",
                    fontsize=9)
        a.set_xlabel("plate travel y (mm)")
        a.set_ylabel("force (N)")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def discrimination_figure(summary: dict, path) -> Path:
    """Left: pressure rise against plate force for pulp and distal presses — one cavity, one
    pressure: a given rise comes from a light pulp press or a harder distal one, so the
    pressure alone tells neither where nor how hard. Right: the pocket forces at the same
    pressure rise — their pattern says where."""
    plt = _plt()
    fig, ax = plt.subplots(1, 2, figsize=(11, 4), constrained_layout=True)
    rows = {site: summary["cases"].get(case_name(site, "high", 40.0))
            for site in ("pulp", "distal")}
    common = []
    for site, row in rows.items():
        if row is None:
            continue
        fem = row["fem"]
        p = _arr(fem["pressure_kPa"])
        ax[0].plot(_arr(fem["force_N"]), p - p[0], "o-", ms=3, label=f"{site} press")
        common.append(np.nanmax(p - p[0]))
    ax[0].set_xlabel("plate force (N)")
    ax[0].set_ylabel("pressure rise (kPa)")
    ax[0].set_title("the pressure sensor: one rise, two forces (high mode, 40 kPa)", fontsize=9)
    ax[0].grid(alpha=0.3)
    if common:
        ax[0].legend(fontsize=8)
    else:  # a study of other cases (--cases): say so rather than draw an empty legend
        ax[0].text(0.5, 0.5, "no high-mode 40 kPa case in this study", ha="center",
                   va="center", transform=ax[0].transAxes, fontsize=9)
    if common:
        level = 0.8 * min(common)
        names, width = None, 0.38
        for k, (site, row) in enumerate(rows.items()):
            if row is None:
                continue
            fem = row["fem"]
            p = _arr(fem["pressure_kPa"])
            rise = p - p[0]
            ok = np.isfinite(rise)
            names = list(fem["pockets_N"])
            vals = [float(np.interp(level, rise[ok], _arr(v)[ok])) for v in fem["pockets_N"].values()]
            ax[1].bar(np.arange(len(names)) + (k - 0.5) * width, vals, width, label=f"{site} press")
        ax[1].set_xticks(np.arange(len(names or [])), names or [])
        ax[1].set_ylabel("pocket force (N)")
        ax[1].set_title(f"what the FSRs see at the same pressure rise ({level:.2g} kPa)",
                        fontsize=9)
        ax[1].legend(fontsize=8)
        ax[1].grid(alpha=0.3, axis="y")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def render_part(vtu, png, *, window=(720, 540)) -> Path:
    """Off-screen render of a whole part's VTU warped by its displacement, coloured by |u|,
    with the plate (perpendicular to the VTU's ``plate_normal``) at its deformed touch point."""
    import warnings

    import pyvista as pv

    grid = pv.read(str(vtu))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        surf = grid.extract_surface(nonlinear_subdivision=1)
    warped = surf.warp_by_vector("displacement")
    warped["|u| (mm)"] = np.linalg.norm(warped["displacement"], axis=1)
    n = np.asarray(grid.field_data.get("plate_normal", [0.0, 0.0, -1.0]), float)
    pts = np.asarray(warped.points)
    top = pts[np.argmin(pts @ n)]
    size = float(np.ptp(pts, axis=0).max())
    with pv.vtk_verbosity("off"):
        pl = pv.Plotter(off_screen=True, window_size=window)
        pl.add_mesh(warped, scalars="|u| (mm)", cmap="viridis", smooth_shading=True,
                    scalar_bar_args={"title": "|u| (mm)", "vertical": True})
        pl.add_mesh(pv.Plane(center=top, direction=-n, i_size=0.8 * size, j_size=0.8 * size),
                    color="lightgray", opacity=0.35)
        pl.camera_position = "iso"
        pl.set_background("white")
        pl.screenshot(str(png))
        pl.close()
    return Path(png)


def draw_all(summary: dict, out) -> dict:
    """Every figure of the study into ``out/figures``; {name: path relative to out}."""
    out = Path(out)
    fig = out / "figures"
    fig.mkdir(parents=True, exist_ok=True)
    made = {"curves": curves_figure(summary, fig / "curves.png"),
            "pockets": pockets_figure(summary, fig / "pockets.png"),
            "discrimination": discrimination_figure(summary, fig / "discrimination.png")}
    for site, mode, p in RENDERED:
        vtu_dir = out / "vtu" / case_name(site, mode, p)
        vtus = sorted(vtu_dir.glob("step-*-press.vtu"))
        if vtus:
            made[f"render-{site}"] = render_part(vtus[-1], fig / f"render-{site}.png")
    return {k: str(Path(v).relative_to(out)) for k, v in made.items()}
