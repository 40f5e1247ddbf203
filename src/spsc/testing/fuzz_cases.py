"""Invalid invocations of every ``spsc`` verb, as a table: the fuzz test runs them in-process
(``tests/test_fuzz_cli.py``) and ``bench/bench_badinput.py`` as subprocesses.

Each :class:`Case` is an argv that must end in exactly one line on stderr naming ``names``
(the option or parameter at fault), exit code 2, before any work starts. The cases are built
on valid base invocations of each verb with one thing wrong: a bad number (text, empty,
non-finite, out of range), a cross-parameter limit, a bad choice, an output path that cannot be
written, a bad input file, or an argparse mistake. :func:`fixtures` writes the files they use.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = ["Case", "fixtures", "invalid_cases"]


@dataclass(frozen=True)
class Case:
    """One invalid invocation: ``argv`` (without ``spsc``), what is wrong (``why``) and the
    name the one-line error must contain (None: any)."""

    argv: tuple[str, ...]
    why: str
    names: str | None = None

    @property
    def verb(self) -> str:
        return self.argv[0] if self.argv else ""


#: Values no number option accepts: text, empty, blank, non-finite, a decimal comma.
NOT_A_NUMBER = ("abc", "", " ", "nan", "inf", "-inf", "1,5", "0x")

#: Out-of-range values per number option (every one must be refused with the option named).
#: Geometry ranges: w, h, l, t0 in mm, with the Type B preset (w = 11, h = 13, l = 3, t0 = 1).
OUT_OF_RANGE = {
    "w": ("0", "-1", "-1e5", "1e9", "1e-9"),
    "h": ("0", "-1", "1e9", "1e-9"),
    "l": ("-1", "1e9"),
    "t0": ("0", "-1", "11", "1e3"),
    "n1": ("0.5", "0", "1e9"),
    "n2": ("0.5", "-2", "1e9"),
    "cy": ("-1", "1", "1.5", "1e9"),
    "pressure": ("-1", "-1e5", "1e5"),
    "reservoir": ("-1", "-1e-3"),
    "stroke": ("-1", "13", "100", "1e9"),
    "points": ("0", "1", "-3", "2.5", "1e9"),
    "polytropic-n": ("0.5", "0", "3"),
    "mesh-size": ("0", "-1", "1e9", "1e-4"),
    "layers": ("0", "-1", "2.5", "1000"),
    "flange-holes": ("3", "2.5", "-2", "1"),
    "tube-id": ("0", "-1", "1e9"),
    "angle": ("10", "100", "-45"),
    "shrinkage": ("-1", "6"),
    "clearance": ("0", "2"),
    "wall": ("1", "100"),
    "pocket-diameter": ("0", "-1", "1e9"),
    "pocket-depth": ("0", "-1", "100"),
    "min-wall": ("0", "-1"),
    "bladder-volume": ("0", "-1"),
    "workers": ("0", "-1", "2.5", "1e3", "257", "1e9"),
}

GEOMETRY = ("w", "h", "l", "t0", "n1", "n2", "cy")
SETUP = ("pressure", "reservoir", "stroke", "points", "polytropic-n")


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
        "t-nocol.csv": tmp / "t-nocol.csv",
        "t-nonmono.csv": tmp / "t-nonmono.csv",
        "t-negative.csv": tmp / "t-negative.csv",
        "t-below1.csv": tmp / "t-below1.csv",
        "t-falling.csv": tmp / "t-falling.csv",
        "t-unit.csv": tmp / "t-unit.csv",
        "t-nan.csv": tmp / "t-nan.csv",
        "t-text.csv": tmp / "t-text.csv",
        "t-header.csv": tmp / "t-header.csv",
        "t-test.csv": tmp / "t-test.csv",
        "ogden.json": tmp / "ogden.json",
        "soft.json": tmp / "soft.json",
        "foreign.json": tmp / "foreign.json",
        "law.json": tmp / "law.json",
        "part.stl": tmp / "dome.stl",
        "open.stl": tmp / "open-dome.stl",
        "bored.stl": tmp / "bored-dome.stl",
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
    from spsc.testing.part_shapes import dome
    from spsc.cad.export import TriMesh, write_stl

    v, fc = dome()
    write_stl(TriMesh(v, fc), f["part.stl"])
    write_stl(TriMesh(v, fc[1:]), f["open.stl"])
    write_stl(TriMesh(*dome(bore=0.8)), f["bored.stl"])


#: A valid uniaxial tension test (neo-Hookean, μ = 1 MPa) and broken variants of it.
_TENSION = "stretch,stress_MPa\n1.0,0.0\n1.25,0.61\n1.5,1.06\n2.0,1.75\n2.5,2.34\n3.0,2.89\n"
_TENSION_BAD = {
    "t-nocol.csv": "stretch,force_N\n1,0\n2,1\n3,2\n",
    "t-nonmono.csv": "stretch,stress_MPa\n1,0\n2,1\n1.5,1.5\n3,2\n",
    "t-negative.csv": "strain,stress_MPa\n0,0\n-1.5,1\n1,2\n",
    "t-below1.csv": "stretch,stress_MPa\n0.9,0\n1.5,1\n2,2\n",
    "t-falling.csv": "stretch,stress_MPa\n1,2\n1.5,1\n2,0.5\n",
    "t-unit.csv": "stretch,stress_bar\n1,0\n1.5,1\n2,2\n",
    "t-nan.csv": "stretch,stress_MPa\n1,0\n1.5,nan\n2,2\n",
    "t-text.csv": "stretch,stress_MPa\n1,0\n1.5,abc\n2,2\n",
    "t-header.csv": "stretch,stress_MPa\n",
    "t-test.csv": "# test: torsion\n" + _TENSION,
}


def _material_fixtures(f: dict[str, Path]) -> None:
    import json

    f["tension.csv"].write_text(_TENSION, encoding="utf-8")
    for key, text in _TENSION_BAD.items():
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


def _bases(f: dict[str, Path], tmp: Path) -> dict[str, tuple[str, ...]]:
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
    }
    for model in ("membrane", "simplified", "wall", "fem"):
        bases[f"curve-{model}"] = ("curve", "--model", model, "--type", "B", "--quiet")
    bases["fem-part"] = ("fem", "--part", str(f["part.stl"]), "--fix", "z<=0", "--quiet")
    return bases


def _numbers(base, options, extra=()) -> list[Case]:
    cases = []
    for opt in options:
        for v in NOT_A_NUMBER + OUT_OF_RANGE.get(opt, ()) + tuple(extra):
            cases.append(Case(base + (f"--{opt}", v), f"--{opt} {v!r}", opt))
    return cases


def _outputs(base, option, f, tmp, suffix=".json") -> list[Case]:
    """``option`` given a path that cannot be written as a file."""
    bad = [(str(f["dir"]), "an existing folder"),
           (str(f["dir.json"]) if suffix == ".json" else str(f["dir"]), "a folder with the suffix"),
           (str(f["file"] / f"x{suffix}"), "a path under a file"),
           (str(tmp / "no" / "such" / f"x{suffix}"), "a missing folder"),
           ("/proc/spsc-fuzz" + suffix, "an unwritable place"),
           ("", "empty")]
    if Path("/dev/full").is_char_device():  # a full disk (not every sandbox has the device)
        bad.append(("/dev/full", "a full device"))
    return [Case(base + (option, p), f"{option} {why}", option.lstrip("-")) for p, why in bad]


def _out_dirs(base, option, f) -> list[Case]:
    """``option`` given a folder that cannot be written or created."""
    bad = [(str(f["file"]), "an existing file"), (str(f["file"] / "sub"), "a folder under a file"),
           ("/proc/spsc-fuzz", "an unwritable place"), ("", "empty")]
    return [Case(base + (option, p), f"{option} {why}", option.lstrip("-")) for p, why in bad]


def invalid_cases(tmp: Path) -> list[Case]:
    """Every invalid invocation, with fixtures under ``tmp``."""
    tmp = Path(tmp)
    f = fixtures(tmp)
    b = _bases(f, tmp)
    cases: list[Case] = []
    geometry_verbs = ("bladder", "membrane", "fem", "identify", "curve-membrane",
                      "curve-simplified", "curve-wall", "curve-fem")
    for verb in geometry_verbs:
        cases += _numbers(b[verb], GEOMETRY)
        cases += [Case(b[verb] + ("--type", "E"), "unknown type", "type"),
                  Case(b[verb] + ("--type", ""), "empty type", "type"),
                  Case(b[verb] + ("--footprint", "huge"), "unknown footprint", "footprint"),
                  Case(b[verb][:1] + b[verb][1:] + ("--cy", "0.999999"), "cy too close to 1",
                       "cy")]
    # the seven parameters without --type: each one missing
    full = ("--w", "11", "--h", "13", "--l", "3", "--t0", "1", "--n1", "2", "--n2", "2.2",
            "--cy", "0")
    for k in range(0, len(full), 2):
        cut = full[:k] + full[k + 2:]
        cases.append(Case(("membrane",) + cut, f"missing {full[k]}", full[k].lstrip("-")))
    for verb in ("membrane", "fem", "curve-membrane", "curve-simplified", "curve-wall",
                 "curve-fem"):
        cases += _numbers(b[verb], SETUP)
        cases += [Case(b[verb] + ("--material", "rubber"), "unknown material", "material"),
                  Case(b[verb] + ("--material", ""), "empty material", "material")]
        cases += _outputs(b[verb], "--json", f, tmp)
        cases += _outputs(b[verb], "--csv", f, tmp, ".csv")
        cases += _outputs(b[verb], "--png", f, tmp, ".png")
        cases += [Case(b[verb] + ("--png", str(tmp / "plot.xyz")), "unknown image format",
                       "png"),
                  Case(b[verb] + ("--png", str(tmp / "plot")), "no image suffix", "png")]
        if verb in ("membrane", "curve-membrane", "curve-simplified"):
            cases.append(Case(b[verb] + ("--pressure", "0"), "a membrane without pressure",
                              "pressure"))
        # stroke against the chamber: above a smaller chamber's height
        cases.append(Case(b[verb] + ("--h", "4", "--stroke", "5"), "stroke above h", "stroke"))
    for verb in ("fem", "curve-wall", "curve-fem"):
        cases += _numbers(b[verb], ("mesh-size", "layers"))
    cases += [Case(b["fem"] + ("--points", "100000"), "100000 FEM positions", "points"),
              Case(b["fem"] + ("--solver", "magic"), "unknown solver", "solver"),
              Case(b["curve-membrane"] + ("--mesh-size", "1"), "option of another model",
                   "mesh-size"),
              Case(b["curve-simplified"] + ("--wrinkling", "on"), "option of another model",
                   "wrinkling"),
              Case(b["curve-membrane"] + ("--wrinkling", "maybe"), "bad choice", "wrinkling"),
              Case(b["curve-fem"] + ("--vtu", str(f["file"])), "--vtu a file", "vtu"),
              Case(b["curve-fem"] + ("--vtu", str(f["file"] / "v")), "--vtu under a file",
                   "vtu"),
              Case(b["curve-membrane"][:1] + ("--model", "nothing", "--type", "B"),
                   "unknown model", "model")]
    # bladder
    cases += _numbers(b["bladder"], ("flange-holes", "tube-id"))
    cases += _out_dirs(b["bladder"][:3], "--out", f)
    cases += [Case(b["bladder"] + ("--material", "rubber"), "unknown material", "material"),
              Case(b["bladder"] + ("--tube-id", "30"), "tube wider than the base", "tube-id")]
    # fem --part: the setup, the part, the mount, the plate
    fp = b["fem-part"]
    cases += _numbers(fp, SETUP + ("mesh-size",))
    cases += _outputs(fp, "--json", f, tmp) + _outputs(fp, "--csv", f, tmp, ".csv")
    cases += _out_dirs(fp, "--vtu", f)
    no_fix = fp[:3] + ("--quiet",)
    cases += [Case(fp + ("--type", "B"), "--type with --part", "type"),
              Case(fp + ("--w", "11"), "a chamber parameter with --part", "w"),
              Case(fp + ("--layers", "2"), "--layers with --part", "layers"),
              Case(fp + ("--full",), "--full with --part", "full"),
              Case(("fem", "--part", str(f["dir"]), "--fix", "z<0"), "a folder as the part",
                   "part"),
              Case(("fem", "--part", str(tmp / "none.stl"), "--fix", "z<0"), "a missing part",
                   "part"),
              Case(("fem", "--part", str(f["obj"]), "--fix", "z<0"), "an .obj part", "part"),
              Case(("fem", "--part", str(f["text.stl"]), "--fix", "z<0"), "a text .stl",
                   "file"),
              Case(("fem", "--part", str(f["open.stl"]), "--fix", "z<0"), "an open surface",
                   "part"),
              Case(("fem", "--part", str(f["stl"]), "--fix", "z<0"), "a part with no cavity",
                   "part"),
              Case(("fem", "--part", str(f["bored.stl"]), "--fix", "z<0"),
                   "a cavity open through its bore", "part"),
              Case(no_fix, "no --fix and no design", "fix"),
              Case(no_fix + ("--fix", "z<-50"), "a selector that fixes nothing", "fix"),
              Case(no_fix + ("--fix", "z>-50"), "a selector that fixes everything", "fix"),
              Case(no_fix + ("--fix", "q<0"), "a selector of no axis", "fix"),
              Case(no_fix + ("--fix", ""), "an empty selector", "fix"),
              Case(fp + ("--plate-at", "50,0,7"), "a plate that misses the part", "plate-at"),
              Case(fp + ("--plate-at", "0,0,-1"), "a plate through the part", "plate-at"),
              Case(fp + ("--plate-at", "apex"), "a site without a design file", "plate-at"),
              Case(fp + ("--plate-at", "1,2"), "two coordinates", "plate-at"),
              Case(fp + ("--motor",), "--motor on a part whose design names no motor",
                   "motor"),
              Case(("fem", "--type", "B", "--motor", "--quiet"), "--motor without --part",
                   "motor"),
              Case(fp + ("--plate-normal", "0,0,1"), "a plate onto the mount", "plate-normal"),
              Case(fp + ("--plate-normal", "0,0,0"), "a zero normal", "plate-normal"),
              Case(fp + ("--plate-normal", "a,b,c"), "a normal of no numbers", "plate-normal"),
              Case(fp + ("--design", str(tmp / "none.design.json")), "a missing design file",
                   "design"),
              Case(fp + ("--design", str(f["bad.json"])), "a design file of bad JSON", "design"),
              Case(b["fem"] + ("--fix", "z<0"), "--fix without --part", "fix"),
              Case(b["fem"] + ("--plate-at", "0,0,1"), "--plate-at without --part", "plate-at")]
    # mold
    cases += _numbers(b["mold"], ("shrinkage", "clearance", "wall", "tube-id", "flange-holes")
                      + GEOMETRY)
    cases += _out_dirs(("mold", "--type", "B", "--no-step", "--no-render"), "--out", f)
    cases += [Case(b["mold"] + ("--process", "injection"), "an unknown process", "process"),
              Case(b["mold"] + ("--material", "pla"), "an unknown silicone", "material"),
              Case(b["mold"] + ("--parting", "y"), "an unknown parting", "parting"),
              Case(("mold", "--no-render"), "no part and no geometry", "geometry"),
              Case(("mold", str(f["part.stl"]), "--no-render"), "a part that is no bladder",
                   "part"),
              Case(("mold", str(tmp / "none.stl"), "--no-render"), "a missing part", "part"),
              Case(("mold", str(f["part.stl"]), "--type", "B"), "a part and a type", "part"),
              Case(b["bladder"] + ("--haptic", "--w", "5", "--h", "5", "--t0", "0.5"),
                   "a chamber too narrow for the motor", "haptic")]
    # fingertip
    cases += _numbers(b["fingertip"], ("angle", "pocket-diameter", "pocket-depth"))
    cases += [Case(b["fingertip"] + ("--mesh-size", "1"), "--mesh-size without --fem",
                   "mesh-size"),
              Case(b["fingertip"] + ("--cases", "pulp-high-40"), "--cases without --fem",
                   "cases"),
              Case(b["fingertip"] + ("--fem", "--cases", "palm-high-40"), "an unknown case",
                   "cases"),
              Case(b["fingertip"] + ("--fem", "--mesh-size", "0.01"), "a mesh too fine",
                   "mesh-size"),
              Case(b["fingertip"] + ("--fem", "--mesh-size", "nan"), "a NaN mesh", "mesh-size")]
    cases += _out_dirs(("fingertip",), "--out", f)
    cases += [Case(b["fingertip"] + ("--process", "foo"), "unknown process", "process"),
              Case(b["fingertip"] + ("--process", ""), "empty process", "process")]
    # check
    cases += _numbers(b["check"], ("min-wall",))
    cases += _outputs(b["check"][:2], "--json", f, tmp)
    cases += [Case(("check", str(tmp / "missing.stl")), "missing file", "missing.stl"),
              Case(("check", str(f["dir.stl"])), "a folder named .stl", "folder.stl"),
              Case(("check", str(f["empty.stl"])), "an empty STL", "empty.stl"),
              Case(("check", str(f["text.stl"])), "text as STL", "text.stl"),
              Case(("check", str(f["obj"])), "an unknown mesh format", "tet.obj"),
              Case(("check", ""), "an empty path", "file"),
              Case(b["check"] + ("--process", "foo"), "unknown process", "process"),
              Case(b["check"] + ("--design", str(tmp / "missing.json")), "missing design",
                   "missing.json"),
              Case(b["check"] + ("--design", str(f["bad.json"])), "design not JSON", "design"),
              Case(b["check"] + ("--design", str(f["dir"])), "design a folder", "design"),
              Case(("check",), "no file", "FILE"),
              Case(("check", str(f["stl"]), str(f["stl"])), "two files", "unrecognized")]
    # identify
    cases += _numbers(b["identify"], ("pressure", "reservoir", "polytropic-n",
                                      "bladder-volume"))
    cases += _outputs(b["identify"], "--json", f, tmp)
    cases += _outputs(b["identify"], "--csv", f, tmp, ".csv")
    ident = b["identify"][2:]
    for v in ("", ",", "abc", "-5", "nan", "inf", "1e5"):
        cases.append(Case(b["identify"] + ("--predict-pressures", v), "bad predict pressures",
                          "predict-pressures"))
    for v in ("", ",", "-1", "nan"):
        cases.append(Case(b["identify"] + ("--predict-reservoirs", v),
                          "bad predict reservoirs", "predict-reservoirs"))
    for key, why in (("empty.csv", "an empty CSV"), ("nocol.csv", "a missing column"),
                     ("badrow.csv", "a text value"), ("short.csv", "too few rows"),
                     ("dir.csv", "a folder named .csv"), ("binary.csv", "binary data")):
        cases.append(Case(("identify", str(f[key])) + ident, why, None))
    cases += [Case(("identify", str(tmp / "missing.csv")) + ident, "missing CSV", "missing.csv"),
              Case(("identify", str(f["csv"]), "--pressure", "40"), "no chamber", None),
              Case(("identify", str(f["csv"]), "--type", "B"), "no pressure", "pressure")]
    # calibrate
    cal = b["calibrate"]
    cases += _numbers(cal, ("pressure", "reservoir", "polytropic-n", "mesh-size", "layers",
                            "predict-stroke"))
    cases += _outputs(cal, "--json", f, tmp)
    cases += _outputs(cal, "--png", f, tmp, ".png")
    for v in (",", "abc", "-5", "nan", "1e5"):
        cases.append(Case(cal + ("--predict-pressures", v), "bad predict pressures",
                          "predict-pressures"))
    for key, why in (("empty.csv", "an empty CSV"), ("badrow.csv", "a text value"),
                     ("short.csv", "too few rows"), ("dir.csv", "a folder named .csv"),
                     ("binary.csv", "binary data")):
        cases.append(Case(("calibrate", str(f[key])) + cal[2:], why, None))
    cases += [Case(("calibrate", str(tmp / "missing.csv")) + cal[2:], "missing CSV",
                   "missing.csv"),
              Case(cal + ("--material", "rubber"), "unknown material", "material"),
              Case(cal + ("--out", str(tmp / "material.txt")), "material file not .json",
                   "out"),
              Case(cal[:2] + ("--pressure", "0", "--type", "B"), "pressures of a vented test",
                   "pressure"),
              Case(cal + ("--h", "2", "--predict-stroke", "1"), "bench stroke above h",
                   "stroke"),
              Case(cal + ("--predict-stroke", "50"), "predicted stroke above h",
                   "predict-stroke"),
              Case(cal[:2] + ("--type", "B"), "no pressure", "pressure")]
    cases += _fit_material_cases(f, b, tmp)
    cases += _sweep_cases(f, b, tmp)
    cases += _design_cases(f, b, tmp)
    # report
    cases += [Case(b["report"] + ("--types", v), f"--types {v!r}", "types")
              for v in ("", "E", "AX", "A-B", "1")]
    rb = b["report"] + ("--bench", str(f["csv"]), "--bench-type", "B", "--bench-pressure", "40")
    cases += _numbers(rb, ("bench-pressure", "bench-reservoir"))
    cases += [Case(b["report"] + ("--bench-type", "B"), "bench type without a bench", "bench-type"),
              Case(rb[:-2], "bench without its pressure", "bench-pressure"),
              Case(rb[:-4] + ("--bench-type", "E", "--bench-pressure", "40"),
                   "unknown bench type", "type"),
              Case(rb + ("--bench-material", "rubber"), "unknown bench material", "material"),
              Case(b["report"] + ("--bench", str(tmp / "missing.csv"), "--bench-type", "B",
                                  "--bench-pressure", "40"), "missing bench", "missing.csv")]
    cases += _numbers(b["report"], ("workers",))
    closed = f"tcp://127.0.0.1:{_closed_port()}"
    cases += [Case(b["report"] + ("--scheduler", closed), "no scheduler answers", "scheduler"),
              Case(b["report"] + ("--workers", "2", "--scheduler", closed),
                   "workers with a scheduler", "workers")]
    cases += [Case(b["report"] + ("--scheduler", v), f"--scheduler {v!r}", "scheduler")
              for v in ("", " ", "http://127.0.0.1:8786", "tcp://", "tcp://127.0.0.1",
                        "tcp://127.0.0.1:port", "127.0.0.1:99999")]
    cases += _out_dirs(("report", "--cache", str(tmp / "cache")), "--out", f)
    cases += _out_dirs(("report", "--out", str(tmp / "out")), "--cache", f)
    # argparse's own mistakes, every verb
    for verb, base in b.items():
        cases += [Case(base + ("--no-such-option",), "unknown option", "no-such-option"),
                  Case(base + ("--quiet=3",) if "--quiet" in base else base + ("--x=1",),
                       "value to a flag or unknown", None)]
    cases += [Case(("membrane", "--type"), "missing value", "type"),
              Case(("nothing",), "unknown verb", None),
              Case((), "no verb", None)]
    return cases


def _closed_port() -> int:
    """A local TCP port nothing listens on (bound, then released)."""
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


#: Values no sweep axis accepts (a value, a list, a grid or, with --samples, a range).
SWEEP_NOT_A_SPEC = ("abc", "", " ", "nan", "inf", "-inf", "0x", "1,,2", ",", "1:2:0", "1:2:1",
                    "2:1:3", "1:2:3:4", "1:2", "1:x:3", "1:2:2.5")
#: Values out of a sweep input's own range (limits between inputs are a row's, not the CLI's).
SWEEP_OUT_OF_RANGE = {"w": ("0", "-1", "1e9", "1e-9", "11,-1", "-1:20:3"),
                      "h": ("0", "-1", "1e9"), "l": ("-1", "1e9"), "t0": ("0", "-1", "1e3"),
                      "n1": ("0.5", "0", "1e9", "0.5:3:3"), "n2": ("0.5", "-2", "1e9"),
                      "cy": ("-1", "1", "1.5", "0:1:3"), "pressure": ("-1", "1e5", "10,-1"),
                      "reservoir": ("-1", "-1e-3", "-1:5:2")}


def _sweep_cases(f, b, tmp) -> list[Case]:
    """spsc sweep: every axis, the Latin hypercube options, the model's settings, where it runs
    and its outputs."""
    base = b["sweep"]
    cases = []
    for name, bad in SWEEP_OUT_OF_RANGE.items():
        for v in SWEEP_NOT_A_SPEC + bad:
            cases.append(Case(base + (f"--{name}", v), f"sweep --{name} {v!r}", name))
    for opt, values in (("samples", ("0", "-1", "2.5", "abc", "")), ("seed", ("-1", "abc", "2.5")),
                        ("points", ("0", "1", "-3", "2.5", "1e9", "abc", "")),
                        ("stroke", ("abc", "", "nan", "inf", "-inf", "-1", "0")),
                        ("workers", ("0", "-1", "2.5", "two", "10000", "")),
                        ("process", ("cnc", "")), ("footprint", ("huge",)),
                        ("type", ("E", "", "A:B", "A,,B", "A:B:3")),
                        ("material", ("rubber", "", "tpu60a,rubber", str(tmp / "missing.json"),
                                      str(f["bad.json"]), str(f["ogden.json"])))):
        extra = ("--w", "9:11") if opt == "samples" else ()
        cases += [Case(base + extra + (f"--{opt}", v), f"sweep --{opt} {v!r}", opt)
                  for v in values]
    cases += [Case(base + ("--model", v), f"sweep --model {v!r}", "model")
              for v in ("fem", "nothing", "")]
    for v in ("", "http://x:1", "tcp://", "tcp://host", "tcp://127.0.0.1:1"):
        cases.append(Case(base + ("--scheduler", v), f"sweep --scheduler {v!r}", "scheduler"))
    cases += [Case(base + ("--workers", "2", "--scheduler", "tcp://127.0.0.1:1"),
                   "workers with a scheduler", "workers"),
              Case(base + ("--w", "9:11:3", "--samples", "4"), "a grid with --samples", "w"),
              Case(base + ("--samples", "4"), "--samples with no range", "samples"),
              Case(base + ("--pressure", "0,40"), "a membrane without pressure", "pressure"),
              Case(base[:3] + ("--out", str(tmp / "sweep.parquet"), "--pressure", "0"),
                   "the default membrane without pressure", "pressure"),
              Case(base + ("--type", "A,B,C,D", "--w", "1:20:60", "--h", "5:20:60"),
                   "a sweep beyond the size limit", "sweep size"),
              Case(("sweep", "--w", "11", "--out", str(tmp / "s.parquet")), "no type, not all "
                   "seven parameters", "geometry"),
              Case(base[:5], "no --out", "out"),
              Case(base[:5] + ("--out", str(tmp / "sweep.csv")), "--out not Parquet", "out"),
              Case(base + ("--csv", str(tmp / "sweep.txt")), "--csv not .csv", "csv")]
    cases += _outputs(base[:5], "--out", f, tmp, ".parquet")
    cases += _outputs(base, "--csv", f, tmp, ".csv")
    return cases


#: Values no design input accepts (a value, a choice a,b or an interval lo:hi).
DESIGN_NOT_A_SPEC = ("abc", "", " ", "nan", "inf", "-inf", "0x", "1,,2", ",", "1:2:3", "2:1",
                     "1:1", "1:x", ":", "1:", "1.0005:2")


def _design_cases(f, b, tmp) -> list[Case]:
    """spsc design: the goal, every input of the space, the search's and the check's settings,
    where it runs and its outputs."""
    base = b["design"]
    cases = []
    for name, bad in SWEEP_OUT_OF_RANGE.items():
        for v in DESIGN_NOT_A_SPEC + bad:
            cases.append(Case(base + (f"--{name}", v), f"design --{name} {v!r}", name))
    for v in ("stiffness=6", "stiffness_high", "stiffness_high>6", "stiffness_high=abc",
              "stiffness_high=0", "stiffness_high=-1", "stiffness_high=inf", "=6", ""):
        cases.append(Case(base[:1] + ("--target", v) + base[3:], f"--target {v!r}", "target"))
    for opt, values in (("minimize", ("volume", "", "cavity_mm3,")),
                        ("maximize", ("stiffness", "")), ("tol", ("abc", "-1", "100", "nan")),
                        ("trials", ("0", "-1", "2.5", "abc", "", "1e9", "1000000")),
                        ("seed", ("-1", "abc", "2.5", "5000000000")),
                        ("points", ("0", "1", "-3", "2.5", "1e9", "abc", "")),
                        ("stroke", ("abc", "", "nan", "inf", "-inf", "-1", "0", "8", "100")),
                        ("workers", ("0", "-1", "2.5", "two", "10000", "")),
                        ("process", ("cnc", "")), ("mesh-size", ("0", "-1", "abc", "nan", "inf")),
                        ("type", ("E", "", "A:B", "A,,B", "A,A", "AB")),
                        ("material", ("rubber", "", "tpu60a,as40", str(tmp / "missing.json"),
                                      str(f["bad.json"]), str(f["ogden.json"])))):
        cases += [Case(base + (f"--{opt}", v), f"design --{opt} {v!r}", opt) for v in values]
    for opt, values in (("model", ("fem", "nothing", "")), ("sampler", ("cmaes", "")),
                        ("verify", ("wall", ""))):
        cases += [Case(base + (f"--{opt}", v), f"design --{opt} {v!r}", opt) for v in values]
    for v in ("", "http://x:1", "tcp://", "tcp://host", "tcp://127.0.0.1:1"):
        cases.append(Case(base + ("--scheduler", v), f"design --scheduler {v!r}", "scheduler"))
    cases += [Case(base + ("--workers", "2", "--scheduler", "tcp://127.0.0.1:1"),
                   "workers with a scheduler", "workers"),
              Case(base[:1] + base[3:], "no goal", "goal"),
              Case(base + ("--minimize", "jnd_mm", "--maximize", "jnd_mm"),
                   "a metric minimised and maximised", "maximize"),
              Case(base + ("--pressure", "0"), "a membrane model without pressure", "pressure"),
              Case(base + ("--h", "3:5"), "stroke above the smallest h", "stroke"),
              Case(base + ("--w", "1:3", "--h", "20:30", "--stroke", "2"),
                   "h/w beyond its limit at the space's middle", "h"),
              Case(base + ("--verify", "fem", "--mesh-size", "1e-4"), "a FEM mesh too fine",
                   "mesh size"),
              Case(base[:5], "no --out", "out"),
              Case(base + ("--json", str(tmp / "design.txt")), "--json not .json", "json"),
              Case(base + ("--csv", str(tmp / "design.txt")), "--csv not .csv", "csv")]
    cases += _out_dirs(base[:5], "--out", f)
    cases += _outputs(base, "--json", f, tmp)
    cases += _outputs(base, "--csv", f, tmp, ".csv")
    return cases


def _fit_material_cases(f, b, tmp) -> list[Case]:
    """spsc fit-material: bad data files, ranges, laws, tests, units, outputs; material files
    refused by the models and the bladder."""
    base, data = b["fit-material"], str(f["tension.csv"])
    cases = [Case(("fit-material", str(f[k])), k, k) for k in _TENSION_BAD]
    cases += [Case(("fit-material", str(tmp / "missing.csv")), "missing file", "missing.csv"),
              Case(("fit-material", str(f["dir.csv"])), "a folder as data", "folder.csv"),
              Case(("fit-material", str(f["binary.csv"])), "binary data", "binary.csv"),
              Case(("fit-material", str(f["empty.csv"])), "an empty file", "empty.csv"),
              Case(("fit-material", data, data), "one file twice", "tension.csv"),
              Case(("fit-material",), "no data", "DATA.csv"),
              Case(("fit-material", data, "--list-catalogue"), "catalogue with data",
                   "list-catalogue")]
    for v in ("5:6", "abc", "3:2", "0:1.2", "1:1", "nan:3", "1:2:3", "", "-1:2", "1,2"):
        cases.append(Case(base + ("--range", v), f"--range {v!r}", "range"))
    cases += [Case(base[:2] + ("--law", v), f"--law {v!r}", "law") for v in ("gent", "")]
    cases += [Case(base + ("--test", v), f"--test {v!r}", "test") for v in ("torsion", "")]
    cases += [Case(base + ("--test", "uniaxial", "--test", "planar"), "two tests, one file",
                   "test"),
              Case(("fit-material", data, "--test", "planar", "--test", "uniaxial", "--test",
                    "planar"), "three tests, one file", "test")]
    cases += [Case(base[:2] + ("--law", "ogden", "--ogden-terms", v), f"--ogden-terms {v}",
                   "ogden-terms") for v in ("0", "4", "2.5", "abc", "")]
    cases += [Case(base[:2] + ("--law", "ogden", "--ogden-terms", "3"), "6 points, 6 constants",
                   "data points")]
    cases += [Case(base + ("--strain-unit", v), f"--strain-unit {v!r}", "strain-unit")
              for v in ("mm", "")]
    cases += [Case(base + ("--stress-unit", v), f"--stress-unit {v!r}", "stress-unit")
              for v in ("bar", "")]
    cases += [Case(base + ("--weighting", "log"), "unknown weighting", "weighting"),
              Case(base + ("--name", " "), "blank name", "name"),
              Case(base + ("--out", str(tmp / "m.txt")), "material file not .json", "out"),
              Case(base + ("--png", str(tmp / "fit.xyz")), "unknown image format", "png")]
    for opt, suffix in (("--json", ".json"), ("--out", ".json"), ("--png", ".png")):
        cases += _outputs(base, opt, f, tmp, suffix)
    # material files through the models and the bladder
    for key, why in (("ogden.json", "an Ogden file in a model"),
                     ("soft.json", "a negative modulus"), ("foreign.json", "another schema"),
                     ("law.json", "an unknown law"), ("bad.json", "not JSON"),
                     ("dir.json", "a folder named .json")):
        for verb in ("membrane", "curve-wall", "curve-fem", "calibrate"):
            cases.append(Case(b[verb] + ("--material", str(f[key])), why, "material"))
    cases += [Case(b["membrane"] + ("--material", str(tmp / "missing.json")),
                   "missing material file", "material"),
              Case(b["bladder"] + ("--material", str(f["ogden.json"])),
                   "a material file for the bladder", "material")]
    return cases


#: Minimum wall (mm) of each material's process (cad/process.py), for random designs that
#: should pass the gate.
_MATERIAL_MIN_WALL = {"tpu60a": 0.8, "elastic50a": 0.5, "silicone40a": 0.5, "as40": 1.0}


def random_design(rng) -> dict:
    """A random valid bladder design (numpy Generator ``rng``): one of the types A–D with its
    form factors drawn in the paper's family (sec. 2.2) and the verified design space (h/w
    0.5–2, l/w 0–3, t0/w 0.02–0.2, n 1–8, c_y ≤ 0.9), a wall at or above the material's
    process minimum, any flange holes and a tube that fits the flange. Values rounded to 4
    significant digits, as a user would type them; :func:`design_argv` makes the options."""
    kind = str(rng.choice(list("ABCD")))
    material = str(rng.choice(list(_MATERIAL_MIN_WALL)))
    w = rng.uniform(5.0, 15.0)
    h = w * rng.uniform(0.5, 2.0)
    l = 0.0 if rng.random() < 0.25 else w * rng.uniform(0.0, 3.0)
    t_min = max(_MATERIAL_MIN_WALL[material], 0.02 * w)
    t0 = rng.uniform(t_min, max(t_min, 0.2 * w))
    n1 = {"A": rng.uniform(3, 8), "B": 2.0, "C": rng.uniform(2, 8), "D": 2.0}[kind]
    n2 = {"A": rng.uniform(2, 8), "B": rng.uniform(2, 8), "C": 1.0, "D": rng.uniform(2, 8)}[kind]
    cy = rng.uniform(0.05, 0.9) if kind == "D" else 0.0
    r4 = lambda v: float(f"{v:.4g}")  # noqa: E731
    return {"type": kind, "w": r4(w), "h": r4(h), "l": r4(l),
            "t0": max(r4(t0), _MATERIAL_MIN_WALL[material]), "n1": r4(n1), "n2": r4(n2),
            "cy": r4(cy), "material": material, "flange_holes": int(rng.choice([0, 2, 4])),
            "tube_id": float(f"{rng.uniform(1.6, 4.4):.3g}")}


def design_argv(d: dict) -> list[str]:
    """``spsc bladder`` options of a design of :func:`random_design`."""
    argv = ["--type", d["type"]]
    for k in ("w", "h", "l", "t0", "n1", "n2", "cy"):
        argv += [f"--{k}", f"{d[k]:g}"]
    return argv + ["--material", d["material"], "--flange-holes", str(d["flange_holes"]),
                   "--tube-id", f"{d['tube_id']:g}"]
