"""The files the invalid invocations use (:func:`fixtures`: a bladder STL, a part, bench and
tension CSVs, material files, folders and a file to stand in for a folder) and a valid base
invocation of each verb (:func:`bases`) that one change makes invalid."""

from __future__ import annotations

from pathlib import Path

__all__ = ["fixtures", "bases", "TENSION_BAD"]


def fixtures(tmp: Path) -> dict[str, Path]:
    """Write the files the cases use under ``tmp``; returns name -> path."""
    tmp.mkdir(parents=True, exist_ok=True)
    f = {
        "dir": tmp / "a-folder",
        "dir.json": tmp / "folder.json",
        "dir.csv": tmp / "folder.csv",
        "dir.stl": tmp / "folder.stl",
        "file": tmp / "a-file.txt",
        "stl": tmp / "tet.stl",
        "empty.stl": tmp / "empty.stl",
        "text.stl": tmp / "text.stl",
        "obj": tmp / "tet.obj",
        "csv": tmp / "bench.csv",
        "empty.csv": tmp / "empty.csv",
        "nocol.csv": tmp / "nocol.csv",
        "badrow.csv": tmp / "badrow.csv",
        "short.csv": tmp / "short.csv",
        "bad.json": tmp / "bad.json",
        "binary.csv": tmp / "binary.csv",
        "tension.csv": tmp / "tension.csv",
        **{k: tmp / k for k in TENSION_BAD},
        "ogden.json": tmp / "ogden.json",
        "soft.json": tmp / "soft.json",
        "foreign.json": tmp / "foreign.json",
        "law.json": tmp / "law.json",
        "part.stl": tmp / "dome.stl",
        "open.stl": tmp / "open-dome.stl",
        "bored.stl": tmp / "bored-dome.stl",
        "nonmanifold.stl": tmp / "nonmanifold-dome.stl",
        "pinched.stl": tmp / "pinched-dome.stl",
        "motor-part.stl": tmp / "motor" / "dome.stl",
        "dome.design.json": tmp / "motor" / "dome.design.json",
        "array.design.json": tmp / "array.design.json",
    }
    for k in ("dir", "dir.json", "dir.csv", "dir.stl"):
        f[k].mkdir(exist_ok=True)
    f["file"].write_text("not a folder\n", encoding="utf-8")
    f["stl"].write_text(_TET_STL, encoding="ascii")
    f["empty.stl"].write_bytes(b"")
    f["text.stl"].write_text("this is not an STL mesh\n", encoding="utf-8")
    f["obj"].write_text("v 0 0 0\n", encoding="ascii")
    f["csv"].write_text(_BENCH_CSV, encoding="utf-8")
    f["empty.csv"].write_text("", encoding="utf-8")
    f["nocol.csv"].write_text("y_mm,force_N\n0,0\n1,1\n2,2\n", encoding="utf-8")
    f["badrow.csv"].write_text(_BENCH_CSV + "3.0,abc,41\n", encoding="utf-8")
    f["short.csv"].write_text("y_mm,force_N,pressure_kPa\n0,0,40\n", encoding="utf-8")
    f["bad.json"].write_text("{not json", encoding="utf-8")
    f["binary.csv"].write_bytes(b"\x00\xff\xfe\x89PNG\x00\x00")
    _material_fixtures(f)
    _part_fixtures(f)
    return f


def _part_fixtures(f) -> None:
    """A closed dome part (one cavity), the same with a triangle missing, and with an open
    inlet bore (no enclosed cavity without its design file)."""
    from .part_shapes import dome
    from spsc.cad.export import TriMesh, write_stl

    v, fc = dome()
    write_stl(TriMesh(v, fc), f["part.stl"])
    write_stl(TriMesh(v, fc[1:]), f["open.stl"])
    write_stl(TriMesh(*dome(bore=0.8)), f["bored.stl"])
    a, b = fc[0][:2]  # an edge of the dome, shared by a tetrahedron outside it
    write_stl(TriMesh(*_with_tet(v, fc, (a, b))), f["nonmanifold.stl"])
    write_stl(TriMesh(*_with_tet(v, fc, (a,))), f["pinched.stl"])
    f["motor-part.stl"].parent.mkdir(exist_ok=True)
    write_stl(TriMesh(v, fc), f["motor-part.stl"])
    f["dome.design.json"].write_text('{"motor": "FIT0774"}', encoding="utf-8")
    f["array.design.json"].write_text('[{"motor": {}}]', encoding="utf-8")


def _with_tet(v, fc, shared):
    """The dome with a closed tetrahedron outside it that shares the dome's vertices
    ``shared`` (two: a non-manifold edge, four triangles on it; one: a pinched vertex)."""
    import numpy as np

    out = np.asarray(v[list(shared)]).mean(axis=0)
    away = out - v.mean(axis=0)
    away /= np.linalg.norm(away)
    side = np.cross(away, [0.0, 0.0, 1.0]) if abs(away[2]) < 0.9 else np.array([1.0, 0, 0])
    new = [out + 3 * away + k * side for k in (1.0, -1.0, 0.5)][: 4 - len(shared)]
    verts = np.vstack([v, new])
    ids = list(shared) + list(range(len(v), len(verts)))
    c = verts[ids].mean(axis=0)
    tet = []
    for tri in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)):
        t = [ids[k] for k in tri]
        n = np.cross(verts[t[1]] - verts[t[0]], verts[t[2]] - verts[t[0]])
        tet.append(t if np.dot(n, verts[t[0]] - c) > 0 else t[::-1])
    return verts, np.vstack([fc, tet])


