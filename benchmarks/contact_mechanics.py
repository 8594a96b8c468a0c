"""Benchmark rows of the contact mechanics (``python benchmarks/run.py --only creep``).

Per case (one patch, one set of creepages), warm: Kalker's exact theory of steady rolling
on a 40 x 40 grid (target 50 ms: tables of it are to be built in minutes on 2 cores),
the same with its default extrapolation from 20 x 20, modified FASTSIM and FASTSIM on
their default 50 x 50 grids, and a batch of 1000 modified-FASTSIM cases. The case is
CONTACT's FASTSIM example (a/b = 2, large spin: a slip area over most of the patch).
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


def _best(fn: Callable[[], object], repeat: int) -> float:
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times) if repeat < 3 else statistics.median(times)


def creep_rows(repeat: int, row) -> list:
    """The rows (``row(case, seconds, target)``) of the contact mechanics."""
    mu_n = PATCH["mu"] * PATCH["normal_force"]
    rows = []
    exact = _best(lambda: exact_creep_forces(*CREEP, PATCH["a"], PATCH["b"], mu_n,
                                             PATCH["shear_modulus"], PATCH["poisson"],
                                             grid=(40, 40), extrapolate=False), repeat)
    rows.append(row("creep forces: exact theory, 40 x 40 grid, per case", exact,
                    EXACT_TARGET))
    both = _best(lambda: creep_forces(*CREEP, law="exact", **PATCH), repeat)
    rows.append(row("creep forces: exact theory, 40 x 40 and 20 x 20 (law 'exact'), per case",
                    both))
    for law in ("fastsim-modified", "fastsim"):
        t = _best(lambda law=law: creep_forces(*CREEP, law=law, **PATCH), max(repeat, 20))
        rows.append(row(f"creep forces: {law}, 50 x 50, per case", t))
    eta = np.linspace(-5e-3, 5e-3, 1000)
    t = _best(lambda: creep_forces(0.0, eta, 0.625, law="fastsim-modified", **PATCH), repeat)
    rows.append(row("creep forces: fastsim-modified, batch of 1000 cases", t))
    return rows
