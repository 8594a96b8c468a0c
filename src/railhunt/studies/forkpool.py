"""Local worker processes forked from the study's own process, fed through pipes.

A study that runs on this machine's cores needs no scheduler: :class:`ForkPool` forks its
workers (copies of this process, railhunt imported and every compiled function loaded: up
in a few milliseconds), sends each a task through a pipe and reads the results back as
they finish. Against a local Dask cluster this saves the cluster's start (the import of
Dask, a scheduler, a nanny per worker: 0.25-0.35 s) and about a millisecond per task; a
given client or scheduler address still runs the study on Dask (:mod:`railhunt.studies.execute`).

What the study promises holds as on Dask:

- results reach the study (its file) in the order they finish, in this process;
- a worker ignores a terminal's Ctrl-C (this process handles it: the study stops and keeps
  its file) and writes to standard streams of its own (:func:`fresh_standard_streams`);
- a task that raises is lost with its exception's name and message, the others go on;
- a worker dies with the study's process (killed, even with SIGKILL: the kernel ends its
  workers); a worker that dies (killed, out of memory) is replaced; the tasks it held run again on
  another worker, and a task that has killed :data:`ALLOWED_DEATHS` workers is lost with
  the reason, so that one bad point cannot stop a study.

Linux only (``fork``); elsewhere studies use Dask's spawned workers.
"""

from __future__ import annotations

import collections
import gc
import multiprocessing
import os
import pickle
import signal
import sys
import time
import warnings
from collections.abc import Callable, Sequence
from multiprocessing.connection import Connection, wait
from typing import Any

__all__ = ["ALLOWED_DEATHS", "QUEUED_TASK_BYTES", "STARTUP_DEATHS", "ForkPool",
           "fresh_standard_streams"]

#: A task whose worker died this many times is lost (Dask's ``allowed-failures`` is 3 reruns).
ALLOWED_DEATHS = 4
#: Largest pickled task (bytes) sent to a worker that is still busy: a pipe's buffer (about
#: 200 kB on Linux) holds it, so that this process never blocks on a send while that worker
#: blocks on sending its result (a larger task waits until the worker is idle). With the
#: default saturation of 2 at most one such task waits in a pipe.
QUEUED_TASK_BYTES = 65536
#: Workers that may die before they hold a task, per worker and run, before :meth:`ForkPool.run`
#: gives up (a process that cannot start, say for want of memory, is not forked forever).
STARTUP_DEATHS = 10


def fresh_standard_streams() -> None:
    """Replace ``sys.stdout`` and ``sys.stderr`` by new line-buffered text streams on the
    same file descriptors (their encodings and error handlers kept); a stream without a
    file descriptor is left as it is."""
    import io

    for name in ("stdout", "stderr"):
        stream = getattr(sys, name, None)
        try:
            fd = stream.fileno()
        except (AttributeError, OSError, ValueError):
            continue
        raw = io.FileIO(fd, "w", closefd=False)
        setattr(sys, name, io.TextIOWrapper(io.BufferedWriter(raw), encoding=stream.encoding,
                                            errors=stream.errors, line_buffering=True))


def _prctl() -> Any:
    """Linux's ``prctl`` from the C library, looked up in this process before it forks
    (None where there is none)."""
    try:
        import ctypes

        return ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError):  # not Linux's C library: the pipe's EOF still stops it
        return None


def _die_with(parent: int, prctl: Any) -> None:
    """Ask the kernel to kill this process when the thread that forked it ends (Linux's
    ``PR_SET_PDEATHSIG``): a study killed with SIGKILL leaves no worker computing on."""
    if prctl is not None:
        prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
    if os.getppid() != parent:  # the study died before the request was made
        os._exit(1)


