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
from dataclasses import dataclass, field

import numpy as np

from railhunt.analysis.linear import eigenvalues, hunting_mode_index, linear_critical_speed
from railhunt.analysis.periodic import (
    MIN_STATE,
    PHASE_INDEX,
    STATE_SCALE,
    PeriodicOrbit,
    Shooting,
    newton,
)
from railhunt.kernel.layout import N_STATE, Y_W1
from railhunt.model import Model
from railhunt.units import kmh_to_ms, ms_to_kmh
from railhunt.vehicle import Vehicle

HOPF_TYPES = ("subcritical", "supercritical-a", "supercritical-b")
__all__ = ["HOPF_TYPES", "BifurcationDiagram", "Branch", "Fold", "bifurcation_diagram",
           "bifurcation_family",
           "classify_hopf"]


@dataclass
class Fold:
    """A turning point of the branch in the speed."""

    speed_kmh: float
    amplitude: float  # m
    index: int  # index of the nearest computed point


@dataclass
class Branch:
    """One branch of limit cycles, in continuation order.

    Attributes
    ----------
    speed_kmh, amplitude, period, stable : numpy.ndarray
        Speed (km/h), amplitude of the leading wheelset's lateral displacement (m), period
        (s) and stability (bool) of each orbit. A branch born at the Hopf point starts with
        the Hopf point itself (amplitude 0, period from the eigenvalue).
    max_multiplier : numpy.ndarray
        Largest non-trivial Floquet multiplier modulus (NaN at the Hopf point).
    wheelset_amplitudes : numpy.ndarray, shape (n, 4)
        Amplitude of every wheelset (m).
    origin : str
        ``"hopf"`` (born at the Hopf point) or ``"simulation"`` (found from a simulated
        large-amplitude cycle and followed both ways).
    folds : list of Fold
        Turning points in the speed.
    """

    speed_kmh: np.ndarray
    amplitude: np.ndarray
    period: np.ndarray
    stable: np.ndarray
    max_multiplier: np.ndarray
    wheelset_amplitudes: np.ndarray
    origin: str
    folds: list[Fold]
    orbits: list[PeriodicOrbit] = field(default_factory=list, repr=False)

    @property
    def frequency_hz(self) -> np.ndarray:
        """Orbit frequencies ``1 / period`` (Hz)."""
        return 1.0 / self.period

    def segments(self) -> list[tuple[int, int, bool]]:
        """Runs of equal stability as ``(first, last, stable)`` (inclusive, overlapping by one)."""
        out = []
        start = 0
        st = self.stable
        for i in range(1, st.size + 1):
            if i == st.size or st[i] != st[start]:
                out.append((start, min(i, st.size - 1), bool(st[start])))
                start = i
        return out

    def speeds_at_amplitude(self, amplitude: float, stable: bool | None = False) -> list[float]:
        """Speeds (km/h) where the branch crosses ``amplitude`` (m), linearly interpolated.

        ``stable=False`` keeps crossings between two unstable orbits, ``True`` between two
        stable ones, ``None`` all.
        """
        a, s, st = self.amplitude, self.speed_kmh, self.stable
        out = []
        for i in range(a.size - 1):
            if (a[i] - amplitude) * (a[i + 1] - amplitude) > 0 or a[i] == a[i + 1]:
                continue
            if stable is not None and not (st[i] == stable and st[i + 1] == stable):
                continue
            w = (amplitude - a[i]) / (a[i + 1] - a[i])
            out.append(float(s[i] + w * (s[i + 1] - s[i])))
        return out

    def to_dict(self) -> dict:
        """JSON-ready arrays (km/h, m, s)."""
        return {
            "origin": self.origin,
            "speed_kmh": self.speed_kmh.tolist(),
            "amplitude": self.amplitude.tolist(),
            "period": self.period.tolist(),
            "stable": self.stable.tolist(),
            "max_multiplier": [None if math.isnan(m) else m for m in self.max_multiplier],
            "wheelset_amplitudes": self.wheelset_amplitudes.tolist(),
            "folds": [{"speed_kmh": f.speed_kmh, "amplitude": f.amplitude} for f in self.folds],
        }


