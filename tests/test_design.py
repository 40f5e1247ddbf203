"""spsc design: the goal and the search space as the command line writes them, the Optuna loop
on a small in-process Dask cluster (reproducible with a seed and a worker count, continued
from its journal, printability as a constraint), and the command end to end."""

from __future__ import annotations

import math

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.design.goal import Goal, Target, parse_goal, parse_target, parse_tol
from spsc.design.space import parse_space


# -- the goal ----------------------------------------------------------------------------------
def test_targets_parse_and_miss_is_relative():
    eq, ge, le = (parse_target(t) for t in ("stiffness_high=6", "sensitivity_high >= 5",
                                            "jnd_mm<=3"))
    assert (eq.metric, eq.relation, eq.value) == ("stiffness_high", "=", 6.0)
    assert (ge.relation, le.relation) == (">=", "<=")
    assert eq.miss({"stiffness_high": 4.5}) == pytest.approx(0.25)
    assert eq.miss({"stiffness_high": 7.5}) == pytest.approx(0.25)
    assert ge.miss({"sensitivity_high": 4.0}) == pytest.approx(0.2)
    assert ge.miss({"sensitivity_high": 9.0}) == 0.0  # an inequality misses only below
    assert le.miss({"jnd_mm": 2.0}) == 0.0 and le.miss({"jnd_mm": 4.5}) == pytest.approx(0.5)
    assert math.isnan(eq.miss({"stiffness_high": math.nan}))
    assert parse_target("cavity_mm3==4000").relation == "="


def test_single_objective_is_the_largest_miss_and_met_within_tol():
    g = parse_goal(["stiffness_high=6", "sensitivity_high>=5"], tol=0.01)
    assert not g.multi and g.directions == ["minimize"]
    m = {"stiffness_high": 6.03, "sensitivity_high": 4.0}
    assert g.values(m) == [pytest.approx(0.2)]
    assert not g.met(m)
    assert g.met({"stiffness_high": 6.05, "sensitivity_high": 5.0})  # 0.83 % <= 1 %
    assert not g.met({"stiffness_high": 6.07, "sensitivity_high": 5.0})
    assert g.constraints(m) == {}


def test_objectives_make_targets_constraints():
    g = parse_goal(["sensitivity_high>=5"], minimize=["cavity_mm3"],
                   maximize=["stiffness_high"], tol=0.02)
    assert g.multi and g.directions == ["minimize", "maximize"]
    m = {"cavity_mm3": 4000.0, "stiffness_high": 7.0, "sensitivity_high": 4.8}
    assert g.values(m) == [4000.0, 7.0]
    assert g.constraints(m) == {"target:sensitivity_high>=5": pytest.approx(0.04 - 0.02)}
    assert parse_goal([], minimize=["cavity_mm3,jnd_mm"]).minimize == ("cavity_mm3", "jnd_mm")


@pytest.mark.parametrize("text", ["stiffness=6", "stiffness_high", "stiffness_high>6",
                                  "stiffness_high=abc", "stiffness_high=0", "stiffness_high=-2",
                                  "stiffness_high=inf", "stiffness_high=nan", "=6", ""])
def test_bad_target_is_one_line_naming_target(text):
    with pytest.raises(ParameterError, match=r"^target = ") as err:
        parse_target(text)
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("kw,name", [({"minimize": ["volume"]}, "minimize"),
                                     ({"maximize": [""]}, "maximize"),
                                     ({"minimize": ["jnd_mm"], "maximize": ["jnd_mm"]},
                                      "maximize"),
                                     ({"minimize": ["jnd_mm", "jnd_mm"]}, "minimize"),
                                     ({}, "goal")])
def test_bad_objectives(kw, name):
    with pytest.raises(ParameterError, match=rf"^{name} = "):
        parse_goal(**kw)


def test_tol_in_percent():
    assert parse_tol("1") == 0.01 and parse_tol("0.5 %") == 0.005
    for bad in ("-1", "100", "abc", "nan"):
        with pytest.raises(ParameterError, match="^tol = "):
            parse_tol(bad)


