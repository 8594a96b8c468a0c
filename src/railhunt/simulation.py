"""Time-domain simulation of the vehicle with named output channels."""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from railhunt.arguments import check_curve
from railhunt.channels import CHANNEL_UNITS, derived_channels
from railhunt.curve import Curve
from railhunt.kernel import integrators
from railhunt.kernel.layout import LAYOUT, N_DAMPER, N_STATE, DamperParam, StateLayout
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.track import (
    DEFAULT_DISPLACED,
    InitialDisplacement,
    SampledTrack,
    SingleDefect,
    check_excitation,
)
from railhunt.units import kmh_to_ms, ms_to_kmh
from railhunt.vehicle import Vehicle

#: Default derailment limit: lateral wheelset displacement relative to the track (m).
Y_LIMIT = 0.025
#: Names of the integrators (:data:`railhunt.kernel.integrators.METHODS`).
METHODS = tuple(integrators.METHODS)
#: Unit of a channel by its name's prefix (``y_w1`` -> ``y``; derived channels too).
_UNITS = {"y": "m", "psi": "rad", "phi": "rad", "dy": "m/s", "dpsi": "rad/s", "dphi": "rad/s",
          "F": "N", "v": "m/s", **CHANNEL_UNITS}  # fmt: skip


def channel_unit(name: str) -> str:
    """SI unit of a channel of :class:`SimulationResult` (``"s"`` for the time ``t``)."""
    return "s" if name == "t" else _UNITS[name.split("_")[0]]


