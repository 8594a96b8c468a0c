"""A study's points grouped into tasks sized by their measured cost, and where tasks run.

The machinery around a task (a Dask task about a millisecond, a forked worker's about
20 us, a write to the results file, a progress tick) costs up to about a millisecond; a
plain function or a closed form costs a microsecond, the linear critical speed about
10 ms, a nonlinear search a few tenths of a second. So:

1. The first points are evaluated in this process and timed (at least two, and as many
   as fit in :data:`PROBE_SECONDS`): their median is the cost of a point.
2. The points are grouped into tasks of about ``task_seconds`` of work (0.5 s by default,
   :class:`railhunt.StudyOptions`): thousands of points of a plain function, one point of
   a nonlinear search. A task's rows are appended to the results file at once (one write,
   one ``fsync``), so a killed study loses at most the task in flight.
3. The points run in this process when processes cannot pay off: one worker, or a study
   whose remaining points are estimated to cost less than starting a local cluster
   (:data:`CLUSTER_START_S`), or a program read from standard input (``python - <
   study.py``), which worker processes cannot import again (one line says so).
   On Linux the local workers are forked (:func:`railhunt.studies.execute.worker_start_method`,
   :class:`railhunt.studies.forkpool.ForkPool`): copies of this process with its
   compiled code, up in a few milliseconds (:data:`FORK_START_S`); a vehicle study of
   :data:`EARLY_FORK_POINTS` points or more forks them before any point is timed, and its
   first tasks (one point per worker) are timed on the workers. Spawned workers are
   started in the background while this process goes on evaluating points; once they are
   up (and have evaluated one point each, which loads their compiled code), the remaining
   tasks go to them. On a cluster that is given (``client``, ``scheduler``) the tasks go
   there after the first points.

A task runs the same function on the same points wherever it runs, so the numbers are the
same in this process, on a local cluster and on a remote one.
"""

from __future__ import annotations

import functools
import math
import os
import signal
import statistics
import sys
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

__all__ = ["CLUSTER_START_S", "FORK_START_S", "PROBE_SECONDS", "BackgroundCluster", "TaskEngine",
           "chunk_size", "run_chunk", "unimportable_main"]  # fmt: skip

#: Evaluation time (s) of the first points timed in this process (at least two points).
PROBE_SECONDS = 0.05
#: Estimated cost (s) of starting a local cluster and loading its workers' code: below it,
#: a study's remaining points run in this process.
CLUSTER_START_S = 3.0
#: Estimated cost (s) of a new worker loading the compiled model code (numba's cache) for a
#: vehicle study, on top of :data:`CLUSTER_START_S`, and of the local cluster's other
#: overheads: a fresh worker's first point of the paper's vehicle takes 1.3-1.6 s against
#: 0.7 s for the next ones (2-core machine, the workers sharing the parent's numba cache
#: folder), but sweeps of 24 and 48 points (6 s and 14-15 s of evaluations) still took as
#: long or longer on 2 new workers as in one process (0.91x and 0.92-1.00x).
WORKER_CODE_S = 15.0
#: Estimated cost (s) of forked local workers (Linux,
#: :func:`railhunt.studies.execute.worker_start_method`;
#: :class:`~railhunt.studies.forkpool.ForkPool`): 2 start in 6-10 ms and stop in 4-8 ms,
#: and have this process's compiled code (2-core machine); a Sobol study of 1 ms points
#: broke even at 80 points (0.09 s either way) and gained from 160 (0.13 s against
#: 0.17 s). A study goes to forked workers when the time they save, ``(1 - 1/workers)`` of
#: its remaining points' cost, is larger.
FORK_START_S = 0.04
#: A vehicle study (one that loads compiled model code) with at least this many points
#: left forks its workers before timing any point, when forked workers are available: its
#: points cost 10 ms (a linear critical speed) to seconds, so that the workers pay off, and
#: the first points are then timed while the workers compute too.
EARLY_FORK_POINTS = 16
#: Tasks a worker of a forked cluster holds: the one it runs and the next, which it starts
#: without waiting for the scheduler (``worker-saturation``; a 24-point sweep on 2 cores
#: ran 1.51-1.61 x faster than in one process with 2.0, 1.40-1.56 x with 1.0).
FORKED_SATURATION = 2.0
#: Tasks per worker a study is split into at least (when its points allow): the last
#: tasks to finish then keep every worker busy until the end.
TASKS_PER_WORKER = 4
#: The same for forked workers (:class:`~railhunt.studies.forkpool.ForkPool`), whose tasks
#: cost about 20 us each against a millisecond on Dask: small tasks keep both workers busy
#: to the end (a 24-point sweep in tasks of 3 points left one worker idle for up to three
#: points' time, 0.6-2 s).
FORKED_TASKS_PER_WORKER = 32

