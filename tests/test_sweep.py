"""Tests of parameter sweeps (railhunt.studies): designs, evaluation, files, resume, Dask."""

from __future__ import annotations

import math
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import railhunt as rh
from railhunt.studies.design import build_design, frequency_speed
from railhunt.studies.store import (
    ResultFileError,
    ResultStore,
    columns_for,
    read_results,
    sidecar_path,
)
from railhunt.studies.sweep import evaluate_point, sweep
from railhunt.vehicle import ParameterError, UnknownParameterError

VEHICLE = rh.Vehicle.paper2019()
#: Cheap points (eigenvalues only, ~10 ms each) for the file and execution tests.
LINEAR = ("linear_critical_speed",)
#: Three yaw-damper settings whose critical speeds the paper's Fig. 10a orders.
CD1 = [20e3, 140e3, 300e3]


@pytest.fixture(scope="module")
def dask_client():
    """A real local Dask cluster: two worker processes, one thread each."""
    pytest.importorskip("distributed")
    from railhunt.studies.execute import local_client
    from railhunt.studies.sweep import warm_up

    warm_up()  # workers read numba's cache, never compile it at the same time
    with local_client(2) as client:
        yield client


@pytest.fixture(scope="module")
def cd1_reference(tmp_path_factory):
    """The C_d1 line with every output, computed in this process."""
    out = tmp_path_factory.mktemp("ref") / "cd1.csv"
    result = sweep(VEHICLE, {"C_d1": CD1}, workers=1, out=out)
    return result, out


# --------------------------------------------------------------------------- designs


def test_lines_vary_one_parameter_at_a_time():
    points = build_design(VEHICLE, {"C_d1": [1e5, 2e5, 3e5], "K_px": [2e7, 4e7]})
    assert [p.line for p in points] == ["C_d1"] * 3 + ["K_px"] * 2
    assert [p.index for p in points] == list(range(5))
    for p in points[:3]:
        assert p.values["K_px"] == VEHICLE.K_px
    assert [p.values["K_px"] for p in points[3:]] == [2e7, 4e7]
    assert all(p.values["C_d1"] == VEHICLE.C_d1 for p in points[3:])


def test_a_tie_needs_its_leader_varied():
    with pytest.raises(ValueError, match="f11 is not varied"):
        build_design(VEHICLE, {"C_d1": [1e5]}, ties={"f22": "f11"})


def test_grid_is_the_full_product_and_ties_follow():
    points = build_design(VEHICLE, {"C_d1": [1e5, 2e5], "f11": [4e6, 6e6, 8e6]}, design="grid",
                          ties={"f22": "f11", "f23": ("f11", 0.5)})  # fmt: skip
    assert len(points) == 6
    assert {(p.values["C_d1"], p.values["f11"]) for p in points} == {
        (c, f) for c in (1e5, 2e5) for f in (4e6, 6e6, 8e6)}
    for p in points:
        assert p.values["f22"] == p.values["f11"]
        assert p.values["f23"] == 0.5 * p.values["f11"]


@settings(max_examples=30, deadline=None)
@given(n=st.integers(1, 40), seed=st.integers(0, 2**31 - 1))
def test_latin_hypercube_uses_every_stratum_once(n, seed):
    ranges = {"C_d1": (1e5, 5e5), "mu": (0.05, 0.5)}
    points = build_design(VEHICLE, ranges, design="lhs", samples=n, seed=seed)
    assert len(points) == n
    for name, (lo, hi) in ranges.items():
        u = np.array([(p.values[name] - lo) / (hi - lo) for p in points])
        assert np.all((u >= 0) & (u <= 1))
        assert sorted(np.minimum(np.floor(u * n), n - 1).astype(int)) == list(range(n))
    again = build_design(VEHICLE, ranges, design="lhs", samples=n, seed=seed)
    assert [p.values for p in again] == [p.values for p in points]


def test_random_design_is_reproducible_and_in_range():
    a = build_design(VEHICLE, {"mu": (0.1, 0.4)}, design="random", samples=50, seed=7)
    b = build_design(VEHICLE, {"mu": (0.1, 0.4)}, design="random", samples=50, seed=7)
    c = build_design(VEHICLE, {"mu": (0.1, 0.4)}, design="random", samples=50, seed=8)
    mu = [p.values["mu"] for p in a]
    assert mu == [p.values["mu"] for p in b] != [p.values["mu"] for p in c]
    assert 0.1 <= min(mu) and max(mu) <= 0.4


