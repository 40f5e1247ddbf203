"""The building blocks of the table of invalid invocations (:mod:`.fuzz_cases`): a
:class:`Case`, the values no number option accepts and each option's out-of-range values, and the
ways an output path can be wrong."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = ["Case", "KINDS", "not_dask_address", "NOT_A_NUMBER", "OUT_OF_RANGE", "GEOMETRY", "SETUP", "numbers", "outputs",
           "out_dirs"]


@dataclass(frozen=True)
class Case:
    """One invalid invocation: ``argv`` (without ``spsc``), what is wrong (``why``), the
    name the one-line error must contain (None: any) and the class of mistake it stands for
    (``kind``, one of :data:`KINDS`)."""

    argv: tuple[str, ...]
    why: str
    names: str | None = None
    kind: str = "other"

    @property
    def verb(self) -> str:
        return self.argv[0] if self.argv else ""


#: The classes of mistake the table covers: each case names one (``Case.kind``).
KINDS = {
    "number": "a number option given text, nothing, a non-finite value or a decimal comma",
    "range": "a number outside its option's range, or beyond a limit set by another option",
    "number list": "a comma list of numbers with an empty item, a non-number or a value out "
                   "of range, or the list option given twice",
    "duplicate": "the same item twice in a list (a case, a type)",
    "output file": "an output path that cannot be written as a file",
    "output folder": "an output folder that cannot be written or created",
    "input file": "an input file missing, a folder, binary, empty or of another format",
    "tension data": "tension-test data that are not one loading curve (stretch below 1 or "
                    "not increasing, stress negative or falling)",
    "part surface": "a part's surface that is not a closed 2-manifold around one cavity",
    "design file": "a design file that is not JSON or not of its schema (a motor that is "
                   "not a table with its fields)",
    "scheduler": "a Dask scheduler address of the wrong form, where nothing listens, or "
                 "where something listens that does not speak Dask",
    "scenario": "a scenario file (spsc simulate) with an entry missing, unknown, of the wrong "
                "type or out of range",
    "choice": "a choice option given an unknown value",
    "combination": "options that do not go together, or one missing",
    "argparse": "argparse's own mistakes: an unknown option or verb, a missing value",
    "other": "anything else (the verb's own checks)",
}

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
    "object-stiffness": ("0", "-2"),
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


def numbers(base, options, extra=()) -> list[Case]:
    cases = []
    for opt in options:
        for v in NOT_A_NUMBER:
            cases.append(Case(base + (f"--{opt}", v), f"--{opt} {v!r}", opt, "number"))
        for v in OUT_OF_RANGE.get(opt, ()) + tuple(extra):
            cases.append(Case(base + (f"--{opt}", v), f"--{opt} {v!r}", opt, "range"))
    return cases


def outputs(base, option, f, tmp, suffix=".json") -> list[Case]:
    """``option`` given a path that cannot be written as a file."""
    bad = [(str(f["dir"]), "an existing folder"),
           (str(f["dir.json"]) if suffix == ".json" else str(f["dir"]), "a folder with the suffix"),
           (str(f["file"] / f"x{suffix}"), "a path under a file"),
           (str(tmp / "no" / "such" / f"x{suffix}"), "a missing folder"),
           ("/proc/spsc-fuzz" + suffix, "an unwritable place"),
           ("", "empty")]
    if Path("/dev/full").is_char_device():  # a full disk (not every sandbox has the device)
        bad.append(("/dev/full", "a full device"))
    return [Case(base + (option, p), f"{option} {why}", option.lstrip("-"), "output file")
            for p, why in bad]


def out_dirs(base, option, f) -> list[Case]:
    """``option`` given a folder that cannot be written or created."""
    bad = [(str(f["file"]), "an existing file"), (str(f["file"] / "sub"), "a folder under a file"),
           ("/proc/spsc-fuzz", "an unwritable place"), ("", "empty")]
    return [Case(base + (option, p), f"{option} {why}", option.lstrip("-"), "output folder")
            for p, why in bad]


_LISTENER: list = []


def not_dask_address() -> str:
    """``tcp://127.0.0.1:PORT`` where something listens that is not a Dask scheduler: a socket
    (one per process, kept open) that accepts every connection and closes it unanswered. The TCP
    probe passes there; only Dask's handshake tells."""
    if not _LISTENER:
        import socket
        import threading

        server = socket.socket()
        server.bind(("127.0.0.1", 0))
        server.listen(64)

        def serve():
            while True:
                try:
                    conn, _ = server.accept()
                except OSError:
                    return
                conn.close()

        threading.Thread(target=serve, daemon=True, name="spsc-fuzz-not-dask").start()
        _LISTENER.append(server)
    return f"tcp://127.0.0.1:{_LISTENER[0].getsockname()[1]}"
