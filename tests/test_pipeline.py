"""The study runner: runs as data, cache keys (inputs and code version), cache hits on a re-run,
failure isolation, progress; the same on a small in-process Dask cluster (2 workers)."""

import contextlib
import io
import json
import os
import time
from pathlib import Path

import pytest

from spsc.core.errors import ParameterError
from spsc.study.cache import Cache
from spsc.study.runner import estimated_seconds, run_all
from spsc.models import MODELS
from spsc.study.runs import Run, Study, code_version, full_study, quick_study, source_closure

SMALL = Study(name="small", types=("B",), pressures_kPa=(40.0,), fem_points=4, fem=False,
              wall_mesh=(2.0, 1))


def test_studies_expand_into_unique_runs_cheap_first():
    for study in (full_study(), quick_study()):
        runs = study.runs()
        labels = [r.label for r in runs]
        assert len(set(labels)) == len(labels)
        assert len({r.key() for r in runs}) == len(runs)
        models = [r.model for r in runs]
        assert models.index("fem") > max(i for i, m in enumerate(models) if m != "fem")
        fem = [r for r in runs if r.model == "fem"]
        # per type: high, low and the open chamber, plus the convergence meshes
        assert {r.mode for r in fem} == {"high", "low", "open"}
        assert all(r.pressure_kPa == 0 for r in fem if r.mode == "open")
    q = quick_study()
    assert q.membrane_points == 2 * (q.fem_points - 1) + 1
    assert {r.mesh_mm for r in q.runs() if r.model == "fem"} == {2.0, 3.0}


def test_run_rejects_bad_inputs_naming_them():
    with pytest.raises(ParameterError, match="model"):
        Run("bench", "B", "tpu60a", 40, 0, 6, 5)
    with pytest.raises(ParameterError, match="mesh size"):
        Run("fem", "B", "tpu60a", 40, 0, 6, 5)
    with pytest.raises(ParameterError, match="mesh_mm"):
        Run("membrane", "B", "tpu60a", 40, 0, 6, 5, mesh_mm=1.0, layers=1)
    with pytest.raises(ParameterError, match="type"):
        Study(types=("E",))


def test_key_follows_inputs_and_the_code_the_model_imports():
    a = SMALL.membrane("membrane", "B", "tpu60a", 40, "high")
    assert a.key() == SMALL.membrane("membrane", "B", "tpu60a", 40.0, "high").key()
    assert a.key() != SMALL.membrane("membrane", "B", "tpu60a", 30, "high").key()
    assert a.key() != SMALL.membrane("simplified", "B", "tpu60a", 40, "high").key()
    assert a.key() != SMALL.membrane("membrane", "D", "tpu60a", 40, "high").key()
    def closure(module):
        src = Path(source_closure("spsc.core.curve")[0]).parents[1]  # src/spsc
        return {p.relative_to(src).as_posix() for p in source_closure(module)}

    fem = closure("spsc.models.fem")
    assert {"models/fem.py", "fem/solid/chamber.py", "fem/engine/newton.py", "fem/solid/mesh.py",
            "materials/law.py", "cad/geometry.py"} <= fem
    assert not any(n.startswith(("cli/", "study/", "membrane/solver")) for n in fem)
    mem = closure("spsc.membrane.solver")
    assert {"membrane/solver.py", "membrane/bvp.py", "membrane/stroke.py"} <= mem
    assert not any(n.startswith("fem/") for n in mem)
    assert len({code_version(m) for m in MODELS}) == len(MODELS)
    assert {"models/wall.py", "fem/wall/curve.py", "fem/wall/model.py",
            "fem/engine/newton.py"} <= closure("spsc.models.wall")

def test_every_model_of_the_registry_is_a_curve_model_with_a_code_version():
    from spsc.models import CurveModel

    assert all(isinstance(m, CurveModel) and m.name == k for k, m in MODELS.items())
    sweep = [m.name for m in MODELS.values() if m.sweep and m.study]
    assert {"membrane", "simplified"} <= set(sweep)
    runs = SMALL.runs()  # every sweep model at every setup pressure and mode
    assert sorted({r.model for r in runs}) == sorted(sweep)
    assert len(runs) == len(sweep) * len(SMALL.all_pressures) * len(SMALL.modes)


