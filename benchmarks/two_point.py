"""Benchmark rows of two-point contact against the per-point (single-patch) model.

The baseline is ``s1002_uic60_per_point`` (one contact per wheel, its own ellipse and
normal force); the new model is ``s1002_uic60_two_point`` (up to two patches per wheel,
tabulated over y and yaw). Rows: building the two-dimensional table for one wheel/rail
pair (target 10 s), the right-hand side per call at a hunting state (target 2x the
per-point one; both timed alternately, minima compared). Run alone with
``python benchmarks/two_point.py``.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import railhunt
from per_point import _hunting_state, rhs_seconds
from railhunt.model import Model

#: Two-point right-hand side over the per-point one, at most.
TARGET = 2.0
#: Seconds to build one wheel/rail pair's table, at most.
TABLE_TARGET = 10.0


def two_point_rows(repeat: int, row: Callable) -> list:
    """Rows: the table's build, and rhs per call, per-point and two-point."""
    from railhunt.contact.patch_table import _vehicle_table
    from railhunt.contact.point_contact import POISSON, SHEAR_MODULUS

    two = railhunt.Vehicle.shipped("s1002_uic60_two_point")
    spec = two.contact
    _vehicle_table.cache_clear()
    t0 = time.perf_counter()
    _vehicle_table(spec, 10900.0 * 9.81 / 2.0, SHEAR_MODULUS, POISSON, False)
    t_table = time.perf_counter() - t0
    rows = [row("two-point table S1002/UIC60 1:40, y +-12 mm x yaw +-12 mrad (241 x 7)",
                t_table, TABLE_TARGET)]
    base = Model(railhunt.Vehicle.shipped("s1002_uic60_per_point"))
    model = Model(two)
    x = _hunting_state(base)
    times = {"per-point": float("inf"), "two-point": float("inf")}
    for _ in range(max(repeat, 3)):
        times["per-point"] = min(times["per-point"], rhs_seconds(base, x, 3))
        times["two-point"] = min(times["two-point"], rhs_seconds(model, x, 3))
    ratio = times["two-point"] / times["per-point"]
    rows.append(row("rhs per call, s1002_uic60_per_point (one patch per wheel): baseline",
                    times["per-point"]))
    rows.append(row(f"rhs per call, s1002_uic60_two_point ({ratio:.2f}x; target "
                    f"{TARGET:g}x)", times["two-point"], TARGET * times["per-point"]))
    return rows


if __name__ == "__main__":
    from dataclasses import dataclass

    @dataclass
    class _Row:
        case: str
        seconds: float
        target: float | None = None

    for r in two_point_rows(3, _Row):
        target = "" if r.target is None else f"  (target <= {r.target:.3g} s)"
        print(f"{r.case}: {r.seconds:.4g} s{target}")
