"""A run of any closed part: inflate its cavity, close the valve, press it with a rigid plate.

The part (:mod:`spsc.fem.part.surface`) is meshed whole (no symmetry); the mount is clamped by a
selector (:mod:`spsc.fem.part.selector`); the plate moves along ``plate_normal`` (a unit vector, the
direction of travel) from where it first touches the part. The solver presses along −z, so the
mesh is turned by the rotation taking ``plate_normal`` to (0, 0, −1) and the results turned back
(forces and pressures are invariant; VTU files are written in part coordinates).

Named contact surfaces (``contacts``): disc-shaped patches of the outer surface (e.g. FSR pocket
floors, by centre, outward normal and radius) met by the plate through a rigid insert of a given
thickness (the sensor); the force through each is reported per point.

A motor (``motor=True``, the design file's ``motor``: a haptic chamber's coin ERM) is a rigid
insert (:mod:`spsc.fem.solid.insert`): seated on the cavity's nodes on its ledge, met from above by
the dome's inner nodes over its footprint, its volume taken off the gas; its force is reported
per point (``force_motor_N``).
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from pathlib import Path

import numpy as np

from spsc.core.curve import Curve
from spsc.core.errors import ParameterError, require

from ..engine import Result, Settings, solve
from ..engine.settings import PART_CONTACT
from ..solid.insert import RigidInsert
from ..solid.mesh import MESH_VERSION, TetMesh
from ..solid.model import FEMModel
from .selector import parse_selector
from .spec import ContactPatch, PartRun, part_run
from .surface import PartSurface, load_part, part_mesh

__all__ = ["ContactPatch", "PartRun", "part_run", "run_part", "part_model", "check_part_run",
           "press_rotation", "part_curve", "write_part_vtu"]


def press_rotation(normal) -> np.ndarray:
    """The rotation R (3, 3) with R @ normal = (0, 0, −1) (the smallest such turn)."""
    d = np.asarray(normal, float)
    d = d / np.linalg.norm(d)
    target = np.array([0.0, 0.0, -1.0])
    axis = np.cross(d, target)
    s, c = np.linalg.norm(axis), float(d @ target)
    if s < 1e-12:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    k = axis / s
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + s * kx + (1 - c) * kx @ kx


def _tolerance(run: PartRun) -> float:
    """Geometric tolerance of selectors and sites (mm): the mesh's surface envelope and a
    margin for the straight-sided facets between curved edge nodes."""
    return min(max(0.05, run.mesh_size_mm / 20), 0.2)


def _file_digest(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _cache_path(run: PartRun, cache_dir) -> Path:
    from ..solid.mesh import CACHE_DIR

    # JSON, not repr: a design built in this process holds NumPy floats (repr np.float64(…)),
    # the same design read from its file plain ones; both must find the one mesh
    port = json.dumps((run.design or {}).get("port"), sort_keys=True)
    key = f"{_file_digest(run.part)}|{port}|{float(run.mesh_size_mm)!r}|{MESH_VERSION}|part-2"
    return Path(cache_dir or CACHE_DIR) / f"part-{hashlib.sha256(key.encode()).hexdigest()[:16]}.npz"


def _cached_part_mesh(run: PartRun, surface: PartSurface, cache_dir) -> tuple[TetMesh, Path | None]:
    """The part's mesh from the cache (keyed by the file's hash, the port, the size), and the
    path to cache a new one at once the run is accepted (None: it came from the cache)."""
    path = _cache_path(run, cache_dir)
    if path.exists():
        try:
            return TetMesh.load(path), None
        except (OSError, ValueError, KeyError):
            pass
    return part_mesh(surface, run.mesh_size_mm), path


def meshed_cavity_volume(mesh: TetMesh) -> float:
    """Volume (mm³) enclosed by the mesh's cavity facets (corner nodes; 0 if it has none)."""
    f = mesh.facets.get("cavity")
    if f is None or len(f) == 0:
        return 0.0
    a, b, c = (mesh.nodes[f[:, k]] for k in range(3))
    return abs(float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum()) / 6.0)


#: The meshed cavity must keep at least this fraction of the part's cavity volume.
CAVITY_KEPT = 0.5


