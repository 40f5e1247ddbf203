"""``spsc membrane``: the short form of ``spsc curve --model membrane`` (or ``--model
simplified``): the fast membrane model of one chamber, one setup — JSON, CSV and PNG.

    spsc membrane --type D --pressure 40 [--reservoir 40000] [--stroke 6] [--material tpu60a]
                  [--points 41] [--meridians] [--json F] [--csv F] [--png F]

Pressures kPa gauge, volumes mm³, lengths mm. Exit 0 when every plate position converged,
1 when some did not (what was computed is still written), 2 on invalid input.
"""

from __future__ import annotations

from spsc.cli.curve import add_curve_parser


def register(subparsers) -> None:
    add_curve_parser(subparsers, "membrane", models=("membrane", "simplified"),
                     help="membrane model: inflation and plate contact "
                     "(= spsc curve --model membrane)",
                     description=__doc__.split("\n\n")[0])
