"""The surrogate's training study: designs sampled over a family's domain (:data:`FAMILIES`,
with its :data:`ANCHORS`), the wall map of each (:func:`.sample.run_design`) on Dask workers,
one file per design, resumable.

A run folder holds ``study.json`` (the domain, the sampling, the code version) and
``runs/NNNNN.npz`` (``runs/aNN.npz`` for an anchor), one per design as it finishes: a re-run with the same folder computes only
the designs it lacks, and refuses a folder of another sampling, travels or code version (its
maps would not be the same model's). A folder trained on fewer pressure levels than
:data:`~spsc.models.surrogate.domain.Q_LEVELS` is extended: each design computes only the
levels it lacks (:func:`.sample.extend_run`), the others kept.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError
from spsc.models.surrogate.domain import BOUNDS, Q_LEVELS, RATIOS, TRAVELS

__all__ = ["FAMILIES", "ANCHORS", "design_points", "anchor_points", "train_maps", "load_runs"]

#: The design families a study samples, each with the ratios it fixes: ``dome`` (l = 0, the
#: axisymmetric wall, 3–8 s a design), ``table1`` (the stadiums of Table 1's proportions,
#: h/w = 13/11, l/w = 3/11, t0/w = 1/11, their shape n1, n2, c_y free: Types A–D and every
#: shape between, the swept wall, about two minutes a design) and ``stadium`` (every ratio
#: free).
FAMILIES = {"dome": {"l/w": 0.0},
            "table1": {"h/w": 13 / 11, "l/w": 3 / 11, "t0/w": 1 / 11},
            "stadium": {}}
#: The designs a family trains besides its sample (n1, n2, c_y): for ``table1`` the corners
#: of its shape's range, Types A and C among them, and Types B and D, which lie on its
#: faces, where a Gaussian process would otherwise extrapolate.
ANCHORS = {"table1": [(n1, n2, cy) for n1 in (2.0, 3.0) for n2 in (1.0, 4.0)
                      for cy in (0.0, 0.6)] + [(2.0, 2.2, 0.0), (2.0, 2.2, 0.6)]}


def design_points(count: int, seed: int, family: str) -> np.ndarray:
    """``count`` designs (rows of the six ratios) of a scrambled Sobol sequence over
    :data:`BOUNDS` (scipy.stats.qmc), the ratios the family fixes at their values."""
    from scipy.stats import qmc

    if family not in FAMILIES:
        raise ParameterError("family", family, "one of " + ", ".join(FAMILIES))
    fixed = FAMILIES[family]
    free = [r for r in RATIOS if r not in fixed]
    # the first ``count`` points of the next power of two's (the same points; scipy warns
    # that a count between powers of two loses the balance it then states)
    whole = 1 << max(0, int(count) - 1).bit_length()
    unit = qmc.Sobol(len(free), scramble=True,
                     seed=np.random.default_rng(seed)).random(whole)[:count]
    out = np.zeros((count, len(RATIOS)))
    for k, name in enumerate(free):
        lo, hi = BOUNDS[name]
        out[:, RATIOS.index(name)] = lo + unit[:, k] * (hi - lo)
    out = np.round(out, 6)
    for name, value in fixed.items():  # exact: 13/11 of w = 11 mm is h = 13 mm
        out[:, RATIOS.index(name)] = value
    return out


def anchor_points(family: str) -> np.ndarray:
    """The family's :data:`ANCHORS` as rows of the six ratios (none: 0 × 6)."""
    fixed = FAMILIES[family]
    rows = []
    for n1, n2, cy in ANCHORS.get(family, []):
        r = dict(fixed, n1=n1, n2=n2, cy=cy)
        rows.append([r[k] for k in RATIOS])
    return np.array(rows, float).reshape(-1, len(RATIOS))


def _job(index, ratios, old: dict | None = None) -> tuple:
    from .sample import extend_run, run_design

    try:
        return index, (run_design(ratios) if old is None else extend_run(old))
    except Exception as exc:  # a design the wall model cannot mesh or solve is a datum too
        return index, {"ratios": np.asarray(ratios, float), "error": repr(exc)}


