"""The speed search shared by the critical-speed methods: bracket by steps, then bisect.

Both the paper's single-defect method (:func:`railhunt.analysis.critical.critical_speed`)
and the acceptance-test criterion (:func:`railhunt.analysis.stochastic.stochastic_critical_speed`)
ask one yes/no question per trial speed (does the vehicle hunt / break the criterion?) and
look for the speed where the answer changes.
"""

from __future__ import annotations

import math
from collections.abc import Callable


def check_search(start_kmh: float, step_kmh: float, tol_kmh: float, min_kmh: float,
                 max_kmh: float) -> None:  # fmt: skip
    """Raise ``ValueError`` naming the first invalid search setting (all km/h); a value
    that is not a number is an :class:`railhunt.arguments.ArgumentTypeError`."""
    from railhunt.arguments import check_real

    for name, value in (("start_kmh", start_kmh), ("step_kmh", step_kmh), ("tol_kmh", tol_kmh),
                        ("min_kmh", min_kmh), ("max_kmh", max_kmh)):  # fmt: skip
        check_real(name, value, "km/h")
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r} km/h is invalid: must be finite and > 0")
    if not (min_kmh <= start_kmh <= max_kmh):
        raise ValueError(
            f"start_kmh = {start_kmh} km/h is invalid: must lie in [{min_kmh:g}, "
            f"{max_kmh:g}] km/h, the range of the search"
        )
    if tol_kmh > step_kmh:
        raise ValueError(f"tol_kmh = {tol_kmh} km/h is invalid: must be <= step_kmh = {step_kmh}")


def bracket_and_bisect(
    unstable: Callable[[float], bool],
    start_kmh: float,
    step_kmh: float,
    tol_kmh: float,
    min_kmh: float,
    max_kmh: float,
) -> tuple[float, float, bool]:
    """Speeds ``lo < hi`` (km/h), ``hi - lo <= tol_kmh``, with ``unstable(lo)`` False and
    ``unstable(hi)`` True.

    Steps by ``step_kmh`` from ``start_kmh`` (up while stable, down while unstable) until
    the answer changes, then bisects on the ``tol_kmh`` grid. Returns ``(lo, hi, True)``, or
    ``(lo, hi, False)`` with the missing end NaN when the answer never changes between
    ``min_kmh`` and ``max_kmh``.
    """
    check_search(start_kmh, step_kmh, tol_kmh, min_kmh, max_kmh)
    speed = start_kmh
    lo = hi = math.nan
    if not unstable(speed):
        lo = speed
        while speed + step_kmh <= max_kmh + 1e-9:
            speed += step_kmh
            if unstable(speed):
                hi = speed
                break
            lo = speed
    else:
        hi = speed
        while speed - step_kmh >= min_kmh - 1e-9:
            speed -= step_kmh
            if not unstable(speed):
                lo = speed
                break
            hi = speed
    if math.isnan(lo) or math.isnan(hi):
        return lo, hi, False
    while hi - lo > tol_kmh + 1e-9:
        mid = lo + tol_kmh * round((hi - lo) / (2 * tol_kmh))
        mid = min(max(mid, lo + tol_kmh), hi - tol_kmh)
        if unstable(mid):
            hi = mid
        else:
            lo = mid
    return lo, hi, True
