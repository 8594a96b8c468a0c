"""Forked local workers (railhunt.studies.forkpool): results, errors, dead workers, streams,
signals, and no process left behind when the study's process is killed."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from railhunt.studies.execute import run_tasks
from railhunt.studies.forkpool import ALLOWED_DEATHS, ForkPool

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="forked workers: Linux")  # fmt: skip


def _square(x: int) -> dict[str, int]:
    return {"x": x, "y": x * x, "pid": os.getpid()}


def test_every_item_once_from_several_processes():
    rows = []
    with ForkPool(2) as pool:
        lost = run_tasks(_square, list(range(50)), rows.append, client=pool)
        assert pool.workers == 2
    assert lost == []
    assert sorted(r["x"] for r in rows) == list(range(50))
    assert all(r["y"] == r["x"] ** 2 for r in rows)
    assert len({r["pid"] for r in rows}) == 2 and os.getpid() not in {r["pid"] for r in rows}


def test_a_task_that_raises_is_lost_with_its_error_and_the_others_finish():
    def task(x):  # a closure: sent to the workers by value
        if x == 3:
            raise ValueError("no third point")
        return {"x": x}

    rows = []
    with ForkPool(2) as pool:
        lost = pool.run(task, list(range(8)), rows.append)
    assert sorted(r["x"] for r in rows) == [0, 1, 2, 4, 5, 6, 7]
    assert lost == [(3, "ValueError: no third point")]


class _Unpicklable:
    """A task that cannot be pickled: only a worker that has it from the fork can run it."""

    def __reduce__(self):
        raise TypeError("this task cannot be pickled")

    def __call__(self, x: int) -> dict[str, int]:
        return {"x": x, "pid": os.getpid()}


def test_functions_given_at_the_start_are_inherited_not_sent():
    """A function given to the pool at its start runs on the workers without pickling,
    also on a worker forked later in place of a dead one; another one is still sent."""
    fn = _Unpicklable()
    rows = []
    with ForkPool(2, functions=(fn,)) as pool:
        assert pool.run(fn, list(range(6)), rows.append) == []
        os.kill(pool.pids()[0], signal.SIGKILL)
        time.sleep(0.2)
        assert pool.run(fn, list(range(6, 12)), rows.append) == []
        assert pool.run(_square, [3], rows.append) == []
        with pytest.raises(TypeError, match="cannot be pickled"):  # not given at the start
            pool.run(_Unpicklable(), [0], rows.append)
    assert sorted(r["x"] for r in rows) == sorted([*range(12), 3])
    assert len({r["pid"] for r in rows}) >= 2


def test_a_task_that_kills_its_workers_is_lost_the_task_behind_it_is_not():
    """The killer takes ALLOWED_DEATHS workers with it, then is given up; the tasks queued
    behind it on the same worker run again, unmarked; the pool keeps its size."""
    def task(x):
        if x == 1:
            os._exit(3)
        return {"x": x}

    rows = []
    with ForkPool(1, saturation=3) as pool:  # one worker: 2 and 3 always queue behind 1
        before = pool.pids()
        lost = pool.run(task, [0, 1, 2, 3], rows.append)
        assert pool.workers == 1 and pool.pids() != before
    assert sorted(r["x"] for r in rows) == [0, 2, 3]
    assert len(lost) == 1 and lost[0][0] == 1
    assert lost[0][1].startswith("KilledWorker") and f"{ALLOWED_DEATHS} times" in lost[0][1]
    assert "exit code 3" in lost[0][1]


def test_workers_ignore_ctrl_c_and_write_to_streams_of_their_own():
    def look(_):
        print("a worker's line", flush=True)
        return (signal.getsignal(signal.SIGINT), id(sys.stdout), id(sys.stderr),
                sys.stdout.fileno(), sys.stderr.fileno())  # fmt: skip

    out = []
    with ForkPool(1) as pool:
        pool.run(look, [0], out.append)
    handler, out_id, err_id, out_fd, err_fd = out[0]
    assert handler == signal.SIG_IGN
    assert out_id != id(sys.stdout) and err_id != id(sys.stderr)
    assert (out_fd, err_fd) == (sys.stdout.fileno(), sys.stderr.fileno())


def test_an_error_in_the_results_handler_stops_the_workers():
    def sink(row):
        raise RuntimeError("disk full")

    pool = ForkPool(2)
    pids = pool.pids()
    with pytest.raises(RuntimeError, match="disk full"):
        pool.run(_square, list(range(10)), sink)
    assert pool.workers == 0
    for pid in pids:
        with pytest.raises((ProcessLookupError, ChildProcessError)):
            _wait_gone(pid, 5.0)


def _wait_gone(pid: int, timeout: float) -> None:
    """Raise ProcessLookupError once ``pid`` is gone (a zombie of ours counts as gone)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            done, _ = os.waitpid(pid, os.WNOHANG)
        except ChildProcessError:
            done = 0
            os.kill(pid, 0)  # not our child: ProcessLookupError when it is gone
        if done:
            raise ProcessLookupError(pid)
        time.sleep(0.05)


