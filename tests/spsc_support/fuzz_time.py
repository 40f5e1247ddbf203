"""Invalid invocations of ``spsc simulate``: a valid scenario file with one entry wrong (each
must be refused in one line naming the entry, before the chamber is mapped), unreadable
scenario files, output folders that cannot be written."""

from __future__ import annotations

from pathlib import Path

from .fuzz_base import Case, out_dirs

__all__ = ["SCENARIO", "scenario_fixture", "simulate_cases"]

#: a valid scenario; ``{chamber}`` ``{circuit}`` ``{press}`` ``{events}`` ``{output}`` are the
#: tables' extra lines, a case puts its one wrong entry in one of them
SCENARIO = """[chamber]
{chamber}
[circuit]
{circuit}
[press]
{press}
{events}
[output]
{output}
{bode}
"""

_GOOD = dict(chamber='type = "B"\nl = 0\n',
             circuit='setup_kPa = 40\nreservoir_mm3 = 40000\nvalve = { C = 0.06, state = "closed" }\n',
             press="profile = [[0, 0], [0.2, 3], [1, 3]]\n", events="", output="dt = 0.001\n",
             bode="")

#: (table, its text, the name the error must contain, why)
_WRONG = (
    ("chamber", 'type = "E"\n', "type", "unknown chamber type"),
    ("chamber", "t0 = -1\n", "t0", "negative wall"),
    ("chamber", 'material = "rubber"\n', "material", "unknown material"),
    ("chamber", 'model = "fem"\n', "chamber.model", "a model the time domain does not map"),
    ("chamber", "mesh_size = 0\n", "chamber.mesh_size", "zero mesh size"),
    ("chamber", "colour = 1\n", "chamber.colour", "unknown chamber key"),
    ("circuit", "setup_kPa = -3\n", "setup_kPa", "negative setup pressure"),
    ("circuit", 'reservoir_mm3 = "big"\n', "reservoir_mm3", "reservoir as text"),
    ("circuit", 'valve = { C = 0.06, state = "ajar" }\n', "valve.state", "unknown valve state"),
    ("circuit", 'valve = { C = 0, state = "open" }\n', "valve C", "zero conductance"),
    ("circuit", "valve = { C = 0.06, area_mm2 = 0.3 }\n", "circuit.valve", "C and area"),
    ("circuit", "valve = { C = 0.06, b = 1.2 }\n", "valve b", "b beyond 1"),
    ("circuit", "valve = 3\n", "circuit.valve", "valve not a table"),
    ("circuit", "gas = { n = 0.5 }\n", "gas n", "n below 1"),
    ("circuit", "gas = { n = 1.4, thermal_time_s = -1 }\n", "thermal_time_s", "negative tau"),
    ("circuit", "gas = { gamma = 1.4 }\n", "circuit.gas.gamma", "unknown gas key"),
    ("circuit", 'sensor = { preset = "xyz" }\n', "sensor preset", "unknown sensor preset"),
    ("circuit", "sensor = { rate_Hz = 0 }\n", "sensor rate_Hz", "zero sampling rate"),
    ("circuit", "sensor = { noise_kPa = -1 }\n", "sensor noise_kPa", "negative noise"),
    # a quoted number is text, not a number the object keeps as text (issue 53, item 8)
    ("circuit", 'gas = { n = "1.4" }\n', "gas n", "a quoted polytropic index"),
    ("circuit", 'valve = { C = "0.06" }\n', "valve C", "a quoted conductance"),
    ("circuit", 'sensor = { rate_Hz = "1000" }\n', "sensor rate_Hz", "a quoted rate"),
    ("circuit", "sensor = { seed = -1 }\n", "sensor seed", "a negative seed"),
    ("circuit", "sensor = { seed = 1.5 }\n", "sensor seed", "a fractional seed"),
    ("circuit", "setup_kPa = 0\n", "circuit.setup_kPa", "a sealed chamber at 0 kPa"),
    ("circuit", "leak = { C = -1 }\n", "circuit.leak.C", "a negative leak conductance"),
    ("circuit", "leak = { drop_kPa = 1 }\n", "circuit.leak", "a leak's loss without its time"),
    ("circuit", "leak = { drop_kPa = 90, over_s = 60 }\n", "circuit.leak.drop_kPa",
     "a leak losing more than the setup pressure"),
    ("circuit", "leak = { C = 1e-8, area_mm2 = 1e-5 }\n", "circuit.leak", "two leak sizes"),
    ("circuit", "leak = 0.1\n", "circuit.leak", "a leak that is no table"),
    ("circuit", 'leak = { C = "1e-8" }\n', "circuit.leak.C", "a quoted leak conductance"),
    ("press", "profile = [[0, 0]]\n", "press profile", "one knot"),
    ("press", "profile = [[0, 0], [1, 2], [0.5, 3]]\n", "press profile t_s", "time going back"),
    ("press", "profile = [[0.1, 0], [1, 2]]\n", "press profile t_s", "not starting at 0"),
    ("press", 'profile = "fast"\n', "press profile", "profile as text"),
    ("press", "", "press", "no profile"),
    ("press", "profile = [[0, 0], [1, 40], [2, 40]]\n", "press.profile",
     "a press deeper than the chamber (13 mm)"),
    ("events", '[[events]]\nt = 5\nvalve = "open"\n', "events[0].t", "event after the press"),
    ("events", '[[events]]\nt = 0.5\nvalve = "shut"\n', "events[0].valve", "unknown event"),
    ("events", '[[events]]\nt = 0.5\nvalve = "open"\nwho = 1\n', "events[0].who",
     "unknown event key"),
    ("events", '[[events]]\nt = 0.5\npressure_above_kPa = 45\nvalve = "open"\n', "events[0]",
     "a time and a threshold"),
    ("events", '[[events]]\nvalve = "open"\n', "events[0]", "no time or threshold"),
    ("events", '[[events]]\nt = 0.5\nvalve = "open"\n[[events]]\nt = 0.5\nvalve = "close"\n',
     "events[1].t", "two events at the same instant"),
    ("events", '[[events]]\nt = 0.5\nafter_s = 0.2\nvalve = "open"\n', "events[0].after_s",
     "arming a timed event"),
    ("events", '[[events]]\npressure_below_kPa = "low"\nvalve = "open"\n',
     "events[0].pressure_below_kPa", "threshold as text"),
    ("events", '[[events]]\npressure_above_kPa = 45\nafter_s = 9\nvalve = "open"\n',
     "events[0].after_s", "armed after the press"),
    ("bode", "[bode]\ny_mm = 9\n", "bode.y_mm", "a Bode point beyond the press"),
    ("bode", "[bode]\nf_min_Hz = 10\nf_max_Hz = 1\n", "bode.f_max_Hz", "frequencies reversed"),
    ("bode", '[bode]\nvalve = "half"\n', "bode.valve", "unknown Bode valve"),
    ("press", "force = [[0, 1], [1, 2]]\n", "press", "a travel and a force press"),
    ("press", "max_travel_mm = 3\n", "press.max_travel_mm", "a depth for a travel press"),
    ("bode", "[stiffness]\ntarget = [[0, -1]]\n", "stiffness.target", "negative stiffness"),
    ("bode", "[stiffness]\ntarget = [[0, 3]]\nreservoir_mm3 = [100, 50]\n",
     "stiffness.reservoir_mm3", "the piston's stroke reversed"),
    ("bode", "[stiffness]\ntarget = [[0, 3]]\nreservoir_mm3 = [1000, 20000]\n",
     "circuit.reservoir_mm3", "the piston starting outside its stroke"),
    ("bode", "[stiffness]\ntarget = [[0, 3]]\nspeed = 1\n", "stiffness.speed",
     "unknown stiffness key"),
    # the wall stepped in time (issue 52): what it cannot run, refused before any work
    ("chamber", 'viscous = "yes"\n', "chamber.viscous", "a viscous flag as text"),
    ("chamber", "mullins = 1\n", "chamber.mullins", "a softening flag as a number"),
    ("chamber", 'friction = "slippery"\n', "chamber.friction", "an unknown friction"),
    ("chamber", "friction = -0.3\n", "chamber.friction", "a negative friction"),
    ("chamber", 'viscous = true\nmaterial = "elastic50a"\n', "chamber.viscous",
     "a viscous wall of a material without Prony terms"),
    ("chamber", 'mullins = true\nmaterial = "as40"\n', "chamber.mullins",
     "a softening wall of a material without its constants"),
    ("chamber", 'viscous = true\nmodel = "surrogate"\nl = 0\n', "chamber.model",
     "a viscous surrogate"),
    ("circuit", "vented = true\n", "circuit.setup_kPa", "a vented chamber with a setup pressure"),
    ("circuit", "vented = 1\n", "circuit.vented", "a vented flag as a number"),
    ("output", "dt = 0\n", "output.dt", "zero time step"),
    ("output", "dt = 1e-9\n", "output.dt", "too many samples"),
    ("output", "dt = 0.001\nevery = 2\n", "output.every", "unknown output key"),
)


