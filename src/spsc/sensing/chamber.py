"""The chamber a log was taken on: its quasi-static map from the wall model, as ``spsc curve``
names a chamber (a preset type with overrides or the seven parameters, a catalogue material or
a material file — the calibrated one ``spsc calibrate --out`` writes), built or read from the
keyed cache of :func:`spsc.dynamics.simulate.chamber_map_for`."""

from __future__ import annotations

from spsc.core.errors import require

__all__ = ["chamber_map"]


def chamber_map(params: dict, *, material: str = "tpu60a", setup_kPa: float = 40.0,
                reservoir_mm3: float = 0.0, stroke_mm: float = 4.0,
                mesh_size: float | None = None, cache_dir=None, progress=None,
                workers: int | None = 1, scheduler: str | None = None):
    """The :class:`~spsc.dynamics.chamber_map.ChamberMap` of the chamber ``params`` (``type``
    [``footprint``] and overrides, or w, h, l, t0, n1, n2, cy) at the setup pressure (kPa
    gauge), for plate travels up to ``stroke_mm`` and the pressures the closed chamber reaches
    there, built with its levels on ``workers`` or ``scheduler``
    (:func:`~spsc.dynamics.chamber_map.build_map`). The map is the same for both modes; the
    reservoir only enters the checks."""
    from spsc.dynamics.scenario import parse_scenario
    from spsc.dynamics.simulate import chamber_map_for

    require("stroke", stroke_mm, gt=0, le=30, unit="mm")
    chamber = {k: v for k, v in params.items() if v is not None}
    chamber["material"] = str(material)
    if mesh_size is not None:
        chamber["mesh_size"] = mesh_size
    doc = {"chamber": chamber,
           "circuit": {"setup_kPa": setup_kPa, "reservoir_mm3": reservoir_mm3},
           "press": {"profile": [[0.0, 0.0], [1.0, float(stroke_mm)]]}}
    return chamber_map_for(parse_scenario(doc), cache_dir=cache_dir, progress=progress,
                           workers=workers, scheduler=scheduler)
