"""Benchmark rows of the contact mechanics (``python benchmarks/run.py --only creep``).

Per case (one patch, one set of creepages), warm: Kalker's exact theory of steady rolling
on a 40 x 40 grid (target 50 ms: tables of it are to be built in minutes on 2 cores),
the same with its default extrapolation from 20 x 20, a sweep of 200 cases of it, modified
FASTSIM and FASTSIM on their default 50 x 50 grids, and a batch of 1000 modified-FASTSIM
cases. The case is CONTACT's FASTSIM example (a/b = 2, large spin: a slip area over most
of the patch). Wall times (medians); the CPU time of the process beside, which a shared
machine inflates less.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable

import numpy as np

from railhunt import creep_forces
from railhunt.mechanics.exact import exact_creep_forces

PATCH = dict(a=8e-3, b=4e-3, mu=0.3, normal_force=82e3, shear_modulus=8.2e10, poisson=0.28)
CREEP = (0.0, -6.25e-4, 0.625)
EXACT_TARGET = 0.050  # s per case, 40 x 40


def _best(fn: Callable[[], object], repeat: int) -> tuple[float, float]:
    """Median wall time and median CPU time of this process (s), warm."""
    fn()
    wall, cpu = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return statistics.median(wall), statistics.median(cpu)


def creep_rows(repeat: int, row) -> list:
    """The rows (``row(case, seconds, target)``) of the contact mechanics."""
    mu_n = PATCH["mu"] * PATCH["normal_force"]
    rows = []
    wall, cpu = _best(lambda: exact_creep_forces(*CREEP, PATCH["a"], PATCH["b"], mu_n,
                                                 PATCH["shear_modulus"], PATCH["poisson"],
                                                 grid=(40, 40), extrapolate=False),
                      max(repeat, 5))  # fmt: skip
    rows.append(row(f"creep forces: exact theory, 40 x 40 grid, per case (CPU "
                    f"{cpu * 1e3:.0f} ms)", wall, EXACT_TARGET))
    wall, cpu = _best(lambda: creep_forces(*CREEP, law="exact", **PATCH), max(repeat, 5))
    rows.append(row(f"creep forces: exact theory, 40 x 40 and 20 x 20 (law 'exact'), per "
                    f"case (CPU {cpu * 1e3:.0f} ms)", wall))
    # a table's worth: a sweep of 200 cases on one patch (each started from the last)
    eta = np.linspace(-3e-3, 3e-3, 200)
    wall, cpu = _best(lambda: creep_forces(0.0, eta, 0.625, law="exact", **PATCH), 1)
    rows.append(row(f"creep forces: exact theory (law 'exact'), sweep of 200 cases (CPU "
                    f"{cpu:.1f} s)", wall))
    for law in ("fastsim-modified", "fastsim"):
        wall, _ = _best(lambda law=law: creep_forces(*CREEP, law=law, **PATCH),
                        max(repeat, 20))
        rows.append(row(f"creep forces: {law}, 50 x 50, per case", wall))
    eta = np.linspace(-5e-3, 5e-3, 1000)
    wall, _ = _best(lambda: creep_forces(0.0, eta, 0.625, law="fastsim-modified", **PATCH),
                    repeat)
    rows.append(row("creep forces: fastsim-modified, batch of 1000 cases", wall))
    return rows
