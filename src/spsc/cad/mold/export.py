"""Write a mold: every piece as STL and 3MF (the mesh mold, the one the gate measured) and STEP
(the exact B-rep of the same recipe), the assembly as one 3MF, and ``mold.json`` listing each
piece's files, role, pull direction, demoulding order and volume (mm³).

Every file ``mold.json`` names is relative to the folder ``mold.json`` is in, so a mold folder
moved, copied or written with ``--out /abs/dir`` reads back from anywhere:
:func:`read_mold` resolves them."""

from __future__ import annotations

import json
from pathlib import Path

import lib3mf
import numpy as np

from spsc.core.clocale import keeps_locale

from ..export import TriMesh, write_3mf, write_step, write_stl
from ..meshbuild import manifold_mesh
from .build import Mold

__all__ = ["write_mold", "read_mold", "ROLES", "PATHS_NOTE"]

#: What each role does, for mold.json and docs/guides/molds.md.
ROLES = {
    "half": "outer mold half, pulled off along its pull direction",
    "pin": "forms a flange hole; pulled down before the halves",
    "core": "forms the cavity and bore; print it in a soluble material (PVA, BVOH) or cast it "
            "in wax, leave it in the part when the halves come off, dissolve or melt it out "
            "through the inlet",
}


#: What mold.json says of its paths.
PATHS_NOTE = "every file is relative to the folder this file is in"


def write_mold(mesh: Mold, brep: Mold | None, outdir, *, gate=None, name: str = "mold") -> dict:
    """Write ``mesh`` (and the STEP files of ``brep``, the same mold on the B-rep kernel) into
    ``outdir``; returns the mold.json dict."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    pieces = []
    meshes = {}
    breps = {p.name: p.solid for p in brep.pieces} if brep is not None else {}
    for p in mesh.pieces:
        m = manifold_mesh(p.solid).canonical()
        meshes[p.name] = m
        files = {"stl": write_stl(m, outdir / f"{p.name}.stl").name,
                 "3mf": write_3mf(m, outdir / f"{p.name}.3mf", name=p.name).name}
        if p.name in breps:
            files["step"] = write_step(breps[p.name], outdir / f"{p.name}.step").name
        pieces.append({"name": p.name, "role": p.role, "files": files,
                       "pull": None if p.pull is None else [float(x) + 0.0 for x in p.pull],
                       "order": p.order, "volume_mm3": float(p.solid.volume()),
                       "triangles": int(len(m.faces)), "note": ROLES[p.role]})
    part = manifold_mesh(mesh.part).canonical()
    write_stl(part, outdir / "part-in-mold.stl")
    _assembly(outdir / "assembly.3mf", meshes, part)
    spec = mesh.spec
    info = {
        "paths": PATHS_NOTE,
        "bladder": {"geometry": mesh.bladder.geometry.as_dict(),
                    "flange_holes": mesh.bladder.flange.holes,
                    "tube_id_mm": mesh.bladder.port.tube_id},
        "process": spec.process, "material": spec.material,
        "shrinkage_pct": 100 * spec.shrinkage, "cavity_scale": spec.scale,
        "clearance_mm": spec.clearance, "mold_wall_mm": spec.wall,
        "parting": {"plane": {"z": "horizontal, through the port axis",
                              "x": "vertical, x = 0"}[mesh.parting],
                    "origin_mm": [float(x) for x in mesh.plane_origin],
                    "undercut_mm2": mesh.undercut},
        "channels_mm3": {k: float(v.volume()) for k, v in mesh.channels.items()},
        "pieces": pieces,
        "part_in_mold": {"file": "part-in-mold.stl",
                         "volume_mm3": float(mesh.part.volume()),
                         "note": "the bladder scaled by 1/(1-s): the space the closed mold "
                                 "leaves"},
        "assembly": "assembly.3mf",
    }
    if gate is not None:
        info["gate"] = {"passed": gate.passed, "failed": list(gate.failed)}
        gate.to_json(outdir / "gate.json")
    (outdir / f"{name}.json").write_text(json.dumps(info, indent=1) + "\n", encoding="utf-8")
    return info


def read_mold(path) -> dict:
    """A ``mold.json`` (or the folder holding it) with every file it names resolved against
    its folder (absolute paths, as strings), whatever the current directory. ParameterError
    (one line) if it is not a mold manifest."""
    from spsc.core.errors import ParameterError

    path = Path(path)
    if path.is_dir():
        path = path / "mold.json"
    try:
        info = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise ParameterError("mold", str(path), f"a readable mold.json ({exc.__class__.__name__})") \
            from None
    # files are relative to mold.json; a manifest written before they were (no "paths" note)
    # named them relative to the directory spsc mold ran in
    base = path.resolve().parent if isinstance(info, dict) and info.get("paths") == PATHS_NOTE \
        else Path.cwd()
    try:
        for p in info["pieces"]:
            p["files"] = {k: str(base / f) for k, f in p["files"].items()}
        info["part_in_mold"]["file"] = str(base / info["part_in_mold"]["file"])
        info["assembly"] = str(base / info["assembly"])
    except (KeyError, TypeError, AttributeError):
        raise ParameterError("mold", str(path), "a mold.json written by spsc mold (pieces with "
                             "their files, part_in_mold, assembly)") from None
    return info


@keeps_locale
def _assembly(path: Path, meshes: dict, part: TriMesh) -> Path:
    """One 3MF with every piece and the part as separate objects, in place."""
    wrapper = lib3mf.get_wrapper()
    model = wrapper.CreateModel()
    model.SetUnit(lib3mf.ModelUnit.MilliMeter)
    for name, m in list(meshes.items()) + [("part-in-mold", part)]:
        obj = model.AddMeshObject()
        obj.SetName(name)
        verts = []
        for x, y, z in np.asarray(m.vertices, float):
            p = lib3mf.Position()
            p.Coordinates[0], p.Coordinates[1], p.Coordinates[2] = float(x), float(y), float(z)
            verts.append(p)
        tris = []
        for a, b, c in np.asarray(m.faces, np.int64):
            t = lib3mf.Triangle()
            t.Indices[0], t.Indices[1], t.Indices[2] = int(a), int(b), int(c)
            tris.append(t)
        obj.SetGeometry(verts, tris)
        model.AddBuildItem(obj, wrapper.GetIdentityTransform())
    model.QueryWriter("3mf").WriteToFile(str(path))
    return path
