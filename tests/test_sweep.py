"""spsc sweep: the space (grids, lists, Latin hypercube), one row per design with the shared
metrics, invalid/partial/failed rows, the journal and resume, CSV, the command line, and a
sweep that survives its workers being killed. Sweeps run on a small in-process LocalCluster
with the simplified model (closed form, milliseconds per curve) and few plate positions."""

from __future__ import annotations

import json
import math
import os
import signal
import threading
import time
from dataclasses import asdict

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.sweep import run as sweep_module
from spsc.cli.main import main
from spsc.study.metrics import design_metrics
from spsc.sweep.run import run_sweep
from spsc.sweep.evaluate import (COLUMNS, INPUTS, METRICS, design_curves, design_key,
                                      evaluate, failed_row, resolve_design)
from spsc.sweep.space import build_space, parse_axis
from spsc.sweep.store import SweepStore, journal_path, read_table

from spsc.testing import sweep_tasks

FAST = dict(model="simplified", process="fdm", points=5, stroke_mm=4.0)
B = {"type": "B", "w": 11.0, "h": 13.0, "l": 3.0, "t0": 1.0, "n1": 2.0, "n2": 2.2, "cy": 0.0,
     "material": "tpu60a", "pressure": 40.0, "reservoir": 40000.0}


@pytest.fixture(scope="module")
def cluster():
    """One small cluster of two single-threaded worker processes for the module's sweeps
    (reached by address, as --scheduler would)."""
    from distributed import LocalCluster

    from spsc.study.executor import _NO_DASHBOARD

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None, scheduler_kwargs=_NO_DASHBOARD) as c:
        yield c.scheduler_address


# -- the space -----------------------------------------------------------------------------
def test_grid_and_lists_cross_multiply_with_presets_filled_in():
    space = build_space({"type": "A,B,C,D", "w": "8:14:7", "t0": "0.8:1.5:4",
                         "pressure": "10,40", "reservoir": "0,40000"})
    designs = list(space)
    assert len(space) == len(designs) == 4 * 7 * 4 * 2 * 2
    assert sorted({d["w"] for d in designs}) == [8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 14.0]
    assert sorted({d["t0"] for d in designs}) == pytest.approx([0.8, 1.0333333, 1.2666667, 1.5])
    assert all(set(d) == set(INPUTS) for d in designs)
    a = next(d for d in designs if d["type"] == "A")
    assert (a["n1"], a["n2"], a["cy"], a["h"], a["l"]) == (3.0, 4.0, 0.0, 13.0, 3.0)
    d = next(d for d in designs if d["type"] == "D")
    assert (d["n1"], d["n2"], d["cy"], d["material"]) == (2.0, 2.2, 0.6, "tpu60a")
    assert len({design_key(x, **{k: FAST[k] for k in ("model", "process")}) for x in designs}) \
        == len(designs)


def test_a_changed_model_changes_the_key(monkeypatch):
    """The key holds the model's code version, so a sweep re-run after the model's source
    changed computes again instead of reading the old rows back."""
    import spsc.sweep.evaluate as se
    from spsc.study.runs import code_version

    args = {k: FAST[k] for k in ("model", "process")}
    before = design_key(B, **args)
    assert design_key(B, **args) == before
    assert se._code(FAST["model"]) == code_version(FAST["model"]) != ""
    monkeypatch.setattr(se, "_code", lambda model: "edited")
    assert design_key(B, **args) != before


def test_latin_hypercube_is_reproducible_stratified_and_crossed_with_lists():
    spec = {"type": "A,B", "w": "8:14", "t0": "0.8:1.5", "pressure": "10:40"}
    one = list(build_space(spec, samples=20, seed=3))
    assert one == list(build_space(spec, samples=20, seed=3))
    assert one != list(build_space(spec, samples=20, seed=4))
    assert len(one) == 40
    by_type = {t: [d for d in one if d["type"] == t] for t in "AB"}
    for name, (lo, hi) in (("w", (8, 14)), ("t0", (0.8, 1.5)), ("pressure", (10, 40))):
        a = np.array([d[name] for d in by_type["A"]])
        # one sample in each of the 20 strata of every range
        assert sorted(np.floor((a - lo) / (hi - lo) * 20).astype(int)) == list(range(20))
        assert [d[name] for d in by_type["B"]] == list(a)  # the same samples for every type


