"""Benchmark rows of the per-point contact mechanics against the centred model.

The baseline is ``s1002_uic60_table`` (the paper's heuristic law on the centred
coefficients, S1002/UIC60 1:40 tabulated geometry); the new model is the same vehicle with
per-point mechanics (``s1002_uic60_per_point``: the same heuristic law; Polach's; Kalker's
exact theory tabulated when its table is built). Both are timed in one run, alternately,
and the minima over the repeats are compared (the targets: at most 1.5 times the
baseline; the rhs is timed as the least of many short runs of 1000 calls, which a busy
machine disturbs least). Run alone with ``python benchmarks/per_point.py``.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np
from numba import njit

import railhunt
from railhunt.kernel.rhs import rhs
from railhunt.model import Model

#: New model's time over the baseline's, at most.
TARGET = 1.5
#: Calls per timed run (about a millisecond: short runs are least often interrupted).
CALLS = 1000


@njit(cache=True)
def _calls(n: int, x: np.ndarray, v: float, s: object, out: np.ndarray) -> float:
    acc = 0.0
    for _ in range(n):
        rhs(0.0, x, v, s, out)
        acc += out[0]
    return acc


def _hunting_state(model: Model) -> np.ndarray:
    """A state on the way to a hunting cycle at 300 km/h (wheelsets displaced 3-5 mm)."""
    res = railhunt.simulate(model.vehicle, 300.0, duration=3.0,
                            excitation=railhunt.InitialDisplacement(0.006), model=model)
    return np.ascontiguousarray(res.x[-1])


def rhs_seconds(model: Model, x: np.ndarray, repeat: int) -> float:
    """Least time (s) of one right-hand side call at state ``x`` and 300 km/h."""
    v, s = model.args(300.0 / 3.6)
    out = np.empty(model.n_state)
    _calls(10, x, v, s, out)
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        _calls(CALLS, x, v, s, out)
        best = min(best, (time.perf_counter() - t0) / CALLS)
    return best


def contact_mechanics_rows(repeat: int, row: Callable) -> list:
    """Rows: rhs per call and one critical-speed search, baseline and per-point."""
    base = Model(railhunt.Vehicle.shipped("s1002_uic60_table"))
    per_point = railhunt.Vehicle.shipped("s1002_uic60_per_point")
    models = {"heuristic": Model(per_point), "polach": Model(per_point, creep_law="polach")}
    try:
        models["exact-table"] = Model(per_point, creep_law="exact-table")
    except ValueError as exc:  # its table is not built in this installation
        print(f"per-point exact-table: not timed ({exc})")
    x = _hunting_state(base)
    times = {"baseline": float("inf"), **dict.fromkeys(models, float("inf"))}
    for _ in range(10 * max(repeat, 3)):
        times["baseline"] = min(times["baseline"], rhs_seconds(base, x, 10))
        for law, m in models.items():
            times[law] = min(times[law], rhs_seconds(m, x, 10))
    rows = [row("rhs per call, s1002_uic60_table (centred, heuristic): baseline",
                times["baseline"])]
    for law in models:
        ratio = times[law] / times["baseline"]
        rows.append(row(f"rhs per call, per-point {law} ({ratio:.2f}x; target "
                        f"{TARGET:g}x)", times[law], TARGET * times["baseline"]))
    searches = {"baseline": float("inf"), "per-point": float("inf")}
    runs = {"baseline": (base.vehicle, None), "per-point": (per_point, None)}
    if "exact-table" in models:
        searches["per-point exact-table"] = float("inf")
        runs["per-point exact-table"] = (per_point, "exact-table")
    for v, law in runs.values():
        railhunt.critical_speed(v, tol_kmh=5.0, creep_law=law)  # warm-up (compilation, caches)
    for _ in range(max(1, repeat // 2)):
        for name, (v, law) in runs.items():
            t0 = time.perf_counter()
            railhunt.critical_speed(v, creep_law=law)
            searches[name] = min(searches[name], time.perf_counter() - t0)
    rows.append(row("critical-speed search, s1002_uic60_table: baseline", searches["baseline"]))
    for name in list(searches)[1:]:
        ratio = searches[name] / searches["baseline"]
        law = "exact-table" if name.endswith("exact-table") else "heuristic"
        rows.append(row(f"critical-speed search, s1002_uic60_per_point {law} ({ratio:.2f}x; "
                        f"target {TARGET:g}x)", searches[name], TARGET * searches["baseline"]))
    return rows


if __name__ == "__main__":
    from dataclasses import dataclass

    @dataclass
    class _Row:
        case: str
        seconds: float
        target: float | None = None

    for r in contact_mechanics_rows(3, _Row):
        target = "" if r.target is None else f"  (target <= {r.target:.3g} s)"
        print(f"{r.case}: {r.seconds:.4g} s{target}")
