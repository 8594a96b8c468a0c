"""Benchmark rows of the global studies (issue 19): the fold speed of one vehicle and a
Sobol study of the seven Table 1 parameters for the linear critical speed on 2 workers
(and, without ``--quick``, for the nonlinear critical speed).

Called by ``benchmarks/run.py``; runnable alone: ``python benchmarks/global_studies.py``.
"""

from __future__ import annotations

import statistics
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import railhunt

#: Targets of issue 19 (s): a fold speed, and the N = 256 Sobol study (2304 points) of the
#: linear and of the nonlinear critical speed.
FOLD_TARGET_S = 1.5
SOBOL_256_TARGET_S = 60.0
SOBOL_256_NONLINEAR_TARGET_S = 15 * 60.0


def table1_factors() -> dict[str, tuple[float, float]]:
    """The seven Table 1 parameters over their whole ranges (SI)."""
    return {k: (p.boundaries[0], p.boundaries[-1]) for k, p in railhunt.load_table1().items()}


def sobol_seconds(samples: int, workers: int = 2,
                  output: str = "linear_critical_speed_kmh") -> tuple[float, Any]:  # fmt: skip
    """Wall time of the Sobol study of Table 1 for ``output`` (the local cluster's start
    included, the compiled code loaded first), and its result."""
    from railhunt.studies.sweep import warm_up

    warm_up()
    with tempfile.TemporaryDirectory() as tmp:
        t = time.perf_counter()
        result = railhunt.sensitivity(railhunt.Vehicle.paper2019(), table1_factors(),
                                      [output], samples=samples, seed=0,
                                      ties={"f22": "f11"}, workers=workers,
                                      out=Path(tmp) / "sobol.csv")  # fmt: skip
        return time.perf_counter() - t, result


def global_study_rows(repeat: int, quick: bool, row: Callable[..., Any]) -> list[Any]:
    """The rows (``row(case, seconds, target)``)."""
    from railhunt.analysis.fold import fold_speed

    vehicle = railhunt.Vehicle.paper2019()
    fold_speed(vehicle)  # load the compiled code
    times = []
    for _ in range(max(2, repeat)):
        t = time.perf_counter()
        fold = fold_speed(vehicle)
        times.append(time.perf_counter() - t)
    rows = [row(f"fold speed of one vehicle ({fold.speed_kmh:.1f} km/h, {fold.orbits} orbits)",
                statistics.median(times), FOLD_TARGET_S)]  # fmt: skip
    samples = 64 if quick else 256
    seconds, result = sobol_seconds(samples)
    target = SOBOL_256_TARGET_S * samples / 256
    rows.append(row(f"Sobol, 7 Table 1 parameters, linear critical speed, N={samples} "
                    f"({result.points} points, 2 workers)", seconds, target))  # fmt: skip
    if not quick:  # minutes: the full report only
        seconds, result = sobol_seconds(256, output="critical_speed_kmh")
        rows.append(row(f"Sobol, 7 Table 1 parameters, nonlinear critical speed, N=256 "
                        f"({result.points} points, 2 workers)", seconds,
                        SOBOL_256_NONLINEAR_TARGET_S))  # fmt: skip
    return rows


if __name__ == "__main__":
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from table import Row, print_table

    print_table(global_study_rows(2, "--quick" in sys.argv, Row))
