"""Bifurcation diagram by pseudo-arclength continuation of the Hopf branch of limit cycles.

From the Hopf point of the centred equilibrium
(:func:`railhunt.analysis.linear.linear_critical_speed`) the branch of periodic orbits is
started along the hunting eigenvector, solved at three
small amplitudes with the amplitude fixed, then followed in the speed by Keller's
pseudo-arclength method on the shooting residual of :mod:`railhunt.analysis.periodic`:
predictor along the tangent (null vector of the 38 x 39 Jacobian), corrector by Newton
on the residual plus the arclength condition, step length adapted to Newton's effort and
limited in speed and amplitude so the diagram is resolved. Folds (turning points in the
speed) are located where the tangent's speed component changes sign; stability comes
from the Floquet multipliers of each orbit.

The paper's Fig. 5 defines the types: *subcritical* (the branch leaves the Hopf point
toward lower speeds, unstable, and turns at a fold ``V_nl < V_lim``), *supercritical (b)*
(the branch leaves toward higher speeds, stable, and grows without folding) and
*supercritical (a)* (the branch leaves toward higher speeds, stable, then folds back
unstable and folds again onto a large stable cycle); :func:`classify_hopf` tells them
apart, with a tolerance explained there.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np

# The tracer of one direction of a branch lives in railhunt.analysis.branch_tracer, below
# this module and the branch's start; BranchLimits and BranchTracer are importable from
# here as before.
from railhunt.analysis.branch_tracer import BranchLimits, BranchTracer
from railhunt.analysis.branches import (
    HOPF_TYPES,
    BifurcationDiagram,
    Branch,
    Fold,
    classify_hopf,
    linear_branch,
    make_branch,
    on_branch,
)
from railhunt.analysis.curving import EquilibriumPath

# The branch's start (crossing mode, measure coordinate, small orbits) lives in
# railhunt.analysis.hopf_start; its names are importable from here as before.
from railhunt.analysis.hopf_start import (  # noqa: F401
    LEADING_SHARE,
    SMALL_ORBIT_SEEDS,
    hopf_branch_start,
    hopf_mode_shape,
    measure_coordinate,
    small_orbit_seeds,
)
from railhunt.analysis.linear import linear_critical_speed
from railhunt.analysis.linearity import LINEAR_MODEL, is_linear
from railhunt.analysis.periodic import (
    PeriodicOrbit,
    Shooting,
    newton,
)
from railhunt.curve import Curve
from railhunt.kernel.integrators import OK, STATUS_NAMES
from railhunt.model import Model
from railhunt.units import kmh_to_ms
from railhunt.vehicle import Vehicle
from railhunt.verdicts import ending

__all__ = ["HOPF_TYPES", "BifurcationDiagram", "Branch", "Fold", "bifurcation_diagram",
           "bifurcation_family",
           "classify_hopf"]


def _check_range(speed_range_kmh: tuple[float, float]) -> tuple[float, float]:
    try:
        lo, hi = (float(s) for s in speed_range_kmh)
    except (TypeError, ValueError):
        raise ValueError(
            f"speed_range_kmh = {speed_range_kmh!r} is invalid: must be two speeds (lo, hi) km/h"
        ) from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi <= 2000):
        raise ValueError(
            f"speed_range_kmh = ({lo}, {hi}) is invalid: need 0 < lo < hi <= 2000 km/h"
        )
    return lo, hi


def bifurcation_diagram(
    vehicle: Vehicle,
    speed_range_kmh: tuple[float, float] = (200.0, 500.0),
    max_amplitude: float = 0.015,
    max_points: int = 600,
    max_step_kmh: float = 5.0,
    max_step_amplitude: float = 4e-4,
    seed_amplitudes: tuple[float, ...] = (0.008, 0.004, 0.012),
    dt: float | None = None,
    symmetric: bool = True,
    creep_law: str | None = None,
    on_point: Callable[[PeriodicOrbit], None] | None = None,
    curve: Curve | None = None,
) -> BifurcationDiagram:
    """Bifurcation diagram of the vehicle: branches of limit cycles versus speed.

    The Hopf branch is followed from the Hopf point (over the range widened to 10 km/h
    around the Hopf point). So that a branch of large cycles not connected to it within
    the range is not missed, the vehicle is also simulated from each of ``seed_amplitudes``
    (an initial lateral displacement of all wheelsets) at the top of the range and, if that
    is below the Hopf point, 10 km/h above the Hopf point, and at lower speeds in steps of
    50 km/h down to the bottom of the range (:func:`seed_ladder`: where the top release
    derails, a lower one settles), so that the large branch and the lowest limit cycle do not
    depend on the top of the range; a cycle a release settles on that lies on no branch
    yet is refined by shooting and followed both ways. ``complete`` is True only when
    every branch was followed to its end and every cycle a release settled on lies on a
    branch; ``message`` says what was not found and which releases left the track.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    speed_range_kmh : (float, float)
        Speeds (km/h) between which branches are followed; the Hopf point is searched up
        to 2000 km/h.
    max_amplitude : float
        Stop a branch when the leading wheelset's amplitude exceeds this (m).
    max_points : int
        Largest number of continuation steps per branch direction.
    max_step_kmh, max_step_amplitude : float
        Largest change of speed (km/h) and amplitude (m) between neighbouring points.
    seed_amplitudes : tuple of float
        Initial displacements (m) of the seeding simulations (release sizes, all tried
        at the first speed where one settles on a cycle); empty for none.
    dt : float, optional
        Largest RK4 step of the shooting (s); default the automatic step at the top speed.
    symmetric : bool
        Shoot over half periods using the vehicle's left/right symmetry.
    creep_law : str
        See :class:`railhunt.model.Model`.
    on_point : callable, optional
        Called with each new orbit (progress reporting).
    curve : Curve, optional
        Limit cycles about the steady-curving equilibrium in this curve's constant part.
        A curve has no mirror symmetry: the orbits are shot over the whole period
        (``symmetric`` is ignored), the Hopf point is that of the curving equilibrium and
        amplitudes are half the peak-to-peak swing of ``y_w1``.

    Returns
    -------
    BifurcationDiagram
    """
    lo, hi = _check_range(speed_range_kmh)
    for name, value, unit in (("max_amplitude", max_amplitude, "m"),
                              ("max_step_kmh", max_step_kmh, "km/h"),
                              ("max_step_amplitude", max_step_amplitude, "m")):  # fmt: skip
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r} {unit} is invalid: must be finite and > 0")
    if int(max_points) < 4:
        raise ValueError(f"max_points = {max_points!r} is invalid: must be >= 4")
    for a in seed_amplitudes:
        if not (math.isfinite(a) and 0 < a < 0.025):
            raise ValueError(f"seed_amplitudes contains {a!r} m: each must be in (0, 0.025) m")
    limits = BranchLimits(lo, hi, max_amplitude, int(max_points), max_step_kmh, max_step_amplitude)
    model = Model(vehicle, creep_law=creep_law)
    linear = linear_critical_speed(vehicle, max_kmh=2000.0, tol_kmh=1e-3, creep_law=creep_law,
                                   curve=curve)  # fmt: skip
    hopf = linear.speed_kmh
    if math.isfinite(linear.unstable_from_kmh):
        raise ValueError(f"the equilibrium is {linear.text}: no Hopf point to start the "
                         "branch of limit cycles from")  # fmt: skip
    if not math.isfinite(hopf):
        where = "centred" if curve is None else "steady-curving"
        raise ValueError(f"the {where} equilibrium stays stable up to 2000 km/h: no Hopf point")
    path = None if curve is None else EquilibriumPath(model, curve)
    shape, period0 = hopf_mode_shape(model, hopf, path)
    if is_linear(model):  # no limit cycles: the neutral orbits at the Hopf speed, no fold
        branch = linear_branch(hopf, period0, shape, model.layout.wheelset_y, max_amplitude)
        return BifurcationDiagram([branch], hopf, hopf, linear.frequency_hz, hopf, "linear",
                                  (lo, hi), True, f"{LINEAR_MODEL} ({hopf:.1f} km/h)")  # fmt: skip
    shoot = Shooting(model, symmetric=symmetric and curve is None, dt=dt,
                     dt_speed=kmh_to_ms(max(hi, hopf)),
                     route=None if path is None else path.route,
                     equilibrium=None if path is None else path.state,
                     phase_coordinate=measure_coordinate(model, shape))  # fmt: skip
    shoot.set_period_hint(period0)
    x_hopf = np.zeros(shoot.n_state) if path is None else path.state(kmh_to_ms(hopf))
    tracer = BranchTracer(shoot, limits, on_point)

    # 1. Three small orbits with the measure coordinate's x(0) fixed (natural parameter),
    # from the eigenvector.
    small = hopf_branch_start(shoot, tracer, x_hopf, shape, period0, hopf)
    a_small = np.array([o.amplitude for _, o, _ in small])
    v_small = np.array([o.speed_kmh for _, o, _ in small])
    hopf_from_orbits = float(np.polyfit(a_small, v_small, 2)[-1])

    # 2. The Hopf branch by pseudo-arclength continuation.
    # The Hopf branch is followed over the range widened to 10 km/h around the Hopf point,
    # so that its type is known even when the Hopf point lies outside the range.
    tangent = small[-1][0] - small[-2][0]
    ds = float(np.linalg.norm(tangent))
    # A branch that comes back below the smallest seeded amplitude has reached another Hopf
    # point (in a curve the equilibrium can lose and regain stability along the speed).
    hopf_limits = dataclasses.replace(limits, lo=min(lo, hopf - 10.0), hi=max(hi, hopf + 10.0),
                                      min_amplitude=0.75 * small_orbit_seeds(shoot, shape)[-1])
    more, msg, complete, below = tracer.trace(small[-1][0], small[-1][2], tangent / ds, ds,
                                              limits.max_points, hopf_limits)  # fmt: skip
    branches = [make_branch([o for _, o, _ in small] + more, "hopf", (hopf, period0))]
    messages = [f"Hopf branch: {msg}"]

    # 3. Branches of large cycles found by simulation: at the top of the range and, when
    # that is below the Hopf point, also just above it (where every disturbance grows to
    # a cycle, while near a fold the large cycles' basins can be too small to reach); when
    # every release derails there, at lower speeds too (seed_ladder), so that the large
    # branch does not depend on the top of the range.
    missed: list[tuple[float, float, str]] = []
    notes: list[str] = []
    for amp, seed_kmh, found in _seed_releases(model, shoot, path, seed_amplitudes,
                                               seed_ladder(lo, hi, hopf), branches,
                                               missed, notes):  # fmt: skip
        u_c, orbit_c, lin_c = found
        if on_point is not None:
            on_point(orbit_c)
        jac = shoot.jacobian(u_c, lin=lin_c)
        t0 = np.zeros(u_c.size)
        t0[-1] = 1.0
        t0 = tracer.null_vector(jac, t0)
        seed_limits = dataclasses.replace(limits, hi=max(hi, seed_kmh))
        parts = []
        for sign in (-1.0, 1.0):
            part, msg, ok, out_low = tracer.trace(u_c, lin_c, sign * t0, 0.5,
                                                  limits.max_points, seed_limits)  # fmt: skip
            parts.append(part)
            complete &= ok
            below |= out_low
            messages.append(f"branch from {amp * 1e3:g} mm at {seed_kmh:g} km/h "
                            f"({'down' if sign < 0 else 'up'}): {msg}")  # fmt: skip
        branches.append(make_branch(parts[0][::-1] + [orbit_c] + parts[1], "simulation"))
    missed_text = [text for v, a, text in missed if not _covered(branches, v, a)]
    if missed_text:
        complete = False
        messages.extend(missed_text)
    messages.extend(notes)

    hopf_type = classify_hopf(branches[0], hopf)
    if below:  # a branch goes on below the range: its lowest cycle is not known
        lowest = math.nan
        messages.append(f"a branch leaves the range below {lo:g} km/h: the lowest limit "
                        "cycle is below the range (fold_speed_kmh is NaN)")  # fmt: skip
    else:
        lowest = min([hopf] + [float(np.min(b.speed_kmh)) for b in branches]
                     + [f.speed_kmh for b in branches for f in b.folds])  # fmt: skip
    return BifurcationDiagram(branches, hopf, hopf_from_orbits, linear.frequency_hz, lowest,
                              hopf_type, (lo, hi), complete, "; ".join(messages),
                              fold_below_range=below)  # fmt: skip


def _seed_orbit(model: Model, shoot: Shooting, speed_kmh: float, amplitude: float,
                path: EquilibriumPath | None = None):  # fmt: skip
    """:func:`_release` without its outcome: the orbit found, or None."""
    return _release(model, shoot, speed_kmh, amplitude, path)[1]


def _release(model: Model, shoot: Shooting, speed_kmh: float, amplitude: float,
             path: EquilibriumPath | None = None):  # fmt: skip
    """Simulate from a displaced state, shoot from where it settles; None if it decays.

    In a curve (``path``) the run starts from the curving equilibrium with the wheelsets
    displaced, and decay is judged toward that equilibrium.
    """
    from railhunt.analysis.periodic import phase_origin
    from railhunt.simulation import auto_step, integrate_model

    speed = kmh_to_ms(speed_kmh)
    layout = model.layout
    y_w1 = shoot.phase_coordinate  # the phase origin is an extremum of this coordinate
    x_eq = np.zeros(layout.n_state) if path is None else path.state(speed)
    x0 = x_eq.copy()
    x0[layout.wheelset_y] += amplitude
    dt = auto_step(model, speed)
    route = None if path is None else path.route
    t, x, status, _ = integrate_model(model, speed, 12.0, x0, dt=dt, route=route)
    if status != OK:
        return ending(STATUS_NAMES[status], x), None
    y = x[:, y_w1]
    tail = y[t > t[-1] - 2.0]
    if np.max(np.abs(tail - x_eq[y_w1])) < 1e-4:
        return "decays", None
    size = float(np.max(np.abs(tail - x_eq[y_w1])))
    failed = f"settles on a cycle of about {size * 1e3:.3g} mm that shooting did not converge on"
    k = phase_origin(t, y)
    # Period guess from the spacing of the last maxima.
    peaks = [i for i in range(1, y.size - 1) if y[i] >= y[i - 1] and y[i] > y[i + 1]
             and t[i] > t[-1] - 2.0]  # fmt: skip
    if len(peaks) < 3:
        return failed, None
    period = float(np.mean(np.diff(t[peaks])))
    u = shoot.pack(np.where(np.arange(layout.n_state) == shoot.phase_index, 0.0, x[k]),
                   period, speed)  # fmt: skip
    vs = u[-1]

    def fun(w: np.ndarray) -> np.ndarray:
        return shoot.residual(np.append(w, vs))

    def jac_fun(w: np.ndarray, r: np.ndarray) -> np.ndarray:
        return shoot.jacobian(np.append(w, vs), r, speed=False)[:, :-1]

    w, norm, it, ok, _ = newton(fun, jac_fun, u[:-1], tol=1e-9, max_iter=20)
    if not ok:
        return failed, None
    u = np.append(w, vs)
    lin = shoot.linearise(u)
    orbit = shoot.orbit(u, norm, it, lin)
    if not orbit.amplitude > 0.5 * size:
        # Newton slid down to the (unstable) equilibrium, which is a periodic solution of
        # any period: not the cycle the run settled on.
        return (f"settles on a cycle of about {size * 1e3:.3g} mm that shooting did not "
                f"converge on (it slid to the equilibrium)"), None
    return "cycle", (u, orbit, lin)


def seed_ladder(lo: float, hi: float, hopf: float, step_kmh: float = 50.0) -> list[float]:
    """Speeds (km/h) a release is tried at, in order: the top of the range, just above
    the Hopf point when the top is below it, then down from the top by ``step_kmh`` to
    the bottom of the range."""
    first = [hi] + ([min(hopf + 10.0, 2.0 * hi)] if hopf + 10.0 > hi else [])
    # On a fixed grid (multiples of step_kmh), so that a wider range tries every speed a
    # narrower one tries: widening a diagram's range cannot lose its lowest limit cycle.
    top = step_kmh * math.ceil(hi / step_kmh - 1e-9) - step_kmh
    down = [float(v) for v in np.arange(top, lo - 1e-9, -step_kmh)]
    return first + [v for v in down if v not in first]


def _seed_releases(model: Model, shoot: Shooting, path: EquilibriumPath | None,
                   amplitudes: tuple[float, ...], speeds: list[float], branches: list,
                   missed: list[tuple[float, float, str]], notes: list[str]):  # fmt: skip
    """Releases that settle on a cycle on no branch yet: yields ``(amplitude, speed,
    found)`` for each, walking every speed of ``speeds`` (:func:`seed_ladder`) with every
    release size (the caller follows each yielded cycle into a branch before the walk goes
    on, so cycles on that branch are not followed again). Appends to ``missed``
    ``(speed_kmh, amplitude, sentence)`` for each cycle a release settled on that shooting
    could not refine, and to ``notes`` which releases left the track."""
    derailed: list[str] = []
    for seed_kmh in speeds:
        for amp in amplitudes:
            outcome, found = _release(model, shoot, seed_kmh, amp, path)
            if outcome in ("derailed", "blow-up"):
                derailed.append(f"{amp * 1e3:g} mm at {seed_kmh:g} km/h ({outcome})")
                continue
            if outcome == "decays":
                continue
            if found is None:
                size = float(outcome.split("about ")[1].split(" mm")[0]) * 1e-3
                if not any(v == seed_kmh for v, _, _ in missed):  # one sentence a speed
                    missed.append((seed_kmh, size, f"not found: a release of "
                                   f"{amp * 1e3:g} mm at {seed_kmh:g} km/h {outcome}"))
                continue
            if any(on_branch(b, found[1]) for b in branches):
                continue
            yield amp, seed_kmh, found
    if derailed:
        notes.append("releases that left the track: " + ", ".join(derailed))


def _covered(branches: list, speed_kmh: float, amplitude: float) -> bool:
    """Whether a branch has an orbit within 5 km/h and 10 % of this cycle's amplitude."""
    for b in branches:
        near = np.abs(b.speed_kmh - speed_kmh) <= 5.0
        if np.any(near & (np.abs(b.amplitude - amplitude) <= 0.1 * amplitude)):
            return True
    return False


