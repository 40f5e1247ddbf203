"""What a solid-model run will cost, known before it starts, and the limits beyond which the CLI
refuses it unless ``--force``.

The estimates come from the mesh's cell counts (:func:`spsc.fem.solid.mesh.wall_mesh_counts`, an
upper bound within a few per cent of the built mesh) and one measurement: ``spsc fem --type B``
(quarter, 1 mm, 2 layers, 28 275 unknowns) peaked at 0.67 GB resident on this 2-core machine,
0.45 GB of it the interpreter and libraries; the sparse factor of a 3D mesh grows as
unknowns^(4/3) (nested dissection), which :func:`fem_memory_gib` extrapolates.
"""

from __future__ import annotations

import math
import sys

from spsc.core.errors import ParameterError

__all__ = ["FEM_MAX_UNKNOWNS", "FEM_MAX_STEPS", "WALL_MAX_UNKNOWNS", "WALL_MAX_STEPS",
           "fem_memory_gib", "wall_counts", "available_gib", "check_size"]

#: Unknowns of the 3D FEM beyond which a run needs --force (~7.5 GB by fem_memory_gib; 14x the
#: default Type B quarter model).
FEM_MAX_UNKNOWNS = 400_000
#: Load steps (plate positions + inflation increments) of the 3D FEM beyond which a run needs
#: --force: each takes a few factorisations (seconds at the default mesh).
FEM_MAX_STEPS = 500
#: The wall model (dome or swept stadium): unknowns and load steps beyond which a run needs
#: --force.
WALL_MAX_UNKNOWNS = 300_000
WALL_MAX_STEPS = 5000

_BASE_GIB = 0.45               # interpreter, numpy/scipy/scikit-fem/OCCT loaded (measured)
_MEASURED = (28_275, 0.22)     # unknowns, GiB above the base for `spsc fem --type B`


def fem_memory_gib(unknowns: int) -> float:
    """Estimated peak memory (GiB) of a 3D FEM run with ``unknowns`` unknowns."""
    n0, g0 = _MEASURED
    return _BASE_GIB + g0 * (max(unknowns, 1) / n0) ** (4.0 / 3.0)


def wall_counts(g, size: float, layers: int, sweep_size: float) -> dict:
    """Estimated unknowns of the wall model (``spsc.fem.wall``): the meridian section has
    (2n+1)(2·layers+1) nodes of Q2 quads, n = profile length / ``size``; a dome is that section
    revolved (two displacement components), a stadium (l > 0) the section swept through
    2m+1 stations (m quadratic elements of about ``sweep_size`` along the half middle and the
    quarter end arc, :func:`spsc.fem.swept.sweep_stations`; three components)."""
    outer = g.outer_profile_points(2001)
    length = float(sum(math.hypot(*(b - a)) for a, b in zip(outer[:-1], outer[1:])))
    n = max(4, math.ceil(length / size))
    section = (2 * n + 1) * (2 * layers + 1)
    if g.l == 0:
        nodes, components = section, 2
    else:
        m = (math.ceil(g.l / 2 / sweep_size - 1e-9)
             + max(2, math.ceil(math.pi / 2 * (g.w + g.t0) / sweep_size - 1e-9)))
        nodes, components = section * (2 * m + 1), 3
    return {"nodes": nodes, "unknowns": components * nodes, "mesh_size": size}


def available_gib() -> float | None:
    """Memory the system could give a new process (GiB; Linux MemAvailable), or None."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) / 2**20
    except OSError:
        pass
    return None


def check_size(verb: str, counts: dict, steps: int, *, limit: int, gib: float | None,
               force: bool, quiet: bool, mesh_size: float, points: int,
               max_steps: int | None = None) -> None:
    """Refuse the run — ParameterError naming the mesh size or the points — when it has more
    than ``limit`` unknowns, more than ``max_steps`` load steps (plate positions + inflation
    increments) or needs more memory than is available, unless ``force``; then print the
    estimate on stderr unless ``quiet``."""
    n = int(counts["unknowns"])
    max_steps = max_steps if max_steps is not None else (
        FEM_MAX_STEPS if gib is not None else WALL_MAX_STEPS)
    memory = f", ~{gib:.2g} GB" if gib is not None else ""
    estimate = f"~{n:,} unknowns{memory}, {steps} load steps"
    if not force:
        _refuse_beyond(n, steps, gib, limit, max_steps, mesh_size, points, estimate)
    if not quiet:  # only when the run goes ahead: an error stays one line
        print(f"spsc {verb}: estimate: {estimate}", file=sys.stderr)


def _refuse_beyond(n, steps, gib, limit, max_steps, mesh_size, points, estimate) -> None:
    avail = available_gib()
    if n > limit:
        raise ParameterError("mesh size", mesh_size,
                             f"a mesh of at most {limit:,} unknowns (this one: {estimate}); "
                             "coarser --mesh-size, fewer --layers, or --force")
    if steps > max_steps:
        raise ParameterError("points", points, f"at most {max_steps} load steps for this model "
                             f"({estimate}); fewer --points, or --force")
    if gib is not None and avail is not None and gib > 0.8 * avail:
        raise ParameterError("mesh size", mesh_size,
                             f"a mesh that fits in memory (this one: {estimate}; "
                             f"{avail:.1f} GB available); coarser --mesh-size, or --force")

