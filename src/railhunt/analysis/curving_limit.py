"""The curving limit: the first speed at which the steady-curving state leaves the
validity envelope (:mod:`railhunt.validity`), found along an equilibrium path.

Searches and stability maps in curves stop there ("curving limit at X km/h: Y/Q 0.8")
instead of reporting a stability the model cannot vouch for.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from railhunt.analysis.curving import CurvingError, curving_state
from railhunt.validity import Limit

__all__ = ["CurvingLimit", "capped_at_curving_limit", "curving_limit"]


@dataclass(frozen=True)
class CurvingLimit:
    """The first speed at which the steady-curving state leaves the validity envelope.

    Attributes
    ----------
    speed_kmh : float
        The lowest speed (km/h, to ``tol_kmh``) whose steady-curving state reaches a limit;
        NaN when none is reached in the range.
    last_valid_kmh : float
        The highest speed below it inside the envelope (km/h); NaN if even the lowest
        speed is beyond it.
    limits : list of Limit
        The limits reached at ``speed_kmh``.
    """

    speed_kmh: float
    last_valid_kmh: float
    limits: tuple[Limit, ...] = ()

    @property
    def reached(self) -> bool:
        """True when a limit is reached within the range."""
        return math.isfinite(self.speed_kmh)

    @property
    def text(self) -> str:
        """E.g. ``"curving limit at 231 km/h: Y/Q 0.81 beyond 0.8 (EN 14363) at ..."``."""
        if not self.reached:
            return ""
        return f"curving limit at {self.speed_kmh:g} km/h: " + "; ".join(
            lim.text for lim in self.limits)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"speed_kmh": self.speed_kmh if self.reached else None,
                "last_valid_kmh": (self.last_valid_kmh if math.isfinite(self.last_valid_kmh)
                                   else None),
                "text": self.text, "limits": [lim.to_dict() for lim in self.limits]}  # fmt: skip


def curving_limit(path: Any, min_kmh: float, max_kmh: float, step_kmh: float = 10.0,
                  tol_kmh: float = 1.0) -> CurvingLimit:  # fmt: skip
    """The first speed at which the steady-curving state reaches a limit.

    Scans the speeds ``min_kmh, min_kmh + step_kmh, ...`` up to ``max_kmh`` on the
    equilibrium path (:class:`railhunt.analysis.curving.EquilibriumPath`), then bisects
    to ``tol_kmh`` between the last speed inside the envelope and the first beyond it.
    A speed with no equilibrium at all (Newton fails: far beyond the curving limit)
    counts as beyond.
    """
    from railhunt.units import kmh_to_ms

    def limits_at(kmh: float) -> tuple[Limit, ...]:
        speed = kmh_to_ms(kmh)
        curve = path.curve_at(speed)
        try:
            state = path.state(speed)
        except CurvingError:
            return (Limit("flange clearance", math.nan, math.nan, "m",
                          f"{kmh:g} km/h: no steady-curving equilibrium", "railhunt"),)
        return tuple(curving_state(path.model, speed, curve, state).limits)

    grid = list(np.arange(min_kmh, max_kmh, step_kmh)) + [max_kmh]
    last = math.nan
    for kmh in grid:
        found = limits_at(float(kmh))
        if not found:
            last = float(kmh)
            continue
        if math.isnan(last):
            return CurvingLimit(float(kmh), math.nan, found)
        lo, hi, at_hi = last, float(kmh), found
        while hi - lo > tol_kmh + 1e-9:
            mid = lo + tol_kmh * max(1, round((hi - lo) / (2 * tol_kmh)))
            got = limits_at(mid)
            if got:
                hi, at_hi = mid, got
            else:
                lo = mid
        return CurvingLimit(hi, lo, at_hi)
    return CurvingLimit(math.nan, last, ())


def capped_at_curving_limit(path: Any, curve: Any, min_kmh: float, max_kmh: float,
                            step_kmh: float = 10.0,
                            tol_kmh: float = 1.0) -> tuple[CurvingLimit, float]:  # fmt: skip
    """The curving limit of a search in a curve and the top speed it leaves to search.

    Every search about the steady-curving state (:func:`railhunt.critical_speed`,
    :func:`railhunt.linear_critical_speed`) stops at the last speed inside the validity
    envelope.

    Returns
    -------
    limit : CurvingLimit
        :func:`curving_limit` over ``[min_kmh, max_kmh]``.
    top_kmh : float
        ``limit.last_valid_kmh`` when a limit is reached, else ``max_kmh`` (km/h).

    Raises
    ------
    CurvingError
        When the state is beyond the envelope already at ``min_kmh``: nothing to search.
    """
    limit = curving_limit(path, min_kmh, max_kmh, step_kmh, tol_kmh)
    if not limit.reached:
        return limit, max_kmh
    if not math.isfinite(limit.last_valid_kmh):  # nothing inside the envelope
        raise CurvingError(
            f"curve = {curve!r}: the steady-curving state is beyond the validity "
            f"envelope already at the lowest speed of the search, {min_kmh:g} km/h "
            f"({limit.text}); there is no speed to search: choose a wider curve"
        )
    return limit, limit.last_valid_kmh
