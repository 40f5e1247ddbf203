"""The interactive-speed figures of issue 26 that take minutes, not hours: the wall model's Table 1
Type B stadium and dome curves (warm, in this process, best of ``--repeat``), the report's slowest
wall curve (Type C at 30 kPa with the reservoir: a snap-through, best of two), the 3D FEM's Type B
curve on the Table 1 chamber and on the dome (whole ``spsc curve`` processes, the median of
``--repeat``: start-up, mesh from the cache and solve) and the CLI's start-up. The rows that
take longer print the command that measures them. Run on a quiet machine.

    python bench/bench_speed.py [--repeat 3] [--no-fem] [--no-snap]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from spsc.cad.geometry import preset
from spsc.fem.wall import wall_curve
from spsc.materials import material

#: the rows measured elsewhere: (figure, target, command)
LONG = [
    ("wall sweep, 200 designs, 2 workers", "≤ 5 min, 0 partial from snaps",
     "python bench/bench_sweep.py --membrane 0 --wall 200 --workers 2 --out /tmp/bench-sweep"),
    ("spsc design, two targets, wall model, --seed 0 to 3", "≤ 2 min",
     "spsc design --target stiffness_high=6 --target 'sensitivity_high>=5' --model wall "
     "--seed 0 --out /tmp/design"),
    ("3D FEM, one fingertip case (2 mm), 40 kPa", "≤ 3 min",
     "spsc fingertip --fem --cases pulp-high-40 --out /tmp/fingertip-40"),
    ("3D FEM, one fingertip case (2 mm), 10 kPa", "≤ 3 min",
     "spsc fingertip --fem --cases pulp-high-10 --out /tmp/fingertip-10"),
    ("clean make report", "≤ 5 min", "spsc report --cache EMPTY_DIR (in a clean worktree)"),
    ("Type C at 10 kPa, complete with its jump", "complete", "python bench/bench_snap.py"),
]


def _wall(dome: bool, repeat: int) -> tuple[float, int]:
    g = preset("B", l=0.0) if dome else preset("B")
    kw = dict(pressure_kPa=40, stroke_mm=4, points=18)
    wall_curve(g, material("tpu60a"), **kw)  # warm: imports, compiled kernels, PARDISO
    best, its = float("inf"), 0
    for _ in range(repeat):
        t0 = time.perf_counter()
        c = wall_curve(g, material("tpu60a"), **kw)
        best, its = min(best, time.perf_counter() - t0), c.solver.iterations
    return best, its


def _snap(repeat: int) -> tuple[float, int, int]:
    """The report's slowest wall curve: Type C, 30 kPa, the 40 cm³ reservoir, 25 points over
    6 mm, with its snap-through (best of ``repeat``; seconds, iterations, jumps)."""
    kw = dict(pressure_kPa=30, reservoir_mm3=40000, stroke_mm=6, points=25)
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        c = wall_curve(preset("C"), material("tpu60a"), **kw)
        best = min(best, time.perf_counter() - t0)
    return best, c.solver.iterations, len(c.solver.details.get("jumps", []))


def _process(args: list[str], repeat: int) -> float:
    """The median wall time of ``spsc ARGS`` as a new process (one unmeasured run first)."""
    cmd = [sys.executable, "-m", "spsc.cli.main", *args]
    times = []
    for k in range(repeat + 1):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if k:
            times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-fem", action="store_true", help="the wall rows only")
    ap.add_argument("--no-snap", action="store_true",
                    help="without the Type C snap-through curve (about 30 s a run)")
    args = ap.parse_args(argv)
    if args.repeat < 1:
        ap.error(f"repeat = {args.repeat}: at least 1 run")
    print(f"{'figure':64} {'now':>10}  target")
    for dome, target in ((False, "≤ 1 s"), (True, "≤ 0.2 s")):
        t, its = _wall(dome, args.repeat)
        name = "dome" if dome else "Table 1 stadium"
        print(f"{'wall: Type B ' + name + ', inflation + 17 points / 4 mm':64} "
              f"{t:9.3f}s  {target}  ({its} Newton iterations, best of {args.repeat})",
              flush=True)
    if not args.no_snap:
        n = min(args.repeat, 2)
        t, its, jumps = _snap(n)
        print(f"{'wall: Type C, 30 kPa + 40 cm³, 25 points / 6 mm (snap-through)':64} "
              f"{t:9.2f}s  —  ({its} Newton iterations, {jumps} jump, best of {n})",
              flush=True)
    if not args.no_fem:
        with tempfile.TemporaryDirectory() as tmp:
            for dome in (False, True):
                fem = ["curve", "--model", "fem", "--type", "B", "--pressure", "40", "--stroke",
                       "3", "--points", "7", "--mesh-size", "1", "--layers", "2", "--quiet",
                       "--json", str(Path(tmp) / "c.json")] + (["--l", "0"] if dome else [])
                t = _process(fem, args.repeat)
                name = ("dome" if dome else "Table 1") + ", 40 kPa, 3 mm, 1 mm x 2 layers, 7 points"
                print(f"{'3D FEM: Type B ' + name:64} "
                      f"{t:9.2f}s  ≤ 15 s  (whole process, median of {args.repeat})", flush=True)
    t = _process(["--help"], args.repeat)
    print(f"{'spsc --help (the CLI start-up)':64} {t:9.2f}s  (median of {args.repeat})")
    print("\nmeasured elsewhere (minutes to an hour each):")
    for name, target, cmd in LONG:
        print(f"  {name} ({target}):\n    {cmd}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