def test_goal_round_trips_through_its_dict():
    g = parse_goal(["stiffness_high=6", "jnd_mm<=3"], maximize=["sensitivity_high"], tol=0.05)
    assert Goal.from_dict(g.to_dict()) == g
    assert Target("jnd_mm", "<=", 3.0) in g.targets


# -- the space ---------------------------------------------------------------------------------
def test_default_space():
    s = parse_space({}, "fdm")
    assert s.to_dict() == {"type": "A,B,C,D", "w": "8:14", "h": "8:16", "l": "0:6",
                           "t0": "0.8:2", "material": "tpu60a", "pressure": "40",
                           "reservoir": "40000"}
    assert [d.name for d in s.searched] == ["type", "w", "h", "l", "t0"]
    assert parse_space({}, "sla")["t0"].values == (0.5, 2.0)  # the process's minimum wall


def test_space_forms_and_the_reservoir_as_a_continuous_variable():
    s = parse_space({"type": "d", "w": "9,11", "n1": "2:4", "reservoir": "0:40000",
                     "material": "TPU60A"})
    assert (s["type"].kind, s["type"].values) == ("fixed", ("D",))
    assert (s["w"].kind, s["w"].values) == ("choice", (9.0, 11.0))
    assert (s["n1"].kind, s["reservoir"].kind) == ("interval", "interval")
    assert "n2" not in s and "cy" not in s  # the type's preset
    assert s["material"].values == ("tpu60a",)


def test_suggested_values_are_short_decimals():
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    s = parse_space({"reservoir": "0:40000", "pressure": "10:40"})
    study = optuna.create_study(sampler=optuna.samplers.RandomSampler(seed=3))
    for _ in range(20):
        d = s.suggest(study.ask())
        for k in ("w", "h", "l", "t0"):
            assert d[k] == round(d[k], 3) and float(repr(d[k])) == d[k]
        assert d["reservoir"] == int(d["reservoir"]) and 0 <= d["reservoir"] <= 40000
        assert d["type"] in "ABCD" and d["n1"] is None


def test_no_type_when_the_three_form_factors_are_given():
    s = parse_space({"n1": "2", "n2": "2.2", "cy": "0:0.5"})
    assert "type" not in s
    assert s.representatives()[0]["type"] is None


@pytest.mark.parametrize("name,text", [("w", "8:"), ("w", "14:8"), ("w", "8:8"),
                                       ("w", "1:2:3"), ("w", "abc"), ("w", "0:5"),
                                       ("h", "8:1e9"), ("t0", "0:1"), ("cy", "0:1"),
                                       ("n1", "0.5:2"), ("l", "-1:2"), ("w", "8.0005:14"),
                                       ("pressure", "-1"), ("pressure", "nan"),
                                       ("reservoir", "-5:10"), ("reservoir", "inf"),
                                       ("type", "E"), ("type", "A,A"), ("type", ""),
                                       ("material", "rubber"), ("material", "tpu60a,as40")])
def test_bad_space_is_one_line_naming_the_input(name, text):
    with pytest.raises(ParameterError, match=rf"^{name} = ") as err:
        parse_space({name: text})
    assert "\n" not in str(err.value)


# -- the loop on Dask (closed-form stand-in for the models: spsc/testing/design_double.py) -------------
@pytest.fixture(scope="module")
def cluster():
    """One small cluster of two single-threaded worker processes for the loop's tests (each
    run reaches it by address, as --scheduler does)."""
    from distributed import LocalCluster

    from spsc.study.executor import WORKER_ENV

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=":0", env=dict(WORKER_ENV)) as c:
        yield c.scheduler_address


def _problem(targets=("stiffness_high=6", "sensitivity_high>=5"), tol=0.01, space=None,
             minimize=(), maximize=(), process="fdm"):
    from spsc.design.loop import Problem

    return Problem(parse_goal(list(targets), minimize, maximize, tol),
                   parse_space(space or {}, process), "simplified", process, 5, 4.0)