#: A valid uniaxial tension test (neo-Hookean, μ = 1 MPa) and broken variants of it.
_TENSION = "stretch,stress_MPa\n1.0,0.0\n1.25,0.61\n1.5,1.06\n2.0,1.75\n2.5,2.34\n3.0,2.89\n"
TENSION_BAD = {
    "t-nocol.csv": "stretch,force_N\n1,0\n2,1\n3,2\n",
    "t-nonmono.csv": "stretch,stress_MPa\n1,0\n2,1\n1.5,1.5\n3,2\n",
    "t-negative.csv": "strain,stress_MPa\n0,0\n-1.5,1\n1,2\n",
    "t-below1.csv": "stretch,stress_MPa\n0.9,0\n1.5,1\n2,2\n",
    "t-falling.csv": "stretch,stress_MPa\n1,2\n1.5,1\n2,0.5\n",
    "t-negstress.csv": "stretch,stress_MPa\n1,0\n1.25,-0.1\n1.5,0.5\n2,1.8\n",
    "t-allneg.csv": "stretch,stress_MPa\n1,-3\n1.5,-2\n2,-1\n",
    "t-dip.csv": "stretch,stress_MPa\n1,0\n1.5,1.06\n2,0.75\n3,2.9\n",
    "t-unit.csv": "stretch,stress_bar\n1,0\n1.5,1\n2,2\n",
    "t-nan.csv": "stretch,stress_MPa\n1,0\n1.5,nan\n2,2\n",
    "t-text.csv": "stretch,stress_MPa\n1,0\n1.5,abc\n2,2\n",
    "t-header.csv": "stretch,stress_MPa\n",
    "t-test.csv": "# test: torsion\n" + _TENSION,
}


def _material_fixtures(f: dict[str, Path]) -> None:
    import json

    f["tension.csv"].write_text(_TENSION, encoding="utf-8")
    for key, text in TENSION_BAD.items():
        f[key].write_text(text, encoding="utf-8")
    base = {"schema": "spsc.material", "schema_version": 1, "name": "m", "law": "neo-hookean",
            "constants": {"C10": 0.5}}
    for key, change in (("ogden.json", {"law": "ogden", "constants": {"mu": [1.0],
                                                                      "alpha": [2.0]}}),
                        ("soft.json", {"constants": {"C10": -0.5}}),
                        ("foreign.json", {"schema": "spsc.curve"}),
                        ("law.json", {"law": "gent"})):
        f[key].write_text(json.dumps(base | change), encoding="utf-8")


_TET_STL = """solid tet
facet normal 0 0 -1
outer loop
vertex 0 0 0
vertex 0 1 0
vertex 1 0 0
endloop
endfacet
facet normal 0 -1 0
outer loop
vertex 0 0 0
vertex 1 0 0
vertex 0 0 1
endloop
endfacet
facet normal -1 0 0
outer loop
vertex 0 0 0
vertex 0 0 1
vertex 0 1 0
endloop
endfacet
facet normal 1 1 1
outer loop
vertex 1 0 0
vertex 0 1 0
vertex 0 0 1
endloop
endfacet
endsolid tet
"""

_BENCH_CSV = """y_mm,force_N,pressure_kPa
0.0,0.0,40.0
0.5,1.0,40.6
1.0,2.1,41.3
1.5,3.3,42.1
2.0,4.6,43.0
"""


def bases(f: dict[str, Path], tmp: Path) -> dict[str, tuple[str, ...]]:
    """A valid invocation of each verb (and model) that one change makes invalid. Their outputs
    go under ``tmp`` so a case that slips through writes nowhere else."""
    out = str(tmp / "out")
    bases = {
        "bladder": ("bladder", "--type", "B", "--out", out),
        "fingertip": ("fingertip", "--out", out),
        "mold": ("mold", "--type", "B", "--out", out, "--no-step", "--no-render"),
        "check": ("check", str(f["stl"]), "--json", str(tmp / "check.json")),
        "membrane": ("membrane", "--type", "B"),
        "fem": ("fem", "--type", "B", "--quiet"),
        "identify": ("identify", str(f["csv"]), "--pressure", "40", "--type", "B"),
        "calibrate": ("calibrate", str(f["csv"]), "--pressure", "40", "--type", "B",
                      "--quiet"),
        "report": ("report", "--out", out, "--cache", str(tmp / "cache"), "--quiet"),
        "fit-material": ("fit-material", str(f["tension.csv"]), "--law", "neo-hookean"),
        "sweep": ("sweep", "--type", "B", "--model", "simplified", "--out",
                  str(tmp / "sweep.parquet"), "--quiet"),
        "design": ("design", "--target", "stiffness_high=6", "--model", "simplified",
                   "--out", str(tmp / "design"), "--quiet"),
        "haptic": ("haptic", "--out", out, "--parts", str(tmp / "parts")),
        "bench-gap": ("bench-gap", "--out", out, "--quiet"),
        "simulate": ("simulate", str(tmp / "scenarios" / "scenario.toml"), "--out", out,
                     "--quiet"),
    }
    for model in ("membrane", "simplified", "wall", "fem"):
        bases[f"curve-{model}"] = ("curve", "--model", model, "--type", "B", "--quiet")
    bases["fem-part"] = ("fem", "--part", str(f["part.stl"]), "--fix", "z<=0", "--quiet")
    return bases