@pytest.mark.parametrize("spec,samples,name", [
    ({"type": "B", "w": "8:14:4"}, 10, "w"),         # a grid with --samples
    ({"type": "B", "w": "8:14"}, None, "w"),         # a range without --samples
    ({"type": "B"}, 10, "samples"),                  # --samples with nothing to sample
    ({"type": "B", "w": ""}, None, "w"),
    ({"type": "B", "w": " "}, None, "w"),
    ({"type": "B", "w": "8,,9"}, None, "w"),
    ({"type": "B", "w": "8:14:0"}, None, "w"),
    ({"type": "B", "w": "8:14:-3"}, None, "w"),
    ({"type": "B", "w": "8:14:2.5"}, None, "w"),
    ({"type": "B", "w": "14:8:3"}, None, "w"),
    ({"type": "B", "w": "8:14:3:1"}, None, "w"),
    ({"type": "B", "w": "abc"}, None, "w"),
    ({"type": "B", "w": "nan"}, None, "w"),
    ({"type": "B", "w": "-1,11"}, None, "w"),
    ({"type": "B", "cy": "0:1:3"}, None, "cy"),
    ({"type": "A:B"}, None, "type"),
    ({"type": "B,E"}, None, "type"),
    ({"type": "B", "material": "tpu60a,rubber"}, None, "material"),
    ({"type": "B", "pressure": "-1"}, None, "pressure"),
    ({"type": "B", "reservoir": "-5:10:3"}, None, "reservoir"),
    ({"w": "11"}, None, "geometry"),
    ({"type": "B"}, 0, "samples"),
])
def test_bad_space_is_one_line_naming_the_option(spec, samples, name):
    with pytest.raises(ParameterError) as err:
        build_space(spec, samples=samples)
    assert str(err.value).startswith(f"{name} = ") and "\n" not in str(err.value)


def test_sweep_size_limit_prints_the_count_and_force_lifts_it():
    spec = {"type": "A,B,C,D", "w": "8:14:51", "t0": "0.8:1.5:51"}
    with pytest.raises(ParameterError, match=r"^sweep size = '10,404 designs' .* at most "
                       r"10,000 without --force"):
        build_space(spec)
    assert len(build_space(spec, force=True)) == 10_404
    assert len(build_space(spec, limit=20_000)) == 10_404


def test_a_value_given_twice_is_refused_and_types_upper_cased():
    # a repeat is refused, as spsc design refuses it (it was silently merged: issue 30)
    with pytest.raises(ParameterError, match=r"^w = '11, 11 ,12' is invalid: allowed a list of "
                       r"distinct values \(11 given twice\)"):
        parse_axis("w", "11, 11 ,12")
    with pytest.raises(ParameterError, match=r"\(B given twice\)"):
        parse_axis("type", "B,b")
    assert parse_axis("w", "11 ,12").values == (11.0, 12.0)
    assert parse_axis("type", "a,b").values == ("A", "B")
    assert parse_axis("w", "10").kind == "fixed"


# -- one design, one row -------------------------------------------------------------------
def test_row_has_every_column_and_the_shared_metrics():
    row = evaluate(B, **FAST)
    assert list(row) == list(COLUMNS)
    assert row["status"] == "ok", row["message"]
    assert row["key"] == design_key(B, **FAST)
    curves = design_curves(B, "simplified", points=5, stroke_mm=4.0)
    expect = asdict(design_metrics([curves["high"]], [curves["low"]]))  # defined once
    assert {k: row[k] for k in METRICS} == pytest.approx(expect)
    assert row["stiffness_high"] > row["stiffness_low"] > 0
    assert row["sensitivity_high"] > row["sensitivity_low"] > 0
    assert row["cavity_mm3"] == pytest.approx(4083.45, rel=1e-4)  # Table 1 B, 4.08 cm³
    assert row["seconds"] > 0
    json.dumps(row, allow_nan=True)


def test_membrane_row_uses_the_model_registry_like_spsc_curve():
    from spsc.core.setup import Setup
    from spsc.models import MODELS

    row = evaluate(B, "membrane", "fdm", 7, 4.0)
    assert row["status"] == "ok", row["message"]
    g, mat, _ = resolve_design(B)
    m = MODELS["membrane"]
    high = m.curve(Setup.of(g, mat, pressure_kPa=40.0, stroke_mm=4.0, points=7),
                   m.Options()).curve
    assert row["stiffness_high"] == pytest.approx(high.mean_stiffness(), rel=1e-9)