def test_rerun_with_nothing_changed_is_read_from_the_cache(tmp_path):
    runs = SMALL.runs()
    assert len(runs) == 6  # membrane, simplified and wall, high and low
    first = run_all(runs, Cache(tmp_path), progress=False)

    def no_compute(*a, **k):
        raise AssertionError("a cached run was computed again")

    second = run_all(runs, Cache(tmp_path), compute=no_compute, progress=False)
    assert all(o.ok and not o.cached for o in first.values())
    assert all(o.ok and o.cached for o in second.values()), [o.error for o in second.values()]
    for r in runs:
        assert second[r].payload["curve"] == first[r].payload["curve"]
        assert second[r].seconds == first[r].seconds  # the compute time is kept
    entries = sorted(p.name for p in (tmp_path / "runs").iterdir())
    assert len(entries) == 6 and not any(e.startswith(".") for e in entries)
    m = second[runs[0]]
    assert m.curve.all_converged and m.payload["meridians"]["pressed"] is not None
    # the payload is the curve's JSON with its solver block; nothing duplicated beside it
    assert m.payload["curve"]["solver"]["converged"] is True and m.solver.converged
    assert not {"converged", "message", "instability"} & set(m.payload)


def test_a_failed_run_is_isolated_reported_and_retried(tmp_path):
    good = SMALL.membrane("simplified", "B", "tpu60a", 40, "high")
    bad_input = Run("simplified", "B", "no-such-material", 40, 0, 6, 7)  # fails at its key
    boom = SMALL.membrane("simplified", "C", "tpu60a", 40, "high")
    calls = []

    def compute(run, directory, progress, **kw):
        calls.append(run.label)
        if run == boom:
            raise RuntimeError("deliberate failure")
        from spsc.study.runner import compute as real
        return real(run, directory, progress, **kw)

    stream = io.StringIO()
    out = run_all([bad_input, boom, good], Cache(tmp_path), compute=compute, stream=stream)
    assert out[good].ok and not out[good].cached
    assert not out[bad_input].ok and "material" in out[bad_input].error
    assert not out[boom].ok and "RuntimeError: deliberate failure" in out[boom].error
    assert "failed" in stream.getvalue() and boom.label in stream.getvalue()
    assert not any(p.name.startswith(".") for p in (tmp_path / "runs").iterdir())  # no debris
    again = run_all([boom, good], Cache(tmp_path), compute=compute, progress=False)
    assert again[good].cached and not again[boom].ok
    assert calls.count(boom.label) == 2  # failures are not cached


def test_progress_bar_names_the_runs(tmp_path):
    runs = SMALL.runs()[:2]
    stream = io.StringIO()
    run_all(runs, Cache(tmp_path), stream=stream)
    text = stream.getvalue()
    assert "spsc report" in text and "2/2" in text and runs[-1].label in text


def test_cache_ignores_a_corrupt_entry(tmp_path):
    run = SMALL.runs()[1]
    cache = Cache(tmp_path)
    run_all([run], cache, progress=False)
    (cache.entry(run) / "result.json").write_text("{not json", encoding="utf-8")
    assert cache.get(run) is None
    out = run_all([run], cache, progress=False)
    assert out[run].ok and not out[run].cached
    assert json.loads((cache.entry(run) / "result.json").read_text(encoding="utf-8"))["key"] == run.key()