@dataclass(repr=False)
class SimulationResult(ResultDisplay):
    """Time histories of one run.

    Attributes
    ----------
    t : numpy.ndarray
        Times (s).
    x : numpy.ndarray
        States, one row per time (see :data:`railhunt.kernel.layout.STATE_NAMES`).
    speed : float
        Forward speed (m/s).
    status : str
        ``"ok"``, ``"derailed"`` (a wheelset's lateral displacement exceeded the limit),
        ``"diverged"`` (non-finite state), ``"step-failed"`` or ``"step-limit"`` (the
        adaptive method used up its step budget before the end: the message says so).
    message : str
        Human-readable description of how the run ended.
    damper_velocity : numpy.ndarray
        Velocity of the viscous part of each yaw damper (m/s), one column per damper.
    excitation_end : float
        Time (s) at which the last wheelset has left the excitation.
    derived : dict
        Derived channels (:mod:`railhunt.channels`): sums of guiding forces ``SY_w1..4``
        (N) and bogie frame accelerations ``ddy_t1``, ``ddy_t2`` (m/s^2), ``ddpsi_t1``,
        ``ddpsi_t2`` (rad/s^2).
    layout : StateLayout
        The vehicle's state layout (names of the states and dampers); default: the
        paper's vehicle.
    """

    t: np.ndarray
    x: np.ndarray
    speed: float
    status: str
    message: str
    damper_velocity: np.ndarray
    excitation_end: float = 0.0
    stats: dict = field(default_factory=dict)
    derived: dict = field(default_factory=dict)
    layout: StateLayout = LAYOUT
    limits: list = field(default_factory=list)

    @property
    def warnings(self) -> list[str]:
        """The limits of the validity envelope the run reached, and a blow-up, in words
        (:mod:`railhunt.validity`)."""
        from railhunt.validity import warnings_of

        out = warnings_of(self.limits)
        if self.ending == "blow-up":
            out.insert(0, f"blow-up: the integration blew up ({self.message}); numerics, "
                          "not physics: give a smaller dt")  # fmt: skip
        return out

    @property
    def ending(self) -> str:
        """How the run ended in verdict words: ``"ok"``, ``"derailed"`` or ``"blow-up"``
        (:func:`railhunt.verdicts.ending`)."""
        from railhunt.verdicts import ending

        return ending(self.status, self.x)

    @property
    def speed_kmh(self) -> float:
        """Forward speed (km/h)."""
        return ms_to_kmh(self.speed)

    @property
    def ok(self) -> bool:
        """True when the run reached its end time."""
        return self.status == "ok"

    @property
    def channel_names(self) -> tuple[str, ...]:
        """All channel names: states (``y_w1``, ``dy_w1``, ``F_d1``, ...), ``v_d1..v_d4``
        and the derived channels (``SY_w1``, ..., ``ddy_t1``, ...)."""
        lay = self.layout
        return lay.state_names + tuple("v_" + n for n in lay.dampers) + tuple(self.derived)

    def __getitem__(self, name: str) -> np.ndarray:
        names, dampers = self.layout.state_names, self.layout.dampers
        if name in names:
            return self.x[:, names.index(name)]
        if name.startswith("v_") and name[2:] in dampers:
            return self.damper_velocity[:, dampers.index(name[2:])]
        if name in self.derived:
            return self.derived[name]
        raise KeyError(
            f"unknown channel {name!r}; channels are: {', '.join(self.channel_names)}"
        )

    def table(self) -> tuple[list[str], np.ndarray]:
        """Column names (with units) and a 2-D array: time, all channels."""
        names = ["t [s]"] + [f"{n} [{channel_unit(n)}]" for n in self.channel_names]
        return names, np.column_stack(
            [self.t, self.x, self.damper_velocity, *self.derived.values()]
        )

    _index = "t"

    def _summary(self) -> list[Row]:
        y = self["y_w1"] if self.t.size else np.zeros(1)
        return [("speed", self.speed_kmh, "km/h"),
                ("status", self.status, ""),
                ("simulated time", float(self.t[-1] - self.t[0]) if self.t.size else 0.0, "s"),
                ("samples", self.t.size, ""),
                ("channels", len(self.channel_names), ""),
                ("largest |y_w1|", float(np.max(np.abs(y))), "m"),
                ("excitation left at", self.excitation_end, "s")]  # fmt: skip

    def _columns(self) -> Columns:
        """Time ``t`` (the index) and every channel, SI units."""
        cols: Columns = {"t": (self.t, "s")}
        for name in self.channel_names:
            cols[name] = (self[name], channel_unit(name))
        return cols

    def to_xarray(self) -> Any:
        """The run as an ``xarray.Dataset`` over the time ``t`` (needs ``railhunt[xarray]``).

        Returns
        -------
        xarray.Dataset
            One variable per channel, its SI unit in ``attrs["units"]``; the coordinate
            ``t`` in s; the dataset's attributes give the speed (km/h), the status and the
            time the excitation was left (s).
        """
        return self._dataset({"speed_kmh": self.speed_kmh, "status": self.status,
                              "message": self.message,
                              "excitation_end_s": self.excitation_end})  # fmt: skip

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write all channels to a CSV file (SI units, header with units)."""
        path = Path(path)
        names, data = self.table()
        with path.open("w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(names)
            for row in data:
                w.writerow([f"{val:.9g}" for val in row])
        return path


def _initial_state(model: Model, excitation: object, x0: np.ndarray | None) -> np.ndarray:
    n = model.layout.n_state
    x = np.zeros(n) if x0 is None else np.array(x0, dtype=np.float64)
    if x.shape != (n,):
        raise ValueError(f"x0 has shape {x.shape}: must be ({n},)")
    if isinstance(excitation, InitialDisplacement):
        ys = model.layout.wheelset_y
        missing = [w for w in excitation.wheelsets if w > len(ys)]
        if missing and tuple(excitation.wheelsets) != DEFAULT_DISPLACED:
            raise ValueError(f"InitialDisplacement(wheelsets={tuple(excitation.wheelsets)!r}): "
                             f"wheelset {missing[0]} is not one of the vehicle's {len(ys)} "
                             f"wheelsets (numbered 1 to {len(ys)} from the front)")  # fmt: skip
        for w in excitation.wheelsets:
            if w <= len(ys):
                x[ys[w - 1]] += excitation.amplitude
    return x


def excitation_end_time(model: Model, excitation: object, speed: float) -> float:
    """Time (s) at which the last wheelset leaves the excitation (0 for none)."""
    if isinstance(excitation, (SingleDefect, SampledTrack)):
        return (excitation.end() + model.wheelset_offsets()[-1]) / speed
    return 0.0


def default_atol(layout: StateLayout = LAYOUT) -> np.ndarray:
    """Absolute tolerances per state for the adaptive integrator (state units)."""
    return integrators.default_atol(layout.n_dof, layout.n_damper)


class StiffDamperError(ValueError):
    """The yaw damper's Maxwell element relaxes so fast that the automatic step collapses."""


