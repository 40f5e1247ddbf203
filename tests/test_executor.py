"""The Dask executor: local workers are separate single-threaded processes, an existing scheduler
is reached by address, and bad addresses or worker counts fail in one line, fast."""

import os
import socket
import time

import pytest

from spsc.core.errors import ParameterError
from spsc.study.executor import _NO_DASHBOARD, check_scheduler, check_workers, dask_client


def _worker_facts(_):
    time.sleep(0.2)  # long enough that both workers take a task
    return os.getpid(), os.environ.get("OPENBLAS_NUM_THREADS"), \
        os.environ.get("MALLOC_TRIM_THRESHOLD_")


def test_local_cluster_runs_on_separate_single_threaded_processes(monkeypatch):
    # (an earlier cluster of another kind may have put Dask's value in this process's environ)
    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    with dask_client(workers=2) as client:
        info = client.scheduler_info()
        assert len(info["workers"]) == 2
        assert all(w["nthreads"] == 1 for w in info["workers"].values())
        facts = client.gather(client.map(_worker_facts, range(6), pure=False))
    pids = {pid for pid, _, _ in facts}
    assert os.getpid() not in pids
    assert len(pids) == 2
    assert {blas for _, blas, _ in facts} == {"1"}
    assert {trim for _, _, trim in facts} == {None}  # glibc's own malloc thresholds


def test_local_workers_stop_before_the_scheduler(monkeypatch):
    # closed together, a worker's heartbeat in flight met a closed scheduler and logged a
    # traceback at the end of a clean run (one close in 25)
    from distributed import LocalCluster

    seen = []
    close = LocalCluster.close

    def recording(self, *args, **kwargs):
        seen.append(len(self.scheduler.workers))
        return close(self, *args, **kwargs)

    monkeypatch.setattr(LocalCluster, "close", recording)
    with dask_client(workers=2) as client:
        assert len(client.scheduler_info()["workers"]) == 2
    assert seen[:1] == [0]


def _worker_config():
    import dask

    return (dask.config.get("distributed.worker.profile.enabled"),
            dask.config.get("distributed.admin.tick.interval"))


def test_local_workers_do_not_profile():
    # the statistical profiler and a 20 ms watchdog cost CPU the models need (executor docstring)
    with dask_client(workers=1) as client:
        config = set(client.run(_worker_config).values())
    assert config == {(False, "200ms")}


def test_existing_scheduler_is_used_by_address():
    from distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp",
                      dashboard_address=None, scheduler_kwargs=_NO_DASHBOARD) as cluster:
        with dask_client(workers=5, scheduler=cluster.scheduler_address) as client:
            # the cluster's own single worker, not five new ones
            assert len(client.scheduler_info()["workers"]) == 1
            assert client.submit(lambda x: x + 1, 41).result() == 42


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_scheduler_that_does_not_answer_is_one_line_error_within_seconds():
    port = _closed_port()
    t0 = time.perf_counter()
    with pytest.raises(ParameterError, match=r"^scheduler = .*nothing answered") as err:
        check_scheduler(f"tcp://127.0.0.1:{port}", timeout=2.0)
    assert time.perf_counter() - t0 < 10.0  # not Dask's retry loop (minutes)
    assert "\n" not in str(err.value)


@pytest.fixture(params=["silent", "http"])
def not_dask(request):
    """A local port where something listens but does not speak Dask: a socket that accepts
    and never answers, or one that answers as an HTTP server would."""
    import threading

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(4)
    held = []

    def serve():
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            held.append(conn)
            if request.param == "http":
                conn.sendall(b"HTTP/1.0 400 Bad Request\r\n\r\n")

    threading.Thread(target=serve, daemon=True).start()
    yield f"tcp://127.0.0.1:{server.getsockname()[1]}"
    server.close()
    for conn in held:
        conn.close()


def test_a_port_that_is_not_a_dask_scheduler_is_refused_within_seconds(not_dask):
    """The TCP probe passes there; Dask's handshake and identity request, bounded by the
    timeout, do not: one line, in about the timeout (2 s), not a hang."""
    t0 = time.perf_counter()
    with pytest.raises(ParameterError, match=r"^scheduler = .*not a Dask scheduler") as err:
        check_scheduler(not_dask, timeout=2.0)
    assert time.perf_counter() - t0 < 8.0
    assert "\n" not in str(err.value)


def test_a_dask_worker_is_not_a_scheduler():
    from distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp",
                      dashboard_address=None, scheduler_kwargs=_NO_DASHBOARD) as cluster:
        assert check_scheduler(cluster.scheduler_address) == cluster.scheduler_address
        worker = next(iter(cluster.scheduler_info["workers"]))
        with pytest.raises(ParameterError, match=r"not a Dask scheduler \(Worker\)"):
            check_scheduler(worker)


@pytest.mark.parametrize("address", ["", "http://x:1", "tcp://", "tcp://host", "tcp://h:port"])
def test_malformed_scheduler_address_is_refused(address):
    with pytest.raises(ParameterError, match="^scheduler = "):
        check_scheduler(address)


@pytest.mark.parametrize("workers", [0, -1, 2.5, "two", True, 10_000])
def test_bad_worker_count_is_refused(workers):
    with pytest.raises(ParameterError, match="^workers = "):
        check_workers(workers)


def test_worker_count_defaults_to_usable_cores():
    assert check_workers(None) >= 1
    assert check_workers(3) == 3
    assert check_workers("2") == 2


def test_cluster_options_are_checked_together():
    from spsc.study.executor import check_cluster, default_workers

    assert check_cluster() == (default_workers(), None)
    assert check_cluster("3") == (3, None)
    from distributed import LocalCluster

    with LocalCluster(n_workers=0, processes=False, protocol="tcp", dashboard_address=None,
                      scheduler_kwargs=_NO_DASHBOARD) as cluster:
        address = cluster.scheduler_address
        bare = address.removeprefix("tcp://")
        assert check_cluster(None, bare) == (None, address)
        with pytest.raises(ParameterError, match="^workers = .*without a scheduler"):
            check_cluster(2, bare)
    with pytest.raises(ParameterError, match="^workers = "):
        check_cluster("0")
    with pytest.raises(ParameterError, match="^scheduler = .*nothing answered"):
        check_cluster(None, f"tcp://127.0.0.1:{_closed_port()}")
