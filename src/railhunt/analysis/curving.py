"""Steady curving: the quasi-static equilibrium in a constant curve, and its stability.

In the constant part of a curve the vehicle, measured from the track, settles on an
equilibrium: every rate zero, every acceleration zero. Newton's method solves that on the
model's own right-hand side (:func:`railhunt.kernel.rhs.rhs` with the curve's steady
route): the unknowns are the 17 coordinates and the 4 yaw damper forces, the equations
their accelerations and force rates, the Jacobian the kernel's (central differences of
``rhs``). No second copy of the equations exists. The eigenvalues of the full Jacobian at
the equilibrium tell whether it is stable and how well the hunting mode is damped.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from railhunt.analysis.modes import hunting_mode_index, sorted_eig
from railhunt.analysis.newton import newton
from railhunt.curve import Curve
from railhunt.kernel.bumpstop import bump_stop_force
from railhunt.kernel.layout import StateLayout, StopParam
from railhunt.kernel.rhs import curve_geometry, derived, rhs
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.units import kmh_to_ms, ms_to_kmh
from railhunt.vehicle import Vehicle


def _equilibrium_slots(layout: StateLayout) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The unknowns of the equilibrium (coordinates and damper forces: rates are zero),
    the equations (accelerations and damper force rates) and the equations' scales for the
    convergence test (m/s^2 or rad/s^2, and N/s)."""
    n, f0, ns = layout.n_dof, layout.force0, layout.n_state
    unknowns = np.concatenate([np.arange(n), np.arange(f0, ns)])
    equations = np.arange(layout.rate0, ns)
    scale = np.concatenate([np.full(n, 1.0), np.full(ns - f0, 1e3)])
    return unknowns, equations, scale


class CurvingError(RuntimeError):
    """No steady-curving equilibrium was found (Newton did not converge)."""


def equilibrium(
    model: Model, speed: float, route: np.ndarray, x0: np.ndarray | None = None,
    tol: float = 1e-9, max_iter: int = 40,
) -> tuple[np.ndarray, float, int]:  # fmt: skip
    """Steady state of the model on a time-invariant route (rates zero, accelerations zero).

    Parameters
    ----------
    model : Model
        The vehicle model.
    speed : float
        Forward speed (m/s).
    route : numpy.ndarray
        A route on which the right-hand side does not depend on time
        (:meth:`railhunt.curve.Curve.steady_route`).
    x0 : numpy.ndarray, optional
        Starting guess (38 states; its rates are ignored); default the centred state.
    tol : float
        Largest scaled residual accepted (accelerations in m/s^2, force rates in kN/s).
    max_iter : int
        Largest number of Newton iterations.

    Returns
    -------
    x : numpy.ndarray
        The equilibrium state (rates zero).
    residual : float
        Its largest scaled residual.
    iterations : int
        Newton iterations used.

    Raises
    ------
    CurvingError
        If Newton's method does not converge.
    """
    v, system = model.args(speed, route=route)
    layout = model.layout
    unknowns, equations, eq_scale = _equilibrium_slots(layout)
    x = np.zeros(layout.n_state) if x0 is None else np.array(x0, dtype=np.float64)
    x[layout.rate0:layout.force0] = 0.0
    out = np.empty(layout.n_state)

    def state_of(z: np.ndarray) -> np.ndarray:
        state = x.copy()
        state[unknowns] = z
        return state

    def residual(z: np.ndarray) -> np.ndarray:
        rhs(0.0, state_of(z), v, system, out)
        return out[equations] / eq_scale

    def jacobian(z: np.ndarray, r: np.ndarray) -> np.ndarray:
        jac = model.jacobian(speed, state_of(z), route=route)
        return jac[np.ix_(equations, unknowns)] / eq_scale[:, None]

    # Up to 12 halvings: from the centred state a tight curve's first steps overshoot the
    # flange (the contact angle steepens sharply there).
    z, norm, iterations, converged, _ = newton(residual, jacobian, x[unknowns], tol=tol,
                                               max_iter=max_iter, halvings=12)  # fmt: skip
    if converged:
        return state_of(z), norm, iterations
    raise CurvingError(
        f"no steady-curving equilibrium found at {ms_to_kmh(speed):.1f} km/h "
        f"(scaled residual {norm:.2e} after Newton's method)"
    )