@settings(max_examples=40, deadline=None)
@given(value=st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.just(-1.0)))
def test_invalid_values_name_the_parameter(value):
    if math.isfinite(value) and 0 < value <= 1.5:
        return  # a valid friction coefficient
    with pytest.raises(ParameterError, match="mu"):
        build_design(VEHICLE, {"mu": [0.3, value]})


def test_design_errors_are_clear():
    with pytest.raises(UnknownParameterError, match="C_d1"):
        build_design(VEHICLE, {"Cd1": [1e5]})
    with pytest.raises(ValueError, match="f22 is both varied and tied"):
        build_design(VEHICLE, {"f22": [1e6]}, ties={"f22": "f11"})
    with pytest.raises(ValueError, match="samples"):
        build_design(VEHICLE, {"mu": (0.1, 0.2)}, design="lhs")
    with pytest.raises(ValueError, match="design = 'sobol'"):
        build_design(VEHICLE, {"mu": [0.1]}, design="sobol")
    with pytest.raises(ValueError, match="low must be below high"):
        build_design(VEHICLE, {"mu": (0.3, 0.2)}, design="random", samples=3)
    with pytest.raises(ValueError, match="outputs"):
        sweep(VEHICLE, {"mu": [0.1]}, outputs=("critical_speed", "max_speed"), workers=1)


def test_frequency_speed_follows_the_paper():
    points = build_design(VEHICLE, {"C_d1": [1e5], "K_d": [5e6], "mu": [0.2]})
    assert [frequency_speed(p, ["C_d1", "K_d", "mu"], None) for p in points] == [300, 300, 350]
    grid = build_design(VEHICLE, {"C_d1": [1e5], "C_d2": [2e4]}, design="grid")
    assert frequency_speed(grid[0], ["C_d1", "C_d2"], None) == 300
    assert frequency_speed(grid[0], ["C_d1", "C_d2"], 250.0) == 250


# --------------------------------------------------------------------------- evaluation


def test_row_equals_the_analyses_run_directly(cd1_reference):
    """A sweep row is exactly what critical_speed, linear_critical_speed and
    hunting_frequency return for the changed vehicle (no second copy of the analysis)."""
    result, _ = cd1_reference
    row = result.rows[1]
    v = VEHICLE.replace(C_d1=CD1[1])
    assert row["critical_speed_kmh"] == rh.critical_speed(v).speed_kmh
    lin = rh.linear_critical_speed(v)
    assert row["linear_critical_speed_kmh"] == lin.speed_kmh
    assert row["linear_frequency_hz"] == lin.frequency_hz
    hf = rh.hunting_frequency(v, 300.0, excitation=rh.SingleDefect())
    assert row["hunting_frequency_hz"] == hf.frequency_hz
    assert row["frequency_source"] == hf.source
    assert row["frequency_speed_kmh"] == 300.0 and row["status"] == "ok"


def test_yaw_damper_line_follows_fig10a(cd1_reference):
    """Fig. 10a: V_cr rises with C_d1; the hunting frequency at 300 km/h is a limit
    cycle's while V_cr < 300 km/h and the eigenvalue's once V_cr > 300 km/h (the jump), as
    the paper's Sec. 3.3 defines it (the frequency run uses the search's defect)."""
    result, _ = cd1_reference
    v_cr = result.column("critical_speed_kmh")
    assert np.all(np.diff(v_cr) > 10), v_cr
    assert v_cr[0] < 300 < v_cr[-1]
    assert result.column("frequency_source") == ["limit-cycle", "limit-cycle", "eigenvalue"]
    assert [s == "limit-cycle" for s in result.column("frequency_source")] == list(v_cr < 300)
    # The nonlinear critical speed never exceeds the Hopf point.
    assert np.all(v_cr <= result.column("linear_critical_speed_kmh") + 1.0)


