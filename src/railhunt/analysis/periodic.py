"""Limit cycles of the autonomous vehicle model by shooting, and their Floquet multipliers.

A periodic orbit ``x(t + T) = x(t)`` of the model on ideal track is found by Newton's
method on the shooting residual, with the period ``T`` as an unknown and a phase condition
that fixes the orbit's time origin at an extremum of the leading wheelset's lateral
displacement (``dy_w1/dt = 0`` at ``t = 0``).

Symmetry. On ideal track the vehicle is left/right symmetric: the right-hand side is odd,
``f(-x) = -f(x)`` (the wheel profiles are mirror images, the damper law is odd). A hunting
orbit is then invariant under that symmetry with a half-period shift,
``x(t + T/2) = -x(t)``, and it suffices to shoot over half a period with the residual
``phi_{T/2}(x0) + x0``. The monodromy matrix is ``(-M_half)**2`` with
``M_half = d phi_{T/2} / d x0``; the Floquet multipliers are the squares of the
eigenvalues of ``-M_half``. ``symmetric=False`` shoots over the whole period instead (for
asymmetric vehicles or orbits).

Non-smoothness. The yaw damper's two-stage law has a kink at ``|F_d| = F_u`` (blow-off).
The flow used here (:func:`railhunt.kernel.flow.flow`) locates each crossing inside a
step and restarts there, so every Runge-Kutta step sees a smooth vector field. The
discrete flow map is then smooth in ``x0``, ``T`` and the speed, Newton converges
quadratically, and the answer converges at fourth order in the step (tests).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from railhunt.analysis.newton import newton
from railhunt.analysis.newton_krylov import newton_krylov
from railhunt.kernel.flow import flow
from railhunt.kernel.layout import LAYOUT, RATE0, Y_W1, StateLayout
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.simulation import auto_step
from railhunt.units import kmh_to_ms, ms_to_kmh

#: Index of dy_w1/dt in the state vector: the phase condition fixes it to zero.
PHASE_INDEX = RATE0 + Y_W1

#: Natural scales of the states (m or rad, m/s or rad/s, N) for Newton and finite differences.
def state_scale(layout: StateLayout) -> np.ndarray:
    """Natural scales of a layout's states (1e-3 m or rad, 1e-2 m/s or rad/s, 1e3 N)."""
    n, nd = layout.n_dof, layout.n_damper
    return np.concatenate([np.full(n, 1e-3), np.full(n, 1e-2), np.full(nd, 1e3)])


#: :func:`state_scale` of the paper's vehicle.
STATE_SCALE = state_scale(LAYOUT)
#: Relative finite-difference step (times STATE_SCALE).
FD_STEP = 1e-5
#: Smallest largest scaled state entry of an orbit (1e-2: 10 micrometres or 0.1 mm/s);
#: below it a solution of the shooting equations is the equilibrium, not a cycle.
MIN_STATE = 1e-2


@dataclass(repr=False)
class PeriodicOrbit(ResultDisplay):
    """A limit cycle of the vehicle on ideal track.

    Attributes
    ----------
    speed : float
        Forward speed (m/s).
    state : numpy.ndarray, shape (38,)
        State at the phase origin (an extremum of the leading wheelset's displacement).
    period : float
        Period (s).
    amplitude : float
        Largest |lateral displacement| of the leading wheelset over the orbit (m).
    multipliers : numpy.ndarray
        Floquet multipliers (complex), sorted by decreasing modulus, the trivial one
        (``~1``, along the orbit) included.
    stable : bool
        True when every non-trivial multiplier lies inside the unit circle.
    residual : float
        Scaled shooting residual at convergence (dimensionless).
    iterations : int
        Newton iterations used.
    symmetric : bool
        True when found with the half-period symmetric residual.
    wheelset_amplitudes : numpy.ndarray, shape (4,)
        Largest |lateral displacement| of each wheelset (m); the first is ``amplitude``.
        A cycle in which the rear bogie hunts has a small ``amplitude`` and a large
        ``wheelset_amplitudes[2:]``.
    """

    speed: float
    state: np.ndarray
    period: float
    amplitude: float
    multipliers: np.ndarray
    stable: bool
    residual: float
    iterations: int
    symmetric: bool
    wheelset_amplitudes: np.ndarray

    @property
    def speed_kmh(self) -> float:
        """Forward speed (km/h)."""
        return ms_to_kmh(self.speed)

    @property
    def frequency_hz(self) -> float:
        """Orbit frequency ``1 / period`` (Hz)."""
        return 1.0 / self.period

    @property
    def max_multiplier(self) -> float:
        """Largest modulus among the non-trivial Floquet multipliers."""
        return float(np.max(np.abs(_nontrivial(self.multipliers))))

    def _summary(self) -> list[Row]:
        return [("speed", self.speed_kmh, "km/h"), ("period", self.period, "s"),
                ("frequency", self.frequency_hz, "Hz"), ("amplitude", self.amplitude, "m"),
                ("stable", self.stable, ""),
                ("largest non-trivial multiplier", self.max_multiplier, ""),
                ("residual", self.residual, ""), ("Newton iterations", self.iterations, "")]

    def _columns(self) -> Columns:
        """One row per wheelset: its amplitude on the orbit."""
        return {"wheelset": (np.arange(1, self.wheelset_amplitudes.size + 1), ""),
                "amplitude": (self.wheelset_amplitudes, "m")}


