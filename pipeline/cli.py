"""The ``spsc`` command line: one sub-command module per verb, each with ``register`` and ``run``.

Every invalid input ends in one line on stderr, ``spsc <verb>: error: <message>``, and exit 2;
a failed check or a non-converged solve exits 1 after writing what it computed.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from spsc.core.errors import ParameterError

#: verb -> module in spsc.pipeline providing ``register(subparsers)``; the parser's ``func`` runs it.
COMMANDS = {
    "bladder": "cmd_bladder",
    "fingertip": "cmd_fingertip",
    "check": "cmd_check",
    "membrane": "cmd_membrane",
    "identify": "cmd_identify",
    "fem": "cmd_fem",
    "report": "cmd_report",
}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="spsc",
        description="Soft pneumatic sensing chambers: CAD, printability, membrane model, FEM.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for verb, module in COMMANDS.items():
        try:
            mod = importlib.import_module(f"spsc.pipeline.{module}")
        except ModuleNotFoundError as exc:
            if exc.name != f"spsc.pipeline.{module}":
                raise
            continue  # a verb whose module is not written yet is simply absent
        mod.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except ParameterError as exc:
        print(f"spsc {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except FileNotFoundError as exc:
        print(f"spsc {args.command}: error: {exc.filename or exc}: no such file", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