Sink = Callable[[list[dict[str, Any]]], None]


def run_chunk(items: Sequence[Any], task: Callable[[Any], dict[str, Any]]) -> list[dict[str, Any]]:
    """One task: ``task`` on each item, the rows in order (picklable, for Dask)."""
    return [task(item) for item in items]


def timed_chunk(items: Sequence[Any], task: Callable[[Any], dict[str, Any]]
                ) -> tuple[list[dict[str, Any]], float]:  # fmt: skip
    """:func:`run_chunk` and its evaluation time (s), measured where it runs."""
    t0 = time.perf_counter()
    rows = run_chunk(items, task)
    return rows, time.perf_counter() - t0


def chunk_size(seconds_per_point: float, left: int, workers: int, task_seconds: float,
               tasks_per_worker: int = TASKS_PER_WORKER) -> int:  # fmt: skip
    """Points per task: about ``task_seconds`` of work, at least one point, and with more
    than one worker at most ``left / (tasks_per_worker * workers)`` points (rounded up)."""
    per_task = max(1, math.ceil(task_seconds / max(seconds_per_point, 1e-9)))
    if workers > 1:
        per_task = min(per_task, max(1, math.ceil(left / (tasks_per_worker * workers))))
    return min(per_task, max(1, left))


def unimportable_main() -> str | None:
    """Why worker processes cannot import this program's main module again (None when
    they can): a script read from standard input (``python - < study.py``) has no file
    that a new process could run."""
    main = sys.modules.get("__main__")
    if main is None or getattr(main, "__spec__", None) is not None:
        return None
    path = getattr(main, "__file__", None)
    if path is None or os.path.isfile(path):
        return None
    return (f"this program was read from {path} (python -), which worker processes cannot "
            "import again")  # fmt: skip


class BackgroundCluster:
    """A local Dask cluster started in a thread, while this process evaluates points.

    The thread blocks SIGINT before it starts the cluster, so the worker processes (whose
    signal mask is inherited) never see a terminal's Ctrl-C, not even while they start;
    this process still does. Once up, each worker runs ``prime`` (a study's first point),
    which loads the compiled code it needs; only then is the cluster :attr:`ready`.
    """

    def __init__(self, workers: int, prime: Callable[[], object] | None = None,
                 saturation: float = 1.0) -> None:  # fmt: skip
        self.workers = workers
        self.saturation = saturation
        self._prime = prime
        self._cm: Any = None
        self._client: Any = None
        self._error: BaseException | None = None
        self._done = threading.Event()
        self._thread = threading.Thread(target=self._start, name="railhunt-cluster",
                                        daemon=True)  # fmt: skip
        self._thread.start()

    def _start(self) -> None:
        from railhunt.studies import execute

        try:
            if hasattr(signal, "pthread_sigmask"):
                signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
            cm = execute.local_client(self.workers, self.saturation)
            self._client = cm.__enter__()
            self._cm = cm
            if self._prime is not None:
                self._client.run(self._prime)
        except BaseException as exc:  # noqa: BLE001 - handed to the main thread
            self._error = exc
        finally:
            self._done.set()

    def wait(self) -> None:
        """Wait until the cluster is up or its start failed."""
        while not self._done.wait(0.1):
            pass

    @property
    def ready(self) -> bool:
        """Whether the cluster is up (or failed to start: :meth:`client` says why)."""
        return self._done.is_set()

    def client(self) -> Any:
        """The cluster's client, once it is up (the start's error, if it failed)."""
        self.wait()
        if self._error is not None:
            raise self._error
        return self._client

    def close(self) -> None:
        """Close the cluster (after its start finished)."""
        self.wait()
        if self._cm is not None:
            cm, self._cm = self._cm, None
            cm.__exit__(None, None, None)


