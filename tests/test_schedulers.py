"""Schedulers never hang: a server that is not Dask, or a Dask scheduler without workers,
is named within the connect timeout; nothing is created before the scheduler is joined.

Every server here listens on 127.0.0.1 only and every wait is bounded.
"""

from __future__ import annotations

import http.server
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Iterator

import pytest

import railhunt
from railhunt.studies.execute import check_workers, default_workers
from railhunt.studies.store import ResultFileError, sidecar_path
from test_cli import assert_input_error, run

VEHICLE = railhunt.Vehicle.paper2019()
LINEAR = ("linear_critical_speed",)
SWEEP = ["sweep", "C_d1", "--from", "1e5", "--to", "2e5", "--num", "2", "--outputs",
         "linear_critical_speed"]  # fmt: skip


def bounded(*args: str, timeout: float = 60.0) -> subprocess.CompletedProcess:
    """``railhunt ARGS`` in a child process that is killed after ``timeout`` s (a hang
    fails the test instead of holding it)."""
    code = "import sys; from railhunt.cli.app import main; sys.exit(main())"
    try:
        return subprocess.run([sys.executable, "-c", code, *args], capture_output=True,
                              text=True, timeout=timeout)  # fmt: skip
    except subprocess.TimeoutExpired:
        pytest.fail(f"railhunt {' '.join(args)} still ran after {timeout:g} s")


def assert_one_line_error(result: subprocess.CompletedProcess, *fragments: str) -> None:
    lines = result.stderr.strip().splitlines()
    assert result.returncode == 2 and len(lines) == 1, result.stderr
    for fragment in fragments:
        assert fragment in lines[0], lines[0]


@pytest.fixture()
def silent() -> Iterator[str]:
    """A TCP server that accepts connections and never says a word."""
    server = socket.create_server(("127.0.0.1", 0))
    held: list[socket.socket] = []
    stop = threading.Event()

    def serve() -> None:
        server.settimeout(0.1)
        while not stop.is_set():
            try:
                held.append(server.accept()[0])
            except OSError:
                continue

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield f"tcp://127.0.0.1:{server.getsockname()[1]}"
    stop.set()
    thread.join()
    for conn in held:
        conn.close()
    server.close()


@pytest.fixture()
def web() -> Iterator[str]:
    """An HTTP server (it waits for a request line before it answers)."""
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0),
                                             http.server.SimpleHTTPRequestHandler)  # fmt: skip
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"tcp://127.0.0.1:{server.server_address[1]}"
    server.shutdown()
    server.server_close()


@pytest.fixture()
def no_workers() -> Iterator[object]:
    """A real Dask scheduler (in this process) with no workers."""
    from distributed import LocalCluster

    cluster = LocalCluster(n_workers=0, processes=False, dashboard_address=None,
                           host="127.0.0.1", protocol="tcp://")  # fmt: skip
    yield cluster
    cluster.close()


@pytest.mark.parametrize("server", ["silent", "web"])
def test_a_server_that_never_answers_is_named_within_the_timeout(tmp_path, request, server):
    address = request.getfixturevalue(server)
    start = time.perf_counter()
    result = bounded(*SWEEP, "--scheduler", address, "--connect-timeout", "2", "--out",
                     str(tmp_path / "x.csv"))  # fmt: skip
    assert_one_line_error(result, f"--scheduler {address}", "no Dask handshake within 2 s")
    assert time.perf_counter() - start < 30.0
    assert list(tmp_path.iterdir()) == []


def test_a_scheduler_without_workers_says_so(tmp_path, no_workers):
    address = no_workers.scheduler_address
    start = time.perf_counter()
    result = bounded(*SWEEP, "--scheduler", address, "--connect-timeout", "2", "--out",
                     str(tmp_path / "x.csv"))  # fmt: skip
    assert_one_line_error(result, "has no workers", "--wait-for-workers")
    assert time.perf_counter() - start < 30.0
    assert list(tmp_path.iterdir()) == []


