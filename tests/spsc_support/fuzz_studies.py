"""Invalid invocations of the study verbs (``spsc sweep``, ``spsc design``, ``spsc
fit-material``) and random valid designs for the gate's property test and the bad-input bench."""

from __future__ import annotations

from pathlib import Path

from .fuzz_base import Case, not_dask_address, out_dirs, outputs
from .fuzz_fixtures import TENSION_BAD

__all__ = ["sweep_cases", "design_cases", "fit_material_cases", "random_design", "design_argv",
           "bench_gap_cases"]



#: Values no sweep axis accepts (a value, a list, a grid or, with --samples, a range).
SWEEP_NOT_A_SPEC = ("abc", "", " ", "nan", "inf", "-inf", "0x", "1,,2", ",", "1:2:0", "1:2:1",
                    "2:1:3", "1:2:3:4", "1:2", "1:x:3", "1:2:2.5")
#: Values out of a sweep input's own range (limits between inputs are a row's, not the CLI's).
SWEEP_OUT_OF_RANGE = {"w": ("0", "-1", "1e9", "1e-9", "11,-1", "-1:20:3"),
                      "h": ("0", "-1", "1e9"), "l": ("-1", "1e9"), "t0": ("0", "-1", "1e3"),
                      "n1": ("0.5", "0", "1e9", "0.5:3:3"), "n2": ("0.5", "-2", "1e9"),
                      "cy": ("-1", "1", "1.5", "0:1:3"), "pressure": ("-1", "1e5", "10,-1"),
                      "reservoir": ("-1", "-1e-3", "-1:5:2")}


def sweep_cases(f, b, tmp) -> list[Case]:
    """spsc sweep: every axis, the Latin hypercube options, the model's settings, where it runs
    and its outputs."""
    base = b["sweep"]
    cases = []
    for name, bad in SWEEP_OUT_OF_RANGE.items():
        for v in SWEEP_NOT_A_SPEC + bad:
            cases.append(Case(base + (f"--{name}", v), f"sweep --{name} {v!r}", name,
                              "range" if v in bad else "number list"))
    for opt, values in (("samples", ("0", "-1", "2.5", "abc", "")), ("seed", ("-1", "abc", "2.5")),
                        ("points", ("0", "1", "-3", "2.5", "1e9", "abc", "")),
                        # 13 and beyond: no chamber of the space (h = 13 mm) takes it
                        ("stroke", ("abc", "", "nan", "inf", "-inf", "-1", "0", "13", "1e9")),
                        ("workers", ("0", "-1", "2.5", "two", "10000", "")),
                        ("process", ("cnc", "")), ("footprint", ("huge",)),
                        ("type", ("E", "", "A:B", "A,,B", "A:B:3")),
                        ("material", ("rubber", "", "tpu60a,rubber", str(tmp / "missing.json"),
                                      str(f["bad.json"])))):
        extra = ("--w", "9:11") if opt == "samples" else ()
        cases += [Case(base + extra + (f"--{opt}", v), f"sweep --{opt} {v!r}", opt)
                  for v in values]
    cases += [Case(base + ("--model", v), f"sweep --model {v!r}", "model")
              for v in ("fem", "nothing", "")]
    cases += [Case(base + (f"--{k}", v), f"sweep --{k} {v!r}: a value twice", k, "duplicate")
              for k, v in (("type", "B,b"), ("w", "9,9.0"), ("material", "tpu60a,tpu60a"))]
    for v in ("", "http://x:1", "tcp://", "tcp://host", "tcp://127.0.0.1:1"):
        cases.append(Case(base + ("--scheduler", v), f"sweep --scheduler {v!r}", "scheduler"))
    cases.append(Case(base + ("--scheduler", not_dask_address()), "a port that listens but is "
                      "not a Dask scheduler", "scheduler", "scheduler"))
    cases += [Case(base + (f"--{k}", bad, f"--{k}", good), f"sweep --{k} {bad!r} then "
                   f"{good!r}", k, "number list") for k, bad, good in TWICE]
    cases += [Case(base + ("--workers", "2", "--scheduler", "tcp://127.0.0.1:1"),
                   "workers with a scheduler", "workers"),
              Case(base + ("--w", "9:11:3", "--samples", "4"), "a grid with --samples", "w"),
              Case(base + ("--samples", "4"), "--samples with no range", "samples"),
              Case(base + ("--pressure", "0,40"), "a membrane without pressure", "pressure"),
              Case(base[:3] + ("--out", str(tmp / "sweep.parquet"), "--pressure", "0"),
                   "the default membrane without pressure", "pressure"),
              Case(base[:1] + base[3:] + ("--type", "A,B,C,D", "--w", "1:20:60", "--h", "5:20:60"),
                   "a sweep beyond the size limit", "sweep size"),
              Case(("sweep", "--w", "11", "--out", str(tmp / "s.parquet")), "no type, not all "
                   "seven parameters", "geometry"),
              Case(base[:5], "no --out", "out"),
              Case(base[:5] + ("--out", str(tmp / "sweep.csv")), "--out not Parquet", "out"),
              Case(base + ("--csv", str(tmp / "sweep.txt")), "--csv not .csv", "csv")]
    cases += outputs(base[:5], "--out", f, tmp, ".parquet")
    cases += outputs(base, "--csv", f, tmp, ".csv")
    return cases