#: The automatic step is refused when the yaw dampers force it more than this many times
#: below the step the rest of the model needs (:func:`auto_step`).
STIFF_RATIO = 100.0


def model_step(model: Model, speed: float, safety: float = 0.6, dt_max: float = 1e-3) -> float:
    """RK4 step (s) the model needs at ``speed`` (m/s) without the yaw dampers' relaxation:
    ``safety`` over the largest eigenvalue modulus of the Jacobian of the coordinates and
    rates with the damper forces held (their own rows and columns left out), capped at
    ``dt_max``."""
    n = 2 * model.layout.n_dof
    rate = float(np.max(np.abs(np.linalg.eigvals(model.jacobian(speed)[:n, :n]))))
    return min(dt_max, safety / rate)


def auto_step(model: Model, speed: float, safety: float = 0.6, dt_max: float = 1e-3) -> float:
    """RK4 step (s) from the fastest dynamics of the model at ``speed`` (m/s).

    ``safety / rate`` with ``rate`` the largest of: the largest eigenvalue modulus of the
    Jacobian at the centred state, and the yaw dampers' relaxation rates ``K_d / C_d1``
    and ``K_d / C_d2`` (the latter governs blow-off), capped at ``dt_max``. With the
    default ``safety = 0.6`` the step sits well inside RK4's stability limit (2.8) and
    the critical speed of the paper's vehicle is converged to 1 km/h (tests).

    Raises
    ------
    StiffDamperError
        When a yaw damper's relaxation forces a step more than :data:`STIFF_RATIO` times
        below the one the rest of the model needs (:func:`model_step`): a tiny ``C_d1``
        (or ``C_d2``) against ``K_d`` would make every run take hours. The message names
        the rate, the step it forces and the smallest damping that avoids it.
    """
    rate = float(np.max(np.abs(model.centred_eigenvalues(speed))))
    d = model.dpar
    k_d = d[:, DamperParam.K_D]
    rate_1 = float(np.max(k_d / d[:, DamperParam.C_D1], initial=0.0))
    rate_2 = float(np.max(k_d / d[:, DamperParam.C_D2], initial=0.0))
    dt = min(dt_max, safety / max(rate, rate_1, rate_2))
    rest = model_step(model, speed, safety, dt_max)
    if dt < rest / STIFF_RATIO:
        raise StiffDamperError(stiff_damper_message(model, rest, dt, rate_1, rate_2, safety))
    return dt


def step_cause(model: Model, speed: float, dt_max: float = 1e-3) -> str:
    """What sets the automatic step of ``model`` at ``speed`` (m/s), in words naming the
    parameters: a yaw damper stage's relaxation ``K_d / C_d1`` (or ``C_d2``), the model's
    fastest mode, or the step's cap of ``dt_max`` s."""
    rate = float(np.max(np.abs(model.centred_eigenvalues(speed))))
    d = model.dpar
    if d.shape[0]:
        k_d = float(np.max(d[:, DamperParam.K_D]))
        c_1 = float(np.min(d[:, DamperParam.C_D1]))
        c_2 = float(np.min(d[:, DamperParam.C_D2]))
        rate_1, rate_2 = k_d / c_1, k_d / c_2
    else:  # no yaw damper (the Cooperrider bogie)
        k_d = c_1 = c_2 = rate_1 = rate_2 = 0.0
    top = max(rate, rate_1, rate_2)
    if 0.6 / top >= dt_max:
        return f"the step is its cap of {dt_max:g} s: the run is long, not stiff"
    if max(rate_1, rate_2) < 0.5 * rate:  # the damper's relaxation is one of the modes
        return (f"the step of {0.6 / top:.2g} s is set by the model's fastest mode "
                f"({rate:.3g} 1/s, the Jacobian's largest eigenvalue): "
                f"{_fastest_mode_body(model, speed)}")  # fmt: skip
    name, c = ("C_d1", c_1) if rate_1 >= rate_2 else ("C_d2", c_2)
    return (f"the step of {0.6 / top:.2g} s is set by the yaw damper's relaxation K_d/{name} "
            f"= {k_d:.4g} N/m / {c:.4g} N*s/m = {top:.3g} 1/s; a larger {name} or a smaller "
            "K_d shortens the run")


