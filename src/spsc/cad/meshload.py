"""Read a triangle mesh for the printability gate: binary/ASCII STL (trimesh) or 3MF (lib3mf).

Vertices come back in mm, as float64, with coincident vertices welded (STL stores every
triangle's corners separately; a slicer welds them the same way). Nothing else is repaired:
the gate must see the defects.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from spsc.core.clocale import keeps_locale
from spsc.core.errors import ParameterError

__all__ = ["load_mesh", "load_surface", "MESH_SUFFIXES", "SURFACE_SUFFIXES", "STEP_TOLERANCE_MM"]

MESH_SUFFIXES = (".stl", ".3mf")
#: what :func:`load_surface` reads: the meshes and STEP solids
SURFACE_SUFFIXES = (".stl", ".3mf", ".step", ".stp")
#: chord sag of a STEP solid's tessellation (mm)
STEP_TOLERANCE_MM = 0.005
#: 3MF unit -> mm (lib3mf ModelUnit enum names)
_UNIT_MM = {"MicroMeter": 1e-3, "MilliMeter": 1.0, "CentiMeter": 10.0, "Meter": 1000.0,
            "Inch": 25.4, "Foot": 304.8}


def load_mesh(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray]:
    """``(vertices (n, 3) float64 mm, faces (m, 3) int64)`` of the STL or 3MF file at ``path``.

    FileNotFoundError if the file is missing; ParameterError (one line) if it is not a readable
    STL/3MF triangle mesh.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(2, "no such file", str(path))
    suffix = path.suffix.lower()
    if suffix not in MESH_SUFFIXES:
        raise ParameterError("file", str(path), "an .stl or .3mf mesh")
    try:
        v, f = _read_3mf(path) if suffix == ".3mf" else _read_stl(path)
    except ParameterError:
        raise
    except Exception as exc:  # every reader failure is one bad-input message
        reason = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        raise ParameterError("file", str(path),
                             f"a readable {suffix[1:].upper()} triangle mesh ({reason})") from None
    if len(f) == 0 or not np.all(np.isfinite(v)):
        raise ParameterError("file", str(path), f"a readable {suffix[1:].upper()} triangle mesh "
                             "(no triangles or non-finite coordinates)")
    return weld(v, f)


