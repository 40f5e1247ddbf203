"""The spsc command line: bad input ends in one line naming the parameter, and exit code 2."""

import json
import subprocess
import sys

import pytest

from spsc.cli.main import build_parser, main


@pytest.mark.parametrize("argv,name", [
    (["bladder", "--type", "E"], "type"),
    (["bladder", "--type", "B", "--n1", "0.5"], "n1"),
    (["bladder", "--type", "B", "--cy", "-1"], "cy"),
    (["bladder", "--type", "B", "--w", "0"], "w"),
    (["bladder", "--w", "5"], "geometry"),
    (["bladder", "--type", "B", "--t0", "-1"], "t0"),
    (["bladder", "--type", "B", "--w", "abc"], "w"),
    (["bladder", "--type", "B", "--material", "rubber"], "material"),
    (["bladder", "--type", "B", "--flange-holes", "3"], "flange.holes"),
    (["fingertip", "--angle", "10"], "angle"),
    (["mold", "--type", "B", "--process", "injection"], "process"),
    (["mold", "--type", "B", "--shrinkage", "-1"], "shrinkage"),
    (["mold", "--type", "B", "--clearance", "2"], "clearance"),
    (["mold", "--type", "B", "--material", "pla"], "material"),
    (["mold", "--type", "B", "--parting", "diagonal"], "parting"),
    (["mold", "/nonexistent/bladder.design.json"], "part"),
    (["mold"], "geometry"),
    (["check", "/nonexistent/part.stl"], None),
    # argparse's own errors: one line (no usage dump), a hint to --help
    (["membrane", "--pressure", "abc"], "pressure"),
    (["membrane", "--type", "B", "--points", "2.5"], "points"),
    (["bladder", "--type", "B", "--flange-holes", "2.5"], "flange_holes"),
    (["membrane", "--type", "B", "--no-such-option"], None),
    (["membrane", "--type"], None),
    (["curve", "--model", "nothing"], None),
    (["nothing"], None),
    # numbers that look like options parse, then validation names the parameter
    (["membrane", "--type", "B", "--w", "-inf"], "w"),
    (["membrane", "--type", "B", "--pressure", "-1e5"], "pressure"),
    (["membrane", "--type", "B", "--reservoir", "nan"], "reservoir"),
    (["membrane", "--type", "B", "--stroke", "inf"], "stroke"),
    (["membrane", "--type", "B", "--w", ""], "w"),
    # --size meant two things: refused with the two names that replace it
    (["membrane", "--type", "B", "--size", "GS1"], None),
    (["membrane", "--type", "B", "--footprint", "huge"], "footprint"),
    (["fem", "--type", "B", "--mesh-size", "-1"], "mesh size"),
    (["identify", "x.csv", "--pressure", "40", "--bladder-volume", "5000",
      "--predict-pressures", ","], "predict-pressures"),
])
def test_bad_input_is_one_line_exit_2(argv, name, capsys):
    assert main(argv) == 2
    out, err = capsys.readouterr()
    err = err.strip()
    verb = "spsc" if argv[0] == "nothing" else f"spsc {argv[0]}"
    assert len(err.splitlines()) == 1 and err.startswith(f"{verb}: error: "), err
    assert "usage:" not in err and out == ""
    if name:
        assert f"error: {name} = " in err


def test_argparse_errors_point_to_help(capsys):
    assert main(["membrane", "--pressure", "abc"]) == 2
    assert capsys.readouterr().err == ("spsc membrane: error: pressure = 'abc' is invalid: "
                                       "allowed a number (kPa gauge) (see spsc membrane --help)\n")


def test_footprint_selects_the_preset_size(tmp_path):
    j = tmp_path / "gs1.json"
    assert main(["membrane", "--model", "simplified", "--type", "B", "--footprint", "GS1",
                 "--json", str(j)]) == 0
    g = json.loads(j.read_text(encoding="utf-8"))["geometry"]
    assert (g["w"], g["h"], g["l"], g["t0"]) == (10.0, 10.0, 10.0, 1.0)