@dataclass
class BifurcationDiagram:
    """Limit-cycle branches of the vehicle versus speed, with the Hopf point and type.

    Attributes
    ----------
    branches : list of Branch
        ``branches[0]`` is born at the Hopf point; further branches were found from
        simulated large-amplitude cycles that do not lie on an earlier branch.
    hopf_speed_kmh : float
        Linear critical speed (the Hopf point, from the eigenvalues).
    hopf_speed_from_orbits_kmh : float
        The Hopf speed found independently, by extrapolating the three smallest orbits of
        the Hopf branch to zero amplitude (checks the continuation against the eigenvalues).
    hopf_frequency_hz : float
        Frequency of the hunting eigenvalue at the Hopf point (Hz).
    fold_speed_kmh : float
        Lowest speed with a limit cycle on any branch: the nonlinear critical speed. Equal
        to the Hopf speed when no branch reaches below it; NaN when a branch leaves the
        range downward (``fold_below_range``: the lowest cycle lies below the range).
    hopf_type : str
        One of ``"subcritical"``, ``"supercritical-a"``, ``"supercritical-b"`` (module
        docstring).
    speed_range_kmh : tuple of float
        The range the continuation was confined to.
    complete : bool
        False when a branch stopped early (Newton failure at the smallest step, or the
        point budget ran out).
    message : str
        Why each branch stopped.
    fold_below_range : bool
        True when a branch leaves the speed range downward.
    """

    branches: list[Branch]
    hopf_speed_kmh: float
    hopf_speed_from_orbits_kmh: float
    hopf_frequency_hz: float
    fold_speed_kmh: float
    hopf_type: str
    speed_range_kmh: tuple[float, float]
    complete: bool
    message: str
    fold_below_range: bool = False

    @property
    def folds(self) -> list[Fold]:
        """Every fold of every branch."""
        return [f for b in self.branches for f in b.folds]

    def speeds_at_amplitude(self, amplitude: float, stable: bool | None = False) -> list[float]:
        """Crossings of ``amplitude`` (m) on all branches (km/h), sorted."""
        return sorted(v for b in self.branches for v in b.speeds_at_amplitude(amplitude, stable))

    def point_p_kmh(self, amplitude: float = 3e-3) -> float:
        """The paper's point P: lowest speed where ``amplitude`` (m) meets an unstable branch.

        Above it a disturbance of that amplitude of the leading wheelset grows to a large
        limit cycle, below it decays (Fig. 7a). NaN when no unstable branch reaches it.
        """
        speeds = self.speeds_at_amplitude(amplitude, stable=False)
        return speeds[0] if speeds else math.nan

    def to_dict(self, point_p_amplitude: float = 3e-3) -> dict:
        """JSON-ready summary (speeds in km/h, amplitudes in m, periods in s)."""
        return {
            "hopf_speed_kmh": self.hopf_speed_kmh,
            "hopf_speed_from_orbits_kmh": self.hopf_speed_from_orbits_kmh,
            "hopf_frequency_hz": self.hopf_frequency_hz,
            "fold_speed_kmh": self.fold_speed_kmh,
            "hopf_type": self.hopf_type,
            "point_p": {"amplitude": point_p_amplitude,
                        "speed_kmh": _none_if_nan(self.point_p_kmh(point_p_amplitude))},
            "folds": [{"speed_kmh": f.speed_kmh, "amplitude": f.amplitude} for f in self.folds],
            "speed_range_kmh": list(self.speed_range_kmh),
            "fold_below_range": self.fold_below_range,
            "complete": self.complete,
            "message": self.message,
            "branches": [b.to_dict() for b in self.branches],
        }


def _none_if_nan(x: float) -> float | None:
    return None if math.isnan(x) else x


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


def _hopf_start(model: Model, hopf_kmh: float) -> tuple[np.ndarray, float]:
    """Hunting eigenvector normalised to y_w1 = 1 (real state shape) and the period (s)."""
    w, vecs = eigenvalues(model, kmh_to_ms(hopf_kmh))
    k = hunting_mode_index(w, vecs, model.vehicle.a)
    lam = w[k]
    if lam.imag < 0:
        lam, vec = np.conj(lam), np.conj(vecs[:, k])
    else:
        vec = vecs[:, k]
    vec = vec / vec[Y_W1]
    return np.real(vec), 2 * math.pi / abs(lam.imag)