def test_unbracketed_point_is_reported_not_raised():
    point = build_design(VEHICLE, {"f11": [2e6]}, ties={"f22": "f11"})[0]
    row = evaluate_point(point, VEHICLE, ("critical_speed",))
    assert row["status"] == "no-critical-speed"
    assert math.isnan(row["critical_speed_kmh"])
    assert "stable at every speed" in row["message"]


def test_failing_point_is_recorded(monkeypatch):
    import railhunt.analysis.linear as linear

    def broken(*args, **kwargs):
        raise RuntimeError("eigen solver exploded")

    monkeypatch.setattr(linear, "linear_critical_speed", broken)
    point = build_design(VEHICLE, {"mu": [0.2]})[0]
    row = evaluate_point(point, VEHICLE, LINEAR)
    assert row["status"] == "failed" and "eigen solver exploded" in row["message"]


# --------------------------------------------------------------------------- files


def test_file_round_trip_is_exact(cd1_reference):
    result, out = cd1_reference
    back = read_results(out)
    assert back.rows == result.rows  # repr() floats: exact
    assert back.columns == columns_for(["C_d1"], rh_outputs())
    assert back.lines == ["C_d1"] and back.parameters == ["C_d1"]
    assert back.meta["points"] == 3 and sidecar_path(out).exists()


def rh_outputs():
    from railhunt.studies.store import OUTPUTS

    return OUTPUTS


def test_resume_computes_only_missing_points(tmp_path):
    values = {"mu": np.linspace(0.1, 0.5, 6)}
    full = sweep(VEHICLE, values, LINEAR, workers=1, out=tmp_path / "full.csv")
    # An interrupted file: header, two complete rows and a torn third line.
    part = tmp_path / "part.csv"
    shutil.copy(sidecar_path(tmp_path / "full.csv"), sidecar_path(part))
    lines = (tmp_path / "full.csv").read_text().splitlines(keepends=True)
    part.write_text("".join(lines[:3]) + lines[3][:9])
    assert len(read_results(part)) == 2  # the torn line is not a point
    calls = []
    resumed = sweep(VEHICLE, values, LINEAR, workers=1, out=part, resume=True,
                    progress=lambda done, total: calls.append((done, total)))  # fmt: skip
    assert (resumed.resumed, resumed.computed) == (2, 4)
    assert calls == [(3, 6), (4, 6), (5, 6), (6, 6)]
    assert part.read_bytes() == (tmp_path / "full.csv").read_bytes()
    again = sweep(VEHICLE, values, LINEAR, workers=1, out=part, resume=True)
    assert again.computed == 0 and again.rows == full.rows


def test_resume_refuses_a_different_study(tmp_path):
    out = tmp_path / "r.csv"
    sweep(VEHICLE, {"mu": [0.2, 0.3]}, LINEAR, workers=1, out=out)
    with pytest.raises(ResultFileError, match="differs in: parameters"):
        sweep(VEHICLE, {"mu": [0.2, 0.4]}, LINEAR, workers=1, out=out, resume=True)
    with pytest.raises(ResultFileError, match="exists"):
        sweep(VEHICLE, {"mu": [0.2, 0.3]}, LINEAR, workers=1, out=out)


def test_store_never_writes_a_point_twice(tmp_path):
    meta = {"columns": columns_for(["mu"], LINEAR), "points": 2}
    store = ResultStore(tmp_path / "s.csv", meta)
    row = {"point": 0, "line": "mu", "mu": 0.2, "linear_critical_speed_kmh": 400.0,
           "linear_frequency_hz": 4.0, "status": "ok", "message": ""}  # fmt: skip
    store.write(row)
    store.write(row)
    store.close(complete=False)
    assert len((tmp_path / "s.csv").read_text().splitlines()) == 2


@pytest.mark.parametrize("design", ["random", "lhs"])
def test_sampled_study_round_trips_and_resumes(tmp_path, design):
    """Sampled values (NumPy scalars) are written as plain floats and read back exactly;
    an interrupted sampled study resumes with the same points (same seed)."""
    ranges = {"mu": (0.1, 0.4), "K_px": (2e7, 6e7)}
    out = tmp_path / f"{design}.csv"
    full = sweep(VEHICLE, ranges, LINEAR, design=design, samples=5, seed=3, workers=1, out=out)
    assert read_results(out).rows == full.rows
    lines = out.read_text().splitlines(keepends=True)
    out.write_text("".join(lines[:3]))  # two points survived an interruption
    again = sweep(VEHICLE, ranges, LINEAR, design=design, samples=5, seed=3, workers=1, out=out,
                  resume=True)  # fmt: skip
    assert (again.resumed, again.computed) == (2, 3)
    assert again.rows == full.rows