#: An input given twice, a bad value first (argparse would keep the last, good one).
TWICE = (("w", "-1", "11"), ("pressure", "1,,2", "40"), ("type", "E", "B"))

#: Values no design input accepts (a value, a choice a,b or an interval lo:hi).
DESIGN_NOT_A_SPEC = ("abc", "", " ", "nan", "inf", "-inf", "0x", "1,,2", ",", "1:2:3", "2:1",
                     "1:1", "1:x", ":", "1:", "1.0005:2")


def design_cases(f, b, tmp) -> list[Case]:
    """spsc design: the goal, every input of the space, the search's and the check's settings,
    where it runs and its outputs."""
    base = b["design"]
    cases = []
    for name, bad in SWEEP_OUT_OF_RANGE.items():
        for v in DESIGN_NOT_A_SPEC + bad:
            cases.append(Case(base + (f"--{name}", v), f"design --{name} {v!r}", name,
                              "range" if v in bad else "number list"))
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
                                      str(f["bad.json"])))):
        cases += [Case(base + (f"--{opt}", v), f"design --{opt} {v!r}", opt) for v in values]
    for opt, values in (("model", ("fem", "nothing", "")), ("sampler", ("cmaes", "")),
                        ("verify", ("wall", ""))):
        cases += [Case(base + (f"--{opt}", v), f"design --{opt} {v!r}", opt) for v in values]
    for v in ("", "http://x:1", "tcp://", "tcp://host", "tcp://127.0.0.1:1"):
        cases.append(Case(base + ("--scheduler", v), f"design --scheduler {v!r}", "scheduler"))
    cases.append(Case(base + ("--scheduler", not_dask_address()), "a port that listens but is "
                      "not a Dask scheduler", "scheduler", "scheduler"))
    cases += [Case(base + (f"--{k}", bad, f"--{k}", good), f"design --{k} {bad!r} then "
                   f"{good!r}", k, "number list") for k, bad, good in TWICE]
    cases += [Case(base + ("--workers", "2", "--scheduler", "tcp://127.0.0.1:1"),
                   "workers with a scheduler", "workers"),
              Case(base[:1] + base[3:], "no goal", "goal"),
              Case(base + ("--target", "stiffness_high=6"), "a target twice", "target",
                   "duplicate"),
              Case(base + ("--target", "stiffness_high=7"), "two values asked of one metric",
                   "target", "combination"),
              Case(base[:1] + ("--target", "stiffness_high>=8", "--target", "stiffness_high<=5")
                   + base[3:], "a lower bound above the upper bound", "target", "combination"),
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
    cases += out_dirs(base[:5], "--out", f)
    cases += outputs(base, "--json", f, tmp)
    cases += outputs(base, "--csv", f, tmp, ".csv")
    return cases


def fit_material_cases(f, b, tmp) -> list[Case]:
    """spsc fit-material: bad data files, ranges, laws, tests, units, outputs; material files
    refused by the models and the bladder."""
    base, data = b["fit-material"], str(f["tension.csv"])
    shape = ("t-nonmono.csv", "t-negative.csv", "t-below1.csv", "t-falling.csv",
             "t-negstress.csv", "t-allneg.csv", "t-dip.csv")
    cases = [Case(("fit-material", str(f[k])), k, k,
                  "tension data" if k in shape else "input file") for k in TENSION_BAD]
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
        cases += outputs(base, opt, f, tmp, suffix)
    # material files through the models and the bladder (an Ogden file is a law the models
    # solve since issue 47)
    for key, why in (("soft.json", "a negative modulus"), ("foreign.json", "another schema"),
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


def bench_gap_cases(f, b) -> list[Case]:
    """spsc bench-gap: its types, material, folder and cluster."""
    g = b["bench-gap"]
    return out_dirs(g[:1], "--out", f) + [
        Case(g + ("--types", "BX"), "an unknown type", "types"),
        Case(g + ("--types", ""), "no type", "types"),
        Case(g + ("--material", "rubber"), "unknown material", "material"),
        Case(g + ("--workers", "0"), "no worker", "workers"),
        Case(g + ("--workers", "2", "--scheduler", "tcp://127.0.0.1:1"),
             "workers with a scheduler", "workers")]


def surrogate_cases(f, tmp) -> list[Case]:
    """spsc surrogate train and check, and spsc curve --model surrogate outside its domain."""
    t = ("surrogate", "train", "--out", str(tmp / "sur"))
    c = ("surrogate", "check")
    curve = ("curve", "--model", "surrogate", "--type", "B", "--l", "0")
    return out_dirs(("surrogate", "train"), "--out", f) + [
        Case(t + ("--designs", "5"), "too few designs", "designs", "range"),
        Case(t + ("--designs", "abc"), "designs as text", "designs", "number"),
        Case(t + ("--calibration", "1"), "too few calibration cases", "calibration", "range"),
        Case(t + ("--family", "cylinder"), "an unknown family", "family", "choice"),
        Case(t + ("--workers", "0"), "no worker", "workers", "range"),
        Case(c + ("--samples", "0"), "no sample", "samples", "range"),
        Case(c + (str(tmp / "missing.npz"),), "missing surrogate file", "surrogate",
             "input file"),
        Case(c + (str(f["file"]),), "a text file as the surrogate", "surrogate", "input file"),
        Case(c + ("--out", str(f["file"])), "--out an existing file", "out", "output folder"),
        Case(curve + ("--l", "4"), "a stadium outside every domain", "l", "range"),
        Case(curve + ("--material", "elastic50a"), "a law outside the domain", "material",
             "range"),
        Case(curve + ("--h", "30"), "h/w outside the domain", "h", "range"),
        Case(curve + ("--stroke", "7.5"), "a stroke beyond the map", "stroke", "range"),
        Case(curve + ("--friction", "0.3"), "friction with the surrogate", "friction",
             "combination")]


def tolerance_cases(f, tmp) -> list[Case]:
    """spsc curve --tolerance and spsc design --tolerance/--confidence (issue 49): bad files,
    options without the file, a robust design outside what it takes."""
    tmp = Path(tmp)
    files = {"unknown.toml": '[x]\ndist = "normal"\nsd = 1\n',
             "dist.toml": '[t0]\ndist = "gauss"\nsd = 0.1\n',
             "nosd.toml": '[t0]\ndist = "normal"\n',
             "quoted.toml": '[t0]\ndist = "normal"\nsd = "0.1"\n',
             "range.toml": '[w]\ndist = "uniform"\nlow = 11.1\nhigh = 10.9\n',
             "wide.toml": '[t0]\ndist = "normal"\nsd = 0.5\n',
             "friction.toml": '[friction]\ndist = "uniform"\nlow = 0\nhigh = 0.5\n',
             "broken.toml": "[t0\n", "empty.toml": ""}
    for name, text in files.items():
        (tmp / name).write_text(text, encoding="utf-8")
    good = tmp / "good.toml"
    good.write_text('[t0]\ndist = "normal"\nsd = 0.05\n', encoding="utf-8")
    curve = ("curve", "--model", "surrogate", "--type", "B", "--l", "0", "--quiet")
    cases = [Case(curve + ("--tolerance", str(tmp / name)), f"tolerance file {name}",
                  "tolerance", "input file") for name in files]
    cases += [Case(curve + ("--tolerance", str(tmp / "missing.toml")), "missing tolerance "
                   "file", "tolerance", "input file"),
              Case(curve + ("--samples", "64"), "--samples without --tolerance", "samples",
                   "combination"),
              Case(curve + ("--seed", "3"), "--seed without --tolerance", "seed",
                   "combination"),
              Case(curve + ("--tolerance", str(good), "--samples", "2"), "too few samples",
                   "samples", "range"),
              Case(curve + ("--tolerance", str(good), "--samples", "abc"), "samples as text",
                   "samples", "number"),
              Case(("curve", "--model", "membrane", "--type", "B", "--quiet", "--tolerance",
                    str(tmp / "friction.toml")), "a friction range with the membrane model",
                   "tolerance [friction]", "combination"),
              Case(("curve", "--model", "wall", "--type", "B", "--l", "0", "--quiet",
                    "--indenter", "sphere:R=10", "--tolerance", str(tmp / "friction.toml")),
                   "a friction range under a sphere", "friction", "combination")]
    design = ("design", "--target", "stiffness_high=5", "--out", str(tmp / "robust"),
              "--verify", "none", "--no-build", "--quiet")
    cases += [Case(design + ("--tolerance", str(good)), "a robust design with the wall model",
                   "tolerance", "combination"),
              Case(design + ("--model", "surrogate", "--confidence", "0.9"),
                   "--confidence without --tolerance", "confidence", "combination"),
              Case(design + ("--model", "surrogate", "--tolerance", str(good),
                             "--confidence", "1"), "a confidence of 1", "confidence", "range"),
              Case(design + ("--model", "surrogate", "--tolerance", str(tmp / "dist.toml")),
                   "a bad tolerance file in design", "tolerance", "input file")]
    return cases


def virtual_cases(f, tmp) -> list[Case]:
    """spsc virtual (issue 50): scene files without a scene, with an unknown one, with a press
    the plate cannot take, unreadable; gripper scenes with a bad object, grasp, valve schedule,
    design or chamber outside the surrogate; --out an existing file."""
    tmp = Path(tmp)
    base = ('[chamber]\ntype = "B"\nl = 0\nmodel = "surrogate"\n[circuit]\nsetup_kPa = 40\n'
            'reservoir_mm3 = 40000\nvalve = { C = 0.06 }\n')
    force = '[press]\nforce = [[0, 0], [0.3, 8], [1, 8]]\n'
    files = {"noscene.toml": base + force,
             "kind.toml": base + force + '[scene]\nkind = "gripper"\n',
             "extra.toml": base + force + '[scene]\nkind = "plate"\nmass = 1\n',
             "spring.toml": base + '[press]\nprofile = [[0, 0], [1, 3]]\nobject_N_per_mm = 2\n'
                            '[scene]\nkind = "plate"\n',
             "broken.toml": "[scene\n"}
    grip = base + '[scene]\nkind = "gripper"\n[grasp]\nopening_mm = [[0, 60], [1, 25]]\n'
    gripper = {  # each names its key
        "object.shape": grip + '[object]\nshape = "torus"\n',
        "object.stiffness_N_per_mm": grip + '[object]\nstiffness_N_per_mm = "soft"\n',
        "grasp.opening_mm": base + '[scene]\nkind = "gripper"\n[grasp]\nlift_mm = [[0, 0]]\n',
        "events[0].t": grip + '[[events]]\nt = 30\nvalve = "open"\n',
        "design": grip.replace('type = "B"\nl = 0', 'design = "none.design.json"'),
        "chamber.l": grip.replace("l = 0", "l = 4"),  # no surrogate holds l/w = 4/11
        "[press]": grip + force}
    for name, text in files.items():
        (tmp / f"scene-{name}").write_text(text, encoding="utf-8")
    good = tmp / "scene-good.toml"
    good.write_text(base + force + '[scene]\nkind = "plate"\n', encoding="utf-8")
    cases = [Case(("virtual", str(tmp / f"scene-{name}"), "--out", str(tmp / "virtual")),
                  f"scene file {name}", "scene", "input file") for name in files]
    for i, (key, text) in enumerate(gripper.items()):
        (tmp / f"grip-{i}.toml").write_text(text, encoding="utf-8")
        cases.append(Case(("virtual", str(tmp / f"grip-{i}.toml"), "--out", str(tmp / "virtual")),
                          f"gripper scene: bad {key}", key, "input file"))
    cases += [Case(("virtual", str(tmp / "missing.toml"), "--out", str(tmp / "virtual")),
                   "missing scene file", "scene", "input file"),
              Case(("virtual", str(good), "--out", str(f["file"])), "--out an existing file",
                   "out", "output folder")]
    return cases
