"""The ``surrogate`` model: the wall model's answers in milliseconds, from maps learnt over
the design space (:mod:`.predict`), with the gas law applied exactly and the error of every
point stated, as a :class:`~spsc.models.base.CurveModel`."""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError
from ..base import ModelBase, Outcome, option
from .domain import ratios_of
from .gp import RISK_FLAG

__all__ = ["SurrogateCurveModel", "SurrogateOptions", "check_material"]

#: posterior samples behind each answer's error estimate
DRAWS = 32


@dataclass(frozen=True)
class SurrogateOptions:
    """``surrogate``: a surrogate file of ``spsc surrogate train`` (None: the shipped one);
    ``allow_extrapolation``: answer outside the trained domain, with a warning."""

    surrogate: str | None = option(None, "--surrogate", "a surrogate file of spsc surrogate "
                                   "train (default: the one shipped with spsc)",
                                   metavar="FILE")
    allow_extrapolation: bool = option(False, "--allow-extrapolation", "answer outside the "
                                       "surrogate's trained domain, with a warning",
                                       kind="flag")


def check_material(material, allow: bool) -> list[str]:
    """A neo-Hookean law (an exact stiffness scale of the trained one) passes; another law is
    refused unless ``allow`` (then the warning: its initial shear modulus stands for it)."""
    if material.neo_hookean:
        return []
    text = (f"a neo-Hookean law (an exact stiffness scale of the trained one); {material.name} "
            f"is {material.law}")
    if not allow:
        raise ParameterError("material", material.name, text + " (--allow-extrapolation: "
                             "answered with its initial shear modulus, or --model wall)")
    return [f"material {material.name} ({material.law}) answered as neo-Hookean with its "
            f"initial shear modulus {material.shear_modulus:.4g} MPa: outside the trained "
            "domain"]


def _refuse_or_note(notes: list, allow: bool, name: str, value, allowed: str) -> None:
    if not allow:
        raise ParameterError(name, value, allowed + " (the surrogate's trained domain; "
                             "--allow-extrapolation or --model wall)")
    notes.append(f"{name} = {value}: outside the trained domain ({allowed})")


@dataclass(frozen=True)
class SurrogateCurveModel(ModelBase):
    """Learnt maps of the wall model with the gas law applied exactly: milliseconds per curve,
    each point with its estimated error."""

    name: str = "surrogate"
    help: str = ("the wall model's surrogate: learnt maps, exact gas law, the error of each "
                 "point stated (milliseconds)")
    module: str = "spsc.models.surrogate.model"
    Options = SurrogateOptions
    stroke_mm: float = 6.0
    points: int = 25
    bending: bool = True
    study: bool = False
    color: str = "C5"
    style: str = ":"
    seconds_per_point: float = 1e-4

    def domain_notes(self, setup, options) -> list[str]:
        """What lies outside the trained domain (ParameterError on the first, unless
        ``allow_extrapolation``: then the list of warnings)."""
        return self._answering(setup, options)[1]

    def _answering(self, setup, options):
        """(the surrogate that answers the setup's chamber, :meth:`domain_notes`)."""
        from .predict import POLYTROPIC, RESERVOIR_MAX_MM3, choose

        allow = bool(options.allow_extrapolation)
        g, lc = setup.body, setup.load
        sur, why = choose(options.surrogate, ratios_of(g))
        notes = check_material(setup.material, allow)
        if why:
            name, text = why.split(": ", 1)
            _refuse_or_note(notes, allow, name, getattr(g, name), text)
        if lc.reservoir_mm3 > RESERVOIR_MAX_MM3:
            _refuse_or_note(notes, allow, "reservoir", f"{lc.reservoir_mm3:g} mm³",
                            f"0 to {RESERVOIR_MAX_MM3:g} mm³")
        lo, hi = POLYTROPIC
        if not lo <= lc.polytropic_n <= hi:
            _refuse_or_note(notes, allow, "polytropic_n", lc.polytropic_n, f"{lo:g} to {hi:g}")
        unit = 1000.0 * setup.material.shear_modulus * g.t0 / g.w
        q_top, d_top = sur.q_levels[-1], sur.travels[-1]
        if lc.pressure_kPa > q_top * unit:
            _refuse_or_note(notes, allow, "pressure", f"{lc.pressure_kPa:g} kPa",
                            f"at most {q_top * unit:.3g} kPa for this wall and material "
                            f"({q_top:g} μ t0/w)")
        if lc.stroke_mm > d_top * g.h:
            _refuse_or_note(notes, allow, "stroke", f"{lc.stroke_mm:g} mm",
                            f"at most {d_top * g.h:.3g} mm ({d_top:g} h)")
        return sur, notes

    def check(self, setup, options, *, verb: str, quiet: bool) -> None:
        self.check_contact(setup)
        self.domain_notes(setup, options)

    def curve(self, setup, options, *, progress=None, cache_dir=None):
        t0 = time.perf_counter()
        sur, notes = self._answering(setup, options)
        g, lc, mat = setup.body, setup.load, setup.material
        y = np.linspace(0.0, lc.stroke_mm, lc.points)
        params = np.array([[g.w, g.h, g.l, g.t0, g.n1, g.n2, g.cy]])
        out = sur.curves(params, mat.shear_modulus, y[None, :], lc.pressure_kPa,
                         lc.reservoir_mm3, lc.polytropic_n, draws=DRAWS,
                         rng=np.random.default_rng(0))
        return Outcome(_to_curve(setup, sur, out, y, notes, bool(options.allow_extrapolation),
                                 time.perf_counter() - t0))

    def curves_many(self, setups, options) -> list:
        """The curves of many setups in one batched evaluation (the sweep's and the design
        search's bulk path): the means of the learnt maps without the error estimate's
        posterior draws (the snap flag kept, in each curve's notes), each surrogate's designs
        together. Each setup is checked as :meth:`curve` checks it (ParameterError on the
        first refused)."""
        setups = list(setups)
        if not setups:
            return []
        answering = [self._answering(s, options) for s in setups]
        groups: dict[int, list[int]] = {}
        for k, (sur, _) in enumerate(answering):
            groups.setdefault(id(sur), []).append(k)
        curves = [None] * len(setups)
        for rows in groups.values():
            sur = answering[rows[0]][0]
            part = _batch(sur, [setups[k] for k in rows], [answering[k][1] for k in rows],
                          bool(options.allow_extrapolation), time.perf_counter())
            for k, c in zip(rows, part):
                curves[k] = c
        return curves


