"""A load that cannot converge gives up early: a contact active set that cycles without
progress, or Newton on one set that does not halve its residual in ``_STUCK`` iterations
(:meth:`_Newton.cycles`, :meth:`_Newton.stuck`). A load that converges is never stopped: the
32 wall curves of the committed report are the same to 7e-14 with both rules (measured, not
a test here: 3 minutes); here the rules themselves, on the sequences the traces showed."""

import numpy as np
import pytest

import spsc.fem.engine.newton  # noqa: F401  (the package's name is shadowed by the function)
import sys

N = sys.modules["spsc.fem.engine.newton"]


class _Plate:
    """A body whose set is set by the test (:class:`spsc.fem.engine.bodies.Body`'s key)."""

    active = np.zeros(0, int)

    def key(self):
        return self.active.tobytes()


def _newton(changes=N._MULTIPLIER_CHANGES + 1):
    nw = N._Newton.__new__(N._Newton)
    nw.visits, nw.returns, nw.trail, nw.changes = {}, 0, [], changes
    nw.bodies = [_Plate()]
    return nw


def _enter(nw, active, res):
    nw.bodies[0].active, nw.res = np.asarray(active), res
    return nw.cycles()


def test_a_two_set_cycle_without_progress_ends_at_the_second_return():
    nw = _newton()
    seen = [_enter(nw, s, 6.7e-5) for s in ([1, 2], [1, 2, 3], [1, 2], [1, 2, 3])]
    assert seen == [False, False, False, True]


def test_a_longer_cycle_is_found_too():
    nw = _newton()
    ring = [[1], [1, 2], [1, 2, 3], [1, 2, 3, 4]]
    seen = [_enter(nw, s, 1e-3) for s in ring * 2]
    assert seen == [False] * 5 + [True] + [True] * 2


def test_returns_that_halve_the_residual_are_progress():
    nw = _newton()
    seen = [_enter(nw, s, 1e-3 * 0.4 ** k) for k, s in enumerate([[1], [1, 2]] * 4)]
    assert not any(seen)


def test_while_the_multipliers_drive_the_set_no_cycle_is_declared():
    nw = _newton(changes=N._MULTIPLIER_CHANGES)
    assert not any(_enter(nw, s, 1e-3) for s in [[1], [1, 2]] * 4)


def _iterate(nw, active, res):
    nw.bodies[0].active, nw.res = np.asarray(active), res
    return nw.stuck()


def test_ten_iterations_on_one_set_without_halving_the_residual_end_the_load():
    nw = _newton()
    res = [2.0, 1.5, 3.6, 3.1, 2.5, 2.3, 2.2, 1.2, 1.2, 1.1, 1.4, 1.1]  # a trace of Type B
    seen = [_iterate(nw, [7, 8], r) for r in res]
    assert seen == [False] * N._STUCK + [True, True]


@pytest.mark.parametrize("case", ["halves", "set changes"])
def test_progress_or_a_new_set_is_not_stuck(case):
    nw = _newton()
    for k in range(3 * N._STUCK):
        active = [7, 8] if case == "halves" or k % 7 else [7]
        res = 2.0 * 0.9 ** k if case == "halves" else 2.0
        assert not _iterate(nw, active, res)