#: The inertia that resists each kind of coordinate, as a body's layout entry names it.
_INERTIA = {"y": ("mass", "kg"), "psi": ("yaw_inertia", "kg*m^2"),
            "phi": ("roll_inertia", "kg*m^2")}


def _fastest_mode_body(model: Model, speed: float) -> str:
    """The coordinate that moves most in the model's fastest mode and the inertia of its
    body, naming the parameters it is written with: the light body (or stiff spring) that
    forces a small step."""
    lam, vec = np.linalg.eig(model.jacobian(speed))
    k = int(np.argmax(np.abs(lam)))
    n_dof = model.layout.n_dof
    shape = np.abs(vec[:, k])
    # the rates of a mode are |lambda| times its displacements: compare like with like
    moves = shape[:n_dof] * abs(lam[k]) + shape[n_dof:2 * n_dof]
    coordinate = model.layout.dof_names[int(np.argmax(moves))]
    kind, tag = coordinate.split("_", 1)
    body = next(b for b in model.layout.bodies if b.tag == tag)
    field, unit = _INERTIA.get(kind, ("mass", "kg"))
    what = f"{coordinate} of {body.name} moves most in it"
    try:
        expression = getattr(model.vehicle.layout.body(body.name), field)
    except (AttributeError, KeyError, ValueError):
        expression = None
    if expression is None:
        return f"{what} (a stiff spring or a light body)"
    values = model.vehicle.as_dict()
    value = expression(values)
    said = f"{field.replace('_', ' ')} {expression.source} = {value:.4g} {unit}"
    if str(expression.source) not in values:  # an expression: the values it is made of
        said += " (" + ", ".join(f"{n} = {values[n]:.4g}" for n in sorted(expression.names)
                                 if n in values) + ")"  # fmt: skip
    return (f"{what}, and its {said} is light for the springs on it (or a spring on it is "
            "stiff)")  # fmt: skip


def stiff_damper_message(model: Model, rest: float, dt: float, rate_1: float, rate_2: float,
                         safety: float) -> str:  # fmt: skip
    """Why :func:`auto_step` refuses: the stage, its rate, the step and the way out."""
    stage, c_name, column = (("first", "C_d1", DamperParam.C_D1) if rate_1 >= rate_2
                             else ("second", "C_d2", DamperParam.C_D2))  # fmt: skip
    k_d = float(np.max(model.dpar[:, DamperParam.K_D]))
    c = float(np.min(model.dpar[:, column]))
    c_min = k_d * rest / (STIFF_RATIO * safety)
    return (f"the yaw damper's {stage} stage relaxes at K_d/{c_name} = {k_d / c:.3g} 1/s "
            f"(K_d = {k_d:.4g} N/m, {c_name} = {c:.4g} N*s/m): the automatic RK4 step "
            f"would be {dt:.2g} s, {rest / dt:.0f} times below the {rest:.2g} s the rest of "
            f"the model needs (every simulated second would take {1 / dt:.2g} steps); give "
            f"{c_name} >= {c_min:.3g} N*s/m or a smaller K_d")


class OutputTooLargeError(ValueError):
    """The time histories a run would store do not fit in the memory available.

    Attributes
    ----------
    rows : int
        Output rows the run would store (or allocate).
    nbytes : float
        Their estimated size (bytes).
    available : float
        Memory available (bytes).
    output_dt : float or None
        An output interval (s) whose histories would fit (None: none does).
    """

    def __init__(self, message: str, rows: int, nbytes: float, available: float,
                 output_dt: float | None) -> None:  # fmt: skip
        super().__init__(message)
        self.rows, self.nbytes, self.available, self.output_dt = rows, nbytes, available, output_dt


#: Bytes per stored output row: the time, 38 states, 4 damper velocities, 32 derived
#: channels, and the working arrays the derived channels are computed in.
ROW_BYTES = 8 * (1 + N_STATE + N_DAMPER + 32 + 24)


