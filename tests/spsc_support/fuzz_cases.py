"""Invalid invocations of every ``spsc`` verb, as a table: the fuzz test runs them in-process
(``tests/test_fuzz_cli.py``) and ``bench/bench_badinput.py`` as subprocesses.

Each :class:`Case` is an argv that must end in exactly one line on stderr naming ``names``
(the option or parameter at fault), exit code 2, before any work starts. The cases are built
on valid base invocations of each verb with one thing wrong: a bad number (text, empty,
non-finite, out of range), a cross-parameter limit, a bad choice, an output path that cannot be
written, a bad input file, or an argparse mistake. :func:`fixtures` writes the files they use.
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from .fuzz_base import (GEOMETRY, KINDS, SETUP, Case, not_dask_address, numbers, out_dirs,
                        outputs)
from .fuzz_fixtures import bases, fixtures
from .fuzz_studies import (bench_gap_cases, design_argv, design_cases, fit_material_cases,
                           random_design, surrogate_cases, sweep_cases, tolerance_cases,
                           virtual_cases)
from .fuzz_sense import sense_cases
from .fuzz_time import simulate_cases
from .fuzz_contact import contact_cases
from .fuzz_durability import fatigue_cases, puncture_cases

__all__ = ["Case", "KINDS", "classes", "fixtures", "invalid_cases", "random_design",
           "design_argv"]


def invalid_cases(tmp: Path) -> list[Case]:
    """Every invalid invocation, with fixtures under ``tmp``."""
    tmp = Path(tmp)
    f = fixtures(tmp)
    b = bases(f, tmp)
    cases: list[Case] = []
    cases += _chamber_cases(f, b, tmp)
    cases += _bladder_cases(f, b, tmp)
    cases += _part_cases(f, b, tmp)
    cases += _mold_fingertip_cases(f, b, tmp)
    cases += _check_identify_cases(f, b, tmp)
    cases += _calibrate_cases(f, b, tmp)
    cases += _report_cases(f, b, tmp)
    cases += simulate_cases(f, tmp)
    cases += bench_gap_cases(f, b)
    cases += surrogate_cases(f, tmp)
    cases += tolerance_cases(f, tmp)
    cases += virtual_cases(f, tmp)
    cases += contact_cases(f, b)
    cases += sense_cases(f, tmp)
    cases += fatigue_cases(f, tmp)
    cases += puncture_cases(f, tmp)
    cases += [replace(c, kind="argparse") for c in _argparse_cases(f, b, tmp)]
    return [c if c.kind != "other" else replace(c, kind=_kind(c.why)) for c in cases]


#: Words of a case's ``why`` -> its class, for the cases built without one (first match).
_WHY_KINDS = (("twice", "duplicate"), ("unknown", "choice"), ("bad choice", "choice"),
              ("empty type", "choice"), ("empty material", "choice"),
              ("empty process", "choice"), ("scheduler", "scheduler"),
              ("missing", "input file"), ("folder", "input file"), ("binary", "input file"),
              ("empty", "input file"), ("text", "input file"), ("not json", "input file"),
              ("design file", "design file"), ("surface", "part surface"),
              ("cavity", "part surface"), ("without", "combination"), ("with --", "combination"),
              ("no ", "combination"), ("predict", "number list"))


def _kind(why: str) -> str:
    low = why.lower()
    return next((kind for word, kind in _WHY_KINDS if word in low), "other")


def classes(cases) -> dict:
    """Class -> number of cases (every class of :data:`~.fuzz_base.KINDS` the table holds)."""
    from collections import Counter

    return dict(Counter(c.kind for c in cases).most_common())


def _chamber_cases(f, b, tmp) -> list[Case]:
    """The chamber's parameters, the setup and each model's options, on every verb that takes them."""
    cases: list[Case] = []
    geometry_verbs = ("bladder", "membrane", "fem", "identify", "curve-membrane",
                      "curve-simplified", "curve-wall", "curve-fem")
    for verb in geometry_verbs:
        cases += numbers(b[verb], GEOMETRY)
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
        cases += numbers(b[verb], SETUP)
        cases += [Case(b[verb] + ("--material", "rubber"), "unknown material", "material"),
                  Case(b[verb] + ("--material", ""), "empty material", "material")]
        cases += outputs(b[verb], "--json", f, tmp)
        cases += outputs(b[verb], "--csv", f, tmp, ".csv")
        cases += outputs(b[verb], "--png", f, tmp, ".png")
        cases += [Case(b[verb] + ("--png", str(tmp / "plot.xyz")), "unknown image format",
                       "png"),
                  Case(b[verb] + ("--png", str(tmp / "plot")), "no image suffix", "png")]
        if verb in ("membrane", "curve-membrane", "curve-simplified"):
            cases.append(Case(b[verb] + ("--pressure", "0"), "a membrane without pressure",
                              "pressure"))
        # stroke against the chamber: above a smaller chamber's height
        cases.append(Case(b[verb] + ("--h", "4", "--stroke", "5"), "stroke above h", "stroke"))
    for verb in ("fem", "curve-wall", "curve-fem"):
        cases += numbers(b[verb], ("mesh-size", "layers"))
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
    return cases


def _bladder_cases(f, b, tmp) -> list[Case]:
    """spsc bladder and spsc haptic."""
    cases: list[Case] = []
    # bladder
    cases += numbers(b["bladder"], ("flange-holes", "tube-id"))
    cases += out_dirs(b["bladder"][:3], "--out", f)
    cases += [Case(b["bladder"] + ("--material", "rubber"), "unknown material", "material"),
              Case(b["bladder"] + ("--tube-id", "30"), "tube wider than the base", "tube-id")]
    # haptic: the mesh of its three part runs and its folder
    cases += numbers(b["haptic"], ("mesh-size",))
    cases += out_dirs(b["haptic"][:1], "--out", f)
    cases += out_dirs(b["haptic"][:3], "--parts", f)
    cases += [Case(b["haptic"] + ("--mesh-size", "0.1"), "a mesh too fine for 2 cores",
                   "mesh size")]
    return cases


def _part_cases(f, b, tmp) -> list[Case]:
    """spsc fem --part: the setup, the part, the mount, the plate."""
    cases: list[Case] = []
    # fem --part: the setup, the part, the mount, the plate
    fp = b["fem-part"]
    cases += numbers(fp, SETUP + ("mesh-size",))
    cases += outputs(fp, "--json", f, tmp) + outputs(fp, "--csv", f, tmp, ".csv")
    cases += out_dirs(fp, "--vtu", f)
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
                   "part"),
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
              Case(b["fem"] + ("--plate-at", "0,0,1"), "--plate-at without --part", "plate-at"),
              Case(b["fem"] + ("--cache", str(tmp / "cache")), "--cache without --part",
                   "cache", "combination")]
    cases += _part_input_cases(f, fp, tmp)
    return cases


def _part_input_cases(f, fp, tmp) -> list[Case]:
    """The part's surface, its design file's fields, and its lists of numbers."""
    fix = ("--fix", "z<=0", "--quiet")
    cases = [Case(("fem", "--part", str(f[k])) + fix, why, "part", "part surface")
             for k, why in (("nonmanifold.stl", "a non-manifold edge (a tetrahedron on it)"),
                            ("pinched.stl", "a non-manifold vertex (manifold3d accepts it)"))]
    motor = ("fem", "--part", str(f["motor-part.stl"])) + fix
    cases += [Case(motor + ("--motor",), "--motor on a design naming the motor as a string",
                   "motor", "design file"),
              Case(motor, "a design file whose motor is a string", "motor", "design file"),
              Case(fp + ("--design", str(f["array.design.json"])), "a design file that is a "
                   "JSON array", "design", "design file")]
    for opt in ("--plate-at", "--plate-normal"):
        cases += [Case(fp + (opt, v), f"{opt} {v!r}", opt.lstrip("-"), "number list")
                  for v in ("0,,1", "0,0,", ",0,0", "0,0,0,1", "0,0,nan")]
        cases.append(Case(fp + (opt, "x,y,z", opt, "0,0,-1"), f"{opt} given twice",
                          opt.lstrip("-"), "number list"))
    cases += out_dirs(fp, "--cache", f)
    return cases


def _mold_fingertip_cases(f, b, tmp) -> list[Case]:
    """spsc mold and spsc fingertip."""
    cases: list[Case] = []
    # mold
    cases += numbers(b["mold"], ("shrinkage", "clearance", "wall", "tube-id", "flange-holes")
                      + GEOMETRY)
    cases += out_dirs(("mold", "--type", "B", "--no-step", "--no-render"), "--out", f)
    cases += [Case(b["mold"] + ("--process", "injection"), "an unknown process", "process"),
              Case(b["mold"] + ("--material", "pla"), "an unknown silicone", "material"),
              Case(b["mold"] + ("--parting", "y"), "an unknown parting", "parting"),
              Case(("mold", "--no-render"), "no part and no geometry", "geometry"),
              Case(("mold", str(f["part.stl"]), "--no-render"), "a part that is no bladder",
                   "part"),
              Case(("mold", str(tmp / "none.stl"), "--no-render"), "a missing part", "part"),
              Case(("mold", str(f["part.stl"]), "--type", "B"), "a part and a type", "part"),
              Case(b["bladder"] + ("--haptic", "--w", "5", "--h", "5", "--t0", "0.5"),
                   "a chamber too narrow for the motor", "haptic"),
              Case(b["bladder"] + ("--haptic", "--type", "D", "--h", "3"),
                   "a dome lower than the motor and its film", "haptic")]
    # fingertip
    cases += numbers(b["fingertip"], ("angle", "pocket-diameter", "pocket-depth"))
    cases += [Case(b["fingertip"] + ("--mesh-size", "1"), "--mesh-size without --fem",
                   "mesh-size"),
              Case(b["fingertip"] + ("--cases", "pulp-high-40"), "--cases without --fem",
                   "cases"),
              Case(b["fingertip"] + ("--fem", "--cases", "palm-high-40"), "an unknown case",
                   "cases"),
              Case(b["fingertip"] + ("--fem", "--mesh-size", "0.01"), "a mesh too fine",
                   "mesh-size"),
              Case(b["fingertip"] + ("--fem", "--mesh-size", "nan"), "a NaN mesh", "mesh-size"),
              Case(b["fingertip"] + ("--fem", "--cases", "pulp-high-40,pulp-high-40"),
                   "a case twice (it would run twice)", "cases", "duplicate"),
              Case(b["fingertip"] + ("--fem", "--cases", "pulp-high-40,pulp-high-40kPa"),
                   "a case twice, spelt two ways", "cases", "duplicate"),
              Case(b["fingertip"] + ("--fem", "--cases", "pulp-high-40,,distal-high-40"),
                   "an empty case", "cases", "number list"),
              Case(b["fingertip"] + ("--fem", "--cases", "palm-x", "--cases", "pulp-high-40"),
                   "--cases given twice", "cases", "number list")]
    cases += out_dirs(("fingertip",), "--out", f)
    cases += [Case(b["fingertip"] + ("--process", "foo"), "unknown process", "process"),
              Case(b["fingertip"] + ("--process", ""), "empty process", "process")]
    return cases


def _check_identify_cases(f, b, tmp) -> list[Case]:
    """spsc check and spsc identify."""
    cases: list[Case] = []
    # check
    cases += numbers(b["check"], ("min-wall",))
    cases += outputs(b["check"][:2], "--json", f, tmp)
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
    cases += numbers(b["identify"], ("pressure", "reservoir", "polytropic-n",
                                      "bladder-volume"))
    cases += outputs(b["identify"], "--json", f, tmp)
    cases += outputs(b["identify"], "--csv", f, tmp, ".csv")
    ident = b["identify"][2:]
    cases += predict_lists(b["identify"], with_empty=True)
    for key, why in (("empty.csv", "an empty CSV"), ("nocol.csv", "a missing column"),
                     ("badrow.csv", "a text value"), ("short.csv", "too few rows"),
                     ("dir.csv", "a folder named .csv"), ("binary.csv", "binary data")):
        cases.append(Case(("identify", str(f[key])) + ident, why, None))
    cases += [Case(("identify", str(tmp / "missing.csv")) + ident, "missing CSV", "missing.csv"),
              Case(("identify", str(f["csv"]), "--pressure", "40"), "no chamber", None),
              Case(("identify", str(f["csv"]), "--type", "B"), "no pressure", "pressure")]
    return cases


def _calibrate_cases(f, b, tmp) -> list[Case]:
    """spsc calibrate, then the fit-material, sweep and design tables."""
    cases: list[Case] = []
    # calibrate
    cal = b["calibrate"]
    cases += numbers(cal, ("pressure", "reservoir", "polytropic-n", "mesh-size", "layers",
                            "predict-stroke"))
    cases += outputs(cal, "--json", f, tmp)
    cases += outputs(cal, "--png", f, tmp, ".png")
    cases += predict_lists(cal, with_empty=False)
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
    cases += fit_material_cases(f, b, tmp)
    cases += sweep_cases(f, b, tmp)
    cases += design_cases(f, b, tmp)
    return cases


def _report_cases(f, b, tmp) -> list[Case]:
    """spsc report."""
    cases: list[Case] = []
    # report
    cases += [Case(b["report"] + ("--types", v), f"--types {v!r}", "types")
              for v in ("", "E", "AX", "A-B", "1")]
    rb = b["report"] + ("--bench", str(f["csv"]), "--bench-type", "B", "--bench-pressure", "40")
    cases += numbers(rb, ("bench-pressure", "bench-reservoir"))
    cases += [Case(b["report"] + ("--bench-type", "B"), "bench type without a bench", "bench-type"),
              Case(rb[:-2], "bench without its pressure", "bench-pressure"),
              Case(rb[:-4] + ("--bench-type", "E", "--bench-pressure", "40"),
                   "unknown bench type", "type"),
              Case(rb + ("--bench-material", "rubber"), "unknown bench material", "material"),
              Case(b["report"] + ("--bench", str(tmp / "missing.csv"), "--bench-type", "B",
                                  "--bench-pressure", "40"), "missing bench", "missing.csv")]
    cases += numbers(b["report"], ("workers",))
    closed = f"tcp://127.0.0.1:{_closed_port()}"
    cases += [Case(b["report"] + ("--scheduler", closed), "no scheduler answers", "scheduler"),
              Case(b["report"] + ("--scheduler", not_dask_address()), "a port that listens "
                   "but is not a Dask scheduler", "scheduler", "scheduler"),
              Case(b["report"] + ("--workers", "2", "--scheduler", closed),
                   "workers with a scheduler", "workers")]
    cases += [Case(b["report"] + ("--scheduler", v), f"--scheduler {v!r}", "scheduler")
              for v in ("", " ", "http://127.0.0.1:8786", "tcp://", "tcp://127.0.0.1",
                        "tcp://127.0.0.1:port", "127.0.0.1:99999")]
    cases += out_dirs(("report", "--cache", str(tmp / "cache")), "--out", f)
    cases += out_dirs(("report", "--out", str(tmp / "out")), "--cache", f)
    return cases


def _argparse_cases(f, b, tmp) -> list[Case]:
    """argparse's own mistakes, every verb."""
    cases: list[Case] = []
    # argparse's own mistakes, every verb
    for verb, base in b.items():
        cases += [Case(base + ("--no-such-option",), "unknown option", "no-such-option"),
                  Case(base + ("--quiet=3",) if "--quiet" in base else base + ("--x=1",),
                       "value to a flag or unknown", None)]
    cases += [Case(("membrane", "--type"), "missing value", "type"),
              Case(("nothing",), "unknown verb", None),
              Case((), "no verb", None)]
    return cases


def predict_lists(base, *, with_empty: bool) -> list[Case]:
    """--predict-pressures / --predict-reservoirs: every way a comma list of numbers goes
    wrong (``with_empty``: an empty list is an error, not 'no predictions')."""
    bad = (",", "abc", "10,,40", "10,", ",10", "10,x", "10,10", "-1", "-5,10", "nan", "inf")
    cases = []
    for opt, extra in (("predict-pressures", ("1e5", "10,1e5")), ("predict-reservoirs", ())):
        for v in bad + extra + (("",) if with_empty else ()):
            cases.append(Case(base + (f"--{opt}", v), f"--{opt} {v!r}", opt, "number list"))
        for first in ("-1", "x", "10,,40"):  # a bad list, then a good one: argparse kept the last
            cases.append(Case(base + (f"--{opt}", first, f"--{opt}", "0"),
                              f"--{opt} {first!r} then 0", opt, "number list"))
    return cases


def _closed_port() -> int:
    """A local TCP port nothing listens on (bound, then released)."""
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]
