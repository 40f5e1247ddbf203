"""Continuation along the plate travel for the contact problem (sec. 2.3.2, eq. 34).

One Newton solve of :class:`.bvp.BoxScheme` per plate position, warm-started by a secant
predictor from the last two solutions, with step halving where Newton fails. When flattening
the cap would compress the membrane on the plate, the solve switches to a slack core
(tension-field theory) and back when the core closes.
"""

from __future__ import annotations

import numpy as np

from spsc.core.constants import P_AMB, to_MPa
from spsc.core.gaslaw import GasLaw

from .bvp import BoxScheme
from .meridian import Meridian
from .shape import Shape, make_shape

__all__ = ["StrokeContinuation"]


class StrokeContinuation:
    """Continuation along the plate travel: secant predictor, step halving, and the switch to a
    slack core when the flattened cap would go into compression (tension-field theory: a
    membrane carries no compression; the core lies wrinkled on the plate, T1 = T2 = 0, and the
    taut annulus starts at λ1 = λ2 = 1)."""

    def __init__(self, geometry, mat, infl: Shape, settings, p_i, v_r, n_poly):
        self.g, self.infl, self.st = geometry, infl, settings
        mer = Meridian(geometry)
        kw = dict(wrinkling=settings.wrinkling)
        self.schemes = {
            False: BoxScheme(mer, mat, settings.contact_intervals, settings.free_intervals, **kw),
            True: BoxScheme(mer, mat, settings.contact_intervals, settings.free_intervals,
                            slack=True, **kw)}
        self.slack = False
        self.gas = GasLaw(p_i, infl.volume_mm3, v_r, n_poly)
        self.apex = float(infl.eta[0])
        self.hist: list[tuple[float, np.ndarray]] = []  # accepted (y, v) in the current mode
        self.y = 0.0
        self.iterations = 0

    @property
    def bs(self) -> BoxScheme:
        return self.schemes[self.slack]

    def _first_guess(self, y: float) -> np.ndarray:
        inf = self.infl
        H = self.apex - y
        # geometric intersection of the inflated shape with the plate (η decreasing in s)
        k = int(np.argmax(inf.eta < H))
        sg = float(np.interp(H, [inf.eta[k], inf.eta[k - 1]], [inf.s[k], inf.s[k - 1]]))
        return self._on_grid(self.schemes[False], inf, sg, 0.0, H, to_MPa(inf.pressure_kPa))

    @staticmethod
    def _on_grid(bs: BoxScheme, sh: Shape, sg, s0, H, p_mpa) -> np.ndarray:
        s = bs.nodes(sg, s0)
        Z = np.column_stack([np.interp(s, sh.s, c) for c in (sh.rho, sh.eta, sh.phi, sh.lambda1)])
        Z[: bs.nc + 1, 1] = H
        Z[: bs.nc + 1, 2] = 0.0
        if bs.slack:
            Z[0, 0], Z[0, 3] = float(bs.mer.x(s0)), 1.0
            return np.concatenate([Z.ravel(), [s0, sg, p_mpa]])
        return np.concatenate([Z.ravel(), [sg, p_mpa]])

    def _predict(self, y: float) -> np.ndarray:
        if not self.hist:
            return self._first_guess(y)
        if len(self.hist) == 1:
            return self.hist[-1][1].copy()
        (y0, v0), (y1, v1) = self.hist[-2], self.hist[-1]
        return v1 + (v1 - v0) * (y - y1) / (y1 - y0)

    def _solve(self, bs: BoxScheme, v0, y: float):
        H = self.apex - y
        r = bs.newton(v0, H=H, gas=self.gas, tol=self.st.rtol,
                      max_iter=self.st.max_iterations)
        self.iterations += r.iterations
        if not r.converged:
            return None, r.v, r.message
        Z, sg, p, s0 = bs.split(r.v)
        sh = make_shape(bs, r.v, p, sg, s0)
        nc = bs.nc
        if np.max(sh.eta[nc:]) > H + 1e-7 * self.g.w:
            return None, r.v, "the free membrane would cross the plate"
        if np.min(sh.T1[nc:]) <= 0.0:
            return None, r.v, "the free membrane loses its meridional tension (T1 <= 0)"
        if p <= -P_AMB:
            return None, r.v, "absolute pressure not positive"
        return sh, r.v, ""

    def _to_slack(self, sh: Shape, y: float):
        """Slack-mode guess from a (taut) contact shape whose cap went into compression."""
        nc = sh.gamma_index
        T = np.minimum(sh.T1[: nc + 1], sh.T2[: nc + 1])
        k = int(np.argmax(T >= 0.0)) if np.any(T >= 0.0) else nc // 2
        s0 = float(min(sh.s[max(k, 1)], 0.9 * sh.s_gamma))
        bs = self.schemes[True]
        return self._on_grid(bs, sh, sh.s_gamma, s0, self.apex - y, to_MPa(sh.pressure_kPa))

    def _to_taut(self, sh: Shape, y: float):
        """Taut-mode guess from a slack-mode shape whose core is closing (s_0 → 0)."""
        bs = self.schemes[False]
        v = self._on_grid(bs, sh, sh.s_gamma, 0.0, self.apex - y, to_MPa(sh.pressure_kPa))
        s = bs.nodes(sh.s_gamma)
        Z = v[:-2].reshape(-1, 4)
        core = s < sh.s_slack
        Z[core, 0] = bs.mer.x(s[core]) * sh.rho[0] / max(float(bs.mer.x(sh.s_slack)), 1e-12)
        Z[core, 3] = 1.0
        return v

    def _try(self, y: float):
        v0 = self._predict(y)
        sh, v, why = self._solve(self.bs, v0, y)
        if self.slack and (sh is None or sh.s_slack < 0.05 * sh.s_gamma):
            base = sh
            if base is None and self.hist:
                bs = self.schemes[True]
                Z, sg, p, s0 = bs.split(self.hist[-1][1])
                base = make_shape(bs, self.hist[-1][1], p, sg, s0)
            if base is not None:  # the core re-tensions: back to a taut cap
                sh2, v2, why2 = self._solve(self.schemes[False], self._to_taut(base, y), y)
                if sh2 is not None and min(sh2.T1[: sh2.gamma_index + 1].min(),
                                           sh2.T2[: sh2.gamma_index + 1].min()) >= 0.0:
                    self.slack, self.hist = False, []
                    sh, v, why = sh2, v2, ""
        if not self.slack and self.st.wrinkling:  # the taut law carries the compression
            base = sh
            if base is None and self.hist:  # taut failed: the cap may need a slack core
                bs = self.schemes[False]
                Z, sg, p, s0 = bs.split(self.hist[-1][1])
                base = make_shape(bs, self.hist[-1][1], p, sg, s0)
            if base is not None and min(base.T1[: base.gamma_index + 1].min(),
                                        base.T2[: base.gamma_index + 1].min()) < 0.0:
                sh2, v2, why2 = self._solve(self.schemes[True], self._to_slack(base, y), y)
                if sh2 is not None and sh2.s_slack > 0.0:
                    self.slack, self.hist = True, []
                    return (sh2, v2), ""
                if sh is not None:
                    why = f"the cap goes into compression and no slack-core solution ({why2})"
                    sh = None
        if sh is None:
            return None, why
        notes = []
        nc = sh.gamma_index
        if self.st.wrinkling and min(sh.T1[: nc + 1].min(), sh.T2[: nc + 1].min()) < -1e-9:
            notes.append("warning: compressive tension in the contact region (min T1 = "
                         f"{sh.T1[:nc + 1].min():.3g}, T2 = {sh.T2[:nc + 1].min():.3g} N/mm)")
        if sh.eta.min() < -1e-3 * self.g.h:
            notes.append(f"warning: the membrane dips {-sh.eta.min():.3g} mm below the base "
                         "plane (floor contact not modelled)")
        return (sh, v), "; ".join(notes)

    def advance(self, y_target: float):
        """Move the plate to ``y_target`` (mm); returns (Shape, note) or (None, reason)."""
        step = y_target - self.y
        min_step = step / 2**self.st.max_halvings
        why = ""
        while self.y < y_target - 1e-12 * max(1.0, y_target):
            y_try = min(self.y + step, y_target)
            out, why = self._try(y_try)
            if out is None:
                step *= 0.5
                if step < min_step * (1 - 1e-9):
                    return None, why
                continue
            sh, v = out
            self.hist = (self.hist + [(y_try, v)])[-2:]
            self.y = y_try
            self._last, self._note = sh, why
        return self._last, self._note
