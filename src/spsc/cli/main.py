"""The ``spsc`` command line: one sub-command module per verb, each with ``register`` and ``run``.

The error contract, in one place (:func:`main`): every invalid input — argparse's own errors
(unknown option, missing or malformed value), a :class:`ParameterError` from validation, a
missing input file, an output path that cannot be written — ends in one line on stderr,
``spsc <verb>: error: <message>``, and exit 2. Warnings are one line on stderr,
``spsc <verb>: warning: <message>``. A failed check or a non-converged solve exits 1 after
writing what it computed, with the reason on stderr. Anything else is a bug: one line,
``spsc <verb>: internal error: ...``, exit 3 (``SPSC_DEBUG=1`` shows the traceback).
"""

from __future__ import annotations

import argparse
import importlib
import os
import re
import sys
from pathlib import Path

from spsc.core.errors import ParameterError

#: verb -> module in spsc.cli providing ``register(subparsers)``; the parser's ``func`` runs it.
COMMANDS = {
    "bladder": "bladder",
    "fingertip": "fingertip",
    "check": "check",
    "curve": "curve",
    "membrane": "membrane",
    "fem": "fem",
    "identify": "identify",
    "calibrate": "calibrate",
    "fit-material": "fit_material",
    "report": "report",
    "sweep": "sweep",
    "design": "design",
    "mold": "mold",
    "haptic": "haptic",
    "simulate": "simulate",
    "sense": "sense",
    "bench-gap": "bench_gap",
    "surrogate": "surrogate",
    "virtual": "virtual",
    "fatigue": "fatigue",
    "puncture": "puncture",
}

#: Exit code of an unexpected exception (a bug): one line on stderr, not a traceback.
INTERNAL_ERROR = 3

#: Numbers as option values: argparse takes ``-inf``, ``-1e5`` or ``-.5e-3`` for option names
#: unless they match this (no spsc option looks like a number).
_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.I)


class UsageError(Exception):
    """An argparse error, carried to :func:`main` (which prints it as one line)."""

    def __init__(self, prog: str, message: str):
        self.prog, self.message = prog, message
        super().__init__(f"{prog}: error: {message}")


class Parser(argparse.ArgumentParser):
    """argparse with the one-line error contract: no usage dump, a hint to ``--help``; values
    such as ``-inf`` or ``-1e5`` are values, not option names."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NUMBER

    def parse_args(self, args=None, namespace=None):
        ns, extra = self.parse_known_args(args, namespace)
        if extra:  # name the verb they were given to, not the top-level parser
            verb = getattr(ns, "command", None)
            prog = f"{self.prog} {verb}" if verb else self.prog
            raise UsageError(prog, f"unrecognized arguments: {' '.join(extra)} "
                             f"(see {prog} --help)")
        return ns

    def error(self, message):
        # a type function's message already names the parameter: drop argparse's prefix
        m = re.match(r"^argument [^:]+: ([^=:]+ = .*)$", message)
        if m:
            message = m.group(1)
        raise UsageError(self.prog, f"{message} (see {self.prog} --help)")


def build_parser(verbs=None) -> argparse.ArgumentParser:
    """The ``spsc`` parser with the sub-commands ``verbs`` (all of :data:`COMMANDS` by default).

    :func:`main` registers only the verb it was given (a verb's module and its imports are all a
    run needs; building all 17 took 17 ms per call), and all of them where the verb is missing
    or unknown, so the top-level help and argparse's list of choices stay whole.
    """
    parser = Parser(
        prog="spsc",
        description="Soft pneumatic sensing chambers: CAD, printability, membrane model, FEM.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True,
                                parser_class=Parser)
    for verb, module in COMMANDS.items():
        if verbs is not None and verb not in verbs:
            continue
        try:
            mod = importlib.import_module(f"spsc.cli.{module}")
        except ModuleNotFoundError as exc:
            if exc.name != f"spsc.cli.{module}":
                raise
            continue  # a verb whose module is not written yet is simply absent
        mod.register(sub)
    return parser


def _fail(prog: str, message: str) -> int:
    print(f"{prog}: error: {message}", file=sys.stderr)
    return 2


def _verb(argv: list[str]) -> str | None:
    """The sub-command ``argv`` names, if it starts with a known one (the parser has no
    top-level option but ``--help``)."""
    return argv[0] if argv and argv[0] in COMMANDS else None


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    verb = _verb(argv)
    parser = build_parser(None if verb is None else {verb})
    try:
        args = parser.parse_args(argv)
    except UsageError as exc:
        return _fail(exc.prog, exc.message)
    except SystemExit as exc:  # --help
        return int(exc.code or 0)
    prog = f"spsc {args.command}"
    try:
        return int(args.func(args) or 0)
    except ParameterError as exc:
        return _fail(prog, str(exc))
    except FileNotFoundError as exc:
        return _fail(prog, f"{exc.filename or exc}: no such file")
    except OSError as exc:  # an input or output path the system refuses (full disk, rights)
        where = f"{exc.filename}: " if exc.filename else ""
        return _fail(prog, f"{where}{exc.strerror or exc}")
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return 130
    except MemoryError:
        print(f"{prog}: error: out of memory (a coarser mesh or fewer points)", file=sys.stderr)
        return 1
    except Exception as exc:  # a bug, not bad input: one line, exit 3, the traceback on request
        if os.environ.get("SPSC_DEBUG"):
            raise
        where = exc.__traceback__
        while where.tb_next is not None:
            where = where.tb_next
        at = f"{Path(where.tb_frame.f_code.co_filename).name}:{where.tb_lineno}"
        print(f"{prog}: internal error: {type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''} "
              f"(at {at}; a bug, please report it with the command; SPSC_DEBUG=1 shows the "
              "traceback)", file=sys.stderr)
        return INTERNAL_ERROR


if __name__ == "__main__":
    sys.exit(main())
