"""The streaming API: one sample in, the state and the events out, in O(1) — the code ``spsc
sense`` runs on a whole log (one :class:`SenseStream`, one :meth:`~SenseStream.push` per row)
and on standard input (``--follow``).

A valve switch comes from the ``valve_open`` column when the log has it. Without it an opening
under load is inferred from the pressure (:meth:`SenseStream._infer_opening`): the closed
chamber's gas pooled with the reservoir's gives, at the travel of the moment, one predicted
pressure (the estimator's pooled table); a fall of at least 80 % of the way to it within
``switch_window_s`` that then stays there (the window's last quarter moved less than a tenth of
the fall) is the valve, which equalises in milliseconds, not a hand or a gripper letting go
(a release keeps falling past it). An opening at rest changes no pressure and a closing
changes none at all: neither can be seen in P, so without the column the valve is taken to stay
as it was (``EstimatorParams.valve_open`` at the start). The paper (sec. 4.1) notes the same
ambiguity for the gripper: "reducing the SPSC stiffness would result in a sudden pressure drop
that would be indistinguishable from a contact loss" — the pooled-pressure prediction is what
tells them apart here.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field
from typing import NamedTuple

from spsc.core.errors import ParameterError, require

from .detectors import (ComplianceParams, ContactParams, LeakParams, SlipParams,
                        build_detector, contact_detector, detector_class)
from .estimator import Estimator, EstimatorParams
from .protocol import Context, Sample

__all__ = ["SenseParams", "SenseStream", "State"]


@dataclass(frozen=True)
class SenseParams:
    """The estimator's, the detectors' parameters; ``rate_Hz`` the nominal sampling rate (the
    detectors' windows in samples); ``infer_switch`` an opening from the pressure when no
    ``valve_open`` is given, within ``switch_window_s``. The detectors after the contact's are
    :attr:`detectors`: ``slip`` (None: off), ``compliance`` (None, the default: off),
    ``leak`` (None: off; :mod:`.leak`), then ``extra_detectors``, the parameters of any other detector of
    :data:`~.detectors.DETECTORS`, in the order they run."""

    estimator: EstimatorParams
    contact: ContactParams = field(default_factory=ContactParams)
    slip: SlipParams | None = field(default_factory=SlipParams)
    compliance: ComplianceParams | None = None
    leak: LeakParams | None = field(default_factory=LeakParams)
    rate_Hz: float = 1000.0
    infer_switch: bool = True
    switch_window_s: float = 0.02
    extra_detectors: tuple = ()

    def __post_init__(self):
        require("rate_Hz", self.rate_Hz, gt=0, le=1e6, unit="Hz")
        require("switch_window_s", self.switch_window_s, gt=0, le=10, unit="s")
        object.__setattr__(self, "extra_detectors", tuple(self.extra_detectors))
        for prm in self.detectors:
            detector_class(prm)  # a registered detector's, or one line naming it

    @property
    def detectors(self) -> tuple:
        """The parameters of the detectors that run after the contact's, in their order."""
        return tuple(p for p in (self.slip, self.compliance, self.leak,
                                 *self.extra_detectors) if p is not None)


class State(NamedTuple):
    """The chamber after one sample: force (N) and its 95 % band, depth (mm), mode
    (``high``: valve closed, ``low``: open), contact, the filtered pressure (kPa), whether
    the pressure was inside the chamber map's table."""

    t_s: float
    force_N: float
    force_lo_N: float
    force_hi_N: float
    depth_mm: float
    mode: str
    in_contact: bool
    pressure_kPa: float
    in_map: bool


class SenseStream:
    """``push`` samples in time order; ``events`` all events so far. ``contact`` is the
    contact detector (:class:`~.protocol.ContactDetector`), ``detectors`` the others
    (:class:`~.protocol.Detector`), in the order they run on each sample."""

    #: the stream's own events (a valve switch) and their colours in ``sense.png``
    kinds = {"switch": "C1"}

    def __init__(self, dense, params: SenseParams):
        self.params = params
        self.est = Estimator(dense, params.estimator)
        context = Context(params.estimator.noise_kPa, params.rate_Hz, self.est)
        self.contact = contact_detector(params.contact, context.noise_kPa, context.rate_Hz)
        self.detectors = [build_detector(prm, context) for prm in params.detectors]
        self.t = -math.inf
        self.recent = deque()  # (t, filtered P, depth) over switch_window_s
        self.events: list[dict] = []

    def detector(self, name: str):
        """The first detector called ``name``, or None."""
        return next((d for d in self.detectors if d.name == name), None)

    @property
    def slip(self):
        """The slip detector, or None."""
        return self.detector("slip")

    @property
    def compliance(self):
        """The object-compliance detector, or None."""
        return self.detector("compliance")

    @property
    def colours(self) -> dict[str, str]:
        """Each event kind the stream and its detectors raise -> its colour in the figure."""
        out = {**self.kinds, **self.contact.kinds}
        for d in self.detectors:
            out.update(d.kinds)
        return out

    def push(self, t_s, pressure_kPa, valve_open=None, fsr=None, angle_deg=None):
        """One sample: (:class:`State`, the events it raised). The contact detector runs
        first (the rest tracked while out of contact), then the others on the
        :class:`~.protocol.Sample`."""
        t, p = float(t_s), float(pressure_kPa)
        if not t > self.t:
            raise ParameterError("t_s", t_s, f"strictly increasing (the last was {self.t:g} s)")
        if not math.isfinite(p):
            raise ParameterError("pressure_kPa", pressure_kPa, f"a finite number (at t = {t:g} s)")
        self.t = t
        est, events = self.est, self._switch(t, p, valve_open)
        e = est.update(t, p)
        # the detectors read the gas at the ambient temperature (the estimator's P_iso): a
        # release's cooling is no contact, a hold's no plate backing off
        q, sigma = est.iso(p), est.sigma_kPa
        base, settled = est.baseline_kPa, est.rest.settled
        ev = self.contact.push(t, q, e.iso_kPa, sigma, base, settled)
        in_contact = self.contact.contact
        if ev is not None:
            events.append(ev)
            if in_contact:
                est.leave_rest()
        if not in_contact:
            est.track_rest(q)
        self.recent.append((t, e.iso_kPa, e.depth_mm))
        while t - self.recent[0][0] > self.params.switch_window_s:
            self.recent.popleft()
        if self.detectors:
            sample = Sample(t, q, e.iso_kPa, sigma, base, settled, est.rest_kPa, e.depth_mm,
                            fsr, None if angle_deg is None else float(angle_deg), in_contact,
                            events)
            for d in self.detectors:
                ev = d.detect(sample)
                if ev is not None:
                    events.append(ev)
        self.events.extend(events)
        return State(t, e.force_N, e.force_lo_N, e.force_hi_N, e.depth_mm,
                     "low" if est.open else "high", in_contact, e.pressure_kPa,
                     e.in_map), events

    def _switch(self, t: float, p: float, valve_open) -> list[dict]:
        """The valve switch this sample shows (the ``valve_open`` column, else an opening
        inferred from the pressure), the contact detector rebased to the level it leads to."""
        est, events = self.est, []
        if valve_open is not None:
            opened = bool(valve_open)
            if opened != est.open:
                info = est.switch(t, opened, p)
                events.append({"t_s": t, "kind": "switch", "trigger": "valve_open column",
                               **info})
        elif self.params.infer_switch and self.contact.contact and est.pooled is not None:
            ev = self._infer_opening(t)
            if ev is not None:
                events.append(ev)
        if events:  # a switch in contact: the release measured against the new level
            to = events[-1].get("pooled_kPa", p if est.p_s is None else est.iso(est.p_s))
            self.contact.rebase((to - est.baseline_kPa) / est.params.noise_kPa)
        return events

    def _infer_opening(self, t: float) -> dict | None:
        """An opening under load, from the fall to the predicted pooled pressure."""
        r = self.recent
        if len(r) < 8 or t - r[0][0] < 0.5 * self.params.switch_window_s:
            return None
        est = self.est
        t0, p0, y0 = r[0]
        p_eq = est.pooled_pressure(y0)
        fall, sig = p0 - p_eq, est.sigma_kPa
        p_now = r[-1][1]
        if fall < 6.0 * sig or p0 - p_now < 0.8 * fall:
            return None
        if abs(p_now - p_eq) > max(3.0 * sig, 0.2 * fall):
            return None
        quarter = [x[1] for x in r if x[0] >= t - 0.25 * self.params.switch_window_s]
        if max(quarter) - min(quarter) > 0.1 * fall + 2.0 * sig:
            return None  # still falling: a release, not the valve
        # the switch: the last sample before the fall began (the filtered P of the sample
        # after it has begun to fall already)
        k = next(i for i, x in enumerate(r) if x[1] < p0 - max(3.0 * sig, 0.02 * fall))
        t0, p0, y0 = r[max(k - 2, 0)]
        info = est.switch(t0, True, p0, y0)
        r.clear()
        return {"t_s": t0, "kind": "switch", "trigger": f"inferred: P fell {p0 - p_now:.3g} "
                f"kPa to the pooled pressure {p_eq:.4g} kPa in {t - t0:.3g} s", **info}
