"""The trained surrogate as a batched predictor: designs in, curves out, each with its domain
checked and its error estimated.

:meth:`Surrogate.curves` takes arrays — the seven parameters of m chambers, their materials'
shear moduli, setup pressures, reservoirs, polytropic indices and travels — and answers with
the exact gas law of :mod:`.assemble` on the learnt maps of :mod:`.gp`. Its domain
(:mod:`.domain`) is checked per design: a ratio outside the trained hull, a travel beyond the
map's deepest, a pressure beyond its highest level, a reservoir or an index outside the trained
ranges. :func:`load` reads a file once. The package ships one surrogate per design family
(:data:`SHIPPED_FILES`: the domes', and Table 1's stadiums with their shape free):
:func:`choose` gives a design the first whose domain holds it.

Units: mm, MPa (shear modulus), kPa gauge, mm³, N.
"""

from __future__ import annotations

import functools
import json
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError
from .assemble import Maps, solve_curves
from .domain import BOUNDS, Q_UNIFORM_16, RATIOS, TRAVELS
from .gp import FieldModel
from .inputs import unit_inputs
from .spline import SplineGrid

__all__ = ["Surrogate", "load", "surrogates", "choose", "SHIPPED", "SHIPPED_FILES",
           "RESERVOIR_MAX_MM3", "POLYTROPIC"]

#: The surrogates the package ships (trained by ``spsc surrogate train --family F``), by
#: family: a design goes to the first whose domain holds it (:func:`choose`).
SHIPPED_FILES = {family: Path(__file__).with_name("data") / f"wall-{family}.npz"
                 for family in ("dome", "table1")}
#: The domes' surrogate: the default file of every verb that takes one.
SHIPPED = SHIPPED_FILES["dome"]
#: a fixed ratio holds within this share of its value (a chamber drawn to 0.01 mm)
FIXED_RTOL = 1e-3
#: The reservoir range (mm³) and polytropic indices the surrogate answers for.
RESERVOIR_MAX_MM3 = 100_000.0
POLYTROPIC = (1.0, 1.4)
#: ratio name -> the parameter a user changes to move it
_NAMED = {"h/w": "h", "l/w": "l", "t0/w": "t0", "n1": "n1", "n2": "n2", "cy": "cy"}


