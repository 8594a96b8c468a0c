"""Benchmark rows of the study machinery: each study as a user runs it, beside its floor.

For each case the table gives the study's wall time, and beside it the floor: the
evaluations alone (the same points, one after the other in this process, divided by the
workers) and, for the plain functions, SALib alone / pymoo alone on the same function.
The machinery per point is (study - evaluations) / points.

Cases: Sobol' indices of the Ishigami function (N = 2048, 10 240 points, default workers);
NSGA-II on ZDT1 (population 40, 100 generations, 4000 designs); Sobol' N = 64 of the
linear critical speed over the seven Table 1 parameters on 2 workers (576 points); a sweep
of 24 points with every output on 1 and on 2 workers. Every study writes its results file
(a temporary folder), as a user's would; the compiled code is loaded first, cluster
start-up is part of the time.

It uses only public API that also exists before the study machinery was reworked, so that
the same script measures the old code::

    git worktree add --detach /work/wt/baseline 4b6e62f
    PYTHONPATH=/work/wt/baseline/src python benchmarks/study_machinery.py

Runnable alone, or as ``python benchmarks/run.py --only machinery``.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

import railhunt

#: Targets (s, or a ratio for the sweep).
ISHIGAMI_TARGET_S = 3.0
ZDT1_TARGET_S = 5.0
SWEEP_SPEEDUP_TARGET = 1.8
PER_POINT_TARGET_S = 0.3e-3
PER_DESIGN_TARGET_S = 1e-3


def ishigami(x1: float, x2: float, x3: float) -> dict[str, float]:
    """The Ishigami function (a = 7, b = 0.1)."""
    return {"y": math.sin(x1) + 7.0 * math.sin(x2) ** 2 + 0.1 * x3**4 * math.sin(x1)}


def zdt1(**x: float) -> dict[str, float]:
    """ZDT1 of 5 variables in [0, 1]."""
    v = [x[f"x{k}"] for k in range(5)]
    g = 1.0 + 9.0 * sum(v[1:]) / 4.0
    return {"f1": v[0], "f2": g * (1.0 - math.sqrt(v[0] / g))}


ISHIGAMI_FACTORS = {k: (-math.pi, math.pi) for k in ("x1", "x2", "x3")}
ZDT_FACTORS = {f"x{k}": (0.0, 1.0) for k in range(5)}


def _timed(fn: Any) -> tuple[float, Any]:
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def ishigami_case() -> dict[str, Any]:
    """railhunt's Sobol study of Ishigami, SALib alone, the evaluations alone."""
    from SALib.analyze import sobol as sobol_analyze
    from SALib.sample import sobol as sobol_sample

    problem = {"num_vars": 3, "names": list(ISHIGAMI_FACTORS),
               "bounds": [list(b) for b in ISHIGAMI_FACTORS.values()]}  # fmt: skip
    x = sobol_sample.sample(problem, 2048, calc_second_order=False, seed=0)
    t_eval, _ = _timed(lambda: [ishigami(*row) for row in x])

    def salib() -> object:
        xs = sobol_sample.sample(problem, 2048, calc_second_order=False, seed=0)
        y = np.array([ishigami(*row)["y"] for row in xs])
        return sobol_analyze.analyze(problem, y, calc_second_order=False, seed=0)

    t_salib, _ = _timed(salib)
    with tempfile.TemporaryDirectory() as tmp:
        t_study, r = _timed(lambda: railhunt.sensitivity(
            ishigami, ISHIGAMI_FACTORS, ["y"], samples=2048, seed=0,
            out=Path(tmp) / "ishigami.csv"))  # fmt: skip
    return {"study": t_study, "evaluations": t_eval, "library": t_salib, "points": r.points}


def zdt1_case() -> dict[str, Any]:
    """railhunt's NSGA-II on ZDT1, pymoo alone, the evaluations alone."""
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import ElementwiseProblem
    from pymoo.optimize import minimize

    class ZDT1(ElementwiseProblem):
        def __init__(self) -> None:
            super().__init__(n_var=5, n_obj=2, xl=np.zeros(5), xu=np.ones(5))

        def _evaluate(self, x: np.ndarray, out: dict, *args: Any, **kwargs: Any) -> None:
            f = zdt1(**{f"x{k}": float(v) for k, v in enumerate(x)})
            out["F"] = [f["f1"], f["f2"]]

    t_pymoo, _ = _timed(lambda: minimize(ZDT1(), NSGA2(pop_size=40), ("n_gen", 100), seed=0,
                                         verbose=False))  # fmt: skip
    xs = np.random.default_rng(0).random((4000, 5))
    t_eval, _ = _timed(lambda: [zdt1(**{f"x{k}": float(v) for k, v in enumerate(x)})
                                for x in xs])  # fmt: skip
    with tempfile.TemporaryDirectory() as tmp:
        t_study, r = _timed(lambda: railhunt.optimize(
            zdt1, ZDT_FACTORS, ["min f1", "min f2"], population=40, generations=100, seed=0,
            out=Path(tmp) / "zdt1.csv"))  # fmt: skip
    timings = getattr(r, "timings", None) or {}
    return {"study": t_study, "evaluations": t_eval, "library": t_pymoo,
            "points": len(r.evaluated), "pymoo_in_study": timings.get("pymoo_s")}  # fmt: skip