@dataclass
class _Limits:
    lo: float
    hi: float
    max_amplitude: float
    max_points: int
    max_step_kmh: float
    max_step_amplitude: float


class _Tracer:
    """Pseudo-arclength continuation of one direction of a branch."""

    def __init__(self, shoot: Shooting, limits: _Limits,
                 on_point: Callable[[PeriodicOrbit], None] | None) -> None:  # fmt: skip
        self.shoot = shoot
        self.limits = limits
        self.on_point = on_point
        keep = np.ones(N_STATE, dtype=bool)
        keep[PHASE_INDEX] = False
        self.iy = int(np.flatnonzero(keep).tolist().index(Y_W1))

    def solve(self, u: np.ndarray, norm: float, it: int) -> tuple[PeriodicOrbit, tuple]:
        lin = self.shoot.linearise(u)
        orbit = self.shoot.orbit(u, norm, it, lin)
        if self.on_point is not None:
            self.on_point(orbit)
        return orbit, lin

    def null_vector(self, jac: np.ndarray, guess: np.ndarray) -> np.ndarray:
        aug = np.vstack([jac, guess])
        e = np.zeros(guess.size)
        e[-1] = 1.0
        t = np.linalg.solve(aug, e)
        return t / np.linalg.norm(t)

    def trace(self, u0: np.ndarray, lin0: tuple, tangent: np.ndarray, ds: float,
              budget: int, limits: _Limits | None = None,
              ) -> tuple[list[PeriodicOrbit], str, bool, bool]:  # fmt: skip
        """Follow the branch from ``u0`` along ``tangent``.

        Returns the new orbits, why it stopped, whether it stopped normally (False: Newton
        failed at the smallest step or the point budget ran out) and whether it left the
        speed range downward (the branch goes on below the range).
        """
        lim, shoot, iy = limits or self.limits, self.shoot, self.iy
        orbits: list[PeriodicOrbit] = []
        u_prev, lin = u0, lin0
        ds_min, ds_max = 1e-3, 50.0
        for _ in range(budget):
            jac = shoot.jacobian(u_prev, lin=lin)
            tangent = self.null_vector(jac, tangent)
            ok = False
            while ds >= ds_min:
                dv_kmh = ms_to_kmh(abs(tangent[-1]) * Shooting.V_SCALE)
                da = abs(tangent[iy]) * STATE_SCALE[Y_W1]
                ds = min(ds, ds_max, lim.max_step_kmh / max(dv_kmh, 1e-12),
                         lim.max_step_amplitude / max(da, 1e-12))  # fmt: skip
                u_pred = u_prev + ds * tangent
                t_row = tangent.copy()

                def fun(w, u_pred=u_pred, t_row=t_row):
                    return np.append(shoot.residual(w), t_row @ (w - u_pred))

                def jac_fun(w, r, t_row=t_row):
                    return np.vstack([shoot.jacobian(w, r[:-1]), t_row])

                u_new, norm, it, ok, _ = newton(fun, jac_fun, u_pred, tol=1e-9, max_iter=8,
                                                jac=np.vstack([jac, t_row]))  # fmt: skip
                # Reject a corrector that strayed far from the predictor (it may have jumped
                # to another branch) or fell onto the equilibrium, which solves the shooting
                # equations for any period.
                if ok and (np.linalg.norm(u_new - u_pred) > ds
                           or np.max(np.abs(u_new[:-2])) < MIN_STATE):  # fmt: skip
                    ok = False
                if ok:
                    break
                ds *= 0.5
            if not ok:
                return orbits, "Newton failed at the smallest step", False, False
            orbit, lin = self.solve(u_new, norm, it)
            orbits.append(orbit)
            u_prev = u_new
            ds *= 1.4 if it <= 4 else 0.7 if it > 6 else 1.0
            going_down = tangent[-1] < 0
            v_kmh = orbit.speed_kmh
            if v_kmh < lim.lo and going_down:
                return orbits, "left the speed range downward", True, True
            if v_kmh > lim.hi and not going_down:
                return orbits, "left the speed range upward", True, False
            if orbit.amplitude > lim.max_amplitude:
                return orbits, f"amplitude above {lim.max_amplitude * 1e3:g} mm", True, False
        return orbits, f"used all its {budget} points (incomplete)", False, False


