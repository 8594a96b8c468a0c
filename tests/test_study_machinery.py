"""The study machinery: one options object, tasks sized by the points' cost, results
appended per task, the in-process path, a program read from standard input, and a study
killed in the middle of a task that resumes to the same file."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

import railhunt
from railhunt import StudyOptions, sensitivity, sweep
from railhunt.studies import store as store_module
from railhunt.studies import tasks
from railhunt.studies.execute import default_workers
from railhunt.studies.tasks import chunk_size

pytest.importorskip("SALib")

PI = math.pi
FACTORS = {"x1": (-PI, PI), "x2": (-PI, PI), "x3": (-PI, PI)}


def ishigami(x1: float, x2: float, x3: float) -> dict[str, float]:
    return {"y": math.sin(x1) + 7.0 * math.sin(x2) ** 2 + 0.1 * x3**4 * math.sin(x1)}


# --------------------------------------------------------------------------- options


def test_run_options_give_the_same_study_as_the_keywords(tmp_path):
    by_keywords = sensitivity(ishigami, FACTORS, ["y"], samples=32, workers=1,
                              out=tmp_path / "k.csv")  # fmt: skip
    run = StudyOptions(out=tmp_path / "r.csv", workers=1)
    by_run = sensitivity(ishigami, FACTORS, ["y"], samples=32, run=run)
    assert by_run.indices == by_keywords.indices
    assert (tmp_path / "r.csv").read_bytes() == (tmp_path / "k.csv").read_bytes()
    again = sensitivity(ishigami, FACTORS, ["y"], samples=32, run=run.replace(resume=True))
    assert again.study.computed == 0 and again.study.resumed == 32 * 5


@pytest.mark.parametrize("study", ["sweep", "sensitivity", "optimize", "stability_map"])
def test_run_and_a_keyword_both_given_is_one_clear_error(study, tmp_path):
    run = StudyOptions(workers=1)
    calls = {
        "sweep": lambda: sweep(railhunt.Vehicle.paper2019(), {"mu": [0.2]}, run=run,
                               out=tmp_path / "a.csv"),
        "sensitivity": lambda: sensitivity(ishigami, FACTORS, ["y"], run=run, resume=True),
        "optimize": lambda: railhunt.optimize(ishigami, FACTORS, ["min y", "max x1"],
                                              run=run, workers=2),
        "stability_map": lambda: railhunt.stability_map(railhunt.Vehicle.paper2019(), [1e3],
                                                        run=run, progress=True),
    }  # fmt: skip
    with pytest.raises(ValueError, match=r"run= and \w+= both given") as info:
        calls[study]()
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("changes, match", [
    ({"workers": 0}, r"workers = 0 is invalid: must be an integer in \[1, 1024\]"),
    ({"task_seconds": -1.0}, r"task_seconds = -1.0 s is invalid: must be in \(0, 3600\] s"),
    ({"connect_timeout": 0.0}, r"connect_timeout = 0.0 s is invalid"),
    ({"wait_for_workers": -2}, r"wait_for_workers = -2 is invalid"),
    ({"client": object(), "scheduler": "tcp://h:1"}, "either client or scheduler"),
])  # fmt: skip
def test_bad_options_name_the_value_and_the_range(changes, match):
    with pytest.raises(ValueError, match=match):
        StudyOptions(**changes)


# --------------------------------------------------------------------------- tasks


def test_tasks_hold_about_their_share_of_work():
    # a plain function (1 us a point) gets hundreds of thousands per 0.5 s task, a
    # nonlinear search (0.3 s) one; with workers, at least 4 tasks each when possible
    assert chunk_size(1e-6, 10_240, 1, 0.5) == 10_240
    assert chunk_size(1e-6, 10_240, 2, 0.5) == 1280
    assert chunk_size(0.012, 576, 2, 0.5) == 42
    assert chunk_size(0.3, 24, 2, 0.5) == 2
    assert chunk_size(0.3, 3, 2, 0.5) == 1
    assert chunk_size(5.0, 100, 1, 0.5) == 1


def test_results_are_appended_per_task_not_per_point(tmp_path, monkeypatch):
    syncs = []
    real = os.fsync
    monkeypatch.setattr(store_module.os, "fsync", lambda fd: (syncs.append(fd), real(fd)))
    r = sensitivity(ishigami, FACTORS, ["y"], samples=256, workers=1, out=tmp_path / "s.csv")
    assert r.study.computed == 1280
    assert len(syncs) <= 4, f"{len(syncs)} syncs for 1280 points"  # the header, a few tasks


def test_cheap_points_on_several_workers_start_no_cluster(monkeypatch):
    import railhunt.studies.execute as execute
    import railhunt.studies.forkpool as forkpool

    def no_cluster(n, *args, **kwargs):
        raise AssertionError("workers were started for a study of milliseconds")

    monkeypatch.setattr(execute, "local_client", no_cluster)
    monkeypatch.setattr(forkpool, "ForkPool", no_cluster)
    r = sensitivity(ishigami, FACTORS, ["y"], samples=64, workers=2)
    assert r.study.computed == 64 * 5


def test_progress_reports_every_point_and_the_file_holds_what_it_was_told(tmp_path):
    """A progress callback that stops the study (Ctrl-C) at point 100: the file holds
    exactly the 100 points reported, although they were computed in one task."""
    def stop(done: int, total: int) -> None:
        if done == 100:
            raise KeyboardInterrupt

    out = tmp_path / "p.csv"
    with pytest.raises(KeyboardInterrupt):
        sensitivity(ishigami, FACTORS, ["y"], samples=64, workers=1, out=out, progress=stop)
    assert len(railhunt.read_results(out)) == 100


# --------------------------------------------------------------------------- processes

SCRIPT = """
import math, sys, time
import railhunt
from railhunt.studies import tasks