def load_surface(path: str | os.PathLike, name: str = "part") -> tuple[np.ndarray, np.ndarray]:
    """(vertices, faces) of an STL, 3MF or STEP file (STEP tessellated with a chord sag of
    :data:`STEP_TOLERANCE_MM`); one-line ParameterError naming ``name`` otherwise."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in SURFACE_SUFFIXES:
        raise ParameterError(name, str(path), "an .stl, .3mf, .step or .stp file")
    if not path.is_file():
        raise ParameterError(name, str(path), "an existing file")
    if suffix in MESH_SUFFIXES:
        try:
            return load_mesh(path)
        except ParameterError as exc:
            raise ParameterError(name, str(path), exc.allowed) from None
    import cadquery as cq

    from .export import tessellate

    try:
        shape = cq.importers.importStep(str(path)).val()
    except Exception as exc:  # OCCT raises its own types for unreadable files
        raise ParameterError(name, str(path), f"a readable STEP file ({exc})") from None
    if not isinstance(shape, cq.Shape) or shape.Volume() <= 0:
        raise ParameterError(name, str(path), "a STEP file holding one solid")
    mesh = tessellate(shape, STEP_TOLERANCE_MM)
    return mesh.vertices, mesh.faces


#: Vertices equal to this many decimals of a mm are one vertex: OCC writes the pole of a sphere
#: once per face, 1e-17 mm apart; no real design has distinct vertices a nanometre apart.
WELD_DECIMALS = 9


def weld(vertices, faces) -> tuple[np.ndarray, np.ndarray]:
    """Merge vertices equal to ``WELD_DECIMALS`` decimals of a mm; drop the triangles that this
    collapses onto an edge (zero area, as a slicer does) and unreferenced vertices."""
    v = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    uniq, inverse = np.unique(np.round(v, WELD_DECIMALS), axis=0, return_inverse=True)
    f = inverse.reshape(-1)[f]
    f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 2] != f[:, 0])]
    used, f = np.unique(f, return_inverse=True)
    return np.ascontiguousarray(uniq[used]), f.reshape(-1, 3)


def _read_stl(path: Path):
    import trimesh

    mesh = trimesh.load_mesh(str(path), file_type="stl", process=False)
    return np.asarray(mesh.vertices), np.asarray(mesh.faces)


def _read_3mf(path: Path):
    """All build items of a 3MF, their (nested) component transforms applied, in mm.

    lib3mf first; if it rejects the package (cadquery's exporter writes object id 0 and no
    content type for the .rels part, which lib3mf refuses and slicers accept), the core-spec
    XML is read directly.
    """
    import lib3mf

    try:
        return _read_3mf_lib3mf(path)
    except lib3mf.ELib3MFException:
        return _read_3mf_xml(path)


def _read_3mf_xml(path: Path):
    import zipfile
    import xml.etree.ElementTree as ET

    core = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"
    with zipfile.ZipFile(path) as z:
        part = "3D/3dmodel.model"
        if "_rels/.rels" in z.namelist():
            for rel in ET.fromstring(z.read("_rels/.rels")):
                if rel.get("Type", "").endswith("/3dmodel"):
                    part = rel.get("Target", part).lstrip("/")
        root = ET.fromstring(z.read(part))
    unit = {"micron": 1e-3, "millimeter": 1.0, "centimeter": 10.0, "meter": 1000.0,
            "inch": 25.4, "foot": 304.8}[root.get("unit", "millimeter")]
    objects = {o.get("id"): o for o in root.iter(core + "object")}
    verts, faces, count = [], [], 0

    def matrix(text):
        if not text:
            return np.eye(4, 3)
        return np.array(text.split(), dtype=np.float64).reshape(4, 3)

    def walk(obj, m, depth=0):
        nonlocal count
        if depth > 32:
            raise ValueError("3MF components nest too deep")
        mesh = obj.find(core + "mesh")
        if mesh is not None:
            v = np.array([[float(e.get(k)) for k in "xyz"]
                          for e in mesh.iter(core + "vertex")], dtype=np.float64).reshape(-1, 3)
            f = np.array([[int(e.get(k)) for k in ("v1", "v2", "v3")]
                          for e in mesh.iter(core + "triangle")], dtype=np.int64).reshape(-1, 3)
            if len(v) and len(f):
                verts.append(v @ m[:3] + m[3])
                faces.append(f + count)
                count += len(v)
        for c in obj.iter(core + "component"):
            walk(objects[c.get("objectid")], _compose(matrix(c.get("transform")), m), depth + 1)

    for item in root.iter(core + "item"):
        walk(objects[item.get("objectid")], matrix(item.get("transform")))
    if not faces:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)
    return np.vstack(verts) * unit, np.vstack(faces)


@keeps_locale
def _read_3mf_lib3mf(path: Path):
    import lib3mf

    wrapper = lib3mf.get_wrapper()
    model = wrapper.CreateModel()
    model.QueryReader("3mf").ReadFromFile(str(path))
    unit = {int(getattr(lib3mf.ModelUnit, k)): s for k, s in _UNIT_MM.items()}[int(model.GetUnit())]
    verts, faces, count = [], [], 0

    def matrix(tr):
        return np.array([[tr.Fields[r][c] for c in range(3)] for r in range(4)], dtype=np.float64)

    def walk(obj, m):
        nonlocal count
        if obj.IsMeshObject():
            mesh = model.GetMeshObjectByID(obj.GetResourceID())
            v = np.array([p.Coordinates[0:3] for p in mesh.GetVertices()], dtype=np.float64)
            f = np.array([t.Indices[0:3] for t in mesh.GetTriangleIndices()], dtype=np.int64)
            if len(v) and len(f):
                verts.append(v @ m[:3] + m[3])  # 3MF: row vector times 4x3 matrix
                faces.append(f.reshape(-1, 3) + count)
                count += len(v)
        elif obj.IsComponentsObject():
            comps = model.GetComponentsObjectByID(obj.GetResourceID())
            for i in range(comps.GetComponentCount()):
                c = comps.GetComponent(i)
                cm = matrix(c.GetTransform()) if c.HasTransform() else np.eye(4, 3)
                walk(c.GetObjectResource(), _compose(cm, m))

    items = model.GetBuildItems()
    while items.MoveNext():
        item = items.GetCurrent()
        m = matrix(item.GetObjectTransform()) if item.HasObjectTransform() else np.eye(4, 3)
        walk(item.GetObjectResource(), m)
    if not faces:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)
    return np.vstack(verts) * unit, np.vstack(faces)


def _compose(inner, outer):
    """4x3 affine (row-vector convention) applying ``inner`` first, then ``outer``."""
    out = np.empty((4, 3))
    out[:3] = inner[:3] @ outer[:3]
    out[3] = inner[3] @ outer[:3] + outer[3]
    return out