def table1_factors() -> dict[str, tuple[float, float]]:
    """The seven Table 1 parameters over their whole ranges (SI)."""
    return {k: (p.boundaries[0], p.boundaries[-1]) for k, p in railhunt.load_table1().items()}


def linear_sobol_case(workers: int = 2) -> dict[str, Any]:
    """Sobol N = 64 of the linear critical speed over Table 1 on ``workers`` workers, and
    the same 576 points evaluated one after the other in this process."""
    from SALib.sample import sobol as sobol_sample

    from railhunt.studies.sweep import warm_up

    warm_up()
    vehicle = railhunt.Vehicle.paper2019()
    factors = table1_factors()
    problem = {"num_vars": len(factors), "names": list(factors),
               "bounds": [list(b) for b in factors.values()]}  # fmt: skip
    x = sobol_sample.sample(problem, 64, calc_second_order=False, seed=0)

    def evaluate_all() -> None:
        for row in x:
            values = dict(zip(factors, map(float, row), strict=True))
            values["f22"] = values["f11"]
            railhunt.linear_critical_speed(vehicle.replace(**values))

    t_serial, _ = _timed(evaluate_all)
    with tempfile.TemporaryDirectory() as tmp, _tail_spy() as tail:
        t_study, r = _timed(lambda: railhunt.sensitivity(
            vehicle, factors, ["linear_critical_speed_kmh"], samples=64, seed=0,
            ties={"f22": "f11"}, workers=workers, out=Path(tmp) / "sobol.csv"))  # fmt: skip
    return {"study": t_study, "evaluations": t_serial / workers, "serial": t_serial,
            "points": r.points, "workers": workers,
            "in_study": getattr(r.study, "evaluation_s", None), "tail": tail[0]}  # fmt: skip


SWEEP_STUDY = {"C_d1": np.linspace(50e3, 600e3, 12), "K_px": np.linspace(10e6, 80e6, 12)}


def sweep_case(workers: int) -> dict[str, Any]:
    """A 24-point sweep with every output on ``workers`` local workers (cluster start
    included), and its evaluations alone (one after the other, in this process)."""
    from railhunt.studies.design import build_design, frequency_speed
    from railhunt.studies.sweep import evaluate_point, warm_up

    warm_up()
    vehicle = railhunt.Vehicle.paper2019()
    points = build_design(vehicle, SWEEP_STUDY)
    names = list(SWEEP_STUDY)
    t_serial, _ = _timed(lambda: [evaluate_point(p, vehicle, frequency_speed_kmh=frequency_speed(
        p, names, None)) for p in points])  # fmt: skip
    with tempfile.TemporaryDirectory() as tmp, _tail_spy() as tail:
        t_study, r = _timed(lambda: railhunt.sweep(vehicle, SWEEP_STUDY, workers=workers,
                                                   out=Path(tmp) / "sweep.csv"))  # fmt: skip
    return {"study": t_study, "evaluations": t_serial / workers, "serial": t_serial,
            "points": len(r.rows), "workers": workers,
            "in_study": getattr(r, "evaluation_s", None), "tail": tail[0]}  # fmt: skip


@contextlib.contextmanager
def _tail_spy() -> Any:
    """Sum the forked workers' tail (``ForkPool.tail_s``: time a worker stood idle at the
    end with nothing left to give it while another still computed) into ``[seconds]``, or
    ``[None]`` for a version without that pool."""
    try:
        from railhunt.studies.forkpool import ForkPool
    except ImportError:
        yield [None]
        return
    tail = [0.0]
    close = ForkPool.close

    def spied(self: Any, *args: Any, **kwargs: Any) -> None:
        tail[0] += getattr(self, "tail_s", 0.0)
        self.tail_s = 0.0
        close(self, *args, **kwargs)

    ForkPool.close = spied  # type: ignore[method-assign]
    try:
        yield tail
    finally:
        ForkPool.close = close  # type: ignore[method-assign]


def _fmt(seconds: float | None) -> str:
    if seconds is None or not math.isfinite(seconds):
        return "-"
    return f"{seconds * 1e3:.1f} ms" if seconds < 1.0 else f"{seconds:.2f} s"