def bifurcation_family(
    vehicle: Vehicle,
    values: list[float] | np.ndarray,
    parameter: str = "F_u",
    speed_range_kmh: tuple[float, float] = (200.0, 500.0),
    **kwargs,
) -> list[tuple[float, BifurcationDiagram]]:
    """Bifurcation diagrams of a family of vehicles that differ in one parameter (Fig. 13).

    Parameters
    ----------
    vehicle : Vehicle
        The base vehicle.
    values : sequence of float
        Values of ``parameter`` in SI units (for the paper's Fig. 13, blow-off forces in N).
    parameter : str
        A :class:`Vehicle` parameter name; default the yaw damper's blow-off force ``F_u``.
    speed_range_kmh : (float, float)
        Speed range of every diagram (km/h).
    **kwargs
        Passed to :func:`bifurcation_diagram`.

    Returns
    -------
    list of (value, BifurcationDiagram)
        In the order of ``values``; ``diagram.hopf_type`` tells how the type changes.
    """
    values = [float(v) for v in values]
    if not values:
        raise ValueError("values is empty: give at least one value of the parameter")
    out = []
    for value in values:
        member = vehicle.replace(**{parameter: value})
        out.append((value, bifurcation_diagram(member, speed_range_kmh, **kwargs)))
    return out


#: The former private name of :func:`railhunt.analysis.hopf_start.hopf_mode_shape`.
_hopf_start = hopf_mode_shape