def _make_branch(orbits: list[PeriodicOrbit], origin: str,
                 hopf: tuple[float, float] | None = None) -> Branch:  # fmt: skip
    """Arrays and folds of a branch; ``hopf = (speed_kmh, period)`` prepends the Hopf point."""
    speed = [o.speed_kmh for o in orbits]
    amp = [o.amplitude for o in orbits]
    period = [o.period for o in orbits]
    stable = [o.stable for o in orbits]
    mmax = [o.max_multiplier for o in orbits]
    wamp = [o.wheelset_amplitudes for o in orbits]
    if hopf is not None:
        speed.insert(0, hopf[0])
        amp.insert(0, 0.0)
        period.insert(0, hopf[1])
        stable.insert(0, stable[0])
        mmax.insert(0, math.nan)
        wamp.insert(0, np.zeros(4))
    speed_a = np.array(speed)
    amp_a = np.array(amp)
    folds = []
    dv = np.diff(speed_a)
    for i in range(1, dv.size):
        if dv[i - 1] * dv[i] < 0:
            # Parabola of speed against the distance along the branch in the (speed / 10
            # km/h, amplitude / 1 mm) plane, through the three points around the turn.
            seg = np.hypot(dv[i - 1:i + 1] / 10.0, np.diff(amp_a[i - 1:i + 2]) / 1e-3)
            dist = np.array([-seg[0], 0.0, seg[1]])
            c = np.polyfit(dist, speed_a[i - 1:i + 2], 2)
            s_turn = float(np.clip(-c[1] / (2 * c[0]), dist[0], dist[2])) if c[0] != 0 else 0.0
            v_turn = float(np.polyval(c, s_turn))
            a_turn = float(np.interp(s_turn, dist, amp_a[i - 1:i + 2]))
            folds.append(Fold(v_turn, a_turn, i))
    return Branch(speed_a, amp_a, np.array(period), np.array(stable, dtype=bool),
                  np.array(mmax), np.array(wamp), origin, folds, list(orbits))  # fmt: skip


