"""``spsc fem``: the short form of ``spsc curve --model fem``: the 3D hyperelastic FEM check
of one chamber, one setup — the membrane's JSON.

    spsc fem --type B --pressure 40 [--reservoir 40000] [--stroke 4] [--points 11]
             [--material tpu60a] [--mesh-size 1.0] [--layers 2] [--full] [--solver auto]
             [--json F] [--csv F] [--png F] [--vtu DIR] [--quiet]

Quarter model of the wall (clamped on z = 0, symmetry planes x = 0, y = 0), P2/P1 mixed
tetrahedra, follower cavity pressure, closed gas volume with reservoir after inflation, rigid
frictionless plate. ``--pressure 0`` is the open chamber (F_el). Pressures kPa gauge, volumes
mm³, lengths mm. Exit 0 when every point converged, 1 when not (what converged is written),
2 on invalid input.
"""

from __future__ import annotations

from .cmd_curve import add_curve_parser


def register(subparsers) -> None:
    add_curve_parser(subparsers, "fem", models=("fem",),
                     help="3D hyperelastic FEM: inflation and plate contact "
                     "(= spsc curve --model fem)",
                     description=__doc__.split("\n\n")[0])
