"""The residual line search (:mod:`spsc.fem.engine.search`) never takes a trial that inverts
an element. Settled constraints: it halves until a trial does not. A pending constraint jump
(no merit to descend on): the load fails at once and the walk cuts the increment — before, the
inverted full step was taken ("inf ≤ inf") and the failure came one evaluation later; halving
instead wandered for 25 iterations on the fingertip's inserts and failed anyway."""

from __future__ import annotations

import numpy as np
import pytest

from spsc.fem.engine.constraints import Constraints
from spsc.fem.engine.result import NewtonFailure
from spsc.fem.engine.search import line_search
from spsc.fem.engine.settings import Settings


class Inverted(Exception):
    pass


class _Ev:
    def __init__(self, r):
        self.r = r


class _Model:
    """One unknown whose state inverts beyond ``limit``; residual x − 1."""

    inadmissible = (Inverted,)

    def __init__(self, limit):
        self.limit, self.calls = limit, []

    def evaluate(self, x, load, *, tangent=True):
        self.calls.append(float(x[0]))
        if x[0] > self.limit:
            raise Inverted("1 elements inverted (the first near 0.00, 0.00, 0.00 mm)")
        return _Ev(x - 1.0)


def _search(limit, jump):
    """The line search of the step x = 0 → 2 with the unknown free (no jump) or prescribed
    with a pending ``jump``; (α, the states evaluated)."""
    model = _Model(limit)
    con = Constraints(1, np.array([0] if jump else [], int), np.array([jump] if jump else []),
                      np.zeros(0, int), np.zeros(0), -1)
    free = np.array([not jump])
    x, step = np.zeros(1), np.array([2.0])
    alpha, _ = line_search(model, x, step, free, None, con, x - 1.0, Settings())
    return alpha, model.calls


def test_an_inverted_full_step_is_halved_on_settled_constraints():
    alpha, calls = _search(limit=1.5, jump=0.0)
    assert alpha == 0.5
    assert calls == [2.0, 1.0]


def test_an_inverted_step_onto_new_constraints_fails_the_load():
    with pytest.raises(NewtonFailure,
                       match="new contact constraints fails: 1 elements inverted"):
        _search(limit=1.5, jump=2.0)


def test_an_admissible_step_onto_new_constraints_is_taken_whole():
    alpha, calls = _search(limit=5.0, jump=2.0)
    assert alpha == 1.0 and calls == [2.0]


def test_every_trial_inverted_fails_the_load_at_once():
    with pytest.raises(NewtonFailure,
                       match="every trial step fails down to α = 0.0625: 1 elements inverted"):
        _search(limit=-1.0, jump=0.0)