def _serve(conn: Connection, foreign: list[Any], parent: int,
           inherited: dict[int, Callable[[Any], Any]], prctl: Any,
           collect: bool) -> None:  # fmt: skip
    """A worker's loop: run each task it is sent, send back its result or its error.

    ``foreign``: the parent's end of this worker's pipe and the other workers' pipe ends
    and sentinels, all closed here (so that the parent's death is an EOF on the pipe);
    ``inherited``: the functions it has from the fork, by key; ``collect``: whether the
    garbage collector was on in the parent (it is off across the fork)."""
    _die_with(parent, prctl)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # Everything inherited is left out of this worker's collections: a collection would
    # write to each object and so copy every page of the parent's memory (the first task of
    # linear critical speeds ran 3-4 times slower than the next ones).
    gc.freeze()
    if collect:
        gc.enable()
    fresh_standard_streams()
    for end in foreign:
        try:
            end.close() if hasattr(end, "close") else os.close(end)
        except OSError:
            pass
    functions: dict[int, Callable[[Any], Any]] = dict(inherited)
    while True:
        try:
            message = conn.recv_bytes()
        except (EOFError, OSError):
            return
        kind, key, payload = pickle.loads(message)
        if kind == "stop":
            return
        if kind == "function":
            import cloudpickle  # noqa: F401 - registers what pickle needs to load its output

            functions[key] = pickle.loads(payload)
            continue
        fn_key, item = payload
        t0 = time.perf_counter()
        try:
            result = ("ok", functions[fn_key](item))
        except Exception as exc:  # noqa: BLE001 - reported as the task's loss
            result = ("error", f"{type(exc).__name__}: {exc}")
        seconds = time.perf_counter() - t0
        try:
            data = pickle.dumps((key, *result, seconds), protocol=pickle.HIGHEST_PROTOCOL)
        except Exception as exc:  # noqa: BLE001 - an unpicklable result
            data = pickle.dumps((key, "error", f"{type(exc).__name__}: {exc}", seconds))
        conn.send_bytes(data)


class _Worker:
    """One forked process, its end of the pipe and the tasks it holds."""

    def __init__(self, others: list[_Worker], inherited: dict[int, Callable[[Any], Any]],
                 prctl: Any, collect: bool) -> None:  # fmt: skip
        ctx = multiprocessing.get_context("fork")
        here, there = ctx.Pipe(duplex=True)
        foreign: list[Any] = [here]
        for w in others:
            foreign.append(w.conn)
            if w.process.pid is not None:
                foreign.append(w.process.sentinel)
        self.process = ctx.Process(target=_serve, args=(there, foreign, os.getpid(), inherited,
                                                         prctl, collect),
                                   daemon=True, name="railhunt-worker")  # fmt: skip
        self._there = there
        self.conn = here
        self.functions: set[int] = set(inherited)  # the function keys it knows
        self.held: collections.deque[int] = collections.deque()  # task keys in flight
        self.idle_since: float | None = None  # when it last ran out of work (perf_counter)
        self.broken = False  # a send to it failed: read what it sent, then replace it

    def start(self) -> None:
        self.process.start()
        self._there.close()  # only the worker holds its end: its death is an EOF here

    @property
    def started(self) -> bool:
        return self.process.pid is not None

    def send(self, message: tuple[str, int, Any]) -> None:
        self.conn.send_bytes(pickle.dumps(message, protocol=pickle.HIGHEST_PROTOCOL))