def test_workers_exit_when_the_study_process_is_killed(tmp_path):
    """SIGKILL leaves no worker behind: each sees the end of its pipe and exits."""
    script = tmp_path / "hold.py"
    script.write_text(textwrap.dedent("""
        import sys, time
        from railhunt.studies.forkpool import ForkPool
        if __name__ == "__main__":
            pool = ForkPool(2)
            print(*pool.pids(), flush=True)
            pool.run(lambda x: time.sleep(60), [0, 1, 2, 3], print)
    """))
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    pids = [int(p) for p in proc.stdout.readline().split()]
    assert len(pids) == 2
    time.sleep(0.3)
    proc.kill()
    proc.wait(timeout=30)
    # The workers are busy for 60 s: they must be gone long before.
    alive = _still_running(pids, 20.0)
    assert not alive, f"workers {alive} outlived the study's process"


def _still_running(pids: list[int], timeout: float) -> set[int]:
    """The processes of ``pids`` still running (not gone, not zombies) after waiting up to
    ``timeout`` s for them to end."""
    deadline = time.monotonic() + timeout
    alive = set(pids)
    while alive and time.monotonic() < deadline:
        for pid in list(alive):
            try:
                os.kill(pid, 0)
                with open(f"/proc/{pid}/stat") as f:
                    if f.read().split()[2] == "Z":
                        alive.discard(pid)
            except (ProcessLookupError, FileNotFoundError):
                alive.discard(pid)
        time.sleep(0.1)
    return alive


def test_bad_worker_count_is_one_clear_line():
    with pytest.raises(ValueError, match=r"workers = 0 is invalid: must be an integer >= 1"):
        ForkPool(0)


def test_each_worker_gets_a_task_before_any_gets_a_second():
    """Two tasks on two workers run at the same time, not one behind the other."""
    def stamp(_):
        t0 = time.monotonic()
        time.sleep(0.3)
        return {"pid": os.getpid(), "start": t0}

    rows = []
    with ForkPool(2, saturation=2) as pool:
        pool.run(stamp, [0, 1], rows.append)
    assert len({r["pid"] for r in rows}) == 2
    assert abs(rows[0]["start"] - rows[1]["start"]) < 0.2


def test_more_items_join_the_run_and_a_drained_run_is_told():
    calls = []

    def more(drained):  # more items once, when the first ones are done
        calls.append(drained)
        if drained and calls.count(True) == 1:
            return [10, 11]
        return None

    rows = []
    with ForkPool(2) as pool:
        lost = pool.run(_square, [0, 1], rows.append, more)
    assert lost == [] and sorted(r["x"] for r in rows) == [0, 1, 10, 11]
    assert calls[0] is False  # asked before any result
    assert calls.count(True) == 2 and calls[-1] is True  # ended when drained and given none


def _gc_state(_):
    import gc

    return {"enabled": gc.isenabled(), "frozen": gc.get_freeze_count()}


def test_workers_collect_garbage_and_leave_what_they_inherit_out_of_it():
    """A worker's garbage collector is on (it is off across the fork) and what it
    inherited is frozen in it; this process's own frozen objects are left as they are."""
    import gc

    keep = [[i] for i in range(1000)]
    gc.freeze()
    try:
        frozen = gc.get_freeze_count()
        rows = []
        with ForkPool(2) as pool:
            pool.run(_gc_state, [0, 1], rows.append)
            os.kill(pool.pids()[0], signal.SIGKILL)  # a worker forked in its place
            time.sleep(0.2)
            pool.run(_gc_state, [2, 3, 4, 5], rows.append)
        assert gc.get_freeze_count() == frozen and gc.isenabled()
    finally:
        gc.unfreeze()
    assert len(rows) == 6 and all(r["enabled"] for r in rows)
    assert all(r["frozen"] >= frozen > len(keep) for r in rows)


def _run_script(tmp_path, body: str, timeout: float = 60.0) -> subprocess.CompletedProcess:
    script = tmp_path / "script.py"
    script.write_text(textwrap.dedent(body))
    return subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=timeout, cwd=tmp_path)  # fmt: skip