def check_meshed_cavity(run: PartRun, surface: PartSurface, mesh: TetMesh) -> None:
    """A mesh size coarse enough to fill the cavity (fTetWild's envelope closes a cavity
    smaller than the elements): one-line ParameterError naming ``mesh size``."""
    kept = meshed_cavity_volume(mesh)
    if not kept >= CAVITY_KEPT * surface.cavity_volume:
        raise ParameterError("mesh size", run.mesh_size_mm, f"a mesh size that keeps the "
                             f"part's cavity ({surface.cavity_volume:.3g} mm³; meshed at "
                             f"{run.mesh_size_mm:g} mm it encloses {kept:.3g} mm³): a finer "
                             "--mesh-size")


def check_plate(run: PartRun, surface: PartSurface, fixed_mask_of) -> None:
    """A plate that misses the part, cuts into it, or meets only the clamped mount: one-line
    ParameterError naming ``plate-at`` / ``plate-normal``."""
    from spsc.cad.meshtopo import surface_distance

    R = press_rotation(run.plate_normal)
    v = surface.vertices
    z = v @ R[2]
    free = ~fixed_mask_of(v)
    if not free.any():
        raise ParameterError("fix", run.fix, "a selector that leaves part of the surface free "
                             "(it takes every vertex)")
    top = int(np.argmax(np.where(free, z, -np.inf)))
    tol = _tolerance(run)
    if z.max() > z[top] + tol:
        where = ", ".join(f"{c:.3g}" for c in v[int(np.argmax(z))])
        raise ParameterError("plate-normal", run.plate_normal,
                             f"a direction in which the plate first meets the free part, not "
                             f"the clamped mount (it first touches at ({where}))")
    room = float(z[top] - z[~free].max())
    if run.stroke_mm >= room:
        raise ParameterError("stroke", run.stroke_mm, f"< {room:.4g} mm, the travel from first "
                             "contact down to the clamped mount along the plate's direction")
    if run.plate_at is None:
        return
    at = np.asarray(run.plate_at, float)
    dist = float(surface_distance(at[None], v, surface.faces)[0])
    if dist > max(0.5, 2 * run.mesh_size_mm):
        raise ParameterError("plate-at", run.plate_at, f"a point on the part's surface (it is "
                             f"{dist:.3g} mm from it: the plate misses the part there)")
    cut = float(z[top] - at @ R[2])
    # a curved body's tip goes over the point; where it first touches, the engine finds
    if run.indenter == "plate" and cut > max(0.1, run.mesh_size_mm / 2):
        where = ", ".join(f"{c:.3g}" for c in v[top])
        raise ParameterError("plate-at", run.plate_at, f"the point where a plate moving along "
                             f"{run.plate_normal} first touches the part (through this point "
                             f"it would cut {cut:.3g} mm into it; it first touches at ({where}))")


def drop_clamped(mesh: TetMesh, clamped) -> tuple[TetMesh, np.ndarray]:
    """The mesh without the elements whose every node is clamped (a mount's bulk: they couple
    only fixed displacements and their own pressure unknowns, so the free solution is the same
    without them), except those holding a cavity facet (the cavity's volume needs them);
    nodes renumbered, facets of removed elements dropped. Returns (mesh, clamped node indices)."""
    clamped = np.asarray(clamped, bool)
    on_cavity = np.zeros(len(mesh.nodes), bool)
    on_cavity[mesh.facets["cavity"].ravel()] = True
    keep = ~np.all(clamped[mesh.tets], axis=1) | np.any(on_cavity[mesh.tets], axis=1)
    tets = mesh.tets[keep]
    used = np.unique(tets)
    new = -np.ones(len(mesh.nodes), np.int64)
    new[used] = np.arange(len(used))
    facets = {}
    for tag, fac in mesh.facets.items():
        fac = fac[np.all(new[fac] >= 0, axis=1)]
        facets[tag] = new[fac]
    # a facet of a removed element that a kept one does not share is no boundary of the part:
    # only boundary facets of the kept elements stay
    from ..solid.mesh import boundary_facets

    bound = {tuple(r) for r in np.sort(boundary_facets(new[tets])[:, :3], axis=1)}
    for tag, fac in facets.items():
        facets[tag] = fac[[tuple(r) in bound for r in np.sort(fac[:, :3], axis=1)]]
    out = TetMesh(mesh.nodes[used], new[tets], facets, mesh.symmetry)
    return out, np.flatnonzero(clamped[used])