def test_cache_put_is_safe_when_processes_store_the_same_run_at_once(tmp_path):
    """Workers (or two reports) may store one run together: every writer gets a whole entry,
    one entry remains, nothing half-written or left over; a stale entry is replaced."""
    import threading

    run = SMALL.runs()[1]
    cache = Cache(tmp_path)
    writers = 8
    barrier = threading.Barrier(writers)
    results, errors = [], []

    def compute(directory, i):
        (directory / "file.txt").write_text(str(i), encoding="utf-8")
        barrier.wait()  # every writer renames into place at about the same moment
        return {"writer": i}

    def put(i):
        try:
            results.append(cache.put(run, lambda d: compute(d, i)))
        except Exception as exc:  # noqa: BLE001 — collected for the assertion
            errors.append(exc)

    threads = [threading.Thread(target=put, args=(i,)) for i in range(writers)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    stored = cache.get(run)
    assert len(results) == writers and all(r == stored for r in results)  # the first one kept
    assert (cache.entry(run) / "file.txt").read_text(encoding="utf-8") == str(stored["writer"])
    assert [p.name for p in (tmp_path / "runs").iterdir()] == [cache.entry(run).name]

    stale = json.loads((cache.entry(run) / "result.json").read_text(encoding="utf-8"))
    stale["key"] = "0" * 64  # stored by other code under the same label and key prefix
    (cache.entry(run) / "result.json").write_text(json.dumps(stale), encoding="utf-8")
    assert cache.put(run, lambda d: {"writer": "new"})["writer"] == "new"
    assert cache.get(run)["writer"] == "new"
    assert [p.name for p in (tmp_path / "runs").iterdir()] == [cache.entry(run).name]


# -- on a Dask cluster --------------------------------------------------------------------------
MIXED = Study(name="mixed", types=("B",), pressures_kPa=(40.0,), fem_points=4,
              wall_mesh=(2.0, 1), mesh=(2.0, 1), convergence_meshes=((3.0, 1),))


def _cheap(run, directory, progress, *, mesh_dir=None):
    """A stand-in model (runs in a worker process): a number of the run, where and when it
    ran; run ``C`` fails."""
    started = time.time()
    time.sleep(0.2)  # long enough that both workers take runs
    if run.type == "C":
        raise RuntimeError("deliberate failure")
    (directory / "note.txt").write_text(run.label, encoding="utf-8")
    return {"value": run.pressure_kPa + run.reservoir_mm3 + (run.mesh_mm or 0),
            "pid": os.getpid(), "started": started, "seconds": 0.2}


def _crash(run, directory, progress, *, mesh_dir=None):
    """Run ``C`` kills its worker process (as the OOM killer would); the others are cheap."""
    if run.type == "C":
        os._exit(3)
    return _cheap(run, directory, progress, mesh_dir=mesh_dir)


@pytest.fixture(scope="module")
def cluster():
    """A factory of the client of one small LocalCluster (2 single-threaded worker processes)
    shared by these tests; a task whose worker dies fails at once (no retries)."""
    import dask
    import distributed  # noqa: F401 — its config defaults loaded before they are overridden

    from spsc.study.executor import dask_client

    with dask.config.set({"distributed.scheduler.allowed-failures": 0}), \
            dask_client(workers=2) as client:
        yield lambda: contextlib.nullcontext(client)


def _no_cluster():
    raise AssertionError("a cluster was started with nothing to compute")


@pytest.mark.slow
def test_cluster_gives_the_sequential_outcomes_longest_first_and_fills_the_cache(
        tmp_path, cluster):
    runs = MIXED.runs()
    assert len(runs) == 10 and runs[0].model == "membrane"  # cheap first, as given
    here = run_all(runs, Cache(tmp_path / "here"), compute=_cheap, progress=False)
    there = run_all(runs, Cache(tmp_path / "there"), compute=_cheap, progress=False,
                    cluster=cluster)
    assert list(there) == runs  # in the order given
    assert all(o.ok and not o.cached for o in there.values())
    assert [o.payload["value"] for o in there.values()] == \
        [o.payload["value"] for o in here.values()]
    pids = {o.payload["pid"] for o in there.values()}
    assert len(pids) == 2 and os.getpid() not in pids
    for pid in pids:  # each worker took the longest run left: FEM, wall, membrane models
        mine = sorted((r for r in runs if there[r].payload["pid"] == pid),
                      key=lambda r: there[r].payload["started"])
        cost = [estimated_seconds(r) for r in mine]
        assert cost == sorted(cost, reverse=True), [r.label for r in mine]
    first = {min((r for r in runs if there[r].payload["pid"] == pid),
                 key=lambda r: there[r].payload["started"]) for pid in pids}
    assert first == set(sorted(runs, key=estimated_seconds, reverse=True)[:2])
    assert {r.model for r in first} == {"fem"}
    again = run_all(runs, Cache(tmp_path / "there"), compute=_no_cluster, progress=False,
                    cluster=_no_cluster)  # written by the workers, read here
    assert all(o.ok and o.cached for o in again.values())
    for r in runs:
        assert again[r].payload == there[r].payload
        assert (Path(again[r].payload["dir"]) / "note.txt").read_text(encoding="utf-8") == r.label


def test_a_failed_run_is_isolated_on_the_cluster(tmp_path, cluster):
    good = MIXED.runs()[:3]
    boom = MIXED.membrane("wall", "C", "tpu60a", 40, "high")
    bad_input = Run("simplified", "B", "no-such-material", 40, 0, 6, 7)  # fails at its key
    stream = io.StringIO()
    out = run_all([good[0], boom, bad_input, *good[1:]], Cache(tmp_path), compute=_cheap,
                  stream=stream, cluster=cluster)
    assert list(out) == [good[0], boom, bad_input, *good[1:]]
    assert all(out[r].ok for r in good)
    assert not out[boom].ok and "RuntimeError: deliberate failure (at test_pipeline.py:" \
        in out[boom].error
    assert not out[bad_input].ok and "material" in out[bad_input].error
    assert f"run {boom.label} failed" in stream.getvalue()
    assert sorted(p.name for p in (tmp_path / "runs").iterdir()) == \
        sorted(Cache(tmp_path).entry(r).name for r in good)  # no debris, the failure not stored


def test_a_lost_worker_fails_only_its_run(tmp_path, cluster):
    runs = MIXED.runs()[:4]
    crash = MIXED.membrane("membrane", "C", "tpu60a", 40, "high")
    out = run_all([crash, *runs], Cache(tmp_path), compute=_crash, progress=False,
                  cluster=cluster)
    assert not out[crash].ok and "KilledWorker" in out[crash].error, out[crash].error
    assert all(out[r].ok for r in runs), [out[r].error for r in runs]
    with cluster() as client:  # the nanny restarts the worker for the next test
        client.wait_for_workers(2, timeout=60)