@pytest.mark.parametrize("t0,process,printable", [(1.0, "fdm", True), (0.6, "fdm", False),
                                                  (0.6, "sla", True), (0.9, "molding", False)])
def test_printability_column_is_the_process_verdict(t0, process, printable):
    from spsc.cad.printability import printability

    design = dict(B, t0=t0)
    row = evaluate(design, **dict(FAST, process=process))
    verdict = printability(resolve_design(design)[0], process)
    assert row["printable"] is printable is verdict.ok
    if printable:
        assert row["printability"] == verdict.summary
        assert row["printability"].startswith(f"{process}: wall {t0:.3f}")
    else:
        assert row["printability"] == "; ".join(verdict.reasons)
        assert f"wall {t0:.3f} mm" in row["printability"]
    assert row["status"] == "ok"  # an unprintable chamber is still a valid design


def test_no_reservoir_means_both_modes_closed_and_no_jnd():
    row = evaluate(dict(B, reservoir=0.0), **FAST)
    assert row["status"] == "ok"
    assert row["stiffness_low"] == row["stiffness_high"]
    assert math.isnan(row["jnd_mm"])


@pytest.mark.parametrize("change,name", [({"t0": 20.0}, "t0"), ({"h": 3.0}, "stroke"),
                                         ({"pressure": 0.0}, "pressure"),
                                         ({"material": "rubber"}, "material"),
                                         ({"type": "E"}, "type")])
def test_a_design_the_models_refuse_is_an_invalid_row(change, name):
    row = evaluate(dict(B, **change), **FAST)
    assert row["status"] == "invalid"
    assert row["message"].startswith(f"{name} = ")
    assert all(math.isnan(row[k]) for k in METRICS if k != "cavity_mm3")
    assert {k: row[k] for k in INPUTS} == dict(B, **change)


def test_a_solve_that_stops_early_is_a_partial_row_with_what_it_reached(monkeypatch):
    from spsc.models import MODELS, Outcome

    entry = MODELS["simplified"]

    class Stops(type(entry)):
        def curve(self, *args, **kw):
            c = entry.curve(*args, **kw).curve
            ok = c.y_mm <= 2.0
            nan = np.where(ok, 1.0, np.nan)
            return Outcome(c.replace(
                force_N=c.force_N * nan, pressure_kPa=c.pressure_kPa * nan, converged=ok,
                message=tuple("" if k else "no equilibrium" for k in ok), solver=None))

    monkeypatch.setitem(MODELS, "simplified", Stops())
    row = evaluate(B, **FAST)
    assert row["status"] == "partial"
    assert row["message"] == "high mode: no equilibrium; low mode: no equilibrium"
    assert np.isfinite(row["stiffness_high"])  # over the stroke it reached
    closed = evaluate(dict(B, reservoir=0.0), **FAST)  # one curve for both modes, said once
    assert closed["message"] == "high mode: no equilibrium"


def test_an_unexpected_exception_is_a_failed_row_never_raised(monkeypatch):
    from spsc.models import MODELS

    class Breaks(type(MODELS["simplified"])):
        def curve(self, *args, **kw):
            raise ZeroDivisionError("the solver divided by zero\nsecond line")

    monkeypatch.setitem(MODELS, "simplified", Breaks())
    row = evaluate(B, **FAST)
    assert row["status"] == "failed"
    assert row["message"] == "ZeroDivisionError: the solver divided by zero"
    assert evaluate({"nonsense": object()}, **FAST)["status"] in ("invalid", "failed")
    assert failed_row(B, "KilledWorker: x", key="k")["status"] == "failed"


def test_design_key_is_stable_and_names_what_the_row_depends_on(tmp_path):
    k = design_key(B, **FAST)
    assert k == design_key(dict(B, w=11, type="b", material="TPU60A"), **FAST)
    assert k != design_key(dict(B, w=11.5), **FAST)
    assert k != design_key(B, **dict(FAST, stroke_mm=5.0))
    assert k != design_key(B, **dict(FAST, model="membrane"))
    assert k != design_key(B, **dict(FAST, points=6))
    assert k != design_key(B, **dict(FAST, process="sla"))
    # defaults are the model's own: None and the default give one key
    assert design_key(B, "membrane", "fdm", None, None) == design_key(B, "membrane", "fdm",
                                                                      41, 6.0)
    f = tmp_path / "m.json"
    f.write_text("{}", encoding="utf-8")
    before = design_key(dict(B, material=str(f)), **FAST)
    f.write_text("{ }", encoding="utf-8")
    assert design_key(dict(B, material=str(f)), **FAST) != before


