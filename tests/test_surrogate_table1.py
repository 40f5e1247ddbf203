"""The shipped surrogate of Table 1's stadiums (``wall-table1``): Types A–D at Table 1's
proportions answer from it at any size, fresh stadiums match the wall model within the stated
accuracy, and its time-domain map is the wall model's."""

from __future__ import annotations

import json

import numpy as np
import pytest

from spsc.models.surrogate.predict import SHIPPED_FILES, choose, load

TABLE1 = {"h/w": 13 / 11, "l/w": 3 / 11, "t0/w": 1 / 11}


@pytest.mark.parametrize("kind", "ABCD")
def test_the_papers_four_chambers_answer_from_the_table1_surrogate(kind, tmp_path, capsys):
    from spsc.cli.main import main

    j = tmp_path / "c.json"
    # Table 1's size, and twice it in silicone (the similarities: any size, any neo-Hookean)
    for extra in ([], ["--w", "22", "--h", "26", "--l", "6", "--t0", "2", "--material",
                       "silicone40a", "--pressure", "20"]):
        assert main(["curve", "--model", "surrogate", "--type", kind, *extra, "--json",
                     str(j)]) == 0
        d = json.loads(j.read_text())
        assert d["solver"]["details"]["surrogate"] == "wall-table1"
        assert len(d["solver"]["details"]["force_err_N"]) == 25
        assert np.all(np.diff(d["curve"]["force_N"]) > 0)
    capsys.readouterr()


def test_the_table1_file_is_a_surrogate_of_the_shape_alone():
    sur = load(str(SHIPPED_FILES["table1"]))
    assert sur.free == ["n1", "n2", "cy"]
    assert sur.fixed == pytest.approx(TABLE1, rel=1e-12)
    # a dome still goes to the domes' surrogate, Table 1's stadium to this one
    assert choose(None, [13 / 11, 3 / 11, 1 / 11, 2.0, 2.2, 0.6])[0] is sur
    assert choose(None, [13 / 11, 0.0, 1 / 11, 2.0, 2.2, 0.6])[0] is load()


@pytest.mark.slow
def test_fresh_table1_stadiums_match_the_wall_model_within_the_stated_accuracy():
    """Two stadiums drawn apart from training's (another seed than the check's), the wall
    model run here (about 10 s a case): force and pressure rise within the issue's 8 % of
    the curve's largest value at every point."""
    from spsc.studies.surrogate.check import _wall_job, check_cases, compare

    cases = check_cases(2, 78, TABLE1)
    result = compare(load(str(SHIPPED_FILES["table1"])), [_wall_job(c) for c in cases])
    assert result["skipped"] == 0
    assert result["points"]["force"].max() < 0.08
    assert result["points"]["pressure"].max() < 0.08


@pytest.mark.slow
def test_the_time_domain_map_of_a_table1_stadium_is_the_wall_models():
    """``[chamber] model = "surrogate"`` on Table 1's Type D stadium against the wall model's
    own map (a swept-wall solve per level, about 20 s): volumes within 0.5 % and forces within
    3 % of the largest."""
    from spsc.cad.geometry import preset
    from spsc_support.surrogate_maps import assert_maps_agree

    assert_maps_agree(preset("D"), (1.0, 2.5, 4.0), (30.0, 40.0, 70.0), force_share=0.03)
