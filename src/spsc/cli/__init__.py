"""The ``spsc`` command line: a thin layer over the library packages. One module per verb, each
with ``register(subparsers)`` and ``run(args)``: parse, call the library, print. The error
contract is in one place, :func:`spsc.cli.main.main`."""
