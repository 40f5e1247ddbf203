"""Point selectors of the form ``"z<0"``, ``"y>=-12 & z<=0.5"``: which nodes a support fixes.

A selector is one or more comparisons joined by ``&`` (all must hold) or ``|`` (any may; ``&``
binds tighter). A comparison is ``AXIS OP NUMBER`` or ``NUMBER OP AXIS`` with AXIS one of
``x``, ``y``, ``z`` (mm, part coordinates), OP one of ``<``, ``<=``, ``>``, ``>=``, ``=``.

A tetrahedral mesh only approximates the part's faces (fTetWild keeps its surface within an
envelope), so every comparison holds within ``tol`` (mm) of its plane: ``z<0`` and ``z<=0``
both take the nodes at z ≤ tol, the base plane included, and ``z=0`` those with |z| ≤ tol.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError

__all__ = ["Selector", "parse_selector"]

_AXES = {"x": 0, "y": 1, "z": 2}
_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_TERM = re.compile(rf"^\s*(?:([xyz])\s*(<=|>=|<|>|=)\s*({_NUM})|({_NUM})\s*(<=|>=|<|>|=)\s*([xyz]))\s*$")
_FLIP = {"<": ">", "<=": ">=", ">": "<", ">=": "<=", "=": "="}
_ALLOWED = ("comparisons like 'z<0', 'y>=-12 & z<=0.5' or 'x<-3 | x>3' "
            "(axes x, y, z in mm; ops < <= > >= =; & binds tighter than |)")


@dataclass(frozen=True)
class Selector:
    """A parsed selector: ``terms`` is a tuple of alternatives (``|``), each a tuple of
    (axis index, op, value) comparisons that must all hold (``&``)."""

    text: str
    terms: tuple

    def __call__(self, points, tol: float = 0.0) -> np.ndarray:
        """Bool mask of the points (n, 3) the selector takes, each comparison within ``tol``."""
        p = np.asarray(points, float)
        out = np.zeros(len(p), bool)
        for alternative in self.terms:
            mask = np.ones(len(p), bool)
            for axis, op, value in alternative:
                c = p[:, axis]
                if op in ("<", "<="):
                    mask &= c <= value + tol
                elif op in (">", ">="):
                    mask &= c >= value - tol
                else:
                    mask &= np.abs(c - value) <= tol
            out |= mask
        return out


def parse_selector(text: str, name: str = "fix") -> Selector:
    """Parse ``text``; ParameterError naming ``name`` (the CLI option) on anything else."""
    if not isinstance(text, str) or not text.strip():
        raise ParameterError(name, text, _ALLOWED)
    terms = []
    for alt in text.split("|"):
        conj = []
        for part in alt.split("&"):
            m = _TERM.match(part)
            if not m:
                raise ParameterError(name, text, _ALLOWED)
            if m.group(1):
                axis, op, value = m.group(1), m.group(2), float(m.group(3))
            else:
                axis, op, value = m.group(6), _FLIP[m.group(5)], float(m.group(4))
            if not np.isfinite(value):
                raise ParameterError(name, text, _ALLOWED)
            conj.append((_AXES[axis], op, value))
        terms.append(tuple(conj))
    return Selector(text.strip(), tuple(terms))