# -- the journal ---------------------------------------------------------------------------
def test_journal_keeps_the_last_row_of_a_key_and_survives_a_cut_line(tmp_path):
    store = SweepStore(tmp_path / "s.parquet")
    assert journal_path(tmp_path / "s.parquet") == tmp_path / "s.journal.jsonl"
    store.append(failed_row(B, "boom", key="k1"))
    store.append(dict(failed_row(B, "x", key="k2"), status="ok"))
    store.close()
    with open(store.journal, "a", encoding="utf-8") as f:
        f.write('{"key": "k3", "sta')  # the process died while writing
    store.append(dict(failed_row(B, "", key="k1"), status="ok"))
    store.close()
    assert store.done() == {"k1", "k2"}
    df = store.write(["k2", "k1", "k3"], csv=tmp_path / "s.csv")
    assert list(df["key"]) == ["k2", "k1"]
    assert list(df.columns) == list(COLUMNS)
    back = read_table(tmp_path / "s.parquet")
    assert back.equals(df)
    assert read_table(tmp_path / "s.csv")[["key", "status"]].equals(df[["key", "status"]])


def test_a_chunk_of_rows_is_one_durable_write(tmp_path, monkeypatch):
    import os

    import spsc.sweep.store as store_module

    syncs, real = [], os.fsync
    monkeypatch.setattr(store_module.os, "fsync", lambda fd: syncs.append(fd) or real(fd))
    store = SweepStore(tmp_path / "s.parquet")
    store.extend([dict(failed_row(B, "", key=f"k{i}"), status="ok") for i in range(5)])
    store.close()
    assert len(syncs) == 1
    assert store.done() == {f"k{i}" for i in range(5)}


# -- sweeps on Dask --------------------------------------------------------------------------
def _space():
    return build_space({"type": "A,B,C", "w": "9,11", "pressure": "20,40"})


def test_sweep_writes_one_row_per_design_and_a_rerun_skips_them(tmp_path, cluster):
    out = tmp_path / "s.parquet"
    space = _space()
    df = run_sweep(space, **FAST, out=out, scheduler=cluster, progress=False,
                   csv=tmp_path / "s.csv")
    assert len(df) == len(space) == 12
    assert list(df["key"]) == [design_key(d, **FAST) for d in space]
    assert (df["status"] == "ok").all()
    assert read_table(out).equals(df)
    assert read_table(tmp_path / "s.csv")[["key", "w", "status"]].equals(
        df[["key", "w", "status"]])
    lines = journal_path(out).read_text(encoding="utf-8").splitlines()
    again = run_sweep(space, **FAST, out=out, scheduler=cluster, progress=False)
    assert again.attrs["sweep"]["evaluated"] == 0 and again.attrs["sweep"]["skipped"] == 12
    assert journal_path(out).read_text(encoding="utf-8").splitlines() == lines
    assert again.equals(df)


def test_resume_retries_failed_rows_and_computes_only_new_designs(tmp_path, cluster):
    out = tmp_path / "s.parquet"
    first = build_space({"type": "A,B", "w": "9,11", "pressure": "20,40", "t0": "1,20"})
    run_sweep(first, **FAST, out=out, scheduler=cluster, progress=False)
    journal = journal_path(out)
    rows = [json.loads(x) for x in journal.read_text(encoding="utf-8").splitlines()]
    assert {r["status"] for r in rows} == {"ok", "invalid"}
    # one design failed in that run (its worker died, say), and the sweep grows by type C
    failed_key = rows[0]["key"]
    with open(journal, "a", encoding="utf-8") as f:
        f.write(json.dumps(dict(rows[0], status="failed", message="KilledWorker: x")) + "\n")
    grown = build_space({"type": "A,B,C", "w": "9,11", "pressure": "20,40", "t0": "1,20"})
    df = run_sweep(grown, **FAST, out=out, scheduler=cluster, progress=False)
    stats = df.attrs["sweep"]
    assert stats["evaluated"] == 8 + 1 and stats["skipped"] == 16 - 1
    assert len(df) == 24 and df["key"].is_unique
    assert df.set_index("key").loc[failed_key, "status"] == "ok"
    assert set(df["status"]) == {"ok", "invalid"}
    assert len(journal.read_text(encoding="utf-8").splitlines()) == 16 + 1 + 9