def _run(problem, out, cluster, trials=12, seed=3, **kw):
    from spsc.testing import design_double
    from spsc.design.loop import run_design

    return run_design(problem, out, trials=trials, seed=seed, scheduler=cluster,
                      progress=False, evaluate=design_double.evaluate, **kw)


def _trace(rows):
    return [(r["trial"], r["state"], r["type"], r["w"], r["h"], r["l"], r["t0"], r["miss"])
            for r in rows]


def test_seed_and_workers_reproduce_the_study(cluster, tmp_path):
    p = _problem(tol=0.0)  # never met: every trial runs
    a = _run(p, tmp_path / "a", cluster)
    b = _run(p, tmp_path / "b", cluster)
    assert len(a.rows) == 12 and a.facts["workers"] == 2
    assert _trace(a.rows) == _trace(b.rows)
    c = _run(p, tmp_path / "c", cluster, seed=4)
    assert _trace(c.rows) != _trace(a.rows)


def test_the_polish_meets_a_near_miss_in_a_few_trials(cluster, tmp_path, monkeypatch):
    """Gauss–Newton from a finite-difference Jacobian (spsc.design.polish) on the smooth
    stand-in: the goal is met by one of its steps, in at most half the trials TPE alone needs
    for the same seed (14 against 50 here; the counts are deterministic: seed and workers)."""
    import spsc.design.polish as polish

    p = _problem()
    r = _run(p, tmp_path / "polished", cluster, trials=80, seed=0)
    assert r.met and r.best["proposer"] == "gauss-newton"
    kinds = [x["proposer"] for x in r.rows]
    assert kinds.count("jacobian") == 4  # one per interval: w, h, l, t0
    assert kinds.index("gauss-newton") > max(i for i, k in enumerate(kinds) if k == "jacobian")
    monkeypatch.setattr(polish, "START", 0.0)  # never starts: TPE alone
    alone = _run(p, tmp_path / "alone", cluster, trials=80, seed=0)
    assert alone.met and {x["proposer"] for x in alone.rows} == {"sampler"}
    assert 2 * len(r.rows) <= len(alone.rows)


def test_the_polish_jacobian_follows_each_step_and_a_worse_step_shrinks_the_trust():
    """Broyden's update: after a step the Jacobian maps the step to the change it caused
    (the secant condition); a step that is worse halves the trust region and keeps the base."""
    from types import SimpleNamespace

    from spsc.design import polish

    pol = polish.Polish(_problem())
    assert [d.name for d in pol.dims] == ["w", "h", "l", "t0"]
    base = {"type": "D", "w": 10.0, "h": 12.0, "l": 3.0, "t0": 1.2}
    pol.base = {"x": pol._scaled(base), "r": np.array([1.1, 0.9]), "miss": 0.1,
                "params": base, "number": 7}
    pol.J = np.array([[0.5, -0.2, 0.1, 0.8], [-0.1, -0.6, 0.05, 0.2]])
    pol.pending[9] = ("gauss-newton", None, 7, dict(base, w=10.3, t0=1.1))
    moved = dict(base, w=10.3, t0=1.1)
    worse = {"stiffness_high": 6 * 1.3, "sensitivity_high": 5 * 0.8}
    pol.tell(SimpleNamespace(number=9, params=moved), worse, 0.3, True)
    ds = pol._scaled(moved) - pol._scaled(base)
    np.testing.assert_allclose(pol.J @ ds, np.array([1.3, 0.8]) - [1.1, 0.9], rtol=1e-12)
    assert pol.base["params"] == base and pol.trust == polish.TRUST / 2 and pol.failures == 1
    assert pol.state == "ready" and pol._step() is not None