class TaskEngine:
    """Runs a study's batches of points: sizes their tasks, decides where they run.

    Parameters
    ----------
    options : StudyOptions
        Where the study runs and the work per task.
    client : dask.distributed.Client, optional
        A cluster to run on (given, or joined from ``options.scheduler``).
    warm_up : callable, optional
        Loads (or compiles) every compiled function a point may use, in this process,
        before a local cluster starts (workers must only read numba's cache).
    remaining : callable
        The number of the study's points not done yet (an optimisation's later
        generations included): the decision to start workers weighs all of them.
    """

    def __init__(self, options: Any, client: Any, warm_up: Callable[[], None] | None,
                 remaining: Callable[[], int]) -> None:  # fmt: skip
        self.options = options
        self.client = client
        self.warm_up = warm_up
        self.remaining = remaining
        self.seconds_per_point: float | None = None
        self.background: BackgroundCluster | None = None
        self.in_process: bool | None = None if client is None else False
        self.note: str | None = None
        self.forked = False  # the tasks go to forked local workers (:meth:`_share`)
        self.pool: Any = None  # those workers (railhunt.studies.forkpool.ForkPool)
        self._pool_task: Any = None  # the task whose chunk functions the workers inherited
        self._pool_fns: dict[str, Callable[..., Any]] = {}
        self.evaluation_s = 0.0  # evaluation time of the points run in this process
        self._closed_pool_s = 0.0  # worker_evaluation_s of pools already closed

    # ------------------------------------------------------------------ in this process

    def _here(self, task: Callable[[Any], dict[str, Any]], items: Sequence[Any],
              sink: Sink) -> None:  # fmt: skip
        """Evaluate ``items`` here; their rows go to ``sink`` at once, even on Ctrl-C."""
        rows: list[dict[str, Any]] = []
        t0 = time.perf_counter()
        try:
            for item in items:
                rows.append(task(item))
        finally:
            self.evaluation_s += time.perf_counter() - t0
            sink(rows)

    def _probe(self, task: Callable[[Any], dict[str, Any]], items: Sequence[Any],
               sink: Sink) -> int:  # fmt: skip
        """Time the first points here (module doc); returns how many were evaluated."""
        rows: list[dict[str, Any]] = []
        times: list[float] = []
        start = time.perf_counter()
        try:
            for item in items:
                t0 = time.perf_counter()
                rows.append(task(item))
                times.append(time.perf_counter() - t0)
                if len(times) >= 2 and time.perf_counter() - start >= PROBE_SECONDS:
                    break
        finally:
            self.evaluation_s += time.perf_counter() - start
            sink(rows)
        # the first point also loads the compiled code: the others tell the cost
        self.seconds_per_point = statistics.median(times[1:]) if len(times) > 1 else times[0]
        return len(times)

    def _size(self, left: int, workers: int) -> int:
        return chunk_size(self.seconds_per_point or 0.0, left, workers,
                          self.options.task_seconds,
                          FORKED_TASKS_PER_WORKER if self.forked else TASKS_PER_WORKER)

    def _run_here(self, task: Callable[[Any], dict[str, Any]], items: Sequence[Any],
                  sink: Sink) -> None:  # fmt: skip
        i = 0
        while i < len(items):
            k = self._size(len(items) - i, 1)
            self._here(task, items[i:i + k], sink)
            i += k

    # ------------------------------------------------------------------ where

    def _decide(self, task: Callable[[Any], dict[str, Any]], first: Any) -> None:
        from railhunt.studies.execute import check_workers, worker_start_method

        n = check_workers(self.options.workers)
        estimate = (self.seconds_per_point or 0.0) * self.remaining()
        forked = worker_start_method() == "fork"
        if forked:  # the time the workers save against their start
            slower_here = estimate * (1.0 - 1.0 / n) > FORK_START_S
        else:
            slower_here = estimate >= CLUSTER_START_S + (
                WORKER_CODE_S if self.warm_up is not None else 0.0)
        if n == 1 or not slower_here:
            self.in_process = True
            return
        if forked:  # a forked worker imports nothing again: any main program will do
            self._fork(n, task)
            return
        why = unimportable_main()
        if why is not None:
            self.note = (f"railhunt: note: {why}: the study runs in this process; save the "
                         f"program to a file to run it on {n} worker processes")  # fmt: skip
            print(self.note, file=sys.stderr, flush=True)
            self.in_process = True
            return
        self._warm_up()
        self.in_process = False
        self.background = BackgroundCluster(n, functools.partial(run_chunk, [first], task))

    def _warm_up(self) -> None:
        if self.warm_up is None:
            return
        try:
            self.warm_up()
        except Exception as exc:
            from railhunt.studies.execute import interrupted

            if interrupted(exc):  # Ctrl-C inside compiled code
                raise KeyboardInterrupt from exc
            raise

    def _fork(self, n: int, task: Callable[[Any], dict[str, Any]]) -> None:
        """Warm up, then fork ``n`` local workers, which have ``task`` (in the chunk
        functions :meth:`_share` and :meth:`_distribute` send) from the fork.

        Forked workers copy this process, compiled code included (nothing to prime). This
        thread waits while they start, so that it holds no lock they would inherit held (a
        fork copies only the thread that forks)."""
        self._warm_up()
        self.in_process = False
        self.forked = True
        # Each worker leaves what it inherits out of its garbage collector's passes
        # (railhunt.studies.forkpool): a collection would otherwise write to every object
        # and so copy each page of this process's memory into the worker.
        try:
            from railhunt.studies.forkpool import ForkPool

            self._pool_task = task
            self._pool_fns = {"timed": functools.partial(timed_chunk, task=task),
                              "chunk": functools.partial(run_chunk, task=task)}
            self.pool = ForkPool(n, saturation=int(FORKED_SATURATION),
                                 functions=tuple(self._pool_fns.values()))  # fmt: skip
        except Exception as exc:  # noqa: BLE001 - the study can still finish here
            self._cluster_failed(exc)

    def _fork_early(self) -> bool:
        """Whether to fork the workers before any point is timed (:data:`EARLY_FORK_POINTS`)."""
        from railhunt.studies.execute import check_workers, worker_start_method

        return (self.client is None and self.warm_up is not None
                and check_workers(self.options.workers) > 1
                and self.remaining() >= EARLY_FORK_POINTS
                and worker_start_method() == "fork")  # fmt: skip

    def _workers(self, client: Any) -> int:
        if client is self.pool and client is not None:
            return client.workers
        try:
            return max(1, len(client.scheduler_info().get("workers", {})))
        except Exception:  # noqa: BLE001 - a client without scheduler info: count one
            return 1

    # ------------------------------------------------------------------ a batch

    def run(self, task: Callable[[Any], dict[str, Any]], items: Sequence[Any],
            sink: Sink) -> list[tuple[Any, str]]:  # fmt: skip
        """Evaluate ``items`` (in tasks, here or on workers); every task's rows go to
        ``sink`` as it finishes. Returns the items lost, with the reason."""
        items = list(items)
        if not items:
            return []
        if self.in_process is None and self.seconds_per_point is None and self._fork_early():
            from railhunt.studies.execute import check_workers

            self._fork(check_workers(self.options.workers), task)
        if self.forked:
            return self._share(task, items, sink)
        i = 0
        if self.seconds_per_point is None:
            i = self._probe(task, items, sink)
        if i == len(items):
            return []
        if self.in_process is None:
            self._decide(task, items[0])
        if self.forked:
            return self._share(task, items[i:], sink)
        if self.in_process:
            self._run_here(task, items[i:], sink)
            return []
        background = self.background
        while background is not None and not background.ready and i < len(items):
            k = self._size(len(items) - i, 1)  # meanwhile, go on here
            self._here(task, items[i:i + k], sink)
            i += k
        if i == len(items):
            return []
        client = self.client
        if client is None:
            try:
                client = background.client()
            except Exception as exc:  # noqa: BLE001 - the study can still finish here
                self._cluster_failed(exc)
                self._run_here(task, items[i:], sink)
                return []
        return self._distribute(client, task, items[i:], sink)

    def _distribute(self, client: Any, task: Callable[[Any], dict[str, Any]],
                    items: list[Any], sink: Sink) -> list[tuple[Any, str]]:  # fmt: skip
        from railhunt.studies.execute import run_tasks

        k = self._size(len(items), self._workers(client))
        groups = [items[j:j + k] for j in range(0, len(items), k)]
        lost = run_tasks(self._chunk_fn("chunk", run_chunk, task, client), groups, sink,
                         client=client)  # type: ignore[arg-type]
        return [(item, reason) for group, reason in lost for item in group]

    def _share(self, task: Callable[[Any], dict[str, Any]], items: list[Any],
               sink: Sink) -> list[tuple[Any, str]]:  # fmt: skip
        """Evaluate ``items`` on a forked local cluster.

        Until a point has been timed, each worker first gets one point, timed where it runs
        (:func:`timed_chunk`); then the remaining points go in tasks of about
        ``task_seconds``, sent as soon as the first point is timed (the others still
        running).
        """
        pool = self.pool
        if pool is None:  # the workers did not start (_cluster_failed said why)
            self._run_here(task, items, sink)
            return []
        if self.seconds_per_point is not None:
            return self._distribute(pool, task, items, sink)
        n = pool.workers
        first, rest = items[:n], items[n:]

        def timed(result: tuple[list[dict[str, Any]], float]) -> None:
            rows, seconds = result
            if self.seconds_per_point is None and rows:
                self.seconds_per_point = seconds / len(rows)
            sink(rows)

        def more(drained: bool) -> list[list[Any]] | None:
            # the rest, in tasks sized by the first point timed (or, when every first point
            # was lost, by none)
            nonlocal rest
            if not rest or (self.seconds_per_point is None and not drained):
                return None
            k = self._size(len(rest), n)
            groups = [rest[j:j + k] for j in range(0, len(rest), k)]
            rest = []
            return groups

        lost = pool.run(self._chunk_fn("timed", timed_chunk, task, pool), [[x] for x in first],
                        timed, more)  # fmt: skip
        return [(item, reason) for group, reason in lost for item in group]

    def _chunk_fn(self, kind: str, chunk: Callable[..., Any], task: Callable[[Any], Any],
                  client: Any) -> Callable[..., Any]:  # fmt: skip
        """``chunk`` with ``task``: the very function the forked workers inherited when
        these are the workers and that the task, a new one otherwise."""
        if client is not None and client is self.pool and task is self._pool_task:
            return self._pool_fns[kind]
        return functools.partial(chunk, task=task)

    def _cluster_failed(self, exc: BaseException) -> None:
        text = " ".join(str(exc).split())[:200]
        self.note = (f"railhunt: note: the local cluster did not start "
                     f"({type(exc).__name__}: {text}); the study goes on in this "
                     "process")  # fmt: skip
        print(self.note, file=sys.stderr, flush=True)
        self.in_process = True
        self.forked = False
        self.close()

    @property
    def worker_evaluation_s(self) -> float:
        """Time (s) forked local workers spent evaluating points, summed over the workers
        (not measured on a Dask cluster: 0 there)."""
        return self._closed_pool_s + (self.pool.busy_s if self.pool is not None else 0.0)

    def close(self) -> None:
        """Close the local workers or cluster this engine started."""
        if self.pool is not None:
            pool, self.pool = self.pool, None
            self._closed_pool_s += pool.busy_s
            pool.close()
        if self.background is not None:
            background, self.background = self.background, None
            background.close()