def machinery_rows() -> list[tuple[str, str, str, str, str]]:
    """The table: (case, study, evaluations alone, library alone, target and verdict)."""
    rows = []
    ish = ishigami_case()
    per = (ish["study"] - ish["evaluations"]) / ish["points"]
    rows.append(("Ishigami Sobol, N=2048 (10 240 points, default workers)", _fmt(ish["study"]),
                 _fmt(ish["evaluations"]), f"SALib {_fmt(ish['library'])}",
                 _verdict(ish["study"], ISHIGAMI_TARGET_S)))  # fmt: skip
    rows.append(("  machinery per point", _fmt(per), "", "",
                 _verdict(per, PER_POINT_TARGET_S)))  # fmt: skip
    zdt = zdt1_case()
    per = (zdt["study"] - zdt["evaluations"]) / zdt["points"]
    rows.append(("ZDT1 NSGA-II, pop 40 x 100 gen (4000 designs)", _fmt(zdt["study"]),
                 _fmt(zdt["evaluations"]), f"pymoo {_fmt(zdt['library'])}"
                 + (f" (in the study {_fmt(zdt['pymoo_in_study'])})"
                    if zdt["pymoo_in_study"] is not None else ""),
                 _verdict(zdt["study"], ZDT1_TARGET_S)))  # fmt: skip
    rows.append(("  machinery per design", _fmt(per), "", "",
                 _verdict(per, PER_DESIGN_TARGET_S)))  # fmt: skip
    lin = linear_sobol_case(2)
    target = 1.3 * lin["evaluations"] + 3.0
    per = (lin["study"] - lin["evaluations"]) / lin["points"]
    rows.append((f"Sobol N=64, linear critical speed, Table 1 ({lin['points']} points, 2 "
                 "workers)", _fmt(lin["study"]),
                 f"{_fmt(lin['evaluations'])} (serial {_fmt(lin['serial'])} / 2)", "",
                 _verdict(lin["study"], target)))  # fmt: skip
    rows.append(("  machinery per point (against the evaluations alone)", _fmt(per), "", "",
                 "-"))  # fmt: skip
    rows.extend(_machinery_row(lin))
    one, two = sweep_case(1), sweep_case(2)
    for case in (one, two):
        per = (case["study"] - case["evaluations"]) / case["points"]
        rows.append((f"sweep of 24 points, every output, {case['workers']} worker(s)",
                     _fmt(case["study"]), f"{_fmt(case['evaluations'])} (serial "
                     f"{_fmt(case['serial'])} / {case['workers']})",
                     f"machinery {_fmt(per)}/point", "-"))  # fmt: skip
        rows.extend(_machinery_row(case))
    speedup = one["study"] / two["study"]
    rows.append(("  2 workers against 1", f"{speedup:.2f}x", "", "",
                 "pass" if speedup >= SWEEP_SPEEDUP_TARGET else
                 ("FAIL (not slower)" if speedup >= 1.0 else "FAIL")))  # fmt: skip
    return rows


def _machinery_row(case: dict[str, Any]) -> list[tuple[str, str, str, str, str]]:
    """Machinery per point against the study's own evaluation time: the wall time less the
    time its processes spent evaluating (``evaluation_s``, summed over them) shared out over
    the workers. Two processes on two cores each evaluate a few per cent slower than one
    alone (shared caches and clock); that is the evaluations' cost, not the machinery's.
    A second row sets aside the forked workers' tail as well: at the end one worker has
    nothing left while the other finishes its last point (0.2-0.75 s for the sweep), which
    the points' granularity sets, not the machinery."""
    if case["in_study"] is None:  # a version that does not measure it (before 0.12.0)
        return [("  machinery per point (study - its evaluations / workers)", "-", "", "",
                 "-")]  # fmt: skip
    per = (case["study"] - case["in_study"] / case["workers"]) / case["points"]
    rows = [(f"  machinery per point (study - its evaluations {_fmt(case['in_study'])} / "
             f"{case['workers']})", _fmt(per), "", "", _verdict(per, PER_POINT_TARGET_S))]
    if case.get("tail"):
        per = ((case["study"] - (case["in_study"] + case["tail"]) / case["workers"])
               / case["points"])  # fmt: skip
        rows.append((f"  the same, the tail aside (workers idle at the end "
                     f"{_fmt(case['tail'])} / {case['workers']})", _fmt(per), "", "",
                     _verdict(per, PER_POINT_TARGET_S)))  # fmt: skip
    return rows


def _verdict(value: float, target: float) -> str:
    return f"<= {_fmt(target)}: " + ("pass" if value <= target else "FAIL")


def print_rows(rows: list[tuple[str, str, str, str, str]]) -> None:
    headers = ("case", "study", "evaluations alone", "library alone", "target")
    widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(headers)]
    line = "  ".join(h.ljust(w) for h, w in zip(headers, widths, strict=True))
    print(line)
    print("-" * len(line))
    for r in rows:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)))


def main() -> int:
    load = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    print(f"railhunt {railhunt.__version__} from {Path(railhunt.__file__).parent}, Python "
          f"{sys.version.split()[0]}, {os.cpu_count()} cores, load average "
          f"{load[0]:.2f} {load[1]:.2f} {load[2]:.2f}\n")  # fmt: skip
    print_rows(machinery_rows())
    load = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    print(f"\nload average at the end {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
