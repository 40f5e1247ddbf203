"""Invalid invocations of ``spsc sense``: a valid log with one thing wrong (a column missing,
time going back, a NaN, a valve state that is not 0/1), unreadable logs, each sensing option
out of range, options that do not go together, output folders that cannot be written — each
refused in one line before the chamber is mapped."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .fuzz_base import Case, numbers, out_dirs

__all__ = ["sense_cases"]

_LOGS = {  # name -> (edit of the good log's columns, the name the error must contain, why)
    "no-pressure": (lambda c: c.pop("pressure_kPa"), "log columns", "no pressure column"),
    "time-back": (lambda c: c["t_s"].__setitem__(5, 0.0), "t_s", "time going back"),
    "nan": (lambda c: c["pressure_kPa"].__setitem__(7, np.nan), "pressure_kPa", "a NaN"),
    "valve-2": (lambda c: c["valve_open"].__setitem__(3, 2.0), "valve_open", "valve 2"),
    "fsr-gap": (lambda c: c.pop("fsr_2"), "fsr columns", "fsr_2 missing"),
}


def _logs(tmp: Path) -> dict:
    tmp.mkdir(parents=True, exist_ok=True)
    n = 50
    good = {"t_s": np.arange(n) * 1e-3, "pressure_kPa": 40 + 0.01 * np.sin(np.arange(n)),
            "valve_open": np.zeros(n), "fsr_1": np.zeros(n), "fsr_2": np.zeros(n),
            "fsr_3": np.zeros(n)}
    files = {}
    for name, (edit, _, _) in [("good", (lambda c: None, None, None))] + list(_LOGS.items()):
        cols = {k: v.copy() for k, v in good.items()}
        edit(cols)
        path = tmp / f"log-{name}.csv"
        keys = list(cols)
        rows = ["{:.9g}".format(cols[k][i]) if k else "" for i in range(n) for k in keys]
        lines = [",".join(keys)] + [",".join(rows[i * len(keys):(i + 1) * len(keys)])
                                    for i in range(n)]
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        files[name] = path
    (tmp / "log.txt").write_text("t_s,pressure_kPa\n0,40\n0.001,40\n", encoding="utf-8")
    files["txt"] = tmp / "log.txt"
    return files


def sense_cases(f: dict, tmp: Path) -> list[Case]:
    """spsc sense."""
    logs = _logs(Path(tmp) / "sense-logs")
    out = str(Path(tmp) / "sense-out")
    base = ("sense", str(logs["good"]), "--out", out, "--type", "B", "--quiet")
    cases = [Case(("sense", str(logs[k]), "--out", out, "--type", "B"), f"log: {why}", name,
                  "input file") for k, (_, name, why) in _LOGS.items()]
    cases += [Case(("sense", str(logs["txt"]), "--out", out, "--type", "B"), "log not csv",
                   "log", "input file"),
              Case(("sense", str(tmp / "none.csv"), "--out", out, "--type", "B"),
                   "missing log", "log", "input file"),
              Case(("sense", str(f["dir"]), "--out", out, "--type", "B"), "log is a folder",
                   "log", "input file"),
              Case(("sense", str(f["binary.csv"]), "--out", out, "--type", "B"), "binary log",
                   "log", "input file"),
              Case(("sense", "--out", out, "--type", "B"), "no log without --follow", "LOG",
                   "combination"),
              Case(("sense", str(logs["good"]), "--type", "B"), "no --out", "out",
                   "combination"),
              Case(("sense", str(logs["good"]), "--follow", "--type", "B"),
                   "a log with --follow", "LOG", "combination"),
              Case(base + ("--detector", "psychic"), "unknown detector", "detector", "choice"),
              *[Case(base + ("--detectors", v), f"--detectors {why}", "detectors", "choice")
                for v, why in (("psychic", "unknown"), ("slip", "a built-in one"),
                               ("compliance", "a built-in one"), ("", "empty"),
                               (",", "empty items"), ("slip,psychic", "a list"))],
              Case(base + ("--valve", "ajar"), "unknown valve", "valve", "choice"),
              Case(("sense", str(logs["good"]), "--out", out, "--type", "E"), "unknown type",
                   "type", "choice"),
              Case(base + ("--material", "rubber"), "unknown material", "material", "choice"),
              Case(base + ("--reservoir", "0", "--valve", "open"), "open without a reservoir",
                   "valve_open", "combination"),
              Case(("sense", "--haptic-calibrate", str(logs["good"]), "--out", out),
                   "a squeeze with no squeeze", "squeeze", "other"),
              Case(("sense", "--haptic-calibrate", str(logs["good"]), "--out", out,
                    "--haptic-fraction", "1.5"), "fraction above 1", "haptic fraction",
                   "range"),
              Case(base + ("--haptic", str(logs["good"])), "haptic file not a calibration",
                   "haptic calibration", "input file"),
              Case(("sense", str(logs["good"]), "--out", out, "--design",
                    str(tmp / "none.design.json")), "missing design file", "design",
                   "input file"),
              Case(("sense", str(logs["good"]), "--out", out, "--design", str(logs["good"])),
                   "a design file that is not json", "design", "input file"),
              Case(base + ("--design", str(logs["good"])), "--design with --type", "type",
                   "combination")]
    for opt, bad in (("model-error", ("-0.1", "1")), ("smoothing", ("-1", "11")),
                     ("noise", ("0", "-1", "abc", "")), ("stiff-mm-per-deg", ("0", "-1")),
                     ("gas", ("0.9", "1.7", "abc", "1.4,-1", "1.4,0.5,1", "nan", "1.4,nan",
                              ""))):
        cases += [Case(base + (f"--{opt}", v), f"--{opt} {v}", opt, "range") for v in bad]
    cases += numbers(base, ("pressure", "reservoir", "stroke", "mesh-size"))
    cases += out_dirs(base[:2] + ("--type", "B", "--quiet"), "--out", f)
    cases += out_dirs(base, "--cache", f)  # checked before the map is built (minutes)
    return cases
