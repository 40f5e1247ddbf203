"""Invalid invocations of what presses the chamber: the plate's friction, the object's
stiffness and the indenter (``--friction``, ``--object-stiffness``, ``--indenter``), each
refused in one line naming the option."""

from __future__ import annotations

from .fuzz_base import Case, numbers

__all__ = ["contact_cases"]

#: indenter spellings that are not one (:mod:`spsc.core.indenter`)
BAD_INDENTERS = ("ball:R=3", "sphere", "sphere:R=10,R=20", "sphere:R=0", "sphere:R=-2",
                 "sphere:R=inf",
                 "cylinder:R=5,axis=z", "wedge:angle=0", "wedge:angle=60,r=-1",
                 "sphere:R=3,axis=x", "plate:R=2", "sphere:R=", "", "plate:tilt=45",
                 "plate:tilt=x")


def contact_cases(f, b) -> list[Case]:
    """``f``: the fixtures (:func:`~.fuzz_fixtures.fixtures`), ``b``: the verbs' valid base
    invocations (:func:`~.fuzz_fixtures.bases`)."""
    dome = ("--l", "0")
    cases = [Case(b["curve-wall"] + ("--friction", "inf"), "an infinite coefficient",
                  "friction"),
             Case(b["curve-wall"] + ("--friction", "0.3", "--object-stiffness", "2"),
                  "Coulomb with a compliant object", "object_stiffness"),
             Case(b["curve-fem"] + ("--friction", "slip"), "unknown friction", "friction"),
             Case(b["fem"] + ("--friction", "-1"), "negative friction", "friction"),
             Case(b["curve-membrane"] + ("--friction", "stick"), "option of another model",
                  "friction"),
             Case(b["curve-membrane"] + ("--object-stiffness", "2"), "option of another model",
                  "object-stiffness"),
             Case(b["curve-wall"] + dome + ("--indenter", "cylinder:R=10"),
                  "a cylinder on the wall model's axisymmetric dome", "indenter"),
             Case(b["curve-wall"] + ("--indenter", "sphere:R=10", "--friction", "0.3"),
                  "Coulomb friction with a curved indenter", "friction"),
             Case(b["fem"] + ("--indenter", "wedge:angle=60", "--friction", "0.3"),
                  "Coulomb with a curved indenter", "friction"),
             Case(b["curve-fem"] + ("--indenter", "plate:tilt=5,axis=y"),
                  "a tilted plate on the quarter model", "indenter"),
             Case(b["curve-wall"] + ("--indenter", "plate:tilt=5"),
                  "a tilted plate on the wall model", "indenter"),
             Case(b["curve-fem"] + ("--indenter", str(f["file"] / "missing.stl")),
                  "a body's file that is missing", "indenter"),
             Case(b["fem"] + ("--indenter", str(f["part.stl"])),
                  "a body from a file on the quarter model", "indenter"),
             Case(b["curve-simplified"] + ("--indenter", "sphere:R=10"),
                  "option of another model", "indenter"),
             Case(b["fem-part"] + ("--indenter", "cylinder:R=10,axis=z"),
                  "bad indenter on a part", "indenter"),
             Case(b["fem-part"] + ("--friction", "stick"), "friction on a part", "friction"),
             Case(b["fem-part"] + ("--object-stiffness", "2"), "a compliant object on a part",
                  "object-stiffness")]
    for verb in ("curve-wall", "curve-fem", "fem"):
        cases += [Case(b[verb] + ("--indenter", bad), f"bad indenter {bad!r}", "indenter")
                  for bad in BAD_INDENTERS]
    for verb in ("fem", "curve-wall"):
        cases += numbers(b[verb], ("object-stiffness",))
    return cases