class ForkPool:
    """``workers`` processes forked from this one (module docstring).

    Parameters
    ----------
    workers : int
        Number of worker processes (>= 1).
    saturation : int
        Tasks each worker holds at once: the one it runs and the next ones, so that it
        starts its next task without waiting for this process.
    functions : sequence of callables
        Functions :meth:`run` will be given: the workers have them from the fork, not
        pickled and sent (a study's task, which carries its vehicle: about 10 ms less
        before the first point).

    Fork from a thread that holds no lock a worker would need (the study's main thread
    while it computes nothing), and close the pool before that thread ends: the kernel
    ends the workers with the thread that forked them (``PR_SET_PDEATHSIG``). Each worker
    leaves the objects it inherits out of its garbage collector's passes (``gc.freeze`` as
    it starts), so that its collections do not copy this process's memory page by page.
    """

    def __init__(self, workers: int, saturation: int = 2,
                 functions: Sequence[Callable[[Any], Any]] = ()) -> None:  # fmt: skip
        if not (isinstance(workers, int) and workers >= 1):
            raise ValueError(f"workers = {workers!r} is invalid: must be an integer >= 1")
        self._owner_pid = os.getpid()
        self.saturation = max(1, int(saturation))
        #: Time (s) the workers spent running tasks, summed over the workers (the tasks
        #: whose result arrived).
        self.busy_s = 0.0
        #: Time (s) workers stood idle at the end of runs, with nothing left to give them,
        #: while another worker still computed (summed over the workers): the study's
        #: tail, set by how its last points' costs differ, not by the pool.
        self.tail_s = 0.0
        self._workers: list[_Worker] = []
        # id(fn) -> (key, fn): the function is kept, so that its id is never reused
        self._function_keys: dict[int, tuple[int, Callable[[Any], Any]]] = {}
        self._functions: dict[int, bytes] = {}  # key -> pickled function
        self._next_key = 0
        self._inherited: dict[int, Callable[[Any], Any]] = {}
        self._prctl = _prctl()
        self._idle_deaths = 0  # workers that died holding no task, in this run
        for fn in functions:
            if id(fn) not in self._function_keys:
                key = self._new_key(fn)
                self._inherited[key] = fn
        try:
            for _ in range(workers):
                self._fork()
        except BaseException:
            self.close()
            raise

    @property
    def workers(self) -> int:
        """Number of worker processes."""
        return len(self._workers)

    def pids(self) -> list[int]:
        """Process ids of the workers."""
        return [w.process.pid for w in self._workers]

    def _fork(self) -> _Worker:
        """Fork one more worker. It is registered before it starts, so that :meth:`close`
        also stops a worker whose start a Ctrl-C interrupted."""
        collect = gc.isenabled()
        worker = _Worker(self._workers, self._inherited, self._prctl, collect)
        self._workers.append(worker)
        gc.disable()  # no collection between the pipe and the fork (enabled again in it)
        try:
            with warnings.catch_warnings():  # Python >= 3.12 on a process with threads
                warnings.filterwarnings("ignore", message=".*multi-threaded.*fork",
                                        category=DeprecationWarning)  # fmt: skip
                worker.start()
        finally:
            if collect:
                gc.enable()
        return worker

    def _function_key(self, fn: Callable[[Any], Any]) -> int:
        known = self._function_keys.get(id(fn))
        if known is not None:
            return known[0]
        import cloudpickle

        key = self._new_key(fn)
        self._functions[key] = cloudpickle.dumps(fn)
        return key

    def _new_key(self, fn: Callable[[Any], Any]) -> int:
        key = self._next_key
        self._next_key += 1
        self._function_keys[id(fn)] = (key, fn)
        return key

    def run(self, fn: Callable[[Any], Any], items: Sequence[Any],
            on_result: Callable[[Any], None],
            more: Callable[[bool], Sequence[Any] | None] | None = None,
            ) -> list[tuple[Any, str]]:  # fmt: skip
        """Run ``fn`` on every item on the workers; each result goes to ``on_result`` (in
        this process) as it arrives. Returns the items lost, with the reason.

        ``more``, if given, is asked after each round of results for further items (None:
        none now), with True when every item given so far is done; the run ends when then
        it has none. A study sizes its tasks from its first results this way, without
        waiting for the others.

        On any exception here (a Ctrl-C, an error in ``on_result``) the workers are
        stopped and the pool closed before it propagates: their tasks are abandoned.

        Raises
        ------
        RuntimeError
            The pool is closed.
        """
        if not self._workers:
            raise RuntimeError("this ForkPool is closed: it has no workers")
        key_fn = self._function_key(fn)
        items = list(items)
        pending = collections.deque(range(len(items)))
        deaths = collections.Counter()
        lost: list[tuple[Any, str]] = []
        left = len(items)
        self._idle_deaths = 0
        try:
            while True:
                extra = more(left == 0) if more is not None else None
                if extra:
                    pending.extend(range(len(items), len(items) + len(extra)))
                    items.extend(extra)
                    left += len(extra)
                if left == 0:
                    break
                # One task to each idle worker first, then the next ones behind them.
                for level in range(1, self.saturation + 1):
                    for worker in list(self._workers):
                        if worker.broken:
                            continue
                        try:
                            self._feed(worker, key_fn, items, pending, level)
                        except OSError:  # it died: read what it sent, then replace it
                            worker.broken = True
                            if not worker.held:
                                left -= self._replace(worker, items, pending, deaths, lost)
                by_conn = {w.conn: w for w in self._workers if w.held}
                if not by_conn:  # a worker replaced just now holds nothing yet: feed it
                    continue
                for conn in wait(list(by_conn)):
                    worker = by_conn[conn]
                    try:
                        task, status, value, seconds = pickle.loads(conn.recv_bytes())
                    except (EOFError, OSError):
                        left -= self._replace(worker, items, pending, deaths, lost)
                        continue
                    self.busy_s += seconds
                    worker.held.remove(task)
                    left -= 1
                    if not worker.held and not pending:
                        worker.idle_since = time.perf_counter()
                    if status == "ok":
                        on_result(value)
                    else:
                        lost.append((items[task], value))
                    if worker.broken and not worker.held:
                        left -= self._replace(worker, items, pending, deaths, lost)
        except BaseException:
            self.close(wait=False)
            raise
        end = time.perf_counter()
        for worker in self._workers:
            if worker.idle_since is not None:
                self.tail_s += end - worker.idle_since
                worker.idle_since = None
        return lost

    def _feed(self, worker: _Worker, key_fn: int, items: Sequence[Any],
              pending: collections.deque, level: int) -> None:  # fmt: skip
        """Send ``worker`` tasks until it holds ``level`` of them (the function first). To
        a worker that is busy, only tasks of at most :data:`QUEUED_TASK_BYTES`."""
        while pending and len(worker.held) < level:
            task = pending[0]
            data = pickle.dumps(("task", task, (key_fn, items[task])),
                                protocol=pickle.HIGHEST_PROTOCOL)  # fmt: skip
            if worker.held and len(data) > QUEUED_TASK_BYTES:
                return  # it would wait in the pipe: sent when the worker is idle
            if key_fn not in worker.functions:
                worker.send(("function", key_fn, self._functions[key_fn]))
                worker.functions.add(key_fn)
            worker.conn.send_bytes(data)
            pending.popleft()
            worker.held.append(task)
            worker.idle_since = None

    def _replace(self, worker: _Worker, items: Sequence[Any], pending: collections.deque,
                 deaths: collections.Counter, lost: list[tuple[Any, str]]) -> int:  # fmt: skip
        """A worker died: fork another in its place; its tasks run again, or are lost
        after :data:`ALLOWED_DEATHS`. Returns the number of tasks lost."""
        worker.process.join(timeout=5.0)
        code = worker.process.exitcode
        worker.conn.close()
        self._workers.remove(worker)
        n_lost = 0
        held = list(worker.held)
        if not held:
            self._idle_deaths += 1
            if self._idle_deaths > STARTUP_DEATHS * max(1, len(self._workers) + 1):
                raise RuntimeError(f"the forked worker processes keep dying before they run "
                                   f"a task (exit code {code}, {self._idle_deaths} times); "
                                   "the points done are kept: run again with one worker "
                                   "(workers=1, --workers 1) or "
                                   "RAILHUNT_WORKER_START=spawn")  # fmt: skip
        # A worker runs its tasks in the order it got them: the first was running when it
        # died, the others waited behind it and run again without a mark.
        for task in reversed(held[1:]):
            pending.appendleft(task)
        if held:
            task = held[0]
            deaths[task] += 1
            if deaths[task] >= ALLOWED_DEATHS:
                lost.append((items[task], f"KilledWorker: the worker process died (exit code "
                                          f"{code}) {deaths[task]} times on this task"))
                n_lost = 1
            else:
                pending.appendleft(task)
        self._fork()
        return n_lost

    def close(self, wait: bool = True) -> None:
        """Stop the workers (after their current task when ``wait``, at once otherwise)."""
        workers, self._workers = self._workers, []
        for w in workers:
            if not w.started:  # registered, its start interrupted before the fork
                w.conn.close()
                w._there.close()
        workers = [w for w in workers if w.started]
        for w in workers:
            try:
                if wait:
                    w.send(("stop", 0, None))
                else:
                    w.process.kill()
            except (OSError, ValueError):
                pass
        for w in workers:
            w.process.join(timeout=10.0 if wait else 2.0)
            if w.process.is_alive():
                w.process.kill()
                w.process.join(timeout=2.0)
            w.conn.close()

    def __enter__(self) -> ForkPool:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close(wait=exc[0] is None)

    def __del__(self) -> None:  # a pool left open by an error: no orphaned processes
        try:
            if self._workers and os.getpid() == self._owner_pid:
                self.close(wait=False)
        except Exception:  # noqa: BLE001 - interpreter shutting down
            pass
