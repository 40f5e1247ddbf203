"""``spsc virtual``: a chamber inside a robot simulator, headless (issue 50).

    spsc virtual SCENE.toml --out DIR [--quiet]

SCENE.toml is a scenario of ``spsc simulate`` (its ``[chamber]``, ``[circuit]`` with the valve,
gas and sensor, timed ``[[events]]``, and a force-controlled ``[press] force = [[t_s, N], ...]``
that becomes the actuator's push) with a ``[scene]`` table naming the MuJoCo scene: ``kind =
"plate"`` (a plate on a damped slide pushed onto the pad, :mod:`spsc.virtual.plate`). The pad
steps on its map (:mod:`spsc.virtual.chambers`) every MuJoCo step and pushes back. Writes
DIR/trace.csv (t_s, y_mm, force_N, pressure_kPa, measured_kPa, valve_open) and DIR/trace.png.
MuJoCo is the optional extra ``pip install spsc[sim]`` (``make``'s environment has it).
"""

from __future__ import annotations

import sys
import time

from spsc.core.errors import ParameterError
from spsc.cli.options import add_quiet_option, check_output_dir

__all__ = ["register", "run"]

#: the scenes there are
SCENES = ("plate",)


def register(subparsers) -> None:
    p = subparsers.add_parser("virtual", help="a chamber inside a MuJoCo scene, headless: "
                              "its force on the scene, its sensor's trace",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("scene", metavar="SCENE.toml", help="a scenario of spsc simulate with a "
                   "[scene] table (kind = \"plate\") and a force-controlled [press]")
    p.add_argument("--out", required=True, metavar="DIR", help="trace.csv and trace.png here")
    add_quiet_option(p)
    p.set_defaults(func=run)


def _read(path):
    """(the scenario without its [scene], the scene table) of SCENE.toml, checked."""
    import tomllib
    from pathlib import Path

    from spsc.dynamics.profile import ForceProfile
    from spsc.dynamics.scenario import parse_scenario

    p = Path(path)
    try:
        doc = tomllib.loads(p.read_text(encoding="utf-8-sig"))
    except OSError as exc:
        raise ParameterError("scene", str(path), f"a readable TOML file ({exc.strerror})") \
            from None
    except (UnicodeDecodeError, tomllib.TOMLDecodeError, RecursionError) as exc:
        raise ParameterError("scene", p.name, f"valid TOML ({str(exc)[:80]})") from None
    scene = doc.pop("scene", None)
    if not isinstance(scene, dict):
        raise ParameterError("scene", p.name, "a [scene] table with kind = "
                             + " | ".join(f'"{s}"' for s in SCENES))
    if scene.get("kind") not in SCENES:
        raise ParameterError("scene.kind", scene.get("kind"), " | ".join(SCENES))
    extra = sorted(set(scene) - {"kind"})
    if extra:
        raise ParameterError(f"scene.{extra[0]}", scene[extra[0]], "only kind (the press is "
                             "[press] force)")
    sc = parse_scenario(doc)
    if not isinstance(sc.press, ForceProfile):
        raise ParameterError("press", "profile", "a force-controlled press, [press] force = "
                             "[[t_s, N], ...]: the plate scene's actuator pushes with it")
    if sc.triggers or sc.stiffness is not None:
        raise ParameterError("events", "pressure triggers or [stiffness]", "timed valve events "
                             "only in a scene")
    if sc.leak is not None:
        raise ParameterError("circuit.leak", sc.leak.describe(), "none in a scene (the "
                             "virtual chambers are sealed; spsc simulate runs a leak)")
    return sc, scene


def run(args) -> int:
    from pathlib import Path

    sc, scene = _read(args.scene)
    out = check_output_dir("--out", args.out)
    try:
        import mujoco  # noqa: F401  (the extra: refused before any work when missing)
    except ImportError:
        raise ParameterError("scene", "mujoco", "the MuJoCo extra installed (pip install "
                             "spsc[sim])") from None
    from spsc.dynamics.circuit import Circuit
    from spsc.dynamics.simulate import chamber_map_for
    from spsc.virtual.chambers import VirtualChambers
    from spsc.virtual.plate import press_plate

    t0 = time.perf_counter()
    m = chamber_map_for(sc)
    pad = VirtualChambers(m, Circuit(sc.setup_kPa, sc.reservoir_mm3, sc.valve, sc.gas),
                          sensor=sc.sensor, y0_mm=m.y_range[0], valve_open=sc.valve_open)
    t_map = time.perf_counter() - t0
    trace = press_plate(pad, lambda t: float(sc.press.force(t)), sc.press.duration,
                        valve_events=sc.events)
    seconds = time.perf_counter() - t0 - t_map
    Path(out).mkdir(parents=True, exist_ok=True)
    _write(trace, Path(out))
    i = -1
    print(f"spsc virtual: {scene['kind']} scene, {sc.press.duration:g} s in {seconds:.1f} s "
          f"(the map {t_map:.1f} s); at the end: travel {trace['y_mm'][i]:.3f} mm, force "
          f"{trace['force_N'][i]:.3f} N, pressure {trace['pressure_kPa'][i]:.2f} kPa "
          f"(read {trace['measured_kPa'][i]:.2f})")
    print(f"written: {Path(out) / 'trace.csv'}, {Path(out) / 'trace.png'}")
    return 0


def _write(trace: dict, out) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    pd.DataFrame(trace).to_csv(out / "trace.csv", index=False)
    fig, ax = plt.subplots(3, 1, figsize=(8, 7), sharex=True, constrained_layout=True)
    t = trace["t_s"]
    ax[0].plot(t, trace["y_mm"])
    ax[0].set_ylabel("plate travel (mm)")
    ax[1].plot(t, trace["force_N"])
    ax[1].set_ylabel("pad force (N)")
    ax[2].plot(t, trace["measured_kPa"], ".", ms=1.5, color="0.6", label="sensor")
    ax[2].plot(t, trace["pressure_kPa"], label="true")
    ax[2].set_ylabel("pressure (kPa)")
    ax[2].set_xlabel("time (s)")
    ax[2].legend(frameon=False)
    for a in ax:
        a.grid(alpha=0.3)
        for x in t[1:][trace["valve_open"][1:] != trace["valve_open"][:-1]]:
            a.axvline(x, color="C3", lw=0.8, ls="--")
    fig.savefig(out / "trace.png", dpi=110)
    plt.close(fig)
    sys.stdout.flush()