@pytest.mark.slow
def test_a_killed_worker_loses_no_design_and_duplicates_none(tmp_path, monkeypatch):
    """SIGKILL a worker process while it is in the middle of a design: Dask runs that design
    again elsewhere and every design is in the table exactly once."""
    import psutil

    running = tmp_path / "running"
    running.mkdir()
    monkeypatch.setenv("SPSC_TEST_RUNNING", str(running))
    out = tmp_path / "k.parquet"
    space = build_space({"type": "A,B", "w": "9,10,11,12", "pressure": "20,40"})
    killed = []

    def killer():
        journal = journal_path(out)
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and not killed:
            done = journal.exists() and len(journal.read_bytes().splitlines()) >= 2
            for mark in running.iterdir() if done else ():
                pid = int(mark.name)
                if psutil.pid_exists(pid):
                    os.kill(pid, signal.SIGKILL)
                    killed.append(pid)
                    break
            time.sleep(0.05)

    t = threading.Thread(target=killer, daemon=True)
    t.start()
    df = run_sweep(space, **FAST, out=out, workers=2, progress=False,
                   task=sweep_tasks.slow_evaluate)
    t.join(5)
    assert killed, "no worker was killed mid-design"
    assert not psutil.pid_exists(killed[0]) or psutil.Process(killed[0]).status() == "zombie"
    expected = [design_key(d, **FAST) for d in space]
    assert list(df["key"]) == expected
    assert (df["status"] == "ok").all(), df["message"].tolist()
    journal = [json.loads(x)["key"] for x in
               journal_path(out).read_text(encoding="utf-8").splitlines()]
    assert sorted(journal) == sorted(expected)  # each row written once


def test_a_design_that_keeps_killing_its_worker_is_a_failed_row(tmp_path):
    """A design whose worker dies every time (a crash in compiled code): Dask gives up on it
    (KilledWorker), the sweep gives it one more chance and then records it as failed; the other
    designs are all there, once, and a re-run retries only the failed one."""
    import dask
    import distributed  # noqa: F401  (its config section first, see spsc.sweep.run)

    out = tmp_path / "p.parquet"
    space = build_space({"type": "B", "w": f"{sweep_tasks.POISON_W},9,9.5,10,10.5,11,11.5,12"})
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):  # give up at once
        df = run_sweep(space, **FAST, out=out, workers=2, progress=False,
                       task=sweep_tasks.poison_evaluate)
    assert len(df) == 8 and df["key"].is_unique
    poisoned = df[df["w"] == sweep_tasks.POISON_W]
    assert list(poisoned["status"]) == ["failed"]
    assert poisoned["message"].iloc[0].startswith("KilledWorker")
    assert (df[df["w"] != sweep_tasks.POISON_W]["status"] == "ok").all(), df["message"].tolist()
    # the poisoned design had its second chance (a design that only shared a dying worker
    # would have one too, and pass it)
    assert df.attrs["sweep"]["retried_killed"] >= 1
    again = run_sweep(space, **FAST, out=out, workers=1, progress=False)
    assert again.attrs["sweep"]["evaluated"] == 1 and (again["status"] == "ok").all()


def test_local_workers_run_without_the_statistical_profiler(tmp_path):
    """Dask's worker profiler keeps an hour of call trees: it grew a sweep's worker by 40 kB a
    design. The sweep's LocalCluster turns it off (and leaves the caller's config alone)."""
    import dask

    df = run_sweep(build_space({"type": "B"}), **FAST, out=tmp_path / "c.parquet", workers=1,
                   progress=False, task=sweep_tasks.config_evaluate)
    assert list(df["message"]) == ["profile False"]
    assert dask.config.get("distributed.worker.profile.enabled") is True