def test_wait_for_workers_waits_for_the_first_one(no_workers):
    # A worker joins 1 s after the study starts: waiting for it, the study runs.
    timer = threading.Timer(1.0, no_workers.scale, args=(1,))
    timer.start()
    try:
        result = railhunt.sweep(VEHICLE, {"mu": [0.2, 0.3]}, LINEAR,
                                scheduler=no_workers.scheduler_address,
                                wait_for_workers=60.0)  # fmt: skip
    finally:
        timer.join()
    assert len(result) == 2 and result.lost == 0


def test_wait_for_workers_needs_a_scheduler(tmp_path):
    assert_input_error(run(*SWEEP, "--wait-for-workers", "--workers", "1", "--out",
                           str(tmp_path / "x.csv")), "--wait-for-workers", "--scheduler")


def test_the_api_creates_no_file_before_it_detects_a_non_dask_server(tmp_path, web):
    # The web server answers Dask's handshake with HTTP: the error comes at once, and
    # the results file must not be there (on a silent server see the tests above).
    out = tmp_path / "s.csv"
    code = ("import railhunt, sys; from railhunt.studies.execute import SchedulerError\n"
            "try:\n"
            f"    railhunt.sweep(railhunt.Vehicle.paper2019(), {{'mu': [0.2]}}, {LINEAR!r},"
            f" scheduler={web!r}, out={str(out)!r}, connect_timeout=1.0)\n"
            "except SchedulerError as exc:\n"
            "    print('SchedulerError', exc)\n")  # fmt: skip
    try:
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              timeout=60)  # fmt: skip
    except subprocess.TimeoutExpired:
        pytest.fail("sweep(scheduler=...) still ran after 60 s")
    assert done.stdout.startswith("SchedulerError"), done.stdout + done.stderr
    assert not out.exists() and not sidecar_path(out).exists()


def test_the_api_creates_no_missing_folder(tmp_path):
    out = tmp_path / "no" / "such" / "s.csv"
    with pytest.raises(ResultFileError, match="does not exist"):
        railhunt.sweep(VEHICLE, {"mu": [0.2]}, LINEAR, workers=1, out=out)
    assert not (tmp_path / "no").exists()


def _probe_one(engine, task, items, sink):
    """Time only the first point (a probe of one)."""
    import time

    t0 = time.perf_counter()
    sink([task(items[0])])
    engine.seconds_per_point = time.perf_counter() - t0
    return 1


def test_workers_are_capped_at_the_cores(tmp_path, monkeypatch):
    import railhunt.studies.execute as execute
    import railhunt.studies.tasks as tasks

    assert check_workers(1000) == default_workers()
    started: list[int] = []

    class Started(Exception):
        pass

    def fake_local_client(n, *args, **kwargs):
        started.append(n)
        raise Started

    import railhunt.studies.forkpool as forkpool

    monkeypatch.setattr(execute, "local_client", fake_local_client)  # spawned workers
    monkeypatch.setattr(forkpool, "ForkPool", fake_local_client)  # forked ones
    # two cheap points would run in this process: make starting workers look free, and
    # time only the first point, so that the second goes to the (fake) cluster
    monkeypatch.setattr(tasks, "CLUSTER_START_S", 0.0)
    monkeypatch.setattr(tasks, "WORKER_CODE_S", 0.0)
    monkeypatch.setattr(tasks, "FORK_START_S", 0.0)
    monkeypatch.setattr(tasks.TaskEngine, "_probe", _probe_one)
    if default_workers() == 1:
        pytest.skip("one core: the points run in this process")
    result = run(*SWEEP, "--workers", "1000", "--out", str(tmp_path / "x.csv"))
    assert "1000 workers asked" in result.stderr
    assert f"{default_workers()} started" in result.stderr
    assert started == [default_workers()]
