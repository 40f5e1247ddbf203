"""The wall section graded toward the apex (``WallSettings(apex_size_mm=...)``,
:func:`spsc.fem.solid.mesh.graded_fractions`): a sharp probe's tip on the axis, resolved
without refining the whole wall. The grading is geometric, the section still encloses the
analytic cavity, and the even mesh is untouched by it."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.core.errors import ParameterError
from spsc.fem.solid.mesh import GRADING_RATIO, graded_fractions
from spsc.fem.wall.model import WallSettings
from spsc.fem.wall.section import section_mesh


def _elements(t):
    return np.diff(t[::2])


def test_the_elements_grow_geometrically_from_the_apex_to_the_mesh_size():
    L = 20.0
    t = graded_fractions(L, 0.25, 0.01)
    assert t[0] == 0.0 and t[-1] == 1.0 and np.all(np.diff(t) > 0)
    h = _elements(t) * L
    # one factor scales them onto the profile's end: within 2 % of the requested lengths
    assert_allclose(h[0], 0.01, rtol=2e-2)
    assert_allclose(h[-1], 0.25, rtol=2e-2)
    assert np.all(h[1:] / h[:-1] <= GRADING_RATIO * (1 + 1e-12))
    assert_allclose(t[1::2], 0.5 * (t[0:-1:2] + t[2::2]), rtol=1e-14)  # midpoints halve


@pytest.mark.parametrize("t", "ABD")
def test_a_graded_section_encloses_the_analytic_cavity(t):
    """Its cavity points are read off 8001 evenly spaced ones (linear between them): the
    chords' error is about (L/8000)², 1e-6 of the volume; measured ≤ 3e-7."""
    g = preset(t, l=0.0)
    s = section_mesh(g, size=0.25, layers=4, apex=0.02)
    assert_allclose(s.volume(np.zeros(s.n_dofs)), g.cavity_volume(), rtol=2e-6)


def test_the_apex_elements_are_the_requested_length():
    g = preset("B", l=0.0)
    s = section_mesh(g, size=0.25, layers=4, apex=0.02)
    outer = s.nodes[s.outer]
    first = np.hypot(*(outer[2] - outer[0]))
    assert_allclose(first, 0.02, rtol=5e-2)
    even = section_mesh(g, size=0.25, layers=4)
    assert len(s.outer) > len(even.outer)  # the grading adds elements near the apex only
    assert len(s.outer) < 1.5 * len(even.outer)


def test_without_an_apex_size_the_section_is_the_even_one():
    g = preset("D", l=0.0)
    a, b = section_mesh(g, size=0.5, layers=2), section_mesh(g, size=0.5, layers=2, apex=None)
    assert np.array_equal(a.nodes, b.nodes) and np.array_equal(a.elements, b.elements)


def test_an_apex_size_is_checked_in_one_line():
    with pytest.raises(ParameterError, match="apex_size"):
        section_mesh(preset("B", l=0.0), size=0.25, apex=0.5)
    with pytest.raises(ParameterError, match="apex_size"):
        WallSettings(apex_size_mm=-1.0)


def test_the_lines_through_the_wall_stay_across_it_near_the_apex():
    """Cavity and outer points at the same fractions of their own arcs: near the apex each
    line through the wall is about the wall's thickness t0 long (a mismatch of the two
    gradings would slant them; measured within 0.2 % over the first 40 points)."""
    g = preset("B", l=0.0)
    s = section_mesh(g, size=0.25, layers=4, apex=0.02)
    across = np.hypot(*(s.nodes[s.outer[:40]] - s.nodes[s.cavity[:40]]).T)
    assert_allclose(across, g.t0, rtol=1e-2)