def test_in_flight_designs_are_bounded(tmp_path, cluster, monkeypatch):
    """The client never holds more than IN_FLIGHT_PER_THREAD futures per worker thread."""
    seen = []
    real = sweep_module.SweepStore.append

    def append(self, row):
        from distributed import default_client

        seen.append(len([k for k in default_client().futures if "spsc-sweep" in str(k)]))
        real(self, row)

    monkeypatch.setattr(sweep_module.SweepStore, "append", append)
    monkeypatch.setattr(sweep_module, "IN_FLIGHT_PER_THREAD", 2)
    df = run_sweep(build_space({"type": "A,B,C,D", "w": "9,10,11", "pressure": "20,40"}),
                   **FAST, out=tmp_path / "b.parquet", scheduler=cluster, progress=False)
    assert len(df) == 24
    assert max(seen) <= 2 * 2


# -- the command line ----------------------------------------------------------------------
def test_cli_sweep_end_to_end(tmp_path, cluster, capsys):
    out, csv = tmp_path / "c.parquet", tmp_path / "c.csv"
    argv = ["sweep", "--type", "A,B", "--w", "9:11:3", "--pressure", "20,40", "--model",
            "simplified", "--points", "5", "--stroke", "4", "--out", str(out), "--csv",
            str(csv), "--scheduler", cluster, "--quiet"]
    assert main(argv) == 0
    o, e = capsys.readouterr()
    assert "12 designs: 12 ok, 0 partial, 0 invalid, 0 failed; printable (fdm): 12 of 12" in o
    assert str(out) in o and e == ""
    df = read_table(out)
    assert len(df) == 12 and list(df.columns) == list(COLUMNS)
    assert main(argv) == 0
    assert "12 done earlier and skipped" in capsys.readouterr().out


def test_cli_sweep_writes_its_page(tmp_path, cluster, capsys):
    out, page = tmp_path / "c.parquet", tmp_path / "page"
    assert main(["sweep", "--type", "A,B", "--t0", "0.5,1", "--model", "simplified",
                 "--points", "5", "--stroke", "4", "--out", str(out), "--html", str(page),
                 "--front", "stiffness_high:max,jnd_mm:min", "--scheduler", cluster,
                 "--quiet"]) == 0
    assert f"page: {page / 'index.html'}" in capsys.readouterr().out
    html = (page / "index.html").read_text(encoding="utf-8")
    assert "Pareto front: highest stiffness, high mode against lowest JND depth" in html
    assert len((page / "table.csv").read_text(encoding="utf-8").splitlines()) == 5


def test_cli_sweep_with_invalid_designs_exits_1_and_keeps_the_rows(tmp_path, cluster, capsys):
    out = tmp_path / "c.parquet"
    assert main(["sweep", "--type", "B", "--t0", "1,20", "--model", "simplified", "--points",
                 "5", "--out", str(out), "--scheduler", cluster, "--quiet"]) == 1
    o, e = capsys.readouterr()
    assert "2 designs: 1 ok, 0 partial, 1 invalid, 0 failed; printable (fdm): 1 of 2 (1 not " \
        "judged)" in o
    assert e.startswith("spsc sweep: 1 invalid (rows kept); first: t0 = 20.0 is invalid")
    assert len(read_table(out)) == 2


