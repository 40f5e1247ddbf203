"""Invalid invocations of ``spsc fatigue``: the chamber, the cycle's setup, the exponent, the
material (a catalogue material with a fatigue test) and the outputs, each refused in one line
naming the option before the calibration's wall solve."""

from __future__ import annotations

from .fuzz_base import GEOMETRY, Case, numbers, outputs

__all__ = ["fatigue_cases", "puncture_cases"]


def fatigue_cases(f, tmp) -> list[Case]:
    """``f``: the fixtures (:func:`~.fuzz_fixtures.fixtures`)."""
    base = ("fatigue", "--type", "B", "--quiet")
    cases = numbers(base, GEOMETRY)
    cases += numbers(base, ("pressure", "reservoir", "stroke", "points", "exponent"))
    cases += [Case(base + ("--type", "E"), "unknown type", "type"),
              Case(base + ("--material", "rubber"), "unknown material", "material"),
              Case(base + ("--material", ""), "empty material", "material"),
              Case(base + ("--material", str(f["ogden.json"])),
                   "a material file (no fatigue test calibrates it)", "material"),
              Case(base + ("--stroke", "20"), "stroke above the chamber's height", "stroke"),
              Case(base + ("--h", "4", "--stroke", "5"), "stroke above h", "stroke"),
              Case(base + ("--exponent", "1"), "an exponent of 1 (no power law)", "exponent"),
              Case(base + ("--exponent", "50"), "an exponent of 50", "exponent"),
              Case(base + ("--pressure", "5000"), "5000 kPa", "pressure"),
              Case(base + ("--points", "2"), "two plate positions", "points"),
              Case(base + ("--reservoir", "-1"), "a negative reservoir", "reservoir")]
    cases += outputs(base, "--json", f, tmp)
    cases += outputs(base, "--png", f, tmp, ".png")
    study = ("fatigue", "--study", "--quiet")
    cases += [Case(study + ("--json", str(tmp / "f.json")), "--json with --study", "json",
                   "combination"),
              Case(study + ("--type", "C"), "a chamber with --study", "type", "combination"),
              Case(base + ("--out", str(tmp / "dur")), "--out without --study", "out",
                   "combination"),
              Case(study + ("--out", str(f["file"])), "--study's folder a file", "--out",
                   "input file"),
              Case(("report", "--durability", str(f["dir"]), "--quiet", "--out",
                    str(tmp / "report")), "a durability folder without its summary",
                   "durability", "input file")]
    design = ("design", "--target", "stiffness_high=6", "--model", "simplified", "--out",
              str(tmp / "design-life"), "--quiet")
    cases += numbers(design + ("--min-life", "1000"), ("life-stroke",))
    cases += numbers(design, ("min-life",))
    cases += [Case(design + ("--min-life", "0"), "a life of no cycles", "min-life"),
              Case(design + ("--min-life", "1e12"), "a life of 1e12 cycles", "min-life"),
              Case(design + ("--life-stroke", "4"), "--life-stroke without --min-life",
                   "life-stroke"),
              Case(design + ("--min-life", "1000", "--life-stroke", "30"),
                   "a life's stroke above every h of the space", "life-stroke"),
              Case(design + ("--min-life", "1000", "--material", str(f["ogden.json"])),
                   "a material file with --min-life (no fatigue test)", "material")]
    fit = ("fit-material", str(f["tension.csv"]), "--law", "neo-hookean")
    cases += [Case(fit + ("--cyclic", str(tmp / "no-cycle.csv")), "a missing cyclic test",
                   "--cyclic", "input file"),
              Case(fit + ("--cyclic", str(f["tension.csv"])), "a cyclic test without t_s",
                   "--cyclic", "input file"),
              Case(fit + ("--cyclic", str(f["tension.csv"]), "--relaxation",
                          str(f["tension.csv"])), "a cyclic and a relaxation test", "cyclic")]
    sweep = ("sweep", "--type", "B", "--model", "simplified", "--out",
             str(tmp / "life.parquet"), "--quiet", "--life")
    cases += [Case(sweep + ("--material", str(f["ogden.json"])),
                   "a material file with --life (no fatigue test)", "material")]
    return cases


def puncture_cases(f, tmp) -> list[Case]:
    """Invalid invocations of ``spsc puncture``: the chamber (a dome), the test's setup, the
    criterion, the mesh, the probe and its friction, the outputs."""
    base = ("puncture", "--type", "B", "--l", "0", "--quiet")
    cases = numbers(base, tuple(g for g in GEOMETRY if g != "l"))
    cases += numbers(base, ("pressure", "reservoir"))
    cases += numbers(base, ("elongation-at-break",), extra=("-5", "0", "1e6"))
    cases += [Case(("puncture", "--type", "B", "--quiet"), "a stadium (l = 3)", "l"),
              Case(base + ("--material", "rubber"), "unknown material", "material"),
              Case(base + ("--material", str(tmp / "none.json")), "a missing material file",
                   "material"),
              Case(base + ("--mesh", "huge"), "unknown mesh", "mesh"),
              Case(base + ("--friction", "0.3"), "Coulomb friction on the probe", "friction"),
              Case(base + ("--probe", "plate"), "a plate for a probe", "probe"),
              Case(base + ("--probe", "cone:angle=200"), "a cone of 200°", "indenter"),
              Case(base + ("--probe", "cylinder:R=5"), "a cylinder off the axis", "probe")]
    cases += outputs(base, "--json", f, tmp)
    cases += outputs(base, "--png", f, tmp, ".png")
    return cases