def test_multiline_message_stays_one_row(tmp_path):
    meta = {"columns": columns_for(["mu"], LINEAR), "points": 2}
    store = ResultStore(tmp_path / "m.csv", meta)
    store.write({"point": 0, "line": "mu", "mu": np.float64(0.2),
                 "linear_critical_speed_kmh": math.nan, "linear_frequency_hz": math.nan,
                 "status": "failed", "message": "TypingError: line 1\nline 2"})  # fmt: skip
    store.close(complete=False)
    text = (tmp_path / "m.csv").read_text()
    assert len(text.splitlines()) == 2 and "np.float64" not in text
    assert read_results(tmp_path / "m.csv").rows[0]["message"] == "TypingError: line 1 line 2"


def test_second_writer_is_refused(tmp_path):
    meta = {"columns": columns_for(["mu"], LINEAR), "points": 2}
    first = ResultStore(tmp_path / "w.csv", meta)
    with pytest.raises(ResultFileError, match="another sweep is writing"):
        ResultStore(tmp_path / "w.csv", meta, resume=True)
    first.close(complete=False)


def test_torn_sidecar_is_tolerated_by_readers(tmp_path):
    out = tmp_path / "t.csv"
    sweep(VEHICLE, {"mu": [0.2, 0.3]}, LINEAR, workers=1, out=out)
    sidecar_path(out).write_text('{"columns": [')  # killed while writing
    assert len(read_results(out)) == 2
    with pytest.raises(ResultFileError, match="missing or unreadable"):
        sweep(VEHICLE, {"mu": [0.2, 0.3]}, LINEAR, workers=1, out=out, resume=True)


def test_unreachable_scheduler_leaves_no_stub(tmp_path, monkeypatch):
    """A study that fails before its first point (here: the scheduler cannot be reached,
    which Dask reports after its 30 s connect timeout) leaves no file to 'resume'."""
    import railhunt.studies.runner as runner_module  # the study loop sweep runs on

    def unreachable(*args, **kwargs):
        raise OSError("Timed out trying to connect to tcp://10.0.0.5:8786 after 30 s")

    monkeypatch.setattr(runner_module, "open_client", unreachable)
    out = tmp_path / "s.csv"
    with pytest.raises(OSError, match="Timed out"):
        sweep(VEHICLE, {"mu": [0.2]}, LINEAR, scheduler="tcp://10.0.0.5:8786", out=out)
    assert not out.exists() and not sidecar_path(out).exists()


def test_parquet_resume(tmp_path):
    pytest.importorskip("pyarrow")
    values = {"mu": [0.2, 0.3, 0.4]}
    out = tmp_path / "p.parquet"
    full = sweep(VEHICLE, values, LINEAR, workers=1, out=out)
    again = sweep(VEHICLE, values, LINEAR, workers=1, out=out, resume=True)
    assert again.computed == 0 and again.rows == full.rows
    assert read_results(out).rows == full.rows


def test_parquet_matches_csv(tmp_path):
    pytest.importorskip("pyarrow")
    values = {"K_px": [2e7, 5e7]}
    csv_result = sweep(VEHICLE, values, LINEAR, workers=1, out=tmp_path / "a.csv")
    pq_result = sweep(VEHICLE, values, LINEAR, workers=1, out=tmp_path / "a.parquet")
    assert not (tmp_path / "a.parquet.journal.csv").exists()
    assert read_results(tmp_path / "a.parquet").rows == csv_result.rows == pq_result.rows


# --------------------------------------------------------------------------- Dask


def test_dask_cluster_gives_identical_numbers(dask_client, cd1_reference, tmp_path):
    result, out = cd1_reference
    on_dask = sweep(VEHICLE, {"C_d1": CD1}, client=dask_client, out=tmp_path / "d.csv")
    assert on_dask.rows == result.rows
    assert (tmp_path / "d.csv").read_bytes() == out.read_bytes()