def test_stops_when_met_and_the_best_is_printable(cluster, tmp_path):
    # thin walls are stiff enough here too, but t0 < 0.8 mm cannot be printed in FDM
    p = _problem(["stiffness_high=4"], tol=0.02, space={"t0": "0.3:1.2"})
    r = _run(p, tmp_path / "d", cluster, trials=60)
    assert r.met and r.best["feasible"] and r.best["printable"]
    assert r.best["t0"] >= 0.8 and r.best["miss"] <= 0.02
    assert len(r.rows) < 60  # stopped once met (the trials in flight are told too)
    infeasible = [x for x in r.rows if x["state"] == "COMPLETE" and not x["printable"]]
    assert infeasible and all(not x["feasible"] for x in infeasible)


def test_refused_designs_are_failed_trials_with_their_reason(cluster, tmp_path):
    p = _problem(tol=0.0, space={"w": "13:14", "type": "B"})
    r = _run(p, tmp_path / "e", cluster, trials=8)
    failed = [x for x in r.rows if x["state"] == "FAIL"]
    assert failed and all(x["w"] > 13.5 and x["reason"].startswith("invalid: w = ")
                          for x in failed)
    assert all(x["w"] <= 13.5 for x in r.rows if x["state"] == "COMPLETE")


def test_a_run_continues_from_its_journal(cluster, tmp_path):
    import optuna

    from spsc.design.loop import INTERRUPTED, open_study

    p = _problem(tol=0.0)
    first = _run(p, tmp_path / "f", cluster, trials=5)
    # a run killed with a trial in flight leaves it RUNNING in the journal
    study, before = open_study(p, tmp_path / "f", sampler="tpe", seed=3, trials=5)
    assert before == 5
    study.ask()
    again = _run(p, tmp_path / "f", cluster, trials=8)
    assert _trace(again.rows[:5]) == _trace(first.rows)
    left = again.rows[5]
    assert left["state"] == "FAIL" and left["reason"] == INTERRUPTED
    assert len(again.rows) == 9 and again.facts["evaluated"] == 3  # 8 counted, 1 interrupted
    assert again.facts["trials_before"] == 6
    done = _run(p, tmp_path / "f", cluster, trials=8)
    assert done.facts["evaluated"] == 0 and len(done.rows) == 9
    with pytest.raises(ParameterError, match=r"^out = .*goal"):
        _run(_problem(["stiffness_high=7"]), tmp_path / "f", cluster, trials=8)
    assert optuna.__version__.startswith("5.")


def test_multi_objective_pareto_front_is_feasible_and_non_dominated(cluster, tmp_path):
    p = _problem(["sensitivity_high>=5"], minimize=["cavity_mm3"], maximize=["stiffness_high"],
                 space={"t0": "0.5:1.5"})
    r = _run(p, tmp_path / "g", cluster, trials=24)
    assert r.facts["sampler"] == "nsga2"
    assert r.pareto and r.best in r.pareto
    for x in r.pareto:
        assert x["feasible"] and x["printable"] and x["sensitivity_high"] >= 5 * 0.99
    pts = [(x["cavity_mm3"], -x["stiffness_high"]) for x in r.rows if x["feasible"]]
    for x in r.pareto:
        q = (x["cavity_mm3"], -x["stiffness_high"])
        assert not any(a <= q[0] and b <= q[1] and (a, b) != q for a, b in pts)


# -- the command end to end (the simplified model: milliseconds per curve) ----------------------
def _design(tmp_path, *extra, name="run"):
    from spsc.cli.main import main

    out = tmp_path / name
    argv = ["design", "--model", "simplified", "--points", "7", "--workers", "2",
            "--verify", "none", "--out", str(out), "--quiet", *extra]
    return main(argv), out