def _with(good: str, wrong: str) -> str:
    """The table ``good`` with the entries of ``wrong`` put in (replacing the same keys);
    nothing: the table emptied."""
    if not wrong:
        return ""
    keys = {line.split("=")[0].strip() for line in wrong.splitlines() if "=" in line}
    kept = [line for line in good.splitlines() if line.split("=")[0].strip() not in keys]
    return "\n".join(kept) + "\n" + wrong


def scenario_fixture(tmp: Path) -> dict[str, Path]:
    """The valid scenario and one file per wrong entry, under ``tmp``."""
    tmp.mkdir(parents=True, exist_ok=True)
    files = {"scenario": tmp / "scenario.toml"}
    files["scenario"].write_text(SCENARIO.format(**_GOOD))
    for i, (table, text, _, _) in enumerate(_WRONG):
        p = tmp / f"scenario-wrong-{i}.toml"
        p.write_text(SCENARIO.format(**{**_GOOD, table: _with(_GOOD[table], text)}))
        files[f"scenario-wrong-{i}"] = p
    (tmp / "scenario-bad.toml").write_text("[chamber\ntype = 'B'\n")
    files["scenario-bad"] = tmp / "scenario-bad.toml"
    return files


def simulate_cases(f: dict, tmp: Path) -> list[Case]:
    """spsc simulate."""
    sc = scenario_fixture(Path(tmp) / "scenarios")
    out = str(Path(tmp) / "out")
    base = ("simulate", str(sc["scenario"]), "--out", out, "--quiet")
    cases = [Case(("simulate", str(sc[f"scenario-wrong-{i}"]), "--out", out, "--quiet"),
                  f"scenario: {why}", name, "scenario")
             for i, (_, _, name, why) in enumerate(_WRONG)]
    cases += [Case(("simulate", str(sc["scenario-bad"]), "--out", out), "scenario not TOML",
                   "scenario", "input file"),
              Case(("simulate", str(tmp / "none.toml"), "--out", out), "missing scenario",
                   "scenario", "input file"),
              Case(("simulate", str(f["dir"]), "--out", out), "scenario is a folder",
                   "scenario", "input file"),
              Case(("simulate", str(f["binary.csv"]), "--out", out), "binary scenario",
                   "scenario", "input file"),
              Case(("simulate", str(sc["scenario"])), "no --out", "out", "argparse"),
              Case(base + ("--study", "--types", "E"), "a study of an unknown type", "--types",
                   "choice"),
              Case(base + ("--workers", "0"), "no map workers", "workers", "range"),
              Case(base + ("--workers", "2", "--scheduler", "tcp://127.0.0.1:1"),
                   "workers and a scheduler", "workers", "combination")]
    cases += out_dirs(base[:2] + ("--quiet",), "--out", f)
    cases += out_dirs(base + ("--bode",), "--cache", f)  # checked before the map is built
    return cases