def slow(x1, x2, x3):
    time.sleep({sleep})
    return {{"y": math.sin(x1) + 7.0 * math.sin(x2) ** 2 + 0.1 * x3 ** 4 * math.sin(x1)}}

if __name__ == "__main__":
    {setup}
    run = railhunt.StudyOptions(out={out!r}, workers={workers}, task_seconds={task},
                                resume={resume})
    r = railhunt.sensitivity(slow, {{k: (-math.pi, math.pi) for k in ("x1", "x2", "x3")}},
                             ["y"], samples={samples}, seed=2, run=run)
    print(r.study.computed, r.study.resumed)
"""


def _script(out: Path, *, sleep: float, workers: int, task: float, samples: int,
            resume: bool = False, setup: str = "pass") -> str:  # fmt: skip
    return textwrap.dedent(SCRIPT).format(sleep=sleep, out=str(out), workers=workers,
                                          task=task, samples=samples, resume=resume,
                                          setup=setup)  # fmt: skip


def _forked_logging_pids(pids: Path) -> str:
    """``setup`` for :data:`SCRIPT`: workers as if they cost nothing (forked at once), and
    each point appends the id of the process that evaluates it to ``pids``."""
    return ("tasks.FORK_START_S = 0.0  # as if workers cost nothing\n"
            "    import os\n"
            "    real = slow\n"
            "    def slow(**x):\n"
            f"        open({str(pids)!r}, 'a').write(f'{{os.getpid()}}\\n')\n"
            "        return real(**x)")  # fmt: skip


def test_a_program_read_from_standard_input_runs_in_process_with_one_line(tmp_path):
    """``python - < study.py`` with spawned workers: they cannot import the program again
    (a local cluster's start died with 'Nanny failed to start' and a traceback); the study
    runs in this process and says so in one line."""
    code = _script(tmp_path / "stdin.csv", sleep=0.005, workers=2, task=0.5, samples=8,
                   setup="tasks.CLUSTER_START_S = 0.0  # as if workers cost nothing")
    done = subprocess.run([sys.executable, "-"], input=code, capture_output=True, text=True,
                          timeout=300, cwd=tmp_path,
                          env={**os.environ, "RAILHUNT_WORKER_START": "spawn"})  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["40", "0"]
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("railhunt: note:"), done.stderr
    assert "<stdin>" in lines[0] and "runs in this process" in lines[0]
    assert "Traceback" not in done.stderr


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forked workers: Linux")
def test_a_program_read_from_standard_input_runs_on_forked_workers(tmp_path):
    """With forked workers (Linux) nothing is imported again: ``python - < study.py`` runs
    on the workers, silently, and gives the same file as in one process."""
    pids = tmp_path / "pids.txt"
    setup = _forked_logging_pids(pids)
    code = _script(tmp_path / "stdin.csv", sleep=0.005, workers=2, task=0.02, samples=8,
                   setup=setup)  # fmt: skip
    done = subprocess.run([sys.executable, "-"], input=code, capture_output=True, text=True,
                          timeout=300, cwd=tmp_path,
                          env={**os.environ, "RAILHUNT_WORKER_START": "fork"})  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["40", "0"]
    assert not done.stderr.strip(), done.stderr
    assert len(set(pids.read_text().split())) >= 2, "the points ran in more than one process"
    (tmp_path / "one.py").write_text(_script(tmp_path / "one.csv", sleep=0.0, workers=1,
                                             task=0.5, samples=8))  # fmt: skip
    one = subprocess.run([sys.executable, "one.py"], capture_output=True, text=True,
                         timeout=300, cwd=tmp_path)  # fmt: skip
    assert one.returncode == 0, one.stderr
    stdin_rows = railhunt.read_results(tmp_path / "stdin.csv").rows
    one_rows = railhunt.read_results(tmp_path / "one.csv").rows
    assert [r["y"] for r in stdin_rows] == [r["y"] for r in one_rows]


def test_a_study_killed_in_the_middle_of_a_task_resumes_to_the_same_file(tmp_path):
    """SIGKILL while a task is being computed: the file holds whole tasks only (the points
    of the task in flight are the only ones lost), and the resumed study's file is
    byte-identical to an uninterrupted run's."""
    samples, per_point, task = 16, 0.02, 0.2  # 80 points in tasks of ~10 points
    ref, part = tmp_path / "ref.csv", tmp_path / "part.csv"
    for name, out, resume in (("ref", ref, False), ("part", part, False),
                              ("resume", part, True)):  # fmt: skip
        (tmp_path / f"{name}.py").write_text(_script(out, sleep=per_point, workers=1,
                                                     task=task, samples=samples,
                                                     resume=resume))  # fmt: skip
    done = subprocess.run([sys.executable, "ref.py"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300)  # fmt: skip
    assert done.returncode == 0, done.stderr
    proc = subprocess.Popen([sys.executable, "part.py"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)  # fmt: skip
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        if part.exists() and len(part.read_text().splitlines()) >= 6:  # header + 2 tasks
            break
        time.sleep(0.01)
    time.sleep(per_point * 3)  # in the middle of the next task
    proc.send_signal(signal.SIGKILL)
    proc.communicate(timeout=60)
    assert proc.returncode == -signal.SIGKILL
    kept = [r["point"] for r in railhunt.read_results(part).rows]
    assert 0 < len(kept) < samples * 5 and kept == list(range(len(kept)))
    lines = part.read_text().splitlines()
    assert len(lines) == 1 + len(kept), "every line a whole point (none torn, none twice)"
    resumed = subprocess.run([sys.executable, "resume.py"], cwd=tmp_path, capture_output=True,
                             text=True, timeout=300)  # fmt: skip
    assert resumed.returncode == 0, resumed.stderr
    assert resumed.stdout.split() == [str(samples * 5 - len(kept)), str(len(kept))]
    assert part.read_bytes() == ref.read_bytes()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forked workers: Linux")
def test_a_study_on_forked_workers_killed_mid_task_resumes_to_the_same_file(tmp_path):
    """SIGKILL of the study's process while 2 forked workers compute: no worker computes
    on, the file holds whole points, each once, and the resumed file is byte-identical to
    an uninterrupted run's."""
    samples, per_point, task = 16, 0.02, 0.1  # 80 points
    pids = tmp_path / "pids.txt"
    setup = _forked_logging_pids(pids)
    ref, part = tmp_path / "ref.csv", tmp_path / "part.csv"
    for name, out, resume in (("ref", ref, False), ("part", part, False),
                              ("resume", part, True)):  # fmt: skip
        (tmp_path / f"{name}.py").write_text(_script(out, sleep=per_point, workers=2,
                                                     task=task, samples=samples,
                                                     resume=resume, setup=setup))  # fmt: skip
    env = {**os.environ, "RAILHUNT_WORKER_START": "fork"}
    done = subprocess.run([sys.executable, "ref.py"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300, env=env)  # fmt: skip
    assert done.returncode == 0, done.stderr
    pids.unlink()
    proc = subprocess.Popen([sys.executable, "part.py"], cwd=tmp_path, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)  # fmt: skip
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        if part.exists() and len(part.read_text().splitlines()) >= 11:
            break
        time.sleep(0.01)
    time.sleep(per_point * 2)  # in the middle of the workers' tasks
    proc.send_signal(signal.SIGKILL)
    proc.communicate(timeout=60)
    assert proc.returncode == -signal.SIGKILL
    workers = {int(line) for line in pids.read_text().split()} - {proc.pid}
    assert workers, "the points ran on forked workers"
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline and any(Path(f"/proc/{w}").exists() for w in workers):
        time.sleep(0.05)
    assert not any(Path(f"/proc/{w}").exists() for w in workers), "a worker computes on"
    kept = [r["point"] for r in railhunt.read_results(part).rows]
    assert 0 < len(kept) < samples * 5 and len(set(kept)) == len(kept)
    assert len(part.read_text().splitlines()) == 1 + len(kept), "every line a whole point"
    resumed = subprocess.run([sys.executable, "resume.py"], cwd=tmp_path, capture_output=True,
                             text=True, timeout=300, env=env)  # fmt: skip
    assert resumed.returncode == 0, resumed.stderr
    assert resumed.stdout.split() == [str(samples * 5 - len(kept)), str(len(kept))]
    assert part.read_bytes() == ref.read_bytes()


def test_the_engine_estimates_the_cost_of_a_point():
    engine = tasks.TaskEngine(StudyOptions(workers=1), None, None, lambda: 10)
    rows = []
    n = engine._probe(lambda i: (time.sleep(0.01), {"point": i})[1], list(range(10)),
                      rows.extend)  # fmt: skip
    assert 2 <= n <= 10 and len(rows) == n
    assert 0.01 <= engine.seconds_per_point < 0.05


def test_a_local_cluster_that_cannot_start_leaves_the_study_to_this_process(
        monkeypatch, capsys, tmp_path):  # fmt: skip
    import railhunt.studies.execute as execute
    import railhunt.studies.forkpool as forkpool

    def broken(n, *args, **kwargs):
        raise OSError("no free port")

    monkeypatch.setattr(execute, "local_client", broken)  # spawned workers
    monkeypatch.setattr(forkpool, "ForkPool", broken)  # forked ones
    monkeypatch.setattr(tasks, "CLUSTER_START_S", 0.0)
    monkeypatch.setattr(tasks, "FORK_START_S", 0.0)

    def slow(x1: float, x2: float, x3: float) -> dict[str, float]:
        time.sleep(0.005)
        return ishigami(x1, x2, x3)

    reference = sensitivity(ishigami, FACTORS, ["y"], samples=8, workers=1)
    r = sensitivity(slow, FACTORS, ["y"], samples=8, workers=2, out=tmp_path / "b.csv")
    assert r.study.computed == 40 and r.indices == reference.indices
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "the local cluster did not start (OSError: no free port)" in err[0]


@pytest.mark.skipif(not sys.platform.startswith("linux") or default_workers() < 2,
                    reason="forked workers: Linux, two cores")  # fmt: skip
def test_a_vehicle_study_on_forked_workers_writes_the_same_file(tmp_path, monkeypatch):
    """A vehicle study of 16 points or more forks its local workers before timing a point
    (they copy this process's compiled code): its file is byte-identical to one process's,
    and the points ran on the cluster."""
    import numpy as np

    from railhunt.studies.forkpool import ForkPool

    started, pids = [], []
    real = ForkPool.__init__

    def spy(self, workers, saturation=2, functions=()):
        started.append((workers, saturation, len(functions)))
        real(self, workers, saturation, functions)
        pids.extend(self.pids())

    monkeypatch.setattr(ForkPool, "__init__", spy)
    monkeypatch.setenv("RAILHUNT_WORKER_START", "fork")
    vehicle = railhunt.Vehicle.paper2019()
    values = {"C_d1": np.linspace(50e3, 600e3, 16)}
    one = railhunt.sweep(vehicle, values, ["linear_critical_speed"], workers=1,
                         out=tmp_path / "one.csv")  # fmt: skip
    assert started == []
    two = railhunt.sweep(vehicle, values, ["linear_critical_speed"], workers=2,
                         out=tmp_path / "two.csv")  # fmt: skip
    assert started == [(2, int(tasks.FORKED_SATURATION), 2)] and len(set(pids)) == 2
    assert two.computed == 16 and not two.lost_reasons
    assert (tmp_path / "one.csv").read_bytes() == (tmp_path / "two.csv").read_bytes()
    assert [r["linear_critical_speed_kmh"] for r in one.rows] == [
        r["linear_critical_speed_kmh"] for r in two.rows]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forked workers: Linux")
def test_forked_workers_write_to_standard_streams_of_their_own(monkeypatch):
    """A forked worker's sys.stdout/sys.stderr are new objects (a copy of the parent's
    could carry a buffer lock another thread held at the fork), on the same descriptors,
    and a worker's warning reaches them."""
    import warnings

    from railhunt.studies.execute import local_client

    monkeypatch.setenv("RAILHUNT_WORKER_START", "fork")

    def streams() -> tuple[int, int, int, int]:
        warnings.warn("a worker's warning", RuntimeWarning, stacklevel=1)
        print("a worker's line", flush=True)
        return id(sys.stdout), id(sys.stderr), sys.stdout.fileno(), sys.stderr.fileno()

    with local_client(1) as client:
        (worker,) = client.run(streams).values()
    assert worker[0] != id(sys.stdout) and worker[1] != id(sys.stderr)
    assert worker[2:] == (sys.stdout.fileno(), sys.stderr.fileno())


@pytest.mark.skipif(not sys.platform.startswith("linux") or default_workers() < 2,
                    reason="forked workers: Linux, two cores")  # fmt: skip
def test_a_study_whose_first_points_all_fail_still_runs_the_rest(monkeypatch):
    """The tasks after the first round are sized by the first point timed; when every first
    point fails (no timing) the rest still runs."""
    monkeypatch.setenv("RAILHUNT_WORKER_START", "fork")
    monkeypatch.setattr(tasks, "FORK_START_S", 0.0)

    def fragile(x1: float, x2: float, x3: float) -> dict[str, float]:
        time.sleep(0.002)
        return ishigami(x1, x2, x3)

    engine = tasks.TaskEngine(StudyOptions(workers=2), None, lambda: None, lambda: 40)
    rows = []

    def task(i):
        if i < 2:
            raise RuntimeError("first points fail")
        return {"point": i, **fragile(0.1 * i, 0.2, 0.3)}

    try:
        lost = engine.run(task, list(range(40)), rows.extend)
    finally:
        engine.close()
    assert engine.forked
    assert sorted(r["point"] for r in rows) == list(range(2, 40))
    assert [item for item, _ in lost] == [0, 1]
    assert engine.worker_evaluation_s > 0