def _nontrivial(mult: np.ndarray) -> np.ndarray:
    k = int(np.argmin(np.abs(mult - 1.0)))
    return np.delete(mult, k)


class Shooting:
    """The shooting problem of one vehicle model: residual, Jacobian, orbit properties.

    The unknowns are packed, scaled by :data:`STATE_SCALE`, as
    ``u = [x0 without dy_w1/dt (37), T / T_SCALE, v / V_SCALE]`` (39 entries). The
    residual has 38 entries, so a fixed speed (:func:`periodic_orbit`) or an extra
    arclength condition (:func:`railhunt.analysis.continuation.bifurcation_diagram`)
    closes the system.

    Parameters
    ----------
    model : Model
        The vehicle model.
    symmetric : bool
        Shoot over half a period with the odd-symmetry residual (module docstring).
    dt : float, optional
        Largest RK4 step (s); default the model's automatic step at ``dt_speed``.
    dt_speed : float
        Speed (m/s) at which the automatic step is evaluated (use the highest speed).
    locate_switching : bool
        Locate damper blow-off switchings inside steps.
    route : numpy.ndarray, optional
        A time-invariant route (a curve's steady route); straight track by default.
    equilibrium : callable, optional
        ``equilibrium(speed) -> state``: the equilibrium at a speed (m/s) on ``route``
        (the steady-curving state), from which orbits are told apart (default: the
        centred state). With a route, an orbit's amplitudes are its half peak-to-peak
        swings (it is not symmetric about the equilibrium).
    phase_coordinate : int, optional
        Index of the displacement whose rate is zero at ``t = 0`` (the phase condition);
        default y_w1. The Hopf branch uses the wheelset that moves most in the crossing
        mode (:func:`railhunt.analysis.continuation.measure_coordinate`).
    """

    T_SCALE = 1e-2
    V_SCALE = 1.0

    def __init__(self, model: Model, symmetric: bool = True, dt: float | None = None,
                 dt_speed: float = 140.0, locate_switching: bool = True,
                 route: np.ndarray | None = None,
                 equilibrium: Callable[[float], np.ndarray] | None = None,
                 phase_coordinate: int | None = None) -> None:  # fmt: skip
        self.model = model
        self.symmetric = symmetric
        self.route = route
        self.equilibrium = equilibrium
        self._system = model.system(route=route)
        self.dt = auto_step(model, dt_speed) if dt is None else float(dt)
        if not (math.isfinite(self.dt) and 0 < self.dt <= 0.01):
            raise ValueError(f"dt = {self.dt!r} s is invalid: must be in (0, 0.01] s")
        self.locate = bool(locate_switching)
        self.n_steps = 0  # set by set_period_hint
        layout = model.layout
        self.n_state = layout.n_state
        #: The displacement whose rate the phase condition fixes to zero (default y_w1),
        #: the index of that rate, and the states' scales of this model.
        self.phase_coordinate = layout.y_w1 if phase_coordinate is None else int(phase_coordinate)
        if not 0 <= self.phase_coordinate < layout.n_dof:
            raise ValueError(f"phase_coordinate = {phase_coordinate!r} is invalid: must be a "
                             f"displacement index in [0, {layout.n_dof})")  # fmt: skip
        self.phase_index = layout.rate0 + self.phase_coordinate
        self.scale = state_scale(layout)
        self.wheelset_y = layout.wheelset_y
        self._keep = np.ones(self.n_state, dtype=bool)
        self._keep[self.phase_index] = False
        self._no_samples = np.empty((0, 0))

    # -- packing --------------------------------------------------------------------
    def set_period_hint(self, period: float) -> None:
        """Fix the number of grid steps from an expected period (s); kept for a branch."""
        horizon = period / 2 if self.symmetric else period
        self.n_steps = max(32, int(math.ceil(horizon / self.dt)))

    def pack(self, x0: np.ndarray, period: float, speed: float) -> np.ndarray:
        """Scaled unknown vector from state, period (s) and speed (m/s)."""
        return np.concatenate([(x0 / self.scale)[self._keep],
                               [period / self.T_SCALE, speed / self.V_SCALE]])  # fmt: skip

    def unpack(self, u: np.ndarray) -> tuple[np.ndarray, float, float]:
        """State (SI), period (s) and speed (m/s) from a scaled unknown vector."""
        x0 = np.zeros(self.n_state)
        x0[self._keep] = u[:-2] * self.scale[self._keep]
        return x0, float(u[-2] * self.T_SCALE), float(u[-1] * self.V_SCALE)

    # -- the map --------------------------------------------------------------------
    def end_state(self, x0: np.ndarray, period: float, speed: float,
                  samples: np.ndarray | None = None) -> np.ndarray:  # fmt: skip
        """State after the shooting horizon (half or whole period)."""
        if self.n_steps == 0:
            self.set_period_hint(period)
        horizon = period / 2 if self.symmetric else period
        smp = self._no_samples if samples is None else samples
        x, _ = flow(np.ascontiguousarray(x0, dtype=np.float64), horizon, self.n_steps,
                    self.locate, speed, self._system, smp)  # fmt: skip
        return x

    def _residual_state(self, x0: np.ndarray, period: float, speed: float) -> np.ndarray:
        xe = self.end_state(x0, period, speed)
        r = xe + x0 if self.symmetric else xe - x0
        return r / self.scale

    def residual(self, u: np.ndarray) -> np.ndarray:
        """Scaled shooting residual (38 entries); infinite where period or speed is <= 0."""
        x0, period, speed = self.unpack(u)
        if not (period > 0 and speed > 0):
            return np.full(self.n_state, np.inf)
        return self._residual_state(x0, period, speed)

    def linearise(self, u: np.ndarray, newton_only: bool = False, speed: bool = True,
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
        """Derivatives of the end state by forward differences (40 flows).

        ``newton_only`` skips the column of the phase-fixed rate (:meth:`jacobian` drops
        it; the Floquet multipliers need it) and ``speed=False`` the speed derivative (a
        fixed speed): one flow less each. A skipped column is NaN.

        Returns
        -------
        x_end : numpy.ndarray
            End state of the shooting horizon.
        m : numpy.ndarray, shape (38, 38)
            ``d x_end / d x0`` (the half-period map's derivative when symmetric).
        d_period, d_speed : numpy.ndarray
            ``d x_end / d T`` (per s) and ``d x_end / d v`` (per m/s).
        """
        x0, period, v = self.unpack(u)
        xe = self.end_state(x0, period, v)
        n = self.n_state
        m = np.empty((n, n))
        for k in range(n):
            if newton_only and k == self.phase_index:
                m[:, k] = np.nan
                continue
            h = FD_STEP * self.scale[k]
            xp = x0.copy()
            xp[k] += h
            m[:, k] = (self.end_state(xp, period, v) - xe) / h
        hp = FD_STEP * 10 * self.T_SCALE
        d_period = (self.end_state(x0, period + hp, v) - xe) / hp
        d_speed = np.full(n, np.nan)
        if speed:
            hv = FD_STEP * 10 * self.V_SCALE
            d_speed = (self.end_state(x0, period, v + hv) - xe) / hv
        return xe, m, d_period, d_speed

    def jacobian(self, u: np.ndarray, r0: np.ndarray | None = None,
                 lin: tuple | None = None, speed: bool = True) -> np.ndarray:  # fmt: skip
        """Jacobian of :meth:`residual` with respect to ``u`` (38 x 39); with
        ``speed=False`` its last column (the speed derivative) is NaN, one flow saved."""
        if lin is None:
            lin = self.linearise(u, newton_only=True, speed=speed)
        _, m, d_period, d_speed = lin
        n, scale = self.n_state, self.scale
        a = m + np.eye(n) if self.symmetric else m - np.eye(n)
        jac = np.empty((n, u.size))
        jac[:, :-2] = (a * scale[None, :])[:, self._keep] / scale[:, None]
        jac[:, -2] = d_period * self.T_SCALE / scale
        jac[:, -1] = d_speed * self.V_SCALE / scale
        return jac

    def floquet(self, m: np.ndarray) -> np.ndarray:
        """Floquet multipliers from the horizon map's derivative, by decreasing modulus."""
        mult = np.linalg.eigvals(-m) ** 2 if self.symmetric else np.linalg.eigvals(m)
        return mult[np.argsort(-np.abs(mult))]

    def near_equilibrium(self, u: np.ndarray) -> bool:
        """True when ``u`` lies within :data:`MIN_STATE` (scaled) of the equilibrium, which
        solves the shooting equations for any period: not a cycle."""
        if self.equilibrium is None:
            return bool(np.max(np.abs(u[:-2])) < MIN_STATE)
        x0, _, speed = self.unpack(u)
        dev = (x0 - self.equilibrium(speed)) / self.scale
        return bool(np.max(np.abs(dev[self._keep])) < MIN_STATE)

    def amplitudes(self, x0: np.ndarray, period: float, speed: float) -> np.ndarray:
        """Amplitude of each wheelset's lateral displacement over the orbit (m), shape (4,).

        On straight track the largest ``|y|`` (half a symmetric orbit holds both
        extremes); on a route half the peak-to-peak swing. Each extreme is refined by a
        parabola through the three samples around it.
        """
        ys = self.wheelset_y
        samples = np.empty((self.n_steps + 1, int(ys.max()) + 1))
        self.end_state(x0, period, speed, samples)
        out = np.empty(len(ys))
        for j, col in enumerate(ys):
            if self.route is None:
                out[j] = _peak(np.abs(samples[:, col]))
            else:
                y = samples[:, col]
                out[j] = 0.5 * (_peak(y) + _peak(-y))
        return out

    def orbit(self, u: np.ndarray, residual: float = 0.0, iterations: int = 0,
              lin: tuple | None = None) -> PeriodicOrbit:  # fmt: skip
        """Orbit properties (amplitude, multipliers, stability) at a converged ``u``."""
        x0, period, speed = self.unpack(u)
        lin = self.linearise(u) if lin is None else lin
        mult = self.floquet(lin[1])
        stable = bool(np.max(np.abs(_nontrivial(mult))) < 1.0)
        amps = self.amplitudes(x0, period, speed)
        return PeriodicOrbit(speed, x0, period, float(amps[0]), mult, stable, residual,
                             iterations, self.symmetric, amps)  # fmt: skip


def _peak(y: np.ndarray) -> float:
    """Largest value of a sampled curve, refined by a parabola through its neighbours."""
    k = int(np.argmax(y))
    out = float(y[k])
    if 0 < k < y.size - 1:
        a, b, c = y[k - 1], y[k], y[k + 1]
        den = a - 2 * b + c
        if den < 0:
            out = float(b - 0.125 * (a - c) ** 2 / den)
    return out


def periodic_orbit(
    vehicle_or_model,
    speed_kmh: float,
    x0: np.ndarray,
    period: float,
    symmetric: bool = True,
    dt: float | None = None,
    tol: float = 1e-8,
    creep_law: str | None = None,
) -> PeriodicOrbit:
    """Limit cycle at a fixed speed by shooting from a guess.

    :func:`shoot_orbit` does the same without the Floquet multipliers.

    Parameters
    ----------
    vehicle_or_model : Vehicle or Model
        The vehicle.
    speed_kmh : float
        Speed (km/h).
    x0 : numpy.ndarray, shape (38,)
        A state on or near the orbit (e.g. the end of a simulation); it is moved to the
        nearest extremum of y_w1 by the phase condition.
    period : float
        Period guess (s).
    symmetric : bool
        Use the half-period symmetric residual.
    dt : float, optional
        Largest RK4 step (s); default automatic.
    tol : float
        Newton tolerance on the scaled residual.

    Raises
    ------
    RuntimeError
        When Newton does not converge.
    """
    return shoot_orbit(vehicle_or_model, speed_kmh, x0, period, symmetric, dt, tol,
                       creep_law).orbit()  # fmt: skip


def shoot_orbit(
    vehicle_or_model,
    speed_kmh: float,
    x0: np.ndarray,
    period: float,
    symmetric: bool = True,
    dt: float | None = None,
    tol: float = 1e-8,
    creep_law: str | None = None,
    krylov: bool = False,
    jacobians: list[np.ndarray] | None = None,
) -> ShotOrbit:
    """:func:`periodic_orbit` (same parameters and errors) up to its Floquet multipliers:
    the converged shooting solution, whose :meth:`ShotOrbit.orbit` computes them.

    ``krylov`` refreshes Newton's Jacobian by Krylov solves
    (:func:`railhunt.analysis.newton_krylov.newton_krylov`): the same orbit to ``tol``
    for far fewer flows from a start that is not yet on the cycle. ``jacobians`` (with
    ``krylov``) carries Newton's last Jacobian from one shot to the next of the same
    problem from nearby starts: its last entry preconditions the first step, and this
    shot's last Jacobian is appended, whether it converges or not."""
    model = vehicle_or_model if isinstance(vehicle_or_model, Model) else Model(
        vehicle_or_model, creep_law=creep_law)
    speed = kmh_to_ms(speed_kmh)
    if not (math.isfinite(period) and period > 0):
        raise ValueError(f"period = {period!r} s is invalid: must be finite and > 0")
    shoot = Shooting(model, symmetric=symmetric, dt=dt, dt_speed=speed)
    shoot.set_period_hint(period)
    x0 = np.array(x0, dtype=np.float64)
    x0[shoot.phase_index] = 0.0
    u0 = shoot.pack(x0, period, speed)[:-1]
    vs = speed / Shooting.V_SCALE

    def fun(w: np.ndarray) -> np.ndarray:
        return shoot.residual(np.append(w, vs))

    def jac_fun(w: np.ndarray, r: np.ndarray) -> np.ndarray:
        return shoot.jacobian(np.append(w, vs), r, speed=False)[:, :-1]

    if krylov:
        previous = jacobians[-1] if jacobians else None
        w, norm, it, ok, last = newton_krylov(fun, jac_fun, u0, tol=tol, max_iter=20,
                                              previous=previous)  # fmt: skip
        if jacobians is not None and last is not None:
            jacobians.append(last)
    else:
        w, norm, it, ok, _ = newton(fun, jac_fun, u0, tol=tol, max_iter=20)
    if not ok:
        raise RuntimeError(
            f"shooting did not converge at {speed_kmh:.1f} km/h "
            f"(scaled residual {norm:.2e} after {it} iterations)"
        )
    if shoot.near_equilibrium(np.append(w, vs)):
        raise RuntimeError(
            f"shooting at {speed_kmh:.1f} km/h fell onto the equilibrium (which solves the "
            "shooting equations for any period): no limit cycle near the guess"
        )
    return ShotOrbit(shoot, np.append(w, vs), norm, it)


@dataclass
class ShotOrbit:
    """A converged shooting solution before its Floquet multipliers are computed (they
    cost one more linearisation, 40 flows): :meth:`orbit` gives the
    :class:`PeriodicOrbit`; ``period``, ``frequency_hz`` and the amplitudes do not
    need them."""

    shoot: Shooting
    u: np.ndarray
    residual: float
    iterations: int

    @property
    def period(self) -> float:
        """Period (s)."""
        return self.shoot.unpack(self.u)[1]

    @property
    def frequency_hz(self) -> float:
        """``1 / period`` (Hz)."""
        return 1.0 / self.period

    @cached_property
    def wheelset_amplitudes(self) -> np.ndarray:
        """Each wheelset's amplitude over the orbit (m), as :class:`PeriodicOrbit`'s."""
        return self.shoot.amplitudes(*self.shoot.unpack(self.u))

    @property
    def amplitude(self) -> float:
        """The leading wheelset's amplitude (m), as :class:`PeriodicOrbit`'s."""
        return float(self.wheelset_amplitudes[0])

    def orbit(self) -> PeriodicOrbit:
        """The orbit with its Floquet multipliers and stability."""
        return self.shoot.orbit(self.u, self.residual, self.iterations)


def phase_origin(t: np.ndarray, y: np.ndarray) -> int:
    """Index of the last local maximum of ``y`` (a good phase origin for shooting)."""
    k = y.size - 2
    while k > 0 and not (y[k] >= y[k - 1] and y[k] >= y[k + 1]):
        k -= 1
    return max(k, 0)
