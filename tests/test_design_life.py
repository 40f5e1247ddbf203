"""spsc design --min-life (issue 51): each trial's life by its wall squeeze cycle is a
constraint beside the printability; refused settings are one line before any work."""

from __future__ import annotations

import json
import math

import pandas as pd
import pytest

from spsc.cli.main import main
from spsc.core.errors import ParameterError
from spsc.design.life import check_life, life_constraint


def test_the_constraint_is_the_decades_missing():
    assert life_constraint({"life_cycles": 1e5}, 1e4) == pytest.approx(-1.0)
    assert life_constraint({"life_cycles": 1e3}, 1e4) == pytest.approx(1.0)
    assert life_constraint({"life_cycles": None}, 1e4) == 1.0  # not computed: infeasible
    assert life_constraint({"life_cycles": math.inf}, 1e4) < 0


@pytest.mark.parametrize("args, name", [
    ((0, 6, None, ["tpu60a"], 13), "min-life"),
    ((1e4, 13, None, ["tpu60a"], 13), "life-stroke"),
    ((1e4, 6, 1.0, ["tpu60a"], 13), "fatigue exponent"),
    ((1e4, 6, None, ["my.json"], 13), "material"),
])
def test_life_settings_are_checked(args, name):
    with pytest.raises(ParameterError, match=name):
        check_life(*args)


@pytest.mark.slow  # 7-10 s: make test-slow (make test stays under 3 min)
def test_a_design_that_must_last(tmp_path, capsys):
    out = tmp_path / "d"
    code = main(["design", "--target", "stiffness_high=5", "--type", "B", "--l", "0",
                 "--model", "simplified", "--min-life", "20000", "--trials", "8", "--seed", "1",
                 "--verify", "none", "--no-build", "--workers", "1", "--out", str(out),
                 "--quiet"])
    assert code in (0, 1)
    rows = pd.read_parquet(out / "trials.parquet")
    done = rows[rows.state == "COMPLETE"]
    assert len(done) >= 4 and done.life_cycles.notna().all()
    assert (done.peak_stretch > 1.0).all() and (done.energy_amplitude_MPa > 0).all()
    # feasible exactly when printable and lasting
    lasting = done.life_cycles >= 20000
    assert (done.feasible == (done.printable & lasting)).all()
    assert (~lasting).any()  # the constraint bit: some trials did not last
    doc = json.loads((out / "design.json").read_text())
    assert doc["life"]["cycles"] == 20000 and doc["life"]["stroke_mm"] == 6.0
    if doc["best"] is not None:
        assert doc["life"]["best"]["life_cycles"] >= 20000
        assert "its life:" in capsys.readouterr().out


@pytest.mark.slow  # 7-10 s: make test-slow (make test stays under 3 min)
def test_a_sweep_with_lives_keys_them_apart(tmp_path):
    out = tmp_path / "s.parquet"
    argv = ["sweep", "--type", "B,C", "--l", "0", "--w", "10,12", "--model", "simplified",
            "--out", str(out), "--workers", "1", "--quiet"]
    assert main(argv + ["--life"]) == 0
    life = pd.read_parquet(out)
    assert len(life) == 4 and life.life_cycles.notna().all()
    assert (life.peak_stretch > 1.0).all()
    # the wider chamber (the same 1 mm wall) cycles less energy and lives longer, in each type
    for t in "BC":
        one = life[life.type == t].sort_values("w")
        assert one.life_cycles.iloc[1] > one.life_cycles.iloc[0]
    assert main(argv) == 0  # the same designs without a life: computed again, not read back
    plain = pd.read_parquet(out)
    assert plain.life_cycles.isna().all() and set(plain.key).isdisjoint(set(life.key))