def test_a_worker_killed_while_it_holds_nothing_does_not_hang_the_run(tmp_path):
    """One worker, killed while this process handles its result: the run goes on with a
    new worker (it used to wait on no pipe at all)."""
    done = _run_script(tmp_path, """
        import os, signal, time
        from railhunt.studies.forkpool import ForkPool
        if __name__ == "__main__":
            for saturation in (1, 2):
                pool = ForkPool(1, saturation=saturation)
                rows = []
                def sink(row):
                    rows.append(row)
                    if row == 0:
                        os.kill(pool.pids()[0], signal.SIGKILL)
                        time.sleep(0.2)
                lost = pool.run(lambda x: x, [0, 1, 2], sink)
                pool.close()
                print(saturation, sorted(rows), lost)
    """)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split("\n")[:2] == ["1 [0, 1, 2] []", "2 [0, 1, 2] []"]


def test_a_closed_pool_says_so():
    pool = ForkPool(1)
    pool.close()
    with pytest.raises(RuntimeError, match="closed"):
        pool.run(_square, [1], print)


def test_large_tasks_and_large_results_do_not_deadlock(tmp_path):
    """Tasks and results larger than a pipe's buffer both ways (a task sent to a busy
    worker blocked while that worker blocked on sending its result)."""
    done = _run_script(tmp_path, """
        from railhunt.studies.forkpool import ForkPool
        if __name__ == "__main__":
            items = [bytes([k]) * 1_000_000 for k in range(6)]
            rows = []
            with ForkPool(1, saturation=2) as pool:
                lost = pool.run(lambda b: b, items, rows.append)
            print(len(rows), lost, sorted(r[0] for r in rows))
    """)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "6 [] [0, 1, 2, 3, 4, 5]"


def test_a_result_sent_before_its_worker_died_is_kept_and_not_run_again(tmp_path):
    """A worker sends its result and dies before this process reads it: the result is
    read (not thrown away and the task run again on a death mark)."""
    done = _run_script(tmp_path, """
        import os, threading, time
        from railhunt.studies.forkpool import ForkPool
        def task(x):
            with open("runs.txt", "a") as f:
                f.write(f"{x}\\n")
            if x == "c":  # dies just after sending this result
                threading.Timer(0.05, os._exit, (1,)).start()
            return x
        if __name__ == "__main__":
            rows = []
            def sink(row):
                rows.append(row)
                if row == "b":
                    time.sleep(0.5)  # meanwhile "c" is done and its worker dead
            with ForkPool(1, saturation=2) as pool:
                lost = pool.run(task, list("abcde"), sink)
            print("".join(rows), lost, open("runs.txt").read().split())
    """)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "abcde [] ['a', 'b', 'c', 'd', 'e']"


def test_workers_exit_on_the_pipes_end_without_the_death_signal(tmp_path):
    """Without PR_SET_PDEATHSIG a worker still exits when the study's process is killed:
    it holds no copy of this process's end of its own pipe."""
    script = tmp_path / "hold.py"
    script.write_text(textwrap.dedent("""
        import time
        from railhunt.studies import forkpool
        if __name__ == "__main__":
            forkpool._prctl = lambda: None
            pool = forkpool.ForkPool(2)
            print(*pool.pids(), flush=True)
            time.sleep(60)
    """))
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    pids = [int(p) for p in proc.stdout.readline().split()]
    proc.kill()
    proc.wait(timeout=30)
    alive = _still_running(pids, 20.0)
    assert not alive, f"workers {alive} outlived the study's process"


def test_a_ctrl_c_while_a_worker_starts_leaves_no_worker(monkeypatch):
    from railhunt.studies import forkpool

    started = []
    real = forkpool._Worker.start

    def start(self):
        real(self)
        started.append(self.process.pid)
        if len(started) == 2:
            raise KeyboardInterrupt

    monkeypatch.setattr(forkpool._Worker, "start", start)
    with pytest.raises(KeyboardInterrupt):
        ForkPool(3)
    assert len(started) == 2
    for pid in started:
        with pytest.raises((ProcessLookupError, ChildProcessError)):
            _wait_gone(pid, 5.0)


def test_workers_that_die_as_they_start_are_not_forked_forever(monkeypatch):
    """A worker that cannot start (here: it exits at once) is replaced a bounded number of
    times: its tasks are lost after ALLOWED_DEATHS each, or, when it dies before it holds
    any, the run stops with what to do."""
    from railhunt.studies import forkpool

    monkeypatch.setattr(forkpool, "_die_with", lambda parent, prctl: os._exit(3))
    pool = ForkPool(1)
    try:
        lost = pool.run(_square, [1, 2], print)
    except RuntimeError as exc:
        assert "keep dying before they run a task (exit code 3" in str(exc)
        assert "workers=1" in str(exc)
    else:
        assert [item for item, _ in lost] == [1, 2]
        assert all(r.startswith("KilledWorker: the worker process died (exit code 3) 4 times")
                   for _, r in lost)  # fmt: skip
    pool.close()