def motor_insert(run: PartRun, mesh: TetMesh, tol: float) -> RigidInsert:
    """The design's motor as a rigid insert of ``mesh`` (part frame = press frame, z up): seat
    = cavity nodes on the ledge plane z_bottom under its footprint, top = cavity nodes over its
    footprint from its top face up (the haptic chamber's flat ceiling lies on it)."""
    m = run.design["motor"]
    radius, height = float(m["diameter_mm"]) / 2, float(m["height_mm"])
    z0 = float(m["z_bottom_mm"])
    cav = mesh.nodes_on("cavity")
    X = mesh.nodes[cav]
    rho = np.hypot(X[:, 0], X[:, 1])
    over = rho <= radius + tol
    seat = cav[over & (np.abs(X[:, 2] - z0) <= tol)]
    top = cav[over & (X[:, 2] >= z0 + height - tol)]
    if seat.size == 0 or top.size == 0:
        raise ParameterError("motor", m.get("name", "motor"), "a motor whose ledge and dome "
                             f"are in the part (no cavity node on the ledge z = {z0:.4g} mm "
                             f"or over its top within r = {radius:.3g} mm)")
    # a ceiling meshed a hair below the motor's top (within the mesh's tolerance) is where the
    # motor's top is: no node may start inside it
    return RigidInsert("motor", seat, top, z0, min(height, float(mesh.nodes[top, 2].min()) - z0),
                       math.pi * radius ** 2 * height)


def check_part_run(run: PartRun, surface: PartSurface) -> None:
    """The checks of a run against its part's surface, before any meshing (milliseconds):
    the selector takes some of the part and leaves some free, the plate meets the free part
    where ``plate_at`` says. One-line ParameterError naming ``fix``/``plate-at``/``plate-normal``."""
    extent = float(np.ptp(surface.vertices, axis=0).min())
    require("mesh size", run.mesh_size_mm, gt=0, le=extent / 2,
            unit=f"mm; at most half the part's smallest extent, {extent:.3g} mm")
    selector = parse_selector(run.fix)
    tol = _tolerance(run)
    if not selector(surface.vertices, tol).any():
        lo, hi = surface.bounds
        span = ", ".join(f"{a} {l:.3g}..{h:.3g}" for a, l, h in zip("xyz", lo, hi))
        raise ParameterError("fix", run.fix, f"a selector that takes part of the part "
                             f"(it takes nothing; the part spans {span} mm)")
    check_plate(run, surface, lambda p: selector(p, tol))


def part_model(run: PartRun, *, cache_dir=None, surface: PartSurface | None = None,
               mesh: TetMesh | None = None):
    """(FEMModel in the press frame, rotation R, surface): read and check the part, check the
    selector and plate, mesh (cached by the file's hash; or ``mesh`` as given), clamp, tag the
    contact patches."""
    surface = surface or load_part(run.part, run.design)
    check_part_run(run, surface)
    selector, tol = parse_selector(run.fix), _tolerance(run)
    mesh, new_path = (mesh, None) if mesh is not None else _cached_part_mesh(run, surface,
                                                                             cache_dir)
    check_meshed_cavity(run, surface, mesh)
    full = mesh
    mesh, clamped = drop_clamped(mesh, selector(mesh.nodes, tol))
    R = press_rotation(run.plate_normal)
    gap = np.zeros(len(mesh.nodes))
    groups = {}
    outer = mesh.nodes_on("outer")
    for patch in run.contacts:
        on = outer[patch.select(mesh.nodes[outer], tol)]
        if on.size == 0:
            raise ParameterError("contact", patch.name, "a patch that lies on the part's outer "
                                 "surface (no mesh node is on it)")
        gap[on] = patch.thickness
        groups[patch.name] = on
    turned = TetMesh(mesh.nodes @ R.T, mesh.tets, mesh.facets, 1)
    insert = motor_insert(run, turned, tol) if run.motor else None
    model = FEMModel.build(turned, run.material, bulk_ratio=run.bulk_ratio, supports={},
                           clamped=clamped, gap=gap, groups=groups, insert=insert)
    if new_path is not None:  # cached only once every check of the run passed
        new_path.parent.mkdir(parents=True, exist_ok=True)
        full.save(new_path)
    return model, R, surface


def run_part(run: PartRun, *, settings: Settings | None = None, progress=None,
             cache_dir=None):
    """Solve ``run`` (``settings`` default: the engine's with a part's onset,
    :data:`~spsc.fem.engine.settings.PART_CONTACT`); returns (Curve, Result, FEMModel, R).
    The Curve's ``series`` hold the force through each contact patch
    (``force_<name>_N``)."""
    t0 = time.perf_counter()
    model, R, surface = part_model(run, cache_dir=cache_dir)
    mesh_seconds = time.perf_counter() - t0
    result = solve(model, run.steps(run.body(model, R)),
                   settings=settings or Settings(**PART_CONTACT), progress=progress)
    return part_curve(run, model, result, surface, mesh_seconds=mesh_seconds), result, model, R