def test_lost_worker_is_recovered(dask_client, tmp_path):
    """Kill a worker process in the middle of a sweep: Dask reruns its tasks; every
    point is in the file exactly once and equals the serial result."""
    values = {"mu": np.linspace(0.1, 0.5, 8)}
    outputs = ("critical_speed",)
    pids = dask_client.run(os.getpid)  # worker address -> process id
    killed = []

    def kill_once(done, total):
        if killed:
            return
        busy = [addr for addr, keys in dask_client.processing().items() if keys]
        if busy:  # a worker with a task in hand: its task must be rerun elsewhere
            os.kill(pids[busy[0]], signal.SIGKILL)
            killed.append(busy[0])
    out = tmp_path / "lost.csv"
    res = sweep(VEHICLE, values, outputs, client=dask_client, out=out, progress=kill_once)
    assert killed
    serial = sweep(VEHICLE, values, outputs, workers=1)
    points = [r["point"] for r in read_results(out).rows]
    assert points == list(range(8))
    assert len(out.read_text().splitlines()) == 9  # header + each point once
    assert res.rows == serial.rows
    dask_client.wait_for_workers(2, timeout=60)
    # the worker the nanny restarted ignores a terminal's Ctrl-C too (dask_setup preload)
    handlers = dask_client.run(lambda: signal.getsignal(signal.SIGINT))
    assert killed[0] not in handlers and set(handlers.values()) == {signal.SIG_IGN}


def _cli(*args: str) -> list[str]:
    return [sys.executable, "-c", "from railhunt.cli import main; main()", *args]


MU_LINE = {"mu": np.linspace(0.1, 0.5, 20)}