def bifurcation_diagram(
    vehicle: Vehicle,
    speed_range_kmh: tuple[float, float] = (200.0, 500.0),
    max_amplitude: float = 0.015,
    max_points: int = 600,
    max_step_kmh: float = 5.0,
    max_step_amplitude: float = 4e-4,
    seed_amplitudes: tuple[float, ...] = (0.008,),
    dt: float | None = None,
    symmetric: bool = True,
    creep_law: str = "heuristic",
    on_point: Callable[[PeriodicOrbit], None] | None = None,
) -> BifurcationDiagram:
    """Bifurcation diagram of the vehicle: branches of limit cycles versus speed.

    The Hopf branch is followed from the Hopf point (over the range widened to 10 km/h
    around the Hopf point). So that a branch of large cycles not connected to it within
    the range is not missed, the vehicle is also simulated from each of ``seed_amplitudes``
    (an initial lateral displacement of all wheelsets) at the top of the range and, if that
    is below the Hopf point, 10 km/h above the Hopf point; a cycle it settles on that lies
    on no branch yet is refined by shooting and followed both ways.

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
        Initial displacements (m) of the seeding simulations; empty for none.
    dt : float, optional
        Largest RK4 step of the shooting (s); default the automatic step at the top speed.
    symmetric : bool
        Shoot over half periods using the vehicle's left/right symmetry.
    creep_law : str
        See :class:`railhunt.model.Model`.
    on_point : callable, optional
        Called with each new orbit (progress reporting).

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
    limits = _Limits(lo, hi, max_amplitude, int(max_points), max_step_kmh, max_step_amplitude)
    model = Model(vehicle, creep_law=creep_law)
    linear = linear_critical_speed(vehicle, max_kmh=2000.0, tol_kmh=1e-3, creep_law=creep_law)
    hopf = linear.speed_kmh
    if not math.isfinite(hopf):
        raise ValueError("the centred equilibrium stays stable up to 2000 km/h: no Hopf point")
    shape, period0 = _hopf_start(model, hopf)
    shoot = Shooting(model, symmetric=symmetric, dt=dt, dt_speed=kmh_to_ms(max(hi, hopf)))
    shoot.set_period_hint(period0)
    tracer = _Tracer(shoot, limits, on_point)
    iy = tracer.iy

    # 1. Three small orbits with y_w1(0) fixed (natural parameter), from the eigenvector.
    seeds = (5e-5, 1e-4, 2e-4)
    small: list[tuple[np.ndarray, PeriodicOrbit, tuple]] = []
    u = shoot.pack(seeds[0] * shape, period0, kmh_to_ms(hopf))
    for n, eps in enumerate(seeds):
        target = eps / STATE_SCALE[Y_W1]
        if n >= 2:
            u = small[-1][0] + (small[-1][0] - small[-2][0]) * (eps - seeds[n - 1]) / (
                seeds[n - 1] - seeds[n - 2])  # fmt: skip
        u = u.copy()
        u[iy] = target

        def fun(w: np.ndarray, target: float = target) -> np.ndarray:
            return np.append(shoot.residual(w), w[iy] - target)

        def jac_fun(w: np.ndarray, r: np.ndarray) -> np.ndarray:
            row = np.zeros(w.size)
            row[iy] = 1.0
            return np.vstack([shoot.jacobian(w, r[:-1]), row])

        u, norm, it, ok, _ = newton(fun, jac_fun, u, tol=1e-9, max_iter=20)
        if not ok:
            raise RuntimeError(f"no small limit cycle found near the Hopf point ({hopf:.1f} km/h)")
        orbit, lin = tracer.solve(u, norm, it)
        small.append((u, orbit, lin))
    a_small = np.array([o.amplitude for _, o, _ in small])
    v_small = np.array([o.speed_kmh for _, o, _ in small])
    hopf_from_orbits = float(np.polyfit(a_small, v_small, 2)[-1])

    # 2. The Hopf branch by pseudo-arclength continuation.
    # The Hopf branch is followed over the range widened to 10 km/h around the Hopf point,
    # so that its type is known even when the Hopf point lies outside the range.
    tangent = small[-1][0] - small[-2][0]
    ds = float(np.linalg.norm(tangent))
    hopf_limits = dataclasses.replace(limits, lo=min(lo, hopf - 10.0), hi=max(hi, hopf + 10.0))
    more, msg, complete, below = tracer.trace(small[-1][0], small[-1][2], tangent / ds, ds,
                                              limits.max_points, hopf_limits)  # fmt: skip
    branches = [_make_branch([o for _, o, _ in small] + more, "hopf", (hopf, period0))]
    messages = [f"Hopf branch: {msg}"]

    # 3. Branches of large cycles found by simulation: at the top of the range and, when
    # that is below the Hopf point, also just above it (where every disturbance grows to
    # a cycle, while near a fold the large cycles' basins can be too small to reach).
    seed_speeds = [hi] + ([min(hopf + 10.0, 2.0 * hi)] if hopf + 10.0 > hi else [])
    for amp in seed_amplitudes:
        for seed_kmh in seed_speeds:
            found = _seed_orbit(model, shoot, seed_kmh, amp)
            if found is None:
                continue
            u_c, orbit_c, lin_c = found
            if any(_on_branch(b, orbit_c) for b in branches):
                continue
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
            branches.append(_make_branch(parts[0][::-1] + [orbit_c] + parts[1], "simulation"))
            break

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


def classify_hopf(branch: Branch, hopf_kmh: float, tol_kmh: float | None = None) -> str:
    """Type of the Hopf bifurcation from the shape of its branch (the paper's Fig. 5).

    ``"subcritical"`` when the branch falls more than ``tol_kmh`` below the Hopf speed
    before it rises more than ``tol_kmh`` above it; otherwise ``"supercritical-a"`` when it
    later turns back toward lower speeds by more than ``tol_kmh`` (a fold pair: small and
    large cycles coexist), else ``"supercritical-b"``.

    The tolerance (default ``max(2 km/h, 1 % of the Hopf speed)``) is needed because the
    heuristic creep saturation (Eq. 28) reduces the creep forces in proportion to the
    amplitude itself (``alpha = 1 - beta/3 + ...``), so the branch always starts toward
    lower speeds, by ``O(amplitude)``: a dip of a km/h or two at sub-millimetre amplitude
    that no excitation of engineering size can tell from a supercritical start.
    """
    tol = max(2.0, 0.01 * hopf_kmh) if tol_kmh is None else float(tol_kmh)
    speed = branch.speed_kmh
    below = np.flatnonzero(speed < hopf_kmh - tol)
    above = np.flatnonzero(speed > hopf_kmh + tol)
    if below.size and (not above.size or below[0] < above[0]):
        return "subcritical"
    if above.size:
        running_max = np.maximum.accumulate(speed[above[0]:])
        if np.any(running_max - speed[above[0]:] > tol):
            return "supercritical-a"
        return "supercritical-b"
    # The branch never left the tolerance band (cut short): judge by where it ended.
    return "subcritical" if speed[-1] < hopf_kmh else "supercritical-b"


def _on_branch(branch: Branch, orbit: PeriodicOrbit, rel: float = 0.02) -> bool:
    """True when ``orbit`` lies on ``branch`` (amplitude and period at its speed within ``rel``)."""
    s, a, p = branch.speed_kmh, branch.amplitude, branch.period
    for i in range(s.size - 1):
        lo_s, hi_s = sorted((s[i], s[i + 1]))
        if not lo_s <= orbit.speed_kmh <= hi_s or hi_s == lo_s:
            continue
        w = (orbit.speed_kmh - s[i]) / (s[i + 1] - s[i])
        ai = a[i] + w * (a[i + 1] - a[i])
        pi = p[i] + w * (p[i + 1] - p[i])
        if abs(ai - orbit.amplitude) <= rel * orbit.amplitude and abs(pi - orbit.period) <= (
            rel * orbit.period
        ):
            return True
    return False


def _seed_orbit(model: Model, shoot: Shooting, speed_kmh: float, amplitude: float):
    """Simulate from a displaced state, shoot from where it settles; None if it decays."""
    from railhunt.analysis.periodic import phase_origin
    from railhunt.simulation import auto_step, integrate_model

    speed = kmh_to_ms(speed_kmh)
    x0 = np.zeros(N_STATE)
    x0[[9, 11, 13, 15]] = amplitude
    dt = auto_step(model, speed)
    t, x, status, _ = integrate_model(model, speed, 12.0, x0, dt=dt)
    if status != 0:
        return None
    y = x[:, Y_W1]
    tail = y[t > t[-1] - 2.0]
    if np.max(np.abs(tail)) < 1e-4:
        return None
    k = phase_origin(t, y)
    # Period guess from the spacing of the last maxima.
    peaks = [i for i in range(1, y.size - 1) if y[i] >= y[i - 1] and y[i] > y[i + 1]
             and t[i] > t[-1] - 2.0]  # fmt: skip
    if len(peaks) < 3:
        return None
    period = float(np.mean(np.diff(t[peaks])))
    u = shoot.pack(np.where(np.arange(N_STATE) == PHASE_INDEX, 0.0, x[k]), period, speed)
    vs = u[-1]

    def fun(w: np.ndarray) -> np.ndarray:
        return shoot.residual(np.append(w, vs))

    def jac_fun(w: np.ndarray, r: np.ndarray) -> np.ndarray:
        return shoot.jacobian(np.append(w, vs), r)[:, :-1]

    w, norm, it, ok, _ = newton(fun, jac_fun, u[:-1], tol=1e-9, max_iter=20)
    if not ok:
        return None
    u = np.append(w, vs)
    lin = shoot.linearise(u)
    return u, shoot.orbit(u, norm, it, lin), lin


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
