"""The fold of the Hopf branch: the lowest speed of a limit cycle, cheaply.

A study needs one number per vehicle that says where hunting can start and is smooth in
the parameters, unlike a bisection's 1 km/h steps: the lowest speed of a limit cycle on
the hunting (Hopf) branch, its *fold*. :func:`fold_speed` finds it with the continuation
of :mod:`railhunt.analysis.continuation` (same shooting, predictor and corrector), but
follows only the Hopf branch and only down to its first turn:

1. the Hopf point (:func:`railhunt.linear_critical_speed`, to 0.001 km/h) and three small
   orbits started from the hunting eigenvector;
2. **coarse** pseudo-arclength steps (up to ``coarse_step_kmh`` and ``coarse_step_amplitude``
   between points) until the speed, having fallen more than the Hopf-type tolerance below
   the Hopf point (:func:`railhunt.analysis.branches.classify_hopf`), rises again: the fold
   has been passed;
3. **refinement**: from the lowest coarse point the branch is traced again with steps of
   ``fine_step_kmh``, ``fine_step_amplitude`` (corrector to 1e-9) toward the side where
   the parabola through the three coarse points around it has its vertex (the other side
   if the speed rises at once), until it turns; the fold is the vertex of the parabola
   through the three fine points around the turn (as for the folds of a whole diagram,
   :func:`railhunt.analysis.branches.make_branch`).

A branch that never turns below the Hopf point (supercritical, type (b)) has its lowest
cycle at the Hopf point: ``speed_kmh`` is then the Hopf speed and ``turned`` is False.
A branch that leaves the range below ``min_kmh`` gives NaN.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from railhunt.analysis.branch_tracer import BranchLimits, BranchTracer
from railhunt.analysis.branches import make_branch
from railhunt.analysis.continuation import (
    hopf_branch_start,
    hopf_mode_shape,
    measure_coordinate,
    small_orbit_seeds,
)
from railhunt.analysis.linear import linear_critical_speed
from railhunt.analysis.periodic import PeriodicOrbit, Shooting
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.units import kmh_to_ms
from railhunt.vehicle import Vehicle

__all__ = ["FoldSpeed", "fold_speed"]

#: First arclength step of the coarse trace (scaled unknowns; then adapted).
FIRST_DS = 0.0


@dataclass(repr=False)
class FoldSpeed(ResultDisplay):
    """Outcome of :func:`fold_speed`.

    Attributes
    ----------
    speed_kmh : float
        Lowest speed of a limit cycle on the Hopf branch (km/h); the Hopf speed when the
        branch does not turn back below it; NaN when it leaves the range below.
    amplitude : float
        Leading wheelset's amplitude there (m).
    hopf_speed_kmh : float
        The Hopf point (km/h).
    turned : bool
        Whether the branch turned (a fold below the Hopf point was found).
    orbits : int
        Limit cycles computed (each one shooting Jacobian at least).
    message : str
        How the trace ended.
    """

    speed_kmh: float
    amplitude: float
    hopf_speed_kmh: float
    turned: bool
    orbits: int
    message: str

    def _summary(self) -> list[Row]:
        return [("fold speed", self.speed_kmh, "km/h"), ("amplitude there", self.amplitude, "m"),
                ("Hopf speed", self.hopf_speed_kmh, "km/h"), ("fold found", self.turned, ""),
                ("orbits computed", self.orbits, "")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row."""
        return {"fold_speed_kmh": (self.speed_kmh, "km/h"), "amplitude": (self.amplitude, "m"),
                "hopf_speed_kmh": (self.hopf_speed_kmh, "km/h"), "turned": (self.turned, "")}


def _vertex_before(three: list[PeriodicOrbit]) -> bool:
    """Whether the parabola's vertex through three orbits around a turn lies before the
    middle one (along the branch: speed against the distance in the (10 km/h, 1 mm) plane)."""
    v = np.array([o.speed_kmh for o in three])
    a = np.array([o.amplitude for o in three])
    seg = np.hypot(np.diff(v) / 10.0, np.diff(a) / 1e-3)
    c = np.polyfit([-seg[0], 0.0, seg[1]], v, 2)
    return bool(c[0] != 0 and -c[1] / (2 * c[0]) < 0)


def _check_positive(name: str, value: float, unit: str) -> float:
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} = {value!r} {unit} is invalid: must be finite and > 0")
    return value