def _lacking(path: Path) -> dict | None:
    """The run in ``path`` if it lacks levels of :data:`Q_LEVELS` (None if it has them all,
    or is a design the wall model could not mesh: its error stands)."""
    from .sample import level_index, levels_of

    with np.load(path, allow_pickle=False) as z:  # its levels read first, the rest if lacking
        if "error" in z.files:
            return None
        head = {k: z[k] for k in ("q_levels", "pressure_kPa", "ratios") if k in z.files}
        if min(level_index(levels_of(head), Q_LEVELS)) >= 0:
            return None
        return {k: z[k] for k in z.files}


def _meta(count, seed, family) -> dict:
    import hashlib

    from spsc.study.runs import source_closure

    # the code that computes a map; the domain's grid is stated apart (a study extended to new
    # levels keeps its maps)
    h = hashlib.sha256()
    for path in source_closure("spsc.studies.surrogate.sample"):
        if path.name != "domain.py" or path.parent.name != "surrogate":
            h.update(path.name.encode() + path.read_bytes())
    return {"count": int(count), "seed": int(seed), "family": family,
            "ratios": list(RATIOS), "bounds": {k: list(v) for k, v in BOUNDS.items()},
            "travels": [float(t) for t in TRAVELS], "levels": [float(q) for q in Q_LEVELS],
            "code": h.hexdigest()[:16]}


def _open(out: Path, meta: dict) -> None:
    out.mkdir(parents=True, exist_ok=True)
    (out / "runs").mkdir(exist_ok=True)
    path = out / "study.json"
    if path.exists():
        old = json.loads(path.read_text())
        for key in ("seed", "family", "bounds", "travels", "code"):
            if old.get(key) != meta[key]:
                raise ParameterError("out", str(out), f"a new folder or one of the same study "
                                     f"(its {key} differs: {old.get(key)} against {meta[key]})")
        meta = {**meta, "count": max(int(old["count"]), meta["count"])}
    path.write_text(json.dumps(meta, indent=1))


def train_maps(out, *, count: int, seed: int = 0, family: str = "dome", workers=None,
               scheduler=None, progress=None) -> int:
    """The wall maps of the first ``count`` designs of the study in ``out`` and of the
    family's :data:`ANCHORS` (computing those it lacks); returns how many were computed now.
    ``progress(done, total)`` per design."""
    out = Path(out)
    # the sample's designs by index, the anchors as a00, a01, …
    points = dict(enumerate(design_points(count, seed, family)))
    points.update({f"a{k:02d}": r for k, r in enumerate(anchor_points(family))})
    _open(out, _meta(count, seed, family))
    count = len(points)
    todo, old = [], {}
    for i in points:
        path = out / "runs" / _name(i)
        if not path.exists():
            todo.append(i)
        elif (run := _lacking(path)) is not None:
            todo.append(i)
            old[i] = run
    if progress is not None:
        progress(count - len(todo), count)
    if not todo:
        return 0
    from distributed import as_completed

    from spsc.study.executor import dask_client

    with dask_client(workers, scheduler) as client:
        futures = [client.submit(_job, i, points[i], old.get(i), pure=False) for i in todo]
        for k, fut in enumerate(as_completed(futures), start=1):
            i, d = fut.result()
            tmp = out / "runs" / _name(i).replace(".npz", ".tmp.npz")
            np.savez_compressed(tmp, **d)
            tmp.replace(out / "runs" / _name(i))
            if progress is not None:
                progress(count - len(todo) + k, count)
    return len(todo)


def _name(index) -> str:
    """A run's file: the sample's by its number, an anchor's by its name."""
    return f"{index:05d}.npz" if isinstance(index, int) else f"{index}.npz"


def load_runs(out) -> list[dict]:
    """Every design's arrays of the study in ``out``: the sample's in index order, then the
    anchors'."""
    runs = []
    for path in sorted((Path(out) / "runs").glob("*.npz")):
        if ".tmp" in path.name:
            continue
        with np.load(path, allow_pickle=False) as z:
            runs.append({k: z[k] for k in z.files})
    return runs
