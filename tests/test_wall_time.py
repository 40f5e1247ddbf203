"""The wall stepped in time inside spsc simulate (issue 52): [chamber] viscous / friction and
[circuit] vented read and checked, what the stepped wall cannot run refused in one line, its
instants."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.dynamics.profile import PressProfile
from spsc.dynamics.scenario import parse_scenario
from spsc.dynamics.wall_time import MAX_DT_S, MAX_DY_MM, instants, stepped

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "viscous-squeeze.toml"


def _doc(**tables):
    doc = tomllib.loads(EXAMPLE.read_text())
    for name, table in tables.items():
        doc[name] = {**doc.get(name, {}), **table} if isinstance(table, dict) else table
    return doc


def test_the_example_is_a_stepped_vented_viscous_wall():
    sc = parse_scenario(_doc())
    assert stepped(sc) and sc.vented and sc.chamber.viscous and sc.setup_kPa == 0.0
    assert sc.chamber.friction is None
    closed = parse_scenario(_doc(circuit={"vented": False, "setup_kPa": 40},
                                 chamber={"viscous": False, "friction": "stick"}))
    assert stepped(closed) and closed.chamber.friction == "stick" and not closed.vented
    plain = parse_scenario(_doc(circuit={"vented": False, "setup_kPa": 40},
                                chamber={"viscous": False}))
    assert not stepped(plain)
    assert parse_scenario(_doc(chamber={"friction": 0.3})).chamber.friction == 0.3
    assert parse_scenario(_doc(chamber={"friction": 0})).chamber.friction is None
    soft = parse_scenario(_doc(chamber={"viscous": False, "mullins": True}))
    assert stepped(soft) and soft.chamber.mullins and not soft.chamber.viscous


@pytest.mark.parametrize("tables, says", [
    ({"chamber": {"model": "surrogate", "l": 0}}, "chamber.model"),
    ({"press": {"force": [[0, 0], [1, 5]]}}, "press"),
    ({"events": [{"pressure_above_kPa": 45, "valve": "open"}],
      "circuit": {"vented": False, "setup_kPa": 40}}, "[[events]]"),
    ({"events": [{"t": 1.0, "valve": "open"}],
      "circuit": {"vented": False, "setup_kPa": 40, "gas": {"n": 1.4}}}, "circuit.gas.n"),
    ({"circuit": {"vented": False, "setup_kPa": 40,
                  "gas": {"n": 1.4, "thermal_time_s": 0.5}}}, "circuit.gas.thermal_time_s"),
    ({"circuit": {"setup_kPa": 40}}, "circuit.setup_kPa"),
    ({"chamber": {"viscous": "yes"}}, "chamber.viscous"),
    ({"circuit": {"vented": 1}}, "circuit.vented"),
    ({"chamber": {"friction": "slippery"}}, "chamber.friction"),
    ({"chamber": {"friction": -0.2}}, "chamber.friction"),
    ({"chamber": {"material": "elastic50a"}}, "chamber.viscous"),
    ({"chamber": {"material": "elastic50a", "viscous": False, "mullins": True}},
     "chamber.mullins"),
    ({"chamber": {"mullins": "yes"}}, "chamber.mullins"),
    ({"press": {"profile": [[0, 0], [6, 6]], "object_N_per_mm": 2}}, "press")])
def test_what_the_stepped_wall_cannot_run_is_one_line(tables, says):
    with pytest.raises(ParameterError) as e:
        parse_scenario(_doc(**tables))
    assert says in str(e.value) and "\n" not in str(e.value)


def test_instants_keep_the_knots_and_the_step_bounds():
    prof = PressProfile((0.0, 0.5, 3.5, 5.0), (-1.0, 0.0, 2.0, 2.0))
    t, y = instants(prof)
    assert set(prof.t_s) <= set(np.round(t, 12))
    assert np.all(np.diff(t) <= MAX_DT_S + 1e-12) and np.all(np.abs(np.diff(y)) <= MAX_DY_MM + 1e-12)
    assert y.min() == 0.0  # above the chamber the plate touches nothing: travel 0
    np.testing.assert_allclose(y, np.maximum(prof.y(t), 0.0), rtol=0, atol=1e-12)


@pytest.mark.slow
def test_the_stepped_walls_gas_is_its_polytrope():
    """A closed dome (viscous wall, n = 1.4 without heat exchange) pressed 2 mm and back:
    (P + Pₐ) Vⁿ holds to the interpolation between instants (1e-5), the temperature is the
    adiabat's, the mass does not change."""
    from spsc.core.constants import P_AMB_KPA
    from spsc.dynamics.simulate import simulate

    sc = parse_scenario(_doc(chamber={"type": "B", "l": 0},
                             circuit={"vented": False, "setup_kPa": 40, "gas": {"n": 1.4}},
                             press={"profile": [[0, 0], [1, 2], [2, 0]]}))
    d = simulate(sc).trace
    inv = (d.pressure_kPa + P_AMB_KPA) * d.volume_mm3 ** 1.4
    assert inv.max() / inv.min() - 1 < 1e-5
    adiabat = 293.15 * ((d.pressure_kPa + P_AMB_KPA) / (40 + P_AMB_KPA)) ** (0.4 / 1.4)
    np.testing.assert_allclose(d.chamber_K, adiabat, rtol=1e-5)
    np.testing.assert_allclose(d.chamber_mg, d.chamber_mg.iloc[0], rtol=1e-12)
    assert d.pressure_kPa.max() > 43.0  # it was pressed (3.2 kPa at 2 mm)