@pytest.fixture(scope="module")
def mu_reference():
    return sweep(VEHICLE, MU_LINE, ("critical_speed",), workers=1)


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGINT])
def test_interrupted_cli_sweep_resumes(tmp_path, sig, mu_reference):
    """Ctrl-C or a killed process: the file keeps the finished points; --resume adds only
    the missing ones, and the result equals an uninterrupted run."""
    out = tmp_path / "k.csv"
    args = ["sweep", "mu", "--from", "0.1", "--to", "0.5", "--num", "20", "--outputs",
            "critical_speed", "--workers", "1", "--out", str(out)]  # fmt: skip
    # A shell's background job starts with SIGINT ignored, and so would the child: give it
    # the default disposition, as at a terminal, so that Python raises KeyboardInterrupt.
    proc = subprocess.Popen(_cli(*args), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        if out.exists() and len(out.read_text().splitlines()) >= 3:  # header + 2 points
            break
        time.sleep(0.05)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    done = read_results(out)
    assert 2 <= len(done) < 20, "interrupted in the middle"
    assert {r["status"] for r in done.rows} == {"ok"}, "the interrupted point is not 'failed'"
    if sig == signal.SIGINT:
        assert proc.returncode == 130
        assert b"--resume" in err
    finished = subprocess.run(_cli(*args, "--resume", "--json"), capture_output=True,
                              timeout=300)  # fmt: skip
    assert finished.returncode == 0, finished.stderr
    final = read_results(out)
    assert [r["point"] for r in final.rows] == list(range(20))
    assert len(out.read_text().splitlines()) == 21  # header + each point once
    assert final.rows == mu_reference.rows


def test_frequency_source_follows_the_critical_speed():
    """Sec. 3.3: eigenvalue below V_cr, limit cycle above. With a soft K_px (10 MN/m,
    V_cr = 329 km/h) an 8 mm release decays at 350 km/h although the defect hunts there;
    the sweep's frequency run over the defect gives the limit cycle."""
    point = build_design(VEHICLE, {"K_px": [10e6]})[0]
    row = evaluate_point(point, VEHICLE, ("critical_speed", "hunting_frequency"), 350.0)
    assert row["critical_speed_kmh"] < 350
    assert row["frequency_source"] == "limit-cycle" and 4.5 < row["hunting_frequency_hz"] < 6
    released = rh.hunting_frequency(VEHICLE.replace(K_px=10e6), 350.0, initial_amplitude=8e-3)
    assert released.source == "eigenvalue"


def test_table1_frequency_speeds_follow_the_sweep_rule():
    """The speeds Table 1 lists per parameter are the ones a sweep line uses by default
    (one rule: 300 km/h for the yaw-damper parameters, 350 km/h otherwise)."""
    from railhunt.studies.sections import load_table1

    table = load_table1()
    points = build_design(VEHICLE, {n: [getattr(VEHICLE, n)] for n in table})
    for p in points:
        assert frequency_speed(p, list(table), None) == table[p.line].frequency_speed_kmh


def test_ctrl_c_on_a_local_cluster_is_one_clean_message(tmp_path, mu_reference):
    """A terminal's Ctrl-C reaches the whole process group, Dask workers included: the
    command says once how to resume (no worker tracebacks), exits 130, and --resume then
    completes the study with the numbers of an uninterrupted run."""
    out = tmp_path / "c.csv"
    args = ["sweep", "mu", "--from", "0.1", "--to", "0.5", "--num", "20", "--outputs",
            "critical_speed", "--out", str(out)]  # fmt: skip
    proc = subprocess.Popen(_cli(*args, "--workers", "2"), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        if out.exists() and len(out.read_text().splitlines()) >= 3:
            break
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGINT)  # what a terminal does
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130
    text = err.decode()
    ours = [line for line in text.splitlines() if line.startswith("railhunt:")]
    assert len(ours) == 1 and "--resume" in ours[0], text
    assert "Traceback" not in text and "KeyboardInterrupt" not in text, text
    assert 2 <= len(read_results(out)) < 20
    finished = subprocess.run(_cli(*args, "--workers", "1", "--resume"), capture_output=True,
                              timeout=300)  # fmt: skip
    assert finished.returncode == 0, finished.stderr
    assert read_results(out).rows == mu_reference.rows


def test_a_task_that_keeps_killing_its_worker_is_lost_not_written():
    """Dask reruns the tasks of a dead worker; a task that kills every worker it runs on is
    given up (KilledWorker) and reported as lost, while the other items finish. Two ways
    the others were lost once (CI failures): queued behind the killer on its worker (a
    local worker now holds only the task it runs), and finished on a worker that died
    before their result was fetched (run_tasks now waits for the recomputation). Its own
    cluster: after four quick deaths Dask's restarts may still be settling."""
    pytest.importorskip("distributed")
    from railhunt.studies.execute import local_client, run_tasks

    def task(item):  # a closure: shipped to the workers by value
        if item == 1:
            os._exit(1)
        return {"point": item}

    done = []
    with local_client(2) as client:
        lost = run_tasks(task, [0, 1, 2], done.append, client=client)
    assert sorted(r["point"] for r in done) == [0, 2]
    assert [item for item, _ in lost] == [1]
    assert "KilledWorker" in lost[0][1]


def slow_ishigami(x1: float, x2: float, x3: float) -> dict[str, float]:
    """Ishigami at about a millisecond a point (a cheap surrogate model)."""
    time.sleep(0.001)
    return {"y": math.sin(x1) + 7.0 * math.sin(x2) ** 2 + 0.1 * x3**4 * math.sin(x1)}


def test_cheap_points_in_tasks_on_dask_give_the_same_file(dask_client, tmp_path):
    """A study of cheap points on a Dask cluster, in tasks of several points: the same
    indices and a byte-identical file as in this process."""
    pytest.importorskip("SALib")
    import cloudpickle

    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    factors = {k: (-math.pi, math.pi) for k in ("x1", "x2", "x3")}
    here = rh.sensitivity(slow_ishigami, factors, ["y"], samples=64, workers=1,
                          out=tmp_path / "here.csv")  # fmt: skip
    busy = []

    def watch(done: int, total: int) -> None:
        busy.append(any(dask_client.processing().values()))

    run = rh.StudyOptions(client=dask_client, out=tmp_path / "dask.csv", task_seconds=0.01,
                          progress=watch)  # fmt: skip
    there = rh.sensitivity(slow_ishigami, factors, ["y"], samples=64, run=run)
    assert any(busy), "no task ran on the cluster"
    assert there.indices == here.indices
    assert (tmp_path / "dask.csv").read_bytes() == (tmp_path / "here.csv").read_bytes()
