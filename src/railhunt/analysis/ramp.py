"""Nonlinear critical speed by the paper's excitation type (a): a slow speed ramp down.

The vehicle is first brought onto a large limit cycle at ``start_kmh`` (released from a
large lateral displacement of all wheelsets on ideal track), then the speed is lowered
slowly with no further excitation; the speed at which the cycle dies is the nonlinear
critical speed (the fold of the branch the vehicle was following). The model's
right-hand side takes a constant speed, so the ramp is a staircase of short constant-speed
segments (``step_kmh`` every ``step_kmh / rate_kmh_per_s`` seconds), the state carried
over from one to the next. A slow passage through a fold lags behind it by an amount that
grows like ``rate**(2/3)``; so a coarse pass at ``rate_kmh_per_s`` is followed by a fine
pass at a tenth of the rate, restarted 10 km/h above where the coarse pass lost the cycle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from railhunt.kernel.integrators import OK
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.simulation import Y_LIMIT, auto_step, integrate_model
from railhunt.units import kmh_to_ms
from railhunt.vehicle import Vehicle


@dataclass(repr=False)
class RampResult(ResultDisplay):
    """Outcome of :func:`critical_speed_ramp`.

    Attributes
    ----------
    speed_kmh : float
        Speed where the limit cycle died (km/h): the first segment whose amplitude fell
        below ``death_fraction`` of the cycle's amplitude at the start. NaN if it never died
        above ``end_kmh``.
    speeds_kmh, amplitudes : numpy.ndarray
        Segment speeds (km/h) and the leading wheelset's largest |displacement| in each (m).
    start_amplitude : float
        Amplitude of the cycle at ``start_kmh`` (m).
    """

    speed_kmh: float
    speeds_kmh: np.ndarray
    amplitudes: np.ndarray
    start_amplitude: float

    def _summary(self) -> list[Row]:
        return [("limit cycle died at", self.speed_kmh, "km/h"),
                ("amplitude at the start", self.start_amplitude, "m"),
                ("segments", self.speeds_kmh.size, "")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row per constant-speed segment of the ramp."""
        return {"speed_kmh": (self.speeds_kmh, "km/h"), "amplitude": (self.amplitudes, "m")}


def critical_speed_ramp(
    vehicle: Vehicle,
    start_kmh: float = 400.0,
    end_kmh: float = 150.0,
    rate_kmh_per_s: float = 0.5,
    step_kmh: float = 0.25,
    initial_amplitude: float = 0.008,
    death_fraction: float = 0.1,
    creep_law: str | None = None,
) -> RampResult:
    """Lower the speed slowly from a limit cycle and report where the cycle dies.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    start_kmh, end_kmh : float
        Ramp from ``start_kmh`` down to ``end_kmh`` (km/h), ``0 < end < start <= 1000``.
    rate_kmh_per_s : float
        Deceleration (km/h per s), > 0.
    step_kmh : float
        Speed step of the staircase (km/h), > 0.
    initial_amplitude : float
        Initial lateral displacement of all wheelsets that starts the cycle (m).
    death_fraction : float
        The cycle counts as dead when the amplitude falls below this fraction of its
        starting amplitude, in (0, 1).
    creep_law : str
        See :class:`railhunt.model.Model`.

    Raises
    ------
    RuntimeError
        When no limit cycle develops at ``start_kmh``.
    """
    for name, value, low, high, unit in (
        ("start_kmh", start_kmh, 0, 1000, "km/h"), ("end_kmh", end_kmh, 0, 1000, "km/h"),
        ("rate_kmh_per_s", rate_kmh_per_s, 0, 100, "km/h/s"), ("step_kmh", step_kmh, 0, 50, "km/h"),
        ("initial_amplitude", initial_amplitude, 0, 0.02, "m"),
        ("death_fraction", death_fraction, 0, 1, ""),
    ):  # fmt: skip
        if not (math.isfinite(value) and low < value <= high):
            raise ValueError(f"{name} = {value!r} {unit} is invalid: must be in ({low}, {high}]")
    if end_kmh >= start_kmh:
        raise ValueError(f"end_kmh = {end_kmh} km/h is invalid: must be below start_kmh = "
                         f"{start_kmh} km/h")  # fmt: skip
    model = Model(vehicle, creep_law=creep_law)
    dt = auto_step(model, kmh_to_ms(start_kmh))
    x = np.zeros(model.layout.n_state)
    x[model.layout.wheelset_y] = initial_amplitude
    t, xs, code, _ = integrate_model(model, kmh_to_ms(start_kmh), 15.0, x, dt=dt, y_limit=Y_LIMIT)
    if code != OK:
        raise RuntimeError(f"the start run at {start_kmh} km/h failed (status {code})")
    tail = np.abs(xs[t >= t[-1] - 2.0, model.layout.y_w1])
    a0 = float(tail.max())
    if a0 < 1e-4:
        raise RuntimeError(f"no limit cycle at start_kmh = {start_kmh} km/h: the motion decays")
    x = xs[-1].copy()
    # Coarse pass at the given rate, then a fine pass at a tenth of it from 10 km/h above
    # where the coarse pass lost the cycle (slow passage through the fold lags ~ rate**(2/3)).
    died, speeds, amps, states = _staircase(model, dt, x, start_kmh, end_kmh, rate_kmh_per_s,
                                            step_kmh, death_fraction * a0)  # fmt: skip
    if math.isfinite(died):
        restart = died + 10.0
        k = int(np.argmin(np.abs(np.array(speeds) - restart)))
        if speeds[k] >= died + 1.0:
            fine = _staircase(model, dt, states[k], speeds[k], end_kmh, rate_kmh_per_s / 10,
                              step_kmh / 10, death_fraction * a0)  # fmt: skip
            if math.isfinite(fine[0]):
                died = fine[0]
                speeds = speeds[:k + 1] + fine[1]
                amps = amps[:k + 1] + fine[2]
    return RampResult(died, np.array(speeds), np.array(amps), a0)


def _staircase(model: Model, dt: float, x: np.ndarray, start_kmh: float, end_kmh: float,
               rate: float, step: float, dead: float):  # fmt: skip
    seg = step / rate
    speeds, amps, states = [], [], []
    v = start_kmh
    while v - step >= end_kmh - 1e-9:
        v -= step
        t, xs, code, _ = integrate_model(model, kmh_to_ms(v), seg, x, dt=dt, y_limit=Y_LIMIT)
        if code != OK:
            raise RuntimeError(f"the ramp failed at {v:.2f} km/h (status {code})")
        x = xs[-1].copy()
        a = float(np.max(np.abs(xs[:, model.layout.y_w1])))
        speeds.append(v)
        amps.append(a)
        states.append(x)
        if a < dead:
            return v, speeds, amps, states
    return math.nan, speeds, amps, states