@pytest.mark.parametrize("argv,name", [
    (["--type", "B", "--w", "8:14"], "w"),
    (["--type", "B", "--w", "8:14:3", "--samples", "5"], "w"),
    (["--type", "B", "--samples", "5"], "samples"),
    (["--type", "B", "--process", "cnc"], "process"),
    (["--type", "B", "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "workers"),
    (["--type", "B", "--scheduler", "tcp://127.0.0.1:1"], "scheduler"),
    (["--type", "B", "--pressure", "0,40"], "pressure"),
    (["--type", "B", "--front", "jnd_mm:min,cavity_mm3:min"], "front"),
    (["--type", "B", "--html", "/dev/null"], "--html"),
    (["--type", "B", "--html", "x", "--front", "speed:max,jnd_mm:min"], "front"),
    (["--type", "A,B,C,D", "--w", "1:20:60", "--h", "5:20:60"], "sweep size"),
])
def test_cli_refuses_before_any_work(argv, name, tmp_path, capsys):
    out = tmp_path / "x.parquet"
    assert main(["sweep", *argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith(f"spsc sweep: error: {name} = "), err
    assert not out.exists() and not journal_path(out).exists()


def test_the_sweep_guide_examples_are_valid_and_their_counts_right(tmp_path):
    """Every ``spsc sweep`` example of the sweeps guide (docs/guides/sweeps.md) passes the checks
    and has the number of designs its comment states (they are not run: minutes each)."""
    import re
    import shlex
    from pathlib import Path

    from spsc.cli.main import build_parser
    from spsc.cli.sweep import prepare

    section = (Path(__file__).parents[1] / "docs" / "guides" / "sweeps.md").read_text(
        encoding="utf-8")
    examples = re.findall(r"# [^\n]*?= ([\d,]+) designs[^\n]*\n(spsc sweep (?:[^\n]*\\\n)*[^\n]*)",
                          section)
    assert len(examples) == 3
    for count, command in examples:
        argv = shlex.split(command.replace("\\\n", " "))[1:]
        for opt, name in (("--out", "x.parquet"), ("--csv", "x.csv")):
            if opt in argv:
                argv[argv.index(opt) + 1] = str(tmp_path / name)
        args = build_parser().parse_args(argv)
        assert len(prepare(args)) == int(count.replace(",", "")), command


# -- a batched model (the surrogate) -------------------------------------------------------------
def _domes(samples=24, seed=3):
    return build_space({"w": "9:13", "h": "11:15", "l": "0", "t0": "0.8:1.4", "n1": "2:3",
                        "n2": "1.5:3.5", "cy": "0:0.5", "pressure": "10:40"},
                       samples=samples, seed=seed)


def test_a_batched_row_is_the_per_design_row():
    from spsc.sweep.evaluate import evaluate_many

    designs = list(_domes(12)) + [dict(B, l=4.0)]  # l/w = 4/11: outside every surrogate
    settings = ("surrogate", "fdm", None, 6.0)
    many = evaluate_many(designs, *settings)
    one = [evaluate(d, *settings) for d in designs]
    for a, b in zip(many, one):
        assert (a["status"], a["printable"], a["printability"], a["key"]) == \
            (b["status"], b["printable"], b["printability"], b["key"])
        assert a["message"].split("; warning")[0] == b["message"].split("; warning")[0]
        # the same maps and gas law, batched: round-off only (the GP weights reach 1.6e7, so
        # its kernel sums keep ~1e-7 of the result, depending on how BLAS blocks them)
        assert_allclose([a[m] for m in METRICS], [b[m] for m in METRICS], rtol=1e-6,
                        equal_nan=True)
    assert many[-1]["status"] == "invalid" and many[-1]["message"].startswith("l")
    assert sum(r["status"] == "ok" for r in many) >= 8


def test_a_batched_sweep_writes_its_table_and_a_rerun_skips_it(tmp_path, cluster):
    out = tmp_path / "s.parquet"
    space = _domes(30)
    settings = dict(model="surrogate", process="fdm", points=None, stroke_mm=6.0)
    df = sweep_module.run_sweep(space, **settings, out=out, scheduler=cluster, progress=False,
                                batch=7)
    assert len(df) == 30 and df["key"].is_unique
    assert list(df["key"]) == [design_key(d, **settings) for d in space]
    assert set(df["status"]) <= {"ok", "partial"} and (df["status"] == "ok").sum() >= 20
    assert df.attrs["sweep"]["evaluated"] == 30
    again = sweep_module.run_sweep(space, **settings, out=out, scheduler=cluster,
                                   progress=False)
    assert again.attrs["sweep"]["evaluated"] == 0 and again.equals(df)


def test_a_surrogate_sweep_may_hold_a_million_designs_without_force(tmp_path, monkeypatch,
                                                                     capsys):
    class Started(Exception):
        pass

    def started(space, **kw):
        raise Started(len(space))

    monkeypatch.setattr(sweep_module, "run_sweep", started)
    args = ["sweep", "--samples", "20000", "--w", "9:13", "--h", "11:15", "--l", "0",
            "--t0", "1", "--n1", "2", "--n2", "2", "--cy", "0", "--out",
            str(tmp_path / "s.parquet")]
    assert main(args + ["--model", "membrane"]) == 2  # 20,000 designs: --force
    assert "at most 10,000 without --force" in capsys.readouterr().err
    main(args + ["--model", "surrogate"])  # reaches the run (caught as an internal error)
    assert "internal error: Started: 20000" in capsys.readouterr().err