def test_command_writes_json_parquet_html_and_exits_1_when_not_met(tmp_path, capsys):
    import json

    import pandas as pd

    rc, out = _design(tmp_path, "--target", "stiffness_high=6", "--target",
                      "sensitivity_high>=5", "--tol", "0", "--trials", "6", "--seed", "1",
                      "--no-build", "--json", str(tmp_path / "copy.json"),
                      "--csv", str(tmp_path / "trials.csv"))
    captured = capsys.readouterr()
    assert rc == 1 and "goal not met" in captured.err
    doc = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert (doc["schema"], doc["schema_version"]) == ("spsc.design", 1)
    assert doc["trials"] == 6 and doc["met"] is False and doc["build"] is None
    assert set(doc["best"]["params"]) == {"type", "w", "h", "l", "t0", "n1", "n2", "cy",
                                          "material", "pressure", "reservoir"}
    assert set(doc["best"]["metrics"]) == {"stiffness_high", "stiffness_low",
                                           "sensitivity_high", "sensitivity_low", "jnd_mm",
                                           "cavity_mm3"}
    assert doc["pareto"] == [doc["best"]] and doc["run"]["seed"] == 1
    assert json.loads((tmp_path / "copy.json").read_text(encoding="utf-8")) == doc
    df = pd.read_parquet(out / "trials.parquet")
    assert len(df) == 6 and df["miss"].min() == pytest.approx(doc["best"]["miss"])
    assert len(pd.read_csv(tmp_path / "trials.csv")) == 6
    html = (out / "index.html").read_text(encoding="utf-8")
    for fig in ("history", "front", "parallel", "curves"):
        assert f"figures/{fig}.png" in html and (out / "figures" / f"{fig}.png").stat().st_size
    assert doc["rerun"]["high"] in html and doc["rerun"]["high"] in captured.out


def test_the_printed_spsc_curve_commands_reproduce_the_best_metrics(tmp_path, capsys):
    import json
    import shlex

    from spsc.core.curve import Curve
    from spsc.cli.main import main
    from spsc.design.verify import metrics_of

    rc, out = _design(tmp_path, "--target", "stiffness_high=6", "--reservoir", "5000:40000",
                      "--trials", "4", "--seed", "2", "--no-build")
    doc = json.loads((out / "design.json").read_text(encoding="utf-8"))
    curves = {}
    for mode, cmd in doc["rerun"].items():
        argv = shlex.split(cmd)
        assert argv[:2] == ["spsc", "curve"]
        path = tmp_path / f"{mode}.json"
        assert main(argv[1:] + ["--json", str(path), "--quiet"]) == 0
        curves[mode] = Curve.from_json(path)
    again = metrics_of(curves["high"], curves["low"])
    for k, v in doc["best"]["metrics"].items():
        assert again[k] == pytest.approx(v, rel=1e-12, abs=0), k
    assert curves["low"].setup["reservoir_mm3"] == doc["best"]["params"]["reservoir"] > 0


@pytest.mark.slow
def test_met_goal_and_a_part_that_passes_the_gate_exit_0(tmp_path, capsys):
    import json

    rc, out = _design(tmp_path, "--target", "sensitivity_high>=1", "--type", "D", "--trials",
                      "10", "--seed", "3")
    doc = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert rc == 0, capsys.readouterr().err
    assert doc["met"] and doc["trials"] == 2  # met at once: the trial in flight is told too
    assert doc["build"]["gate"]["passed"]
    for f in doc["build"]["files"].values():
        assert (out / "part" / f).stat().st_size > 0
    assert (out / "figures" / "part.png").stat().st_size > 0
    # a re-run on the same folder continues the study: nothing more to do
    rc, out = _design(tmp_path, "--target", "sensitivity_high>=1", "--type", "D", "--trials",
                      "10", "--seed", "3", "--no-build")
    again = json.loads((out / "design.json").read_text(encoding="utf-8"))
    assert rc == 0 and again["trials"] == 2 and again["run"]["evaluated"] == 0
    assert again["best"] == doc["best"]


