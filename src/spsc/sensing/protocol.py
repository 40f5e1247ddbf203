"""What a detector of :class:`~.stream.SenseStream` is: the :class:`Sample` the stream builds
once per sample, the :class:`Detector` protocol every event detector but the contact's
follows (slip, object compliance, any added one: a class and a line in
:data:`~.detectors.DETECTORS`), the :class:`Context` it is built with, and the
:class:`ContactDetector` protocol of the one detector the stream itself asks (in contact or
not: the rest tracking, the slip and the compliance depend on it).

A detector's class has a ``name`` (its key in the registry), ``kinds`` (the event kinds it
raises, each with its colour in ``sense.png``), ``Params`` (its frozen parameters dataclass)
and is built as ``cls(params, context)``; :meth:`Detector.detect` takes one sample in time
order and returns an event or None.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple, Protocol

__all__ = ["Sample", "Context", "Detector", "ContactDetector"]


class Sample(NamedTuple):
    """One sample as the detectors read it, after the contact detector and the rest tracking
    ran on it. The pressures are at the ambient temperature (the estimator's P_iso: a
    release's cooling is no contact, a hold's no plate backing off).

    ``t_s`` (s); ``pressure_kPa`` the sensor's sample (gauge, at the ambient temperature);
    ``filtered_kPa`` the α-β filtered one (gauge, at the ambient temperature) and
    ``sigma_kPa`` its σ; ``baseline_kPa`` the rest the contact detector measured this sample
    against and ``settled`` whether the rest tracker had settled then; ``rest_kPa`` the
    pressure of the current content with nothing touching (after this sample's rest
    tracking); ``depth_mm`` the plate's travel; ``fsr`` the FSR readings (N, fsr_1 at the
    base; None without FSR columns); ``angle_deg`` the finger's closure (None without it);
    ``in_contact`` the contact detector's state after this sample; ``events`` the events this
    sample raised so far (switch, contact or release, then those of the detectors before this
    one, in order; read it, do not change it)."""

    t_s: float
    pressure_kPa: float
    filtered_kPa: float
    sigma_kPa: float
    baseline_kPa: float
    settled: bool
    rest_kPa: float
    depth_mm: float
    fsr: Sequence[float] | None
    angle_deg: float | None
    in_contact: bool
    events: Sequence[dict]


class Context(NamedTuple):
    """What a detector may need to be built: the sensor's σ ``noise_kPa`` (kPa), the nominal
    sampling rate ``rate_Hz`` (its windows in samples) and the stream's ``estimator``
    (:class:`~.estimator.Estimator`: the chamber's depth at a pressure, ``depth_at``)."""

    noise_kPa: float
    rate_Hz: float
    estimator: Any


class Detector(Protocol):
    """An event detector: ``name`` its key in :data:`~.detectors.DETECTORS`, ``kinds`` the
    event kinds it raises with their colours (a Matplotlib colour each), and :meth:`detect`
    one sample at a time."""

    name: str
    kinds: Mapping[str, str]

    def detect(self, sample: Sample) -> dict | None:
        """The event ``sample`` raises (a dict with at least ``t_s``, ``kind`` and
        ``trigger``, what made it), or None."""


class ContactDetector(Protocol):
    """The contact detector (:mod:`.contact`): ``contact`` whether in contact after the last
    sample; :meth:`push` one sample (the raw and filtered pressure, kPa, the filtered one's σ,
    the rest it is measured against and whether the rest tracker has settled);
    :meth:`rebase` a valve switch in contact, the pressure's new level in σ above the
    rest."""

    name: str
    kinds: Mapping[str, str]
    contact: bool

    def push(self, t: float, p_raw: float, p_f: float, sigma_f: float, rest: float,
             settled: bool = True) -> dict | None: ...

    def rebase(self, level: float) -> None: ...