def part_curve(run: PartRun, model: FEMModel, result: Result, surface: PartSurface, *,
               mesh_seconds: float = float("nan")) -> Curve:
    """The Curve of a part run (as :func:`spsc.fem.solid.chamber.to_curve`, plus the patch
    forces and the motor's)."""
    from ..solid.chamber import curve_points, solve_info

    pts = curve_points(run, result)
    n = int(run.points)
    names = list(model.groups) + ([model.insert.name] if model.insert is not None else [])
    series = {f"force_{name}_N": np.full(n, np.nan) for name in names}
    if pts["conv"][0]:
        for k in series:
            series[k][0] = 0.0
    for k, rec in enumerate(pts["presses"], start=1):
        for name, f in rec.group_forces.items():
            series[f"force_{name}_N"][k] = f
        if model.insert is not None:
            series[f"force_{model.insert.name}_N"][k] = rec.insert_force
    part = {"file": Path(run.part).name, "fix": run.fix, "indenter": run.indenter,
            "plate_normal": list(run.plate_normal),
            "plate_at": None if run.plate_at is None else list(run.plate_at),
            "port_plugged": surface.capped,
            "surface_cavity_volume_mm3": surface.cavity_volume,
            "contacts": [{"name": c.name, "center": list(c.center), "normal": list(c.normal),
                          "radius": c.radius, "insert_mm": c.thickness,
                          "nodes": int(len(model.groups.get(c.name, ())))}
                         for c in run.contacts]}
    if model.insert is not None:
        ins = model.insert
        part["motor"] = {"name": run.design["motor"].get("name"), "volume_mm3": ins.volume,
                         "seat_nodes": int(ins.seat.size), "top_nodes": int(ins.top.size),
                         "z_bottom_mm": ins.z_bottom, "height_mm": ins.height}
    setup = {"p_i_kPa": run.pressure_kPa, "reservoir_mm3": run.reservoir_mm3,
             "polytropic_n": run.polytropic_n, "mesh_size_mm": run.mesh_size_mm,
             "dofs": model.disc.n, "model_part": "full", "part": part}
    if result.instability:
        setup["instability"] = result.instability
    info = solve_info(result, model, pts, mesh_seconds,
                      {"mesh_size_mm": run.mesh_size_mm, "model_part": "full",
                       "clamped_nodes": int(model.fixed[: model.disc.n_u].sum() // 3),
                       "bulk_ratio": run.bulk_ratio, "mesh_seconds": mesh_seconds})
    return Curve(pts["y"], pts["F"], pts["P"], pts["A"], pts["dV"], model="fem-part",
                 geometry={}, material=run.material.name, setup=setup,
                 nominal_volume_mm3=pts["start"].volume,
                 inflated_volume_mm3=pts["inflated"].volume, converged=pts["conv"],
                 message=pts["msg"], solver=info, series=series)


def write_part_vtu(model: FEMModel, result: Result, R, directory, body=None) -> list[Path]:
    """One VTU per converged record in part coordinates (the press frame turned back by Rᵀ):
    quadratic tetrahedra with displacement, hydrostatic pressure, the pressing body's force
    per node (``contact_force_N``; ``body``: the placed curved indenter, None: the plate) and
    each contact patch's nodes marked (point data ``contact_<name>``)."""
    from ..solid.chamber import write_vtu

    R = np.asarray(R, float)
    paths = write_vtu(model, result, directory, body)
    import pyvista as pv

    X = model.disc.X @ R
    for path, rec in zip(paths, result.records):
        grid = pv.read(path)
        grid.points = X
        grid.point_data["displacement"] = model.displacement(rec.x) @ R
        for name in ("contact_force_N", "contact_shear_MPa"):
            grid.point_data[name] = grid.point_data[name] @ R
        for name, nodes in model.groups.items():
            mark = np.zeros(len(X))
            mark[nodes] = 1.0
            grid.point_data[f"contact_{name}"] = mark
        grid.field_data["plate_normal"] = R[2] * -1.0
        for name, f in rec.group_forces.items():
            grid.field_data[f"force_{name}_N"] = np.array([f])
        if model.insert is not None:
            mark = np.zeros(len(X))
            mark[model.insert.seat], mark[model.insert.top] = 1.0, 2.0
            grid.point_data["motor_seat1_top2"] = mark
            grid.field_data["force_motor_N"] = np.array([rec.insert_force])
        grid.save(path)
    return paths