def _batch(sur, setups, notes, allow, t0) -> list:
    """The curves of ``setups`` that ``sur`` answers, in one call of its predictor (each
    curve's seconds its share of the call, from ``t0``)."""
    from spsc.cad.cavity import cavity_volumes

    params = np.array([[s.body.w, s.body.h, s.body.l, s.body.t0, s.body.n1, s.body.n2,
                        s.body.cy] for s in setups])
    loads = [s.load for s in setups]
    width = max(lc.points for lc in loads)
    # rows of different lengths padded with their last travel (dropped again below)
    y = np.array([np.pad(np.linspace(0.0, lc.stroke_mm, lc.points), (0, width - lc.points),
                         mode="edge") for lc in loads])
    out = sur.curves(params, np.array([s.material.shear_modulus for s in setups]), y,
                     np.array([lc.pressure_kPa for lc in loads]),
                     np.array([lc.reservoir_mm3 for lc in loads]),
                     np.array([lc.polytropic_n for lc in loads]))
    cavity = cavity_volumes(*np.delete(params, 3, axis=1).T)  # all at once
    share = (time.perf_counter() - t0) / len(setups)
    curves = []
    for k, (s, lc) in enumerate(zip(setups, loads)):
        one = {key: (v[k:k + 1, :lc.points] if np.ndim(v) == 2 else v[k:k + 1])
               for key, v in out.items()}
        curves.append(_to_curve(s, sur, one, y[k, :lc.points], notes[k], allow, share,
                                cavity=float(cavity[k])))
    return curves


def _to_curve(setup, sur, out, y, notes, allow, seconds, cavity=None):
    from spsc.core.curve import Curve, SolveInfo

    g, lc = setup.body, setup.load
    inside = out["inside"][0]
    solved = out["converged"][0]
    beyond = ("beyond the surrogate's map (the travel from this pressure's first contact "
              f"past {sur.travels[-1]:g} h or the pressure past {sur.q_levels[-1]:g} μ t0/w)")
    msg = ["" if ok else (beyond + (": extrapolated" if allow else ""))
           for ok in inside]
    # a solve that ran off the map (its bracket's top, 4 × the highest level) is the map's
    # limit, said as such; only inside the map is a failed solve the gas law's
    msg = [m if s or not ok else "the gas law did not converge on the map"
           for m, s, ok in zip(msg, solved, inside)]
    conv = solved & (inside | allow)
    risk = float(out["snap_risk"][0])
    snap = ""
    if risk >= RISK_FLAG:
        snap = (f"near designs that snap through or that the wall model could not press at "
                f"these pressures ({risk:.0%} of the nearest training designs): the "
                "surrogate smooths what the wall model resolves; --model wall for this "
                "chamber")  # said once, as the curve's instability
    if notes:
        msg = [m or notes[0] for m in msg]
    details = {"surrogate": sur.meta.get("name", ""), "trained": sur.meta.get("trained", ""),
               "training_designs": int(sur.fields.X.shape[0]),
               "snap_risk": round(risk, 3), "snap_flag": risk >= RISK_FLAG,
               "inflated_height_note": "the outer top less t0 (the map holds the outer top)"}
    if "force_err_N" in out:
        details.update(error_scale=sur.error_scale, draws=DRAWS,
                       force_err_N=out["force_err_N"][0].round(6).tolist(),
                       pressure_err_kPa=out["pressure_err_kPa"][0].round(6).tolist())
    i = np.flatnonzero(conv)
    info = SolveInfo(converged=bool(conv.all()), message="converged" if conv.all() else
                     next(m for m in msg if m), y_reached_mm=float(y[i[-1]]) if i.size
                     else float("nan"), instability=snap, seconds=seconds, notes=tuple(notes),
                     details=details)
    H, V0 = float(out["top_mm"][0]), float(out["inflated_volume_mm3"][0])
    nan = lambda a: np.where(conv, a, np.nan)  # noqa: E731
    setup_rec = {"p_i_kPa": lc.pressure_kPa, "reservoir_mm3": lc.reservoir_mm3,
                 "polytropic_n": lc.polytropic_n}
    return Curve(y, nan(out["force_N"][0]), nan(out["pressure_kPa"][0]),
                 nan(np.maximum(out["contact_area_mm2"][0], 0.0)),
                 nan(out["volume_change_mm3"][0]), model="surrogate",
                 geometry=g.as_dict(), material=setup.material.name, setup=setup_rec,
                 nominal_volume_mm3=g.cavity_volume() if cavity is None else cavity,
                 inflated_volume_mm3=V0,
                 inflated_height_mm=H - g.t0, converged=conv, message=tuple(msg),
                 solver=info)
