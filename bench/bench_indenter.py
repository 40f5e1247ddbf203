"""Curved indenters (``--indenter``): the figures of issue 27 and the contact patches.

1. ``plate``: a sphere of R = 1e4 mm against the plate on the Type B dome (Table 1 footprint,
   l = 0), 40 kPa closed, 3 mm: the largest relative difference of force and pressure rise
   at y = 1-3 mm, wall model and 3D FEM.
2. ``sphere``: R = 10 mm on the dome's axis, 4 mm: wall model against 3D FEM at y = 1-4 mm.
3. ``bodies``: the Table 1 Type B chamber (the stadium, l = 3 mm) at 40 kPa pressed 3 mm by
   the plate, a sphere, cylinders across and along the stadium and a rounded wedge, in the
   wall model (its swept wall) and the 3D FEM; the 3D FEM's contact patches drawn from above
   (``OUT/patches.png``).

The 3D FEM runs on its 1 mm quarter mesh with two layers.

    python bench/bench_indenter.py [--part plate,sphere,bodies] [--out build/bench-indenter]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path

import numpy as np

from spsc.cad.geometry import preset
from spsc.core.indenter import parse_indenter
from spsc.fem.solid.chamber import chamber_run, contact_forces, run_chamber
from spsc.fem.solid.contact import contact_tractions
from spsc.fem.wall import wall_curve
from spsc.materials import material

MAT = material("tpu60a")
DOME = dataclasses.replace(preset("B"), l=0.0)
STADIUM = preset("B")
BODIES = ("plate", "sphere:R=10", "cylinder:R=10,axis=x", "cylinder:R=10,axis=y",
          "wedge:angle=60,axis=y,r=0.5")


def _pair(geometry, indenter, stroke, points):
    """(wall curve, (fem curve, result, model), seconds of each)."""
    kw = dict(pressure_kPa=40, stroke_mm=stroke, points=points)
    t = time.perf_counter()
    wall = wall_curve(geometry, MAT, indenter=indenter, **kw)
    tw = time.perf_counter() - t
    t = time.perf_counter()
    fem = run_chamber(chamber_run(geometry, MAT, mesh_size_mm=1.0, indenter=indenter, **kw))
    return wall, fem, (tw, time.perf_counter() - t)


def _diff(a, b, y_from, y_to):
    """Largest relative difference of force and of pressure rise over y_from..y_to."""
    at = (a.y_mm >= y_from - 1e-9) & (a.y_mm <= y_to + 1e-9)
    dF = np.max(np.abs(a.force_N[at] / b.force_N[at] - 1))
    dp = np.max(np.abs((a.pressure_kPa[at] - a.pressure_kPa[0])
                       / (b.pressure_kPa[at] - b.pressure_kPa[0]) - 1))
    return float(dF), float(dp)


def part_plate(out: dict) -> None:
    rows = {}
    for name in ("plate", "sphere:R=1e4"):
        rows[name] = _pair(DOME, name, 3.0, 7)
    for k, model in ((0, "wall"), (1, "fem")):
        a = rows["sphere:R=1e4"][k] if k == 0 else rows["sphere:R=1e4"][1][0]
        b = rows["plate"][k] if k == 0 else rows["plate"][1][0]
        dF, dp = _diff(a, b, 1.0, 3.0)
        out[f"plate_{model}"] = {"force": dF, "pressure_rise": dp}
        print(f"R = 1e4 against the plate, {model}: force {100 * dF:.3f} %, pressure rise "
              f"{100 * dp:.3f} % (y = 1-3 mm; target 0.5 %)")


def part_sphere(out: dict) -> None:
    wall, (fem, _, model), (tw, tf) = _pair(DOME, "sphere:R=10", 4.0, 9)
    dF, dp = _diff(fem, wall, 1.0, 4.0)
    out["sphere_R10"] = {"force": dF, "pressure_rise": dp, "wall_s": tw, "fem_s": tf,
                         "y": wall.y_mm.tolist(), "F_wall": wall.force_N.tolist(),
                         "F_fem": fem.force_N.tolist(), "p_wall": wall.pressure_kPa.tolist(),
                         "p_fem": fem.pressure_kPa.tolist()}
    print(f"R = 10 on the dome, 3D FEM against wall: force {100 * dF:.2f} %, pressure rise "
          f"{100 * dp:.2f} % (y = 1-4 mm; target 2 %); wall {tw:.1f} s, 3D FEM {tf:.0f} s")


def part_bodies(out: dict, folder: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    fig, axes = plt.subplots(1, len(BODIES), figsize=(3.2 * len(BODIES), 3.6))
    print("Table 1 Type B (stadium), 40 kPa, 3 mm: F (N), dp (kPa), A (mm2); wall | 3D FEM")
    for ax, name in zip(axes, BODIES):
        wall, (fem, res, model), (tw, tf) = _pair(STADIUM, name, 3.0, 7)
        row = {m: {"F": float(c.force_N[-1]), "dp": float(c.pressure_kPa[-1] - 40),
                   "A": float(c.contact_area_mm2[-1]), "converged": bool(np.all(c.converged))}
               for m, c in (("wall", wall), ("fem", fem))}
        row.update(wall_s=tw, fem_s=tf)
        out[f"body {name}"] = row
        w, f = row["wall"], row["fem"]
        print(f"  {name:28s} {w['F']:6.3f} {w['dp']:6.3f} {w['A']:7.2f} | {f['F']:6.3f} "
              f"{f['dp']:6.3f} {f['A']:7.2f}   ({tw:.1f} s | {tf:.0f} s)")
        rec = res.of("press")[-1]
        body = parse_indenter(name)
        forces = contact_forces(model, rec, body)
        pressure = contact_tractions(model, rec.x, forces, body)[0]
        facets = model.mesh.facets["outer"]
        # the facets with a node on the body (the projection rings a little beyond them)
        keep = np.isin(facets, np.flatnonzero(np.any(forces != 0, axis=1))).any(axis=1)
        # the P2 field at each facet's centroid: −1/9 of the vertices, 4/9 of the edges
        mid = (-pressure[facets[:, :3]].sum(1) + 4 * pressure[facets[:, 3:]].sum(1)) / 9
        xyz = (model.disc.X + model.displacement(rec.x))[facets[:, :3]]
        sel = keep & (mid > 0)
        for sx, sy in ((1, 1), (-1, 1), (1, -1), (-1, -1)):  # the quarter mirrored
            xy = xyz[sel][:, :, :2] * np.array([sx, sy])
            pc = ax.add_collection(PolyCollection(xy, array=1e3 * mid[sel], cmap="viridis",
                                                  edgecolors="none"))
            pc.set_clim(0, 1e3 * np.percentile(mid[sel], 99))
        fig.colorbar(pc, ax=ax, shrink=0.7, label="contact pressure (kPa)")
        ax.set_xlim(-12, 12)
        ax.set_ylim(-14, 14)
        ax.set_aspect("equal")
        ax.set_title(f"{name}\nF = {f['F']:.2f} N, A = {f['A']:.1f} mm²", fontsize=8)
        ax.set_xlabel("x (mm)")
    axes[0].set_ylabel("y (mm)")
    fig.suptitle("3D FEM contact pressure (recovered from the nodal contact forces), Table 1 "
                 "Type B, 40 kPa, y = 3 mm", fontsize=9)
    fig.tight_layout()
    folder.mkdir(parents=True, exist_ok=True)
    fig.savefig(folder / "patches.png", dpi=130)
    print(f"wrote {folder / 'patches.png'}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", default="plate,sphere,bodies")
    ap.add_argument("--out", default="build/bench-indenter")
    args = ap.parse_args(argv)
    out: dict = {}
    folder = Path(args.out)
    parts = args.part.split(",")
    if "plate" in parts:
        part_plate(out)
    if "sphere" in parts:
        part_sphere(out)
    if "bodies" in parts:
        part_bodies(out, folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "figures.json").write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