@pytest.mark.slow
def test_verify_fem_on_a_coarse_mesh(tmp_path, capsys):
    """The FEM check end to end: both modes on the workers, the four curves written, the
    wall model's metrics compared with the coarse 3D FEM's (a 2 mm mesh: within 10 %)."""
    import json

    from spsc.cli.main import main

    out = tmp_path / "fem"
    rc = main(["design", "--target", "sensitivity_high>=1", "--type", "B", "--w", "10",
               "--h", "10", "--l", "0", "--t0", "1", "--model", "wall", "--stroke", "3",
               "--mesh-size", "2", "--trials", "1", "--workers", "2", "--no-build",
               "--out", str(out), "--quiet"])
    doc = json.loads((out / "design.json").read_text(encoding="utf-8"))
    v = doc["verify"]
    assert rc == 0, capsys.readouterr().err
    assert v["converged"] and v["points"] == {"fast": 25, "fem": 7}
    for name in v["files"].values():
        assert (out / "verify" / name).exists()
    for k, x in doc["best"]["metrics"].items():  # the check re-runs the trial's model exactly
        assert v["metrics"]["fast"][k] == (pytest.approx(x, rel=1e-12) if x is not None
                                           else None), k
    for k in ("stiffness_high", "stiffness_low", "sensitivity_high", "sensitivity_low"):
        assert abs(v["difference_pct"][k]) < 10.0, (k, v["difference_pct"][k])
    assert abs(v["difference_pct"]["cavity_mm3"]) < 0.01  # the same cavity, meshed by the FEM
    assert "3D FEM" in (out / "index.html").read_text(encoding="utf-8")


@pytest.mark.parametrize("text", ['garbage{{{\n{"op_code": 99}\n', '{"op_code": 99}\n', "x\ny\n"])
def test_a_journal_that_cannot_be_read_is_one_line_naming_it(tmp_path, text):
    """Issue 53: a garbage or cut design journal on a re-run ended in an internal error."""
    from spsc.design.journal import JOURNAL, check_resumable

    (tmp_path / JOURNAL).write_text(text)

    class Problem:
        def to_dict(self):
            return {}

    with pytest.raises(ParameterError, match=f"{JOURNAL} is a study spsc design wrote"):
        check_resumable(tmp_path, Problem())


def test_a_surrogate_search_is_confirmed_by_the_wall_model(tmp_path, capsys):
    """The surrogate screens; its best designs run again with the wall model, which decides
    whether the goal is met and is the model of the re-run commands."""
    import json

    from spsc.cli.main import main
    from spsc.design.confirm import CONFIRM
    from spsc.sweep.evaluate import evaluate

    out = tmp_path / "run"
    rc = main(["design", "--model", "surrogate", "--target", "stiffness_high=5", "--l", "0",
               "--type", "B,D", "--trials", "40", "--seed", "4", "--tol", "2", "--workers",
               "2", "--verify", "none", "--no-build", "--out", str(out), "--quiet"])
    printed = capsys.readouterr().out
    doc = json.loads((out / "design.json").read_text(encoding="utf-8"))
    c = doc["confirmed"]
    assert c["model"] == "wall" and 1 <= len(c["candidates"]) <= CONFIRM
    assert "confirmed with the wall model" in printed
    chosen = c["candidates"][c["chosen"]]
    # the confirmation is the wall model's own row, and the goal is judged on it
    row = evaluate(chosen["params"], "wall", "fdm", None, 6.0)
    assert chosen["metrics"]["stiffness_high"] == pytest.approx(row["stiffness_high"],
                                                                rel=1e-12)
    assert chosen["miss"] == min(d["miss"] for d in c["candidates"] if d["miss"] is not None)
    assert doc["met"] == (chosen["miss"] <= 0.02 + 1e-12) and rc == (0 if doc["met"] else 1)
    assert doc["rerun"]["high"].startswith("spsc curve --model wall")
    # the surrogate's screen and the wall model agree on these domes within its stated error
    assert abs(chosen["metrics"]["stiffness_high"] - chosen["screened"]["stiffness_high"]) \
        <= 0.03 * chosen["metrics"]["stiffness_high"]


def test_a_screening_search_stops_at_half_the_tolerance():
    from spsc.design.loop import stop_tol

    assert stop_tol(_problem(tol=0.02)) == pytest.approx(0.02)
    surrogate = _problem(tol=0.02)
    surrogate = type(surrogate)(surrogate.goal, surrogate.space, "surrogate",
                                surrogate.process, surrogate.points, surrogate.stroke_mm)
    assert stop_tol(surrogate) == pytest.approx(0.01)