def row_bytes(layout: StateLayout = LAYOUT) -> int:
    """:data:`ROW_BYTES` of a layout: the time, its states, its damper velocities, the
    derived channels (7 per wheelset, 2 per bogie frame) and their working arrays."""
    n_ws = len(layout.wheelsets)
    n_frames = sum(1 for b in layout.bodies if not b.is_wheelset and b.tag.startswith("t"))
    derived = 7 * n_ws + 2 * n_frames
    return 8 * (1 + layout.n_state + layout.n_damper + derived + 5 * n_ws + 2 * n_frames)
#: Largest share of the available memory a run's histories may take.
MEMORY_SHARE = 0.5


def output_rows(duration: float, dt: float, output_dt: float | None, method: str) -> int:
    """Rows a run of ``duration`` s stores (RK4 at step ``dt`` s, or what DOPRI5 allocates:
    one per ``output_dt``, or without it one per possible step of 10 us)."""
    if output_dt is not None:
        every = output_dt if method != "rk4" else dt * max(1, round(output_dt / dt))
        return int(duration / every) + 2
    if method == "rk4":
        return int(round(duration / dt)) + 1
    return int(max(1000, duration / 1e-5)) + 1


def memory_available() -> float | None:
    """Memory available to a new allocation (bytes): Linux's ``MemAvailable``, else the
    free physical memory; None when unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0
    except OSError:
        pass
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):
        return None


def check_output_size(duration: float, dt: float, output_dt: float | None,
                      method: str, layout: StateLayout = LAYOUT) -> None:  # fmt: skip
    """Refuse a run whose histories would not fit in memory, before it allocates them
    (``layout``: the vehicle's states, default the paper's vehicle).

    Raises
    ------
    OutputTooLargeError
        With the size, the memory available and an ``output_dt`` that fits.
    """
    available = memory_available()
    rows = output_rows(duration, dt, output_dt, method)
    per_row = row_bytes(layout)
    nbytes = float(rows) * per_row
    if available is None or nbytes <= MEMORY_SHARE * available:
        return
    fits = None
    for candidate in (k * 10.0**e for e in range(-3, 4) for k in (1.0, 2.0, 5.0)):
        if candidate >= dt and output_rows(duration, dt, candidate, method) * per_row <= \
                0.5 * MEMORY_SHARE * available:  # fmt: skip
            fits = candidate
            break
    hint = f"give output_dt (e.g. {fits:g} s)" if fits else "give output_dt"
    raise OutputTooLargeError(
        f"the histories of duration = {duration:g} s ({rows:.3g} rows) would need about "
        f"{nbytes / 1e9:.3g} GB, more than the {MEMORY_SHARE * available / 1e9:.3g} GB "
        f"a run may take ({MEMORY_SHARE:.0%} of the memory available): {hint} or a shorter "
        "duration", rows, nbytes, available, fits)


def integrate_model(
    model: Model,
    speed: float,
    duration: float,
    x0: np.ndarray,
    t0: float = 0.0,
    excitation: object = None,
    method: str = "rk4",
    dt: float = 1e-3,
    output_dt: float | None = None,
    rtol: float = 1e-6,
    atol: np.ndarray | None = None,
    y_limit: float = Y_LIMIT,
    route: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, int, dict]:
    """Integrate the model (low-level; :func:`simulate` is the friendly entry point).

    ``route`` is the track geometry (:meth:`railhunt.curve.Curve.route`); straight track
    by default. Returns times, states, the integrator's status code and a dict of
    statistics.
    """
    if method not in integrators.METHODS:
        raise ValueError(f"method = {method!r} is invalid: must be one of {METHODS}")
    return integrators.METHODS[method](
        x0, t0, duration, *model.args(speed, excitation, route), dt=dt, output_dt=output_dt,
        rtol=rtol, atol=atol, y_limit=y_limit,
    )  # fmt: skip


def _check_positive(name: str, value: float, unit: str, low: float = 0.0,
                    high: float = math.inf) -> float:
    from railhunt.arguments import check_real

    value = check_real(name, value, unit)
    if not (math.isfinite(value) and low < value <= high):
        raise ValueError(
            f"{name} = {value!r} {unit} is invalid: must be finite and in ({low}, {high}] {unit}"
        )
    return value


def simulate(
    vehicle: Vehicle,
    speed_kmh: float,
    duration: float = 10.0,
    excitation: object = None,
    method: str = "rk4",
    dt: float | None = None,
    output_dt: float | None = None,
    rtol: float = 1e-6,
    x0: np.ndarray | None = None,
    creep_law: str | None = None,
    y_limit: float = Y_LIMIT,
    model: Model | None = None,
    curve: Curve | None = None,
) -> SimulationResult:
    """Simulate the vehicle at constant speed on straight track or through a curve.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    speed_kmh : float
        Forward speed (km/h), in (0, 1000].
    duration : float
        Simulated time (s).
    excitation : SingleDefect or InitialDisplacement or SampledTrack, optional
        Track input or initial condition; ideal track and ``x0`` (default centred) otherwise.
        A stochastic irregularity (:func:`railhunt.track_irregularity`) or a measured one
        (:func:`railhunt.load_irregularity`) is a ``SampledTrack``: the excitation type (c)
        of the paper. Wheelset *j* meets every track input at its own delay
        ``offset_j / v`` (``offset_j`` its distance behind the leading wheelset).
    method : {"rk4", "dopri5"}
        Fixed-step classical Runge-Kutta (the paper's) or adaptive Dormand-Prince 5(4).
    dt : float, optional
        Step of ``"rk4"`` (s); default from :func:`auto_step` (1 ms for the paper's
        vehicle).
    output_dt : float, optional
        Resample to this fixed step (s): every n-th step for RK4, cubic Hermite dense
        output for the adaptive method. Default: every step.
    rtol : float
        Relative tolerance of ``"dopri5"``.
    x0 : numpy.ndarray, optional
        Initial state (38 values, SI).
    creep_law : str
        See :class:`railhunt.model.Model`.
    y_limit : float
        Lateral wheelset displacement relative to the track at which the run stops as
        derailed (m).
    model : Model, optional
        A model already built for ``vehicle`` (saves assembling it again).
    curve : Curve, optional
        Run through this curve (:class:`railhunt.Curve`): straight track up to
        ``curve.start``, the entry transition, the constant curve, the exit transition
        (if it has a length) and straight track again. Coordinates are measured from the
        track at each body's position; the channels include the yaw damper forces
        (``F_d1``..) and velocities (``v_d1``..), the guiding forces ``Y``, wheel loads
        ``Q`` and ``Y/Q`` of every wheel and ``ΣY`` of every wheelset.

    Returns
    -------
    SimulationResult
    """
    speed = kmh_to_ms(_check_positive("speed_kmh", speed_kmh, "km/h", 0.0, 1000.0))
    _check_positive("duration", duration, "s", 0.0, 1e5)
    if dt is not None:
        _check_positive("dt", dt, "s", 0.0, 0.01)
    if output_dt is not None:
        _check_positive("output_dt", output_dt, "s", 0.0, duration)
    _check_positive("rtol", rtol, "", 0.0, 0.1)
    if method not in METHODS:
        raise ValueError(f"method = {method!r} is invalid: must be one of {', '.join(METHODS)}")
    check_excitation(excitation, (SingleDefect, InitialDisplacement, SampledTrack))
    check_curve(curve)
    if model is None:
        model = Model(vehicle, creep_law=creep_law)
    x_init = _initial_state(model, excitation, x0)
    if dt is None:
        dt = auto_step(model, speed)
    elif method == "rk4":
        from railhunt.stepsize import check_step

        check_step(model, speed, dt)
    check_output_size(duration, dt, output_dt, method, model.layout)
    route = None if curve is None else curve.route()
    t, x, code, stats = integrate_model(
        model, speed, duration, x_init, excitation=excitation, method=method, dt=dt,
        output_dt=output_dt, rtol=rtol, y_limit=y_limit, route=route,
    )  # fmt: skip
    vd = model.damper_velocities(x[:, model.layout.forces])
    result = SimulationResult(
        t=t, x=x, speed=speed, status=integrators.STATUS_NAMES[code],
        message=integrators.status_message(code, t[-1], y_limit), damper_velocity=vd,
        excitation_end=excitation_end_time(model, excitation, speed), stats=stats,
        derived=derived_channels(t, x, *model.args(speed, excitation, route), model.layout),
        layout=model.layout,
    )  # fmt: skip
    from railhunt.validity import run_limits

    result.limits = run_limits(result, model, excitation, route)
    return result