@dataclass(repr=False)
class CurvingResult(ResultDisplay):
    """The steady-curving state of a vehicle in a constant curve (SI units).

    Wheels are given per wheelset (leading first) as ``[left, right]``. Lateral quantities
    of bodies are relative to the track at each body's position, + toward +y (left):
    in a curve to the left the outside is -y.

    Attributes
    ----------
    speed_kmh : float
        Speed (km/h).
    curve : Curve
        The curve.
    state : numpy.ndarray, shape (38,)
        The equilibrium state (rates zero).
    wheelset_y : numpy.ndarray, shape (4,)
        Lateral displacement of each wheelset relative to the track (m).
    attack_angle : numpy.ndarray, shape (4,)
        Angle of attack of each wheelset (rad): its yaw relative to the track's direction,
        positive when its front points toward the outer rail.
    Y : numpy.ndarray, shape (4, 2)
        Guiding force of each wheel on its rail (N), positive outward from the track
        centre (toward the wheel's flange side).
    Q : numpy.ndarray, shape (4, 2)
        Wheel loads (N).
    derailment_quotient : numpy.ndarray, shape (4, 2)
        ``Y / Q`` of each wheel.
    sum_Y : numpy.ndarray, shape (4,)
        Sum of the guiding forces of each wheelset on the track (N), + toward +y.
    unbalanced_acceleration : float
        Unbalanced lateral acceleration in the track plane (m/s^2), + outward.
    cant_deficiency : float
        Cant deficiency (m), negative for a cant excess.
    car_body_y : float
        Lateral displacement of the car body relative to the track (m).
    bogie_y : numpy.ndarray, shape (2,)
        Lateral displacement of each bogie frame relative to the track (m).
    bump_stop_force : numpy.ndarray, shape (2,)
        Force in each secondary lateral bump stop (N, + when the bogie sits toward +y of
        the car body); 0 inside the free play.
    stable : bool
        True when every eigenvalue of the linearised motion about the state has a negative
        real part.
    least_damping_ratio : float
        Smallest damping ratio ``-Re/|lambda|`` over all eigenvalues.
    hunting_eigenvalue : complex
        The hunting mode's eigenvalue (1/s, upper half plane).
    eigenvalues : numpy.ndarray
        All eigenvalues (1/s), sorted by decreasing real part.
    residual : float
        Scaled residual of the equilibrium.
    """

    speed_kmh: float
    curve: Curve
    state: np.ndarray
    wheelset_y: np.ndarray
    attack_angle: np.ndarray
    Y: np.ndarray
    Q: np.ndarray
    derailment_quotient: np.ndarray
    sum_Y: np.ndarray
    unbalanced_acceleration: float
    cant_deficiency: float
    car_body_y: float
    bogie_y: np.ndarray
    bump_stop_force: np.ndarray
    stable: bool
    least_damping_ratio: float
    hunting_eigenvalue: complex
    eigenvalues: np.ndarray = field(repr=False)
    residual: float = 0.0
    limits: list = field(default_factory=list)

    @property
    def warnings(self) -> list[str]:
        """The limits of the validity envelope this state reaches, in words
        (:mod:`railhunt.validity`)."""
        from railhunt.validity import warnings_of

        return warnings_of(self.limits)

    @property
    def hunting_frequency_hz(self) -> float:
        """Frequency of the hunting mode (Hz)."""
        return abs(self.hunting_eigenvalue.imag) / (2 * math.pi)

    @property
    def hunting_damping_ratio(self) -> float:
        """Damping ratio of the hunting mode (dimensionless)."""
        lam = self.hunting_eigenvalue
        return -lam.real / abs(lam) if abs(lam) > 0 else math.nan

    def _summary(self) -> list[Row]:
        return [("speed", self.speed_kmh, "km/h"), ("curve radius", self.curve.radius, "m"),
                ("cant", self.curve.cant, "m"), ("cant deficiency", self.cant_deficiency, "m"),
                ("unbalanced acceleration", self.unbalanced_acceleration, "m/s^2"),
                ("largest Y/Q", float(np.max(self.derailment_quotient)), ""),
                ("largest |ΣY|", float(np.max(np.abs(self.sum_Y))), "N"),
                ("leading wheelset y", float(self.wheelset_y[0]), "m"),
                ("stable", self.stable, ""),
                ("hunting frequency", self.hunting_frequency_hz, "Hz"),
                ("hunting damping ratio", self.hunting_damping_ratio, "")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row per wheel (leading wheelset first, left then right)."""
        n = self.wheelset_y.size
        rep = lambda a: np.repeat(np.asarray(a), 2)  # noqa: E731  (one value per wheelset)
        return {"wheelset": (rep(np.arange(1, n + 1)), ""), "side": (["left", "right"] * n, ""),
                "Y": (self.Y.ravel(), "N"), "Q": (self.Q.ravel(), "N"),
                "Y_over_Q": (self.derailment_quotient.ravel(), "1"),
                "sum_Y": (rep(self.sum_Y), "N"), "wheelset_y": (rep(self.wheelset_y), "m"),
                "attack_angle": (rep(self.attack_angle), "rad")}  # fmt: skip

    def to_dict(self) -> dict:
        """JSON-ready summary (SI units; speed in km/h)."""
        return {
            "speed_kmh": self.speed_kmh,
            "radius_m": self.curve.radius,
            "cant_m": self.curve.cant,
            "direction": self.curve.direction,
            "unbalanced_acceleration_m_s2": self.unbalanced_acceleration,
            "cant_deficiency_m": self.cant_deficiency,
            "wheelset_y_m": self.wheelset_y.tolist(),
            "attack_angle_rad": self.attack_angle.tolist(),
            "Y_N": self.Y.tolist(),
            "Q_N": self.Q.tolist(),
            "derailment_quotient": self.derailment_quotient.tolist(),
            "sum_Y_N": self.sum_Y.tolist(),
            "car_body_y_m": self.car_body_y,
            "bogie_y_m": self.bogie_y.tolist(),
            "bump_stop_force_N": self.bump_stop_force.tolist(),
            "stable": self.stable,
            "least_damping_ratio": self.least_damping_ratio,
            "hunting_frequency_hz": self.hunting_frequency_hz,
            "hunting_damping_ratio": self.hunting_damping_ratio,
            "warnings": self.warnings,
            "limits": [lim.to_dict() for lim in self.limits],
        }


def _wheel_forces(model: Model, speed: float, route: np.ndarray,
                  x: np.ndarray) -> tuple[np.ndarray, ...]:  # fmt: skip
    """ΣY (4,), Y (4, 2) and Q (4, 2) at state ``x`` (the kernel's derived channels)."""
    v, system = model.args(speed, route=route)
    res = derived(np.zeros(1), x[None, :].copy(), v, system, np.zeros(0, dtype=np.int64))[0]
    nw = system.wheelsets.shape[0]
    sum_y = res[:nw]
    y_force = np.column_stack([res[nw:2 * nw], res[2 * nw:3 * nw]])
    q = np.column_stack([res[3 * nw:4 * nw], res[4 * nw:5 * nw]])
    return sum_y, y_force, q


def bump_stop_forces(model: Model, speed: float, route: np.ndarray, x: np.ndarray,
                     t: float = 0.0) -> np.ndarray:  # fmt: skip
    """Force in each bump stop (N) at state ``x`` and time ``t`` on ``route``."""
    v, system = model.args(speed, route=route)
    geo = curve_geometry(t, v, system)
    n = model.layout.n_dof
    dist = system.stop_rows @ (x[:n] + geo[:n])
    par = system.stop
    return np.array([bump_stop_force(d, p[StopParam.GAP], p[StopParam.K1], p[StopParam.K3])
                     for d, p in zip(dist, par, strict=True)])  # fmt: skip


def _kind(body: object) -> str:
    kind = getattr(body, "kind", "")
    if kind:
        return kind
    name = body.name  # type: ignore[attr-defined]
    return "car" if name == "car" else "frame" if name.startswith("bogie") else "wheelset"


def _first_y(layout: StateLayout, x: np.ndarray, kind: str) -> float:
    """Lateral displacement of the first body of ``kind`` (m); NaN if the layout has none."""
    for b in layout.bodies:
        if _kind(b) == kind and "y" in b.coordinates:
            return float(x[layout.dof(f"y_{b.tag}")])
    return math.nan


def curving_state(model: Model, speed: float, curve: Curve, x: np.ndarray,
                  residual: float = 0.0) -> CurvingResult:  # fmt: skip
    """Everything :class:`CurvingResult` holds, at an equilibrium ``x`` already found."""
    route = curve.steady_route()
    sum_y, y_force, q = _wheel_forces(model, speed, route, x)
    w, vecs = sorted_eig(model.jacobian(speed, x, route=route))
    layout = model.layout
    k = hunting_mode_index(w, vecs, model.half_gauge, layout)
    hunt = complex(w[k]) if k >= 0 else complex(math.nan, math.nan)
    mod = np.abs(w)
    zeta = np.where(mod > 0, -w.real / np.where(mod > 0, mod, 1.0), 1.0)
    outward = 1.0 if curve.curvature > 0 else -1.0
    result = CurvingResult(
        speed_kmh=ms_to_kmh(speed), curve=curve, state=x.copy(),
        wheelset_y=x[layout.wheelset_y].copy(), attack_angle=-outward * x[layout.wheelset_psi],
        Y=y_force, Q=q, derailment_quotient=y_force / q, sum_Y=sum_y,
        unbalanced_acceleration=curve.unbalanced_acceleration(speed, model.gravity),
        cant_deficiency=curve.cant_deficiency(speed, model.gravity),
        car_body_y=_first_y(layout, x, "car"),
        bogie_y=np.array([x[layout.dof(f"y_{b.tag}")] for b in layout.bodies
                          if _kind(b) == "frame" and "y" in b.coordinates]),
        bump_stop_force=bump_stop_forces(model, speed, route, x),
        stable=bool(w[0].real < 0), least_damping_ratio=float(np.min(zeta)),
        hunting_eigenvalue=hunt, eigenvalues=w, residual=residual,
    )  # fmt: skip
    from railhunt.validity import curving_limits

    result.limits = curving_limits(result, model)
    return result


def curving(vehicle: Vehicle, speed_kmh: float, curve: Curve, creep_law: str | None = None,
            contact: object = None, x0: np.ndarray | None = None) -> CurvingResult:  # fmt: skip
    """Steady curving of a vehicle in the constant part of a curve, and its stability.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    speed_kmh : float
        Speed (km/h), in (0, 1000].
    curve : Curve
        The curve (its radius, cant and direction matter here; transitions do not).
    creep_law : str
        See :class:`railhunt.model.Model`.
    contact : ContactGeometry, optional
        Tabulated contact geometry instead of the polynomials (see ``Model``).
    x0 : numpy.ndarray, optional
        Starting guess for Newton's method (e.g. the result at a nearby speed).

    Returns
    -------
    CurvingResult

    Raises
    ------
    CurvingError
        If no equilibrium is found (e.g. far beyond the curving limit of the vehicle).
    """
    if not isinstance(curve, Curve):
        raise TypeError(f"curve = {curve!r} is invalid: must be a railhunt.Curve")
    if not (math.isfinite(speed_kmh) and 0 < speed_kmh <= 1000):
        raise ValueError(f"speed_kmh = {speed_kmh!r} km/h is invalid: must be in (0, 1000] km/h")
    model = Model(vehicle, creep_law=creep_law, contact=contact)
    speed = kmh_to_ms(speed_kmh)
    x, res = solve_curving(model, speed, curve, x0)
    return curving_state(model, speed, curve, x, res)


def solve_curving(model: Model, speed: float, curve: Curve,
                  x0: np.ndarray | None = None) -> tuple[np.ndarray, float]:  # fmt: skip
    """Equilibrium in the constant curve (speed in m/s), with a homotopy if needed.

    Newton's method from ``x0`` (default: the centred state) first; if it fails, the
    curve is approached through gentler ones (curvature and cant times 1/8, 1/4, ..., 1),
    each solved from the last: tight curves put the wheelsets on their flanges and the
    car body on its bump stops, far from the centred state.

    Returns
    -------
    x : numpy.ndarray
        The equilibrium state.
    residual : float
        Its scaled residual.
    """
    try:
        x, res, _ = equilibrium(model, speed, curve.steady_route(), x0)
        return x, res
    except CurvingError:
        pass
    x = None if x0 is None else np.asarray(x0, dtype=float)
    for fraction in (0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0):
        x, res, _ = equilibrium(model, speed, curve.scaled(fraction).steady_route(), x)
    return x, res


class EquilibriumPath:
    """Steady-curving equilibria of one model in one curve, followed along the speed.

    Each speed is solved from the equilibrium of the nearest speed solved before (the
    equilibrium moves smoothly with the cant deficiency), so scans and root searches over
    the speed cost a few Newton iterations per speed.

    Parameters
    ----------
    model : Model
        The vehicle model.
    curve : Curve or callable
        The curve, or ``curve(speed) -> Curve`` giving it at each speed (m/s), e.g. the
        cant for a fixed cant deficiency (:func:`railhunt.curve.fixed_deficiency`).
    """

    def __init__(self, model: Model, curve: Curve | Callable[[float], Curve]) -> None:
        from railhunt.arguments import check_curve

        check_curve(curve, speed_dependent=True)
        self.model = model
        self.curve = curve
        self._solved: dict[float, np.ndarray] = {}

    def curve_at(self, speed: float) -> Curve:
        """The curve at ``speed`` (m/s)."""
        return self.curve if isinstance(self.curve, Curve) else self.curve(speed)

    def route_at(self, speed: float) -> np.ndarray:
        """The steady route of the curve at ``speed`` (m/s)."""
        return self.curve_at(speed).steady_route()

    @property
    def route(self) -> np.ndarray:
        """The steady route of a fixed curve (not one that changes with speed)."""
        if not isinstance(self.curve, Curve):
            raise TypeError("this path's curve changes with the speed: use route_at(speed)")
        return self.curve.steady_route()

    def state(self, speed: float) -> np.ndarray:
        """The equilibrium state at ``speed`` (m/s)."""
        if speed not in self._solved:
            guess = None
            if self._solved:
                near = min(self._solved, key=lambda s: abs(s - speed))
                guess = self._solved[near]
            self._solved[speed], _ = solve_curving(self.model, speed, self.curve_at(speed),
                                                   guess)  # fmt: skip
        return self._solved[speed]

    def jacobian(self, speed: float) -> np.ndarray:
        """Jacobian of the motion about the equilibrium at ``speed`` (m/s)."""
        return self.model.jacobian(speed, self.state(speed), route=self.route_at(speed))

    def jacobian_kmh(self, speed_kmh: float) -> np.ndarray:
        """:meth:`jacobian` at a speed in km/h."""
        return self.jacobian(kmh_to_ms(speed_kmh))