class Surrogate:
    """A fitted surrogate: its :class:`~.gp.FieldModel`, the ratios it varies (``free``; the
    others fixed at ``fixed``), its map's grid (``q_levels``, ``travels``: the file's, or the
    sixteen even levels and :data:`~.domain.TRAVELS` of a file that does not state them), its
    metadata (training, calibration of the error)."""

    def __init__(self, arrays: dict, meta: dict):
        self.fields = FieldModel(arrays)
        self.q_levels = np.asarray(arrays.get("q_levels", Q_UNIFORM_16), float)
        self.travels = np.asarray(arrays.get("travels", TRAVELS), float)
        self.qgrid, self.dgrid = SplineGrid(self.q_levels), SplineGrid(self.travels)
        self.meta = meta
        self.free = self.fields.free
        self.fixed = {k: float(v) for k, v in meta.get("fixed", {}).items()}
        #: the calibrated factors of the posterior spread (force and area; pressure and
        #: volume), :mod:`spsc.studies.surrogate.build`
        self.error_scale = dict(meta.get("error_scale", {"force": 1.0, "pressure": 1.0}))

    # -- the domain --------------------------------------------------------------------------
    def outside(self, ratios: np.ndarray) -> list[str]:
        """Why each design (rows of the six ratios) is outside the trained hull ('' inside):
        the first ratio out, named as the user's parameter."""
        out = []
        for r in np.atleast_2d(ratios):
            why = ""
            for k, name in enumerate(RATIOS):
                v = r[k]
                if name in self.fixed:
                    fixed = self.fixed[name]
                    if abs(v - fixed) > FIXED_RTOL * abs(fixed) + 1e-9:
                        why = (f"{_NAMED[name]}: {name} = {fixed:.4g} "
                               f"({self.meta.get('name') or 'the surrogate'} is trained on "
                               f"it only; {name} = {v:.4g} here)")
                        break
                    continue
                lo, hi = BOUNDS[name]
                if not lo - 1e-9 <= v <= hi + 1e-9:
                    why = (f"{_NAMED[name]}: {name} from {lo:g} to {hi:g} ({name} = {v:.4g} "
                           "here)")
                    break
            out.append(why)
        return out

    def domain(self) -> str:
        """The trained domain in words: its fixed ratios and the ranges of the free ones."""
        fixed = ", ".join(f"{k} = {v:.4g}" for k, v in self.fixed.items())
        free = ", ".join(f"{k} {BOUNDS[k][0]:g}–{BOUNDS[k][1]:g}" for k in self.free)
        return f"{self.meta.get('name', 'the surrogate')}: {fixed}; {free}"

    def unit_inputs(self, ratios) -> np.ndarray:
        """The GP inputs of design ratios (:func:`.inputs.unit_inputs`)."""
        return unit_inputs(ratios, self.free)

    # -- the maps and the curves -------------------------------------------------------------
    def maps(self, params: np.ndarray, mu_MPa, draws: int = 0, rng=None):
        """The :class:`~.assemble.Maps` of designs ``params`` (m × 7: w, h, l, t0, n1, n2,
        c_y) of shear modulus ``mu_MPa`` (m); with ``draws``, also a list of posterior
        samples of them."""
        p = np.atleast_2d(np.asarray(params, float))
        w, h, t0 = p[:, 0], p[:, 1], p[:, 3]
        ratios = np.column_stack([h / w, p[:, 2] / w, t0 / w, p[:, 4], p[:, 5], p[:, 6]])
        f = self.fields.fields(self.unit_inputs(ratios), draws, rng)
        mu = np.broadcast_to(np.asarray(mu_MPa, float), w.shape)
        nt, nq = len(self.travels), len(self.q_levels)

        scales = np.column_stack([w**3, mu * t0 * w, w**2])  # ΔV, F, A in real units

        def build(get):
            fields = np.empty((w.size, nq, 3, nt))  # scaled into place, no stacked copy
            for k, b in enumerate(Maps.FIELDS):
                np.multiply(get(b).reshape(-1, nq, nt), scales[:, k, None, None],
                            out=fields[:, :, k])
            levels = np.stack([get("H") * w[:, None], get("V0") * w[:, None] ** 3], axis=-1)
            return Maps(levels, fields, h, 1000.0 * mu * t0 / w, self.qgrid, self.dgrid)

        maps = build(lambda b: f[b])
        if not draws:
            return maps, []
        return maps, [build(lambda b, d=d: f[b + ".draws"][d]) for d in range(draws)]

    def curves(self, params, mu_MPa, y, p_i, reservoir, n_poly, *, draws: int = 0,
               rng=None) -> dict:
        """The curves of m designs (see :func:`~.assemble.solve_curves`) with, per point,
        ``inside`` (the map's travel and pressure ranges hold it) and, with ``draws``, the
        estimated error (``force_err_N``, ``pressure_err_kPa``: the posterior spread of
        ``draws`` sampled maps times the calibrated :attr:`error_scale`; the area's with the
        force's scale, the volume's with the pressure's)."""
        maps, samples = self.maps(params, mu_MPa, draws, rng)
        out = solve_curves(maps, y, p_i, reservoir, n_poly)
        h = maps.h[:, None]
        out["inside"] = ((out["delta_mm"] <= self.travels[-1] * h * (1 + 1e-6))
                         & (out["q"] <= self.q_levels[-1] * (1 + 1e-6)))
        out["snap_risk"] = self.snap_risk(params, out["q"])
        if samples:
            runs = [solve_curves(s, y, p_i, reservoir, n_poly) for s in samples]
            for key, name, scale in (
                    ("force_N", "force_err_N", "force"),
                    ("pressure_kPa", "pressure_err_kPa", "pressure"),
                    ("contact_area_mm2", "area_err_mm2", "force"),
                    ("volume_change_mm3", "volume_err_mm3", "pressure")):
                spread = np.std([r[key] for r in runs], axis=0)
                out[name] = self.error_scale[scale] * spread
        return out

    def snap_risk(self, params, q) -> np.ndarray:
        """Per design, the share of its nearest training designs that snapped through or could
        not be pressed at the pressure levels its curve passes (q, m × points, one level of
        margin each side): at or above :data:`~.gp.RISK_FLAG` its answer is flagged."""
        p = np.atleast_2d(np.asarray(params, float))
        w = p[:, 0]
        ratios = np.column_stack([p[:, 1] / w, p[:, 2] / w, p[:, 3] / w, p[:, 4], p[:, 5],
                                  p[:, 6]])
        L = self.q_levels  # from the last level below the curve's to the first above
        lo = np.searchsorted(L, np.nanmin(q, axis=1), side="left") - 1
        hi = np.searchsorted(L, np.nanmax(q, axis=1), side="right")
        k = np.arange(L.size)[None, :]
        levels = (k >= lo[:, None]) & (k <= hi[:, None])
        return self.fields.snap_risk(self.unit_inputs(ratios), levels)


@functools.lru_cache(maxsize=4)
def surrogates(path: str | None = None) -> tuple[Surrogate, ...]:
    """The surrogates that answer: the one in ``path``, or every shipped one
    (:data:`SHIPPED_FILES`, the domes' first)."""
    if path:
        return (load(path),)
    return (load(),) + tuple(load(str(f)) for k, f in SHIPPED_FILES.items()
                             if k != "dome" and f.exists())


def choose(path: str | None, ratios) -> tuple[Surrogate, str]:
    """The surrogate that answers the design of ``ratios`` (:data:`~.domain.RATIOS`), of
    :func:`surrogates` (``path``), and why none holds it ('' if one does): the first's
    reason, naming the parameter, with the others' domains. Outside every domain the first
    answers (with ``--allow-extrapolation``)."""
    surs = surrogates(path)
    whys = [s.outside(ratios)[0] for s in surs]
    for s, why in zip(surs, whys):
        if not why:
            return s, ""
    return surs[0], "; or ".join([whys[0]] + [s.domain() for s in surs[1:]])


@functools.lru_cache(maxsize=4)
def load(path: str | None = None) -> Surrogate:
    """The surrogate in ``path`` (None: the domes', :data:`SHIPPED`); a one-line
    ParameterError if it is missing or not a surrogate file."""
    path = Path(path) if path else SHIPPED
    try:
        with np.load(path, allow_pickle=False) as z:
            arrays = {k: z[k] for k in z.files}
        meta = json.loads(str(arrays.pop("meta")))
    except (OSError, KeyError, ValueError) as exc:
        raise ParameterError("surrogate", str(path), f"a surrogate file of spsc surrogate "
                             f"train ({type(exc).__name__}: {exc})") from None
    return Surrogate(arrays, meta)
