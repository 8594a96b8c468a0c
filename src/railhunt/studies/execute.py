"""Running a study's points: in this process, on a local Dask cluster, or on a remote one.

Every point is one task (a point costs 0.1-2 s, so the ~1 ms of scheduler overhead per
task is negligible and each point can be written as soon as it finishes). The compiled
(numba) functions are loaded or compiled in this process before a local cluster starts,
so that the workers only read numba's cache (workers that compile the same cache at once
can crash: numba issue #4807).

A worker that dies has its tasks rerun elsewhere by Dask; a task that still cannot finish
is counted as lost (not written) and a later ``resume`` computes it again.
"""

from __future__ import annotations

import logging
import math
import os
import signal
import socket
import struct
import sys
import time
import warnings
from collections.abc import Callable, Iterator, Sequence
from contextlib import ExitStack, contextmanager
from typing import Any

from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    Task,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)
from rich.text import Text

from railhunt.studies.forkpool import fresh_standard_streams


class RateColumn(ProgressColumn):
    """Points per second."""

    def render(self, task: Task) -> Text:
        speed = task.finished_speed or task.speed
        return Text("   - pts/s" if speed is None else f"{speed:6.2f} pts/s", style="cyan")


def progress_bar(console: Console | None = None) -> Progress:
    """A rich progress bar: points done/total, rate, elapsed and remaining time."""
    return Progress(TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(),
                    RateColumn(), TimeElapsedColumn(), TextColumn("left"),
                    TimeRemainingColumn(), console=console or Console(stderr=True),
                    transient=False)  # fmt: skip