def fold_speed(
    vehicle: Vehicle,
    min_kmh: float = 50.0,
    max_amplitude: float = 0.015,
    coarse_step_kmh: float = 20.0,
    coarse_step_amplitude: float = 1.5e-3,
    fine_step_kmh: float = 1.5,
    fine_step_amplitude: float = 1e-4,
    max_points: int = 80,
    max_ds: float = 150.0,
    coarse_tol: float = 1e-5,
    creep_law: str | None = None,
) -> FoldSpeed:
    """Lowest speed of a limit cycle on the Hopf branch, by a short continuation.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    min_kmh : float
        Give up (NaN) when the branch goes below this speed (km/h).
    max_amplitude : float
        Stop when the leading wheelset's amplitude exceeds this (m).
    coarse_step_kmh, coarse_step_amplitude : float
        Largest change of speed (km/h) and amplitude (m) between coarse points.
    fine_step_kmh, fine_step_amplitude : float
        The same for the refinement around the fold.
    max_points : int
        Largest number of continuation steps of the coarse trace.
    max_ds : float
        Largest arclength step of the coarse trace (scaled unknowns: mm, 10 mm/s, kN, ...);
        the speed and amplitude caps usually bind first.
    coarse_tol : float
        Corrector tolerance of the coarse trace (scaled shooting residual); the
        refinement solves to 1e-9, as the bifurcation diagram does.
    creep_law : str, optional
        See :class:`railhunt.model.Model`; default: the layout's own law.

    Returns
    -------
    FoldSpeed

    Raises
    ------
    ValueError
        When the centred running has no Hopf point below 2000 km/h, or an option is out of
        range.
    """
    for name, value, unit in (("min_kmh", min_kmh, "km/h"), ("max_amplitude", max_amplitude, "m"),
                              ("coarse_step_kmh", coarse_step_kmh, "km/h"),
                              ("coarse_step_amplitude", coarse_step_amplitude, "m"),
                              ("fine_step_kmh", fine_step_kmh, "km/h"),
                              ("fine_step_amplitude", fine_step_amplitude, "m")):  # fmt: skip
        _check_positive(name, value, unit)
    if int(max_points) < 4:
        raise ValueError(f"max_points = {max_points!r} is invalid: must be >= 4")
    model = Model(vehicle, creep_law=creep_law)
    linear = linear_critical_speed(vehicle, max_kmh=2000.0, tol_kmh=1e-3, creep_law=creep_law)
    hopf = linear.speed_kmh
    if not math.isfinite(hopf):
        raise ValueError("the centred equilibrium stays stable up to 2000 km/h: no Hopf point")
    shape, period0 = hopf_mode_shape(model, hopf)
    shoot = Shooting(model, symmetric=True, dt_speed=kmh_to_ms(hopf),
                     phase_coordinate=measure_coordinate(model, shape))
    shoot.set_period_hint(period0)
    smallest = 0.75 * small_orbit_seeds(shoot, shape)[-1]
    coarse = BranchLimits(min_kmh, hopf + 50.0, max_amplitude, int(max_points), coarse_step_kmh,
                     coarse_step_amplitude, min_amplitude=smallest, max_ds=max_ds,
                     newton_tol=coarse_tol)  # fmt: skip
    tracer = BranchTracer(shoot, coarse, None)
    small = hopf_branch_start(shoot, tracer, np.zeros(shoot.n_state), shape, period0, hopf)
    tol = max(2.0, 0.01 * hopf)

    def passed_fold(orbits: list[PeriodicOrbit]) -> str:
        speeds = [o.speed_kmh for o in orbits]
        low = int(np.argmin(speeds))
        if speeds[low] < hopf - tol and low < len(speeds) - 1:
            return "passed the fold"
        return ""

    tangent = small[-1][0] - small[-2][0]
    ds = float(np.linalg.norm(tangent))
    first_ds = max(ds, FIRST_DS)
    orbits, msg, _, below = tracer.trace(small[-1][0], small[-1][2], tangent / ds, first_ds,
                                         coarse.max_points, stop=passed_fold)  # fmt: skip
    count = len(small) + len(orbits)
    if below:
        return FoldSpeed(math.nan, math.nan, hopf, False, count, f"Hopf branch {msg}")
    if msg != "passed the fold":
        branch = make_branch([o for _, o, _ in small] + orbits, "hopf", (hopf, period0))
        i = int(np.argmin(branch.speed_kmh))
        return FoldSpeed(float(branch.speed_kmh[i]), float(branch.amplitude[i]), hopf, False,
                         count, f"Hopf branch {msg}: no fold below the Hopf point")  # fmt: skip
    # Refine: from the lowest coarse point, with fine steps toward the side of the turn
    # (the vertex of the parabola through the three coarse points around the lowest).
    speeds = np.array([o.speed_kmh for o in orbits])
    low = int(np.argmin(speeds))
    fine = BranchLimits(min_kmh, hopf + 50.0, max_amplitude, 60, fine_step_kmh, fine_step_amplitude)
    before = 1 <= low < len(orbits) - 1 and _vertex_before(orbits[low - 1:low + 2])
    u0 = shoot.pack(orbits[low].state, orbits[low].period, kmh_to_ms(speeds[low]))
    prev = orbits[low - 1] if low >= 1 else small[-1][1]
    u_prev = shoot.pack(prev.state, prev.period, kmh_to_ms(prev.speed_kmh))
    lin0 = shoot.linearise(u0)
    t0 = (u_prev - u0) if before else (u0 - u_prev)
    t0 /= np.linalg.norm(t0)

    def turned(part: list[PeriodicOrbit]) -> str:
        s = [orbits[low].speed_kmh] + [o.speed_kmh for o in part]
        return "turned" if s[-1] > s[-2] else ""

    tracer_fine = BranchTracer(shoot, fine, None)
    pts: list[PeriodicOrbit] = []
    msg_fine = ""
    for direction in (t0, -t0):  # toward the turn; the other way if it rose at once
        part, msg_fine, _, _ = tracer_fine.trace(u0, lin0, direction, 0.3 * ds,
                                                 fine.max_points, fine, stop=turned)  # fmt: skip
        count += len(part)
        pts = [orbits[low], *part]
        if len(part) >= 2 or msg_fine != "turned":
            break
    branch = make_branch(pts, "hopf")
    if branch.folds and msg_fine == "turned":
        f = min(branch.folds, key=lambda f: f.speed_kmh)
        return FoldSpeed(f.speed_kmh, f.amplitude, hopf, True, count, "fold refined")
    coarse_branch = make_branch(orbits, "hopf")
    f = min(coarse_branch.folds, key=lambda f: f.speed_kmh) if coarse_branch.folds else None
    if f is None:
        return FoldSpeed(float(speeds[low]), float(orbits[low].amplitude), hopf, True, count,
                         f"fold not refined ({msg_fine}): lowest coarse point")  # fmt: skip
    return FoldSpeed(f.speed_kmh, f.amplitude, hopf, True, count,
                     f"fold not refined ({msg_fine}): coarse parabola")  # fmt: skip
