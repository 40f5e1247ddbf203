"""Bad input across every ``spsc`` verb: how each invalid invocation ends.

    .venv/bin/python bench/bench_badinput.py [--fork] [--only TEXT] [--timeout S] [--jobs N]
                                             [--designs N] [--determinism] [--list]

Invalid invocations (the table of ``spsc_support.fuzz_cases``, over 300) run as subprocesses
(``python -m spsc.cli.main``) with a timeout, and each outcome is counted: a clean one-line
error with exit 2 naming the option, a clean error not naming it, a traceback, an argparse usage
dump, a silent exit 0, a timeout, or anything else. ``--fork`` runs each case in a forked copy
of one warm interpreter instead (same classification, ~20x faster; for iterating).

``--designs N``: N random valid bladders (``fuzz_cases.random_design``, all types, flange holes
and tube sizes) through ``spsc bladder``: gate passes, named rejections (exit 2), gate failures
(exit 1, with the failed checks) and anything else. ``--determinism``: the same bladder built
twice, STL and 3MF compared byte for byte.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import hashlib
import io
import os
import re
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from spsc_support.fuzz_cases import Case, design_argv, invalid_cases, random_design

OUTCOMES = ("clean", "clean, not naming the option", "traceback", "internal error (exit 3)",
            "usage dump", "silent exit 0", "timeout", "other")


def classify(case: Case, rc, err: str) -> str:
    """The outcome of ``case`` from its exit code (None: timed out) and stderr."""
    if rc is None:
        return "timeout"
    if "Traceback (most recent call last)" in err:
        return "traceback"
    if "usage:" in err:
        return "usage dump"
    if rc == 3 and ": internal error: " in err:
        return "internal error (exit 3)"
    if rc == 0:
        return "silent exit 0"
    lines = err.strip().splitlines()
    if rc != 2 or len(lines) != 1 or ": error: " not in lines[0]:
        return "other"
    message = lines[0].split(": error: ", 1)[1]
    if case.names and not names(case.names, message):
        return "clean, not naming the option"
    return "clean"


def names(name: str, message: str) -> bool:
    """``message`` names ``name`` as a word (``-``, ``_``, ``.`` and a space are one
    separator)."""
    pattern = "".join("[-_ .]" if ch in "-_ ." else re.escape(ch) for ch in name)
    return re.search(rf"(?<![A-Za-z_]){pattern}(?![A-Za-z_])", message) is not None


def run_subprocess(case: Case, timeout: float, cwd: Path) -> tuple:
    try:
        r = subprocess.run([sys.executable, "-m", "spsc.cli.main", *case.argv],
                           capture_output=True, text=True, timeout=timeout, cwd=cwd,
                           stdin=subprocess.DEVNULL)
        return r.returncode, r.stderr
    except subprocess.TimeoutExpired as exc:
        err = exc.stderr.decode(errors="replace") if isinstance(exc.stderr, bytes) else ""
        return None, err


def run_forked(case: Case, timeout: float, cwd: Path) -> tuple:
    """Run ``case`` through ``cli.main`` in a forked child (imports already warm)."""
    from spsc.cli.main import main

    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:  # child: run, write "rc\0stderr", exit
        os.close(r)
        err = io.StringIO()
        rc = 99
        try:
            os.chdir(cwd)
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
                rc = main(list(case.argv))
        except SystemExit as exc:
            rc = exc.code if isinstance(exc.code, int) else 1
        except BaseException:
            import traceback
            err.write(traceback.format_exc())
            rc = 1
        os.write(w, f"{rc}\0{err.getvalue()}".encode(errors="replace"))
        os._exit(0)
    os.close(w)
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            data = b""
            while chunk := os.read(r, 65536):
                data += chunk
            os.close(r)
            rc, _, err = data.decode(errors="replace").partition("\0")
            return (int(rc) if rc else 1), err
        time.sleep(0.01)
    os.kill(pid, 9)
    os.waitpid(pid, 0)
    os.close(r)
    return None, ""


def bad_input(args) -> dict:
    tmp = Path(tempfile.mkdtemp(prefix="spsc-badinput-"))
    cases = [c for c in invalid_cases(tmp / "fixtures")
             if not args.only or args.only in " ".join(c.argv)]
    cwd = tmp / "cwd"
    cwd.mkdir()
    if args.list:
        for c in cases:
            print(" ".join(repr(a) if not a or " " in a else a for a in c.argv), "#", c.why)
        return {}
    print(f"{len(cases)} invalid invocations across "
          f"{len({c.verb for c in cases})} verbs ({'forked' if args.fork else 'subprocess'}, "
          f"timeout {args.timeout:g} s)")
    t0 = time.perf_counter()
    if args.fork:  # warm the heavy imports once, before any thread starts
        for mod in ("spsc.cad.bladder", "spsc.cad.check", "spsc.cad.fingertip",
                    "spsc.membrane.solver", "spsc.fem.solid.chamber", "spsc.report.build"):
            __import__(mod)
        results = (run_forked(c, args.timeout, cwd) for c in cases)
    else:
        pool = ThreadPoolExecutor(args.jobs)
        results = pool.map(lambda c: run_subprocess(c, args.timeout, cwd), cases)
    counts = collections.Counter()
    by_verb = collections.defaultdict(collections.Counter)
    for c, (rc, err) in zip(cases, results):
        kind = classify(c, rc, err)
        counts[kind] += 1
        by_verb[c.verb][kind] += 1
        if kind != "clean":
            last = (err.strip().splitlines() or [""])[-1][:200]
            print(f"  {kind}: spsc {' '.join(repr(a) if not a or ' ' in a else a for a in c.argv)}"
                  f"  [{c.why}] rc={rc}: {last}", flush=True)
    print(f"in {time.perf_counter() - t0:.0f} s:")
    for kind in OUTCOMES:
        print(f"  {kind:32s} {counts[kind]:5d}")
    print("  by verb: " + "; ".join(f"{v} {sum(n.values())} ({n['clean']} clean)"
                                    for v, n in sorted(by_verb.items())))
    return counts


def designs(n: int, seed: int, timeout: float, jobs: int) -> None:
    """``n`` random valid bladders through ``spsc bladder`` (subprocess each)."""
    import numpy as np

    rng = np.random.default_rng(seed)
    tmp = Path(tempfile.mkdtemp(prefix="spsc-designs-"))
    argvs = [design_argv(random_design(rng)) for _ in range(n)]

    def one(k):
        argv = ["bladder", *argvs[k], "--out", str(tmp / f"d{k}")]
        t = time.perf_counter()
        try:
            r = subprocess.run([sys.executable, "-m", "spsc.cli.main", *argv],
                               capture_output=True, text=True, timeout=timeout,
                               stdin=subprocess.DEVNULL)
            rc, out, err = r.returncode, r.stdout, r.stderr
        except subprocess.TimeoutExpired:
            rc, out, err = None, "", ""
        return argv, rc, out, err, time.perf_counter() - t

    t0 = time.perf_counter()
    with ThreadPoolExecutor(jobs) as pool:
        rows = list(pool.map(one, range(n)))
    counts = collections.Counter()
    failed_checks = collections.Counter()
    for argv, rc, out, err, dt in rows:
        if rc == 0:
            kind = "gate passed"
        elif rc == 2 and len(err.strip().splitlines()) == 1 and "error:" in err:
            kind = "named rejection (exit 2)"
        elif rc == 1 and "FAILED:" in out:
            checks = out.split("FAILED:")[-1].strip().split(", ")
            failed_checks.update(checks)
            kind = "gate failed: " + ", ".join(checks)
        elif rc is None:
            kind = "timeout"
        else:
            kind = "other"
        counts[kind.split(":")[0]] += 1
        if kind != "gate passed":
            print(f"  {kind}: spsc {' '.join(argv[:-2])} ({dt:.0f} s) "
                  f"{(err.strip().splitlines() or [''])[-1][:160]}")
    print(f"{n} random valid designs (seed {seed}) in {time.perf_counter() - t0:.0f} s:")
    for kind, k in counts.most_common():
        print(f"  {kind:32s} {k:5d}")
    for check, k in failed_checks.most_common():
        print(f"    failed check {check}: {k}")


def determinism() -> None:
    """Build the same bladder twice (two processes) and compare the files byte for byte."""
    tmp = Path(tempfile.mkdtemp(prefix="spsc-determinism-"))
    argv = ["bladder", "--type", "D", "--no-check"]
    for k in (1, 2):
        subprocess.run([sys.executable, "-m", "spsc.cli.main", *argv, "--out",
                        str(tmp / f"run{k}")], check=True, capture_output=True)
    print(f"determinism: spsc {' '.join(argv)}, built twice in two processes:")
    for suffix in (".stl", ".3mf", ".step", ".design.json"):
        a, b = (tmp / f"run{k}" / f"bladder-D{suffix}" for k in (1, 2))
        same = a.read_bytes() == b.read_bytes()
        digest = hashlib.sha256(a.read_bytes()).hexdigest()[:12]
        print(f"  {suffix:13s} {'byte-identical' if same else 'DIFFERENT'} "
              f"({a.stat().st_size} bytes, sha256 {digest}…)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fork", action="store_true", help="fork one warm interpreter per case")
    ap.add_argument("--only", help="only the cases whose argv contains this text")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per invocation")
    ap.add_argument("--jobs", type=int, default=2, help="parallel subprocesses")
    ap.add_argument("--list", action="store_true", help="list the invalid invocations")
    ap.add_argument("--designs", type=int, default=0, metavar="N",
                    help="also N random valid designs through spsc bladder (slow: ~10 s each)")
    ap.add_argument("--seed", type=int, default=10)
    ap.add_argument("--determinism", action="store_true",
                    help="also build one bladder twice and compare the files")
    ap.add_argument("--no-invalid", action="store_true", help="skip the invalid invocations")
    args = ap.parse_args()
    if not args.no_invalid:
        bad_input(args)
    if args.designs:
        designs(args.designs, args.seed, max(args.timeout, 300.0), args.jobs)
    if args.determinism:
        determinism()


if __name__ == "__main__":
    main()