def default_workers() -> int:
    """Number of worker processes used by default: the cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def check_workers(workers: int | None) -> int:
    """Validate a number of worker processes and cap it at the cores.

    A point is single-threaded and compute-bound: more worker processes than cores only
    share the same cores (each with its own memory and compiled code), so a larger
    request is capped at :func:`default_workers` (:func:`capped_workers` says when).

    Parameters
    ----------
    workers : int, optional
        Requested number; None means all cores (:func:`default_workers`).

    Returns
    -------
    int
        The number of workers, in [1, cores].
    """
    if workers is None:
        return default_workers()
    if isinstance(workers, bool) or int(workers) != workers or not 1 <= workers <= 1024:
        raise ValueError(f"workers = {workers!r} is invalid: must be an integer in [1, 1024]")
    return min(int(workers), default_workers())


def capped_workers(workers: int | None) -> str | None:
    """Why ``workers`` processes will not all start (None when they will): the cap of
    :func:`check_workers`, in one sentence."""
    cores = default_workers()
    if workers is None or workers <= cores:
        return None
    return (f"{workers} workers asked, {cores} started: this machine has {cores} cores and "
            "each point keeps one core busy, so more processes would only share them")


#: Environment variable that chooses how a local cluster's worker processes start
#: (:func:`worker_start_method`).
START_METHOD_ENV = "RAILHUNT_WORKER_START"
_START_METHODS = ("fork", "spawn", "forkserver")


def worker_start_method() -> str:
    """How a local cluster's worker processes start: ``"fork"`` on Linux, else ``"spawn"``.

    A forked worker is a copy of this process: it has railhunt imported and every compiled
    function this process has loaded, so it starts in about 0.1 s and evaluates its first
    point as fast as this process does (a spawned worker imports railhunt and loads the
    compiled model from numba's cache first: about 1 s to start and 1.3-1.6 s for its first
    point of the paper's vehicle, on 2 cores). A study forks its workers while its own
    thread waits (Dask forks them from a thread of its own). ``RAILHUNT_WORKER_START=spawn`` (or
    ``forkserver``) chooses another method; macOS and Windows always spawn.
    """
    value = os.environ.get(START_METHOD_ENV, "").strip().lower()
    if value:
        if value not in _START_METHODS:
            raise ValueError(f"{START_METHOD_ENV} = {value!r} is invalid: must be one of "
                             f"{', '.join(_START_METHODS)}")  # fmt: skip
        if value != "spawn" and not sys.platform.startswith("linux"):
            return "spawn"
        return value
    return "fork" if sys.platform.startswith("linux") else "spawn"


def local_cluster(workers: int, saturation: float = 1.0) -> Any:
    """A ``dask.distributed.LocalCluster`` of ``workers`` single-threaded processes.

    Without a dashboard; its HTTP server takes any free port (no warning when 8787, the
    default, is taken by another cluster). The workers start by
    :func:`worker_start_method`. Three settings suit studies of many long points:

    - a worker holds only the task it is running (``worker-saturation`` 1.0, Dask's
      default 1.1 sends a second one to queue behind it): a worker that dies takes only
      its own point with it, and a free worker never waits behind a slow point
      (``saturation`` 2.0 gives each worker its next task beside the running one, which
      it then starts without a round trip to the scheduler: a study's forked cluster);
    - every worker process, and each one the nanny restarts, ignores SIGINT (see
      :func:`dask_setup`);
    - Dask's own log messages below CRITICAL are silenced: railhunt reports what a study
      lost and why itself, and when a study is interrupted the workers would otherwise
      print tracebacks about the results they could no longer send.
    """
    import dask
    from distributed import LocalCluster

    with warnings.catch_warnings(), \
            dask.config.set({"distributed.scheduler.worker-saturation": saturation,
                             "distributed.worker.multiprocessing-method":
                                 worker_start_method()}):  # fmt: skip
        warnings.filterwarnings("ignore", message="Port .* is already in use")
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                            dashboard_address=None, silence_logs=logging.CRITICAL,
                            preload=[__name__])  # fmt: skip


def dask_setup(worker: Any) -> None:
    """Dask preload hook, run in each local worker process as it starts: ignore SIGINT,
    and give a forked worker standard streams of its own.

    A terminal's Ctrl-C reaches every process of the group; the process that runs the
    study handles it (cancels, closes the cluster, keeps the file), the workers do not each
    print a traceback of their own. A forked worker's ``sys.stdout`` and ``sys.stderr`` are
    copies of the parent's, whose buffer locks may have been held by another thread of the
    parent (a progress bar redrawing) at the instant of the fork: its first warning would
    then wait for ever. New stream objects on the same file descriptors have free locks.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if worker_start_method() == "fork":
        fresh_standard_streams()


@contextmanager
def local_client(workers: int, saturation: float = 1.0) -> Iterator[Any]:
    """A ``dask.distributed.Client`` on a new :func:`local_cluster`, closed on exit.

    Closing does not raise: after workers died and were restarted, Dask's cluster can fail
    its own bookkeeping while it closes (a ``KeyError`` on a worker address it never saw
    arrive), once its processes are already gone; the study's results are not affected.
    """
    from distributed import Client

    cluster = local_cluster(workers, saturation)
    try:
        client = Client(cluster)
    except BaseException:
        _close_quietly(cluster)
        raise
    try:
        yield client
    finally:
        _close_quietly(client)
        _close_quietly(cluster)


class SchedulerError(OSError):
    """A Dask scheduler that cannot be joined: nothing listens, no answer within the connect
    timeout, or a server that speaks another protocol. The message is one line."""


#: Default connect timeout for a Dask scheduler (s).
CONNECT_TIMEOUT = 30.0


def check_connect_timeout(timeout: float) -> float:
    """A connect timeout (s), finite and in (0, 3600]."""
    value = float(timeout)
    if not (math.isfinite(value) and 0 < value <= 3600):
        raise ValueError(f"connect_timeout = {timeout!r} s is invalid: must be in (0, 3600] s")
    return value


def probe_scheduler(address: str, timeout: float) -> None:
    """Open and close a TCP connection to a ``tcp://HOST:PORT`` scheduler address.

    A refused port fails at once (Dask itself retries until its timeout); other schemes
    (``tls://``, ``ucx://`` ...) are left to Dask.

    Raises
    ------
    SchedulerError
        Not an address, connection refused, no answer within ``timeout`` s, or unreachable.
    """
    scheme, sep, rest = address.partition("://")
    if not sep:
        scheme, rest = "tcp", address
    if scheme != "tcp":
        return
    host, colon, port_text = rest.rpartition(":")
    host = host.strip("[]")
    if not colon or not host or not port_text.isdigit() or not 0 < int(port_text) < 65536:
        raise SchedulerError(f"{address!r} is not a scheduler address: expected "
                             "tcp://HOST:PORT, e.g. tcp://10.0.0.5:8786")  # fmt: skip
    try:
        socket.create_connection((host, int(port_text)), timeout=timeout).close()
    except ConnectionRefusedError:
        raise SchedulerError(f"nothing listens at {host}:{port_text} (connection refused)") \
            from None  # fmt: skip
    except TimeoutError:
        raise SchedulerError(f"no answer from {host}:{port_text} within {timeout:g} s") from None
    except OSError as exc:
        raise SchedulerError(f"cannot reach {host}:{port_text} "
                             f"({exc.strerror or exc})") from None  # fmt: skip


#: The largest first message (bytes) a Dask scheduler's handshake can be; a larger length
#: is another protocol's bytes read as a frame size.
_HANDSHAKE_MAX = 1 << 20
#: How long (s) a scheduler without workers is given to get one, unless told to wait.
WORKER_WAIT = 5.0


def _recv_exactly(sock: socket.socket, n: int, deadline: float) -> bytes:
    buf = bytearray()
    while len(buf) < n:
        left = deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError
        sock.settimeout(left)
        chunk = sock.recv(min(n - len(buf), 65536))
        if not chunk:
            raise ConnectionResetError("the server closed the connection")
        buf += chunk
    return bytes(buf)


def probe_handshake(address: str, timeout: float) -> None:
    """Read the handshake a Dask scheduler sends as soon as it accepts a connection, within
    ``timeout`` s, and check that it is one (``tcp://`` addresses; others are left to Dask).

    Dask's own client waits for that handshake without a time limit, so a server that
    accepts and stays silent (a busy port of another program, an HTTP server waiting for
    its request) would hold it forever.

    Raises
    ------
    SchedulerError
        Silent for ``timeout`` s, closed, or answering in another protocol.
    """
    scheme, sep, rest = address.partition("://")
    if sep and scheme != "tcp":
        return
    host, _, port = (rest if sep else address).rpartition(":")
    host = host.strip("[]")
    where = f"{host}:{port}"
    deadline = time.monotonic() + timeout
    try:
        with socket.create_connection((host, int(port)), timeout=timeout) as sock:
            (size,) = struct.unpack("<Q", _recv_exactly(sock, 8, deadline))
            if not 0 < size <= _HANDSHAKE_MAX:
                raise SchedulerError(f"{where} is not a Dask scheduler (it answered in "
                                     "another protocol)")  # fmt: skip
            body = _recv_exactly(sock, size, deadline)
    except TimeoutError:
        raise SchedulerError(f"{where} accepted the connection but sent no Dask handshake "
                             f"within {timeout:g} s: not a Dask scheduler (another server "
                             "on that port?), or one too busy to answer; check the address "
                             "or raise --connect-timeout") from None  # fmt: skip
    except OSError as exc:
        raise SchedulerError(f"{where} closed the connection before a Dask handshake "
                             f"({exc.strerror or exc}): not a Dask scheduler") \
            from None  # fmt: skip
    try:
        from distributed.protocol.core import loads
        from distributed.protocol.utils import unpack_frames

        message = loads(unpack_frames(body), deserialize=False)
    except Exception:  # noqa: BLE001 - any failure to decode means another protocol
        message = None
    if not isinstance(message, dict):
        raise SchedulerError(f"{where} is not a Dask scheduler (it answered in another "
                             "protocol)")  # fmt: skip


def await_workers(client: Any, address: str, wait: bool | float = False) -> int:
    """The number of workers of the scheduler ``client`` is joined to, after waiting for
    a first one: :data:`WORKER_WAIT` s, forever with ``wait=True``, or ``wait`` s.

    Raises
    ------
    SchedulerError
        No worker joined in time (the tasks would wait for one forever).
    """
    limit = None if wait is True else (WORKER_WAIT if wait is False else float(wait))
    try:
        client.wait_for_workers(1, timeout=limit)
    except (TimeoutError, OSError):
        raise SchedulerError(f"the Dask scheduler at {address} has no workers (none joined "
                             f"within {limit:g} s): start some ('dask worker {address}'), or "
                             "wait for them (--wait-for-workers, wait_for_workers=True)") \
            from None  # fmt: skip
    return len(client.scheduler_info().get("workers", {}))


def join_scheduler(address: str, timeout: float = CONNECT_TIMEOUT, *,
                   wait_for_workers: bool | float = False) -> Any:  # fmt: skip
    """A ``dask.distributed.Client`` joined to the scheduler at ``address``, with workers.

    Parameters
    ----------
    address : str
        ``tcp://HOST:PORT`` (or another scheme Dask knows).
    timeout : float
        Connect timeout (s), in (0, 3600]: it bounds the connection and the handshake.
    wait_for_workers : bool or float
        A scheduler without workers is an error after :data:`WORKER_WAIT` s (or
        ``timeout``, if shorter); True waits for a first worker as long as it takes, a
        number waits that many seconds.

    Raises
    ------
    SchedulerError
        Nothing listens there, no answer within ``timeout``, the server is not a Dask
        scheduler (it stays silent, or answers in another protocol), or no worker joined.
    """
    from distributed import Client

    timeout = check_connect_timeout(timeout)
    probe_scheduler(address, timeout)
    probe_handshake(address, timeout)
    try:
        client = Client(address, timeout=f"{timeout}s")
    except (MemoryError, ValueError, TypeError, KeyError, EOFError) as exc:
        raise SchedulerError(f"{address} is not a Dask scheduler (it answered in another "
                             f"protocol: {type(exc).__name__})") from None  # fmt: skip
    except OSError as exc:  # Dask's own connect timeout, or a closed connection
        raise SchedulerError(f"no Dask scheduler answered at {address} within {timeout:g} s "
                             f"({' '.join(str(exc).split())[:120]})") from None  # fmt: skip
    if wait_for_workers is False:
        wait_for_workers = min(WORKER_WAIT, timeout)
    try:
        await_workers(client, address, wait_for_workers)
    except BaseException:
        _close_quietly(client)
        raise
    return client


@contextmanager
def open_client(scheduler: str | None, workers: int, timeout: float | str = CONNECT_TIMEOUT,
                wait_for_workers: bool | float = False) -> Iterator[Any]:  # fmt: skip
    """A ``dask.distributed.Client``, closed on exit: joined to ``scheduler``
    (:func:`join_scheduler`), or else on a new :func:`local_client` of ``workers`` processes.

    Parameters
    ----------
    scheduler : str, optional
        Address of a Dask scheduler to join (``tcp://host:8786``).
    workers : int
        Worker processes of the local cluster (used without ``scheduler``).
    timeout : float or str
        How long to try to reach ``scheduler`` (s; or Dask's duration text such as
        ``"10s"``) before :class:`SchedulerError`.
    wait_for_workers : bool or float
        See :func:`join_scheduler`.
    """
    if scheduler is None:
        with local_client(workers) as client:
            yield client
        return
    if isinstance(timeout, str):
        timeout = float(timeout.strip().rstrip("s"))
    client = join_scheduler(scheduler, timeout, wait_for_workers=wait_for_workers)
    try:
        yield client
    finally:
        _close_quietly(client)


def run_tasks(
    task: Callable[[Any], dict[str, Any]],
    items: Sequence[Any],
    on_result: Callable[[dict[str, Any]], None],
    client: Any = None,
    scheduler: str | None = None,
    workers: int | None = None,
    warm_up: Callable[[], None] | None = None,
    connect_timeout: float = CONNECT_TIMEOUT,
) -> list[tuple[Any, str]]:
    """Run ``task`` on every item and hand each result to ``on_result`` as it finishes.

    Parameters
    ----------
    task : callable
        Picklable function of one item returning a dict (a results row).
    items : sequence
        The items (sweep points).
    on_result : callable
        Called in this process with each result, in the order they finish.
    client : dask.distributed.Client or railhunt.studies.forkpool.ForkPool, optional
        Run on this client's cluster, or on these forked workers (left open either way).
    scheduler : str, optional
        Address of a Dask scheduler to join (``tcp://host:8786``).
    workers : int, optional
        Worker processes of the local cluster (default: all cores). With 1 and neither
        ``client`` nor ``scheduler``, the items run in this process without Dask.
    warm_up : callable, optional
        Called once in this process before any worker starts (compiles numba's cache).
    connect_timeout : float
        How long to try to reach ``scheduler`` (s).

    Returns
    -------
    list of (item, str)
        The items that were lost (their task failed to finish) with the reason.
    """
    if client is not None and scheduler is not None:
        raise ValueError("give either client or scheduler, not both")
    n = check_workers(workers)
    if warm_up is not None:
        warm_up()
    if not items:
        return []
    if client is None and scheduler is None and n == 1:
        for item in items:
            on_result(task(item))
        return []
    from railhunt.studies.forkpool import ForkPool

    if isinstance(client, ForkPool):  # forked local workers, no scheduler
        return client.run(task, items, on_result)
    from distributed import as_completed

    with ExitStack() as stack:
        if client is None:
            client = stack.enter_context(open_client(scheduler, n, connect_timeout))
        futures = client.map(task, list(items), pure=False)
        index = {f.key: item for f, item in zip(futures, items, strict=True)}
        lost: list[tuple[Any, str]] = []
        try:
            for future in as_completed(futures):
                try:
                    # A task that finished on a worker that died before its result was
                    # fetched is computed again: result() waits for that, it is not lost.
                    row = future.result()
                except Exception as exc:  # noqa: BLE001 - KilledWorker, cancelled, ...
                    lost.append((index[future.key], f"{type(exc).__name__}: {exc}"))
                else:
                    on_result(row)
                future.release()
        except BaseException:
            client.cancel(futures)
            raise
        return lost


def _close_quietly(obj: Any) -> None:
    try:
        obj.close()
    except Exception:  # noqa: BLE001 - shutting down; nothing left to save
        pass


def interrupted(exc: BaseException) -> bool:
    """Whether ``exc`` stands for a Ctrl-C.

    A SIGINT that arrives inside compiled (numba) code surfaces as ``SystemError: ...
    returned a result with an exception set`` whose context is the KeyboardInterrupt; it
    must stop the study, not be written down as a failed point.
    """
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False