#: Options each verb's help must show (besides every option its parser declares).
KEY_OPTIONS = {
    "virtual": ["--out", "--quiet"],
    "bladder": ["--type", "--footprint", "--material", "--out", "--flange-holes"],
    "fingertip": ["--angle", "--process", "--out"],
    "mold": ["--type", "--process", "--material", "--shrinkage", "--clearance", "--wall",
             "--parting", "--out", "--no-step", "--no-render"],
    "check": ["--min-wall", "--process", "--design", "--json"],
    "haptic": ["--mesh-size", "--out", "--parts"],
    "bench-gap": ["--out", "--material", "--types", "--material-row", "--factors", "--workers",
                  "--scheduler", "--quiet"],
    "curve": ["--model", "--pressure", "--reservoir", "--stroke", "--points", "--mesh-size",
              "--layers", "--vtu", "--meridians", "--json", "--csv", "--png", "--quiet"],
    "membrane": ["--model", "--pressure", "--meridians", "--json", "--csv", "--png"],
    "fem": ["--pressure", "--mesh-size", "--layers", "--full", "--solver", "--vtu", "--quiet"],
    "identify": ["--pressure", "--bladder-volume", "--reservoir", "--polytropic-n",
                 "--predict-pressures", "--json"],
    "report": ["--quick", "--out", "--cache", "--no-fem", "--no-sweep", "--types", "--quiet",
               "--workers", "--scheduler"],
    "calibrate": ["--pressure", "--reservoir", "--material", "--mesh-size", "--layers",
                  "--predict-pressures", "--predict-reservoirs", "--predict-stroke", "--json",
                  "--png", "--out", "--quiet"],
    "sweep": ["--type", "--w", "--t0", "--cy", "--material", "--pressure", "--reservoir",
              "--samples", "--seed", "--model", "--process", "--points", "--stroke", "--out",
              "--csv", "--html", "--front", "--workers", "--scheduler", "--force", "--quiet"],
    "design": ["--target", "--minimize", "--maximize", "--tol", "--type", "--w", "--t0",
               "--reservoir", "--material", "--pressure", "--model", "--process", "--trials",
               "--seed", "--sampler", "--verify", "--mesh-size", "--no-build", "--points",
               "--stroke", "--out", "--json", "--csv", "--workers", "--scheduler", "--quiet"],
    "fit-material": ["--test", "--law", "--ogden-terms", "--range", "--strain-unit",
                     "--stress-unit", "--json", "--png", "--out", "--list-catalogue"],
    "simulate": ["--out", "--csv", "--cache", "--quiet"],
    "surrogate": [],
    "fatigue": ["--type", "--material", "--pressure", "--reservoir", "--stroke", "--points",
                "--exponent", "--json", "--png", "--quiet"],
    "puncture": ["--type", "--material", "--elongation-at-break", "--pressure", "--reservoir",
                 "--probe", "--friction", "--mesh", "--json", "--png", "--quiet"],
    "sense": ["--out", "--type", "--material", "--pressure", "--reservoir", "--noise",
              "--model-error", "--detector", "--follow", "--haptic-calibrate", "--haptic",
              "--cache", "--quiet"],
}


def _verbs():
    import argparse

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices


def test_every_verb_is_covered():
    assert set(_verbs()) == set(KEY_OPTIONS)


@pytest.mark.parametrize("verb", sorted(KEY_OPTIONS))
def test_help_of_every_verb(verb, capsys):
    """``spsc VERB --help`` exits 0 and mentions every option the verb declares."""
    import argparse

    assert main([verb, "--help"]) == 0
    out = capsys.readouterr().out
    declared = [s for a in _verbs()[verb]._actions if a.help != argparse.SUPPRESS
                for s in a.option_strings]
    assert "--help" in declared
    for opt in declared + KEY_OPTIONS[verb]:
        assert opt in out, (verb, opt)
    assert "--size" not in out.replace("--mesh-size", "")


def test_console_script_help():
    out = subprocess.run([sys.executable, "-m", "spsc.cli.main", "--help"],
                         capture_output=True, encoding="utf-8", check=True).stdout
    for verb in KEY_OPTIONS:
        assert verb in out


def test_a_verb_imports_its_own_module_only():
    """``spsc bladder`` builds the bladder's parser, not all 17 (each imports its stack); a
    missing or unknown verb still gets the whole list of choices."""
    import argparse

    code = ("import sys; from spsc.cli.main import main; main(['bladder', '--type', 'Q']); "
            "print(sorted(m for m in sys.modules if m.startswith('spsc.cli.')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "spsc.cli.bladder" in out.stdout and "spsc.cli.fem'" not in out.stdout, out.stdout
    sub = next(a for a in build_parser({"bladder"})._actions
               if isinstance(a, argparse._SubParsersAction))
    assert list(sub.choices) == ["bladder"]
