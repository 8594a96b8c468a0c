"""Time integrators beside the right-hand side: fixed-step RK4 and adaptive DOPRI5.

Both call :func:`railhunt.kernel.rhs.rhs` directly (compiled together, no Python in the
loop), stop cleanly when the run leaves the track or diverges, and report a status code
(:data:`STATUS_NAMES`, :data:`MESSAGES`). They are chosen by name from :data:`METHODS`
(as ``scipy.integrate.solve_ivp`` chooses its solvers), each entry a function with one
signature::

    METHODS[name](x0, t0, duration, v, s, *, dt, output_dt, rtol, atol, y_limit)
        -> (t, x, status, stats)

The switching-aware flow used for shooting lives in :mod:`railhunt.kernel.flow`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numba import njit

from railhunt.kernel.layout import NO_REFCOUNT, SystemArrays
from railhunt.kernel.rhs import rhs
from railhunt.kernel.track import alignment

#: Status codes of a run.
OK, DERAILED, DIVERGED, STEP_FAILED, STEP_LIMIT = 0, 1, 2, 3, 4
#: Status code -> name (as results and JSON report it).
STATUS_NAMES = {OK: "ok", DERAILED: "derailed", DIVERGED: "diverged", STEP_FAILED: "step-failed",
                STEP_LIMIT: "step-limit"}  # fmt: skip
#: The adaptive method's step budget: one accepted step per this many seconds of the run
#: on average (at least 1000 steps); its output without ``output_dt`` is sized by it.
DOPRI5_MEAN_STEP = 1e-5
#: Status code -> how a run with that status ended (``t``: end time in s, ``y_limit_mm``:
#: the derailment limit in mm).
MESSAGES = {
    OK: "reached t = {t:.3f} s",
    DERAILED: "stopped at t = {t:.3f} s: a wheelset moved more than {y_limit_mm:.1f} mm from "
              "the track centre line",
    DIVERGED: "stopped at t = {t:.3f} s: the state became non-finite",
    STEP_FAILED: "stopped at t = {t:.3f} s: step size underflow",
    STEP_LIMIT: "stopped at t = {t:.3f} s before the end: the adaptive method used up its "
                "budget of one step per 10 us of the run (the run is that stiff there); "
                "use method 'rk4' (--method rk4), or a larger rtol",
}  # fmt: skip


def status_message(code: int, t_end: float, y_limit: float) -> str:
    """How a run ended, in words (``t_end`` in s, ``y_limit`` in m)."""
    return MESSAGES[code].format(t=t_end, y_limit_mm=y_limit * 1e3)


def default_atol(n_dof: int, n_damper: int) -> np.ndarray:
    """Absolute tolerances per state for the adaptive integrator (state units).

    1e-8 m (or rad) on the coordinates, 1e-7 m/s on the rates, 1e-3 N on damper forces.
    """
    return np.concatenate([np.full(n_dof, 1e-8), np.full(n_dof, 1e-7), np.full(n_damper, 1e-3)])


@njit(cache=True, **NO_REFCOUNT)
def check_state(t: float, x: np.ndarray, y_limit: float, v: float, s: SystemArrays) -> int:
    """Status of state ``x`` at time ``t``: DIVERGED if non-finite, DERAILED if a wheelset
    is more than ``y_limit`` (m) off the rails laterally, else OK."""
    ws, delay, trk, trs = s.wheelsets, s.wheelset_delay, s.track, s.track_samples
    for i in range(x.shape[0]):
        if not np.isfinite(x[i]):
            return DIVERGED
    for j in range(ws.shape[0]):
        yr, _ = alignment(v * t - delay[j], trk, trs)
        if abs(x[ws[j, 0]] - yr) > y_limit:
            return DERAILED
    return OK


@njit(cache=True, **NO_REFCOUNT)
def rk4_step(t, x, h, v, s, k1, k2, k3, k4, tmp, out):
    """One classical Runge-Kutta step of size ``h`` from ``(t, x)`` into ``out``.

    ``k1 .. k4`` and ``tmp`` are work arrays of the state's size; ``out`` may be ``x``
    itself (the update is elementwise after all stages are computed).
    """
    n = x.shape[0]
    rhs(t, x, v, s, k1)
    for i in range(n):
        tmp[i] = x[i] + 0.5 * h * k1[i]
    rhs(t + 0.5 * h, tmp, v, s, k2)
    for i in range(n):
        tmp[i] = x[i] + 0.5 * h * k2[i]
    rhs(t + 0.5 * h, tmp, v, s, k3)
    for i in range(n):
        tmp[i] = x[i] + h * k3[i]
    rhs(t + h, tmp, v, s, k4)
    for i in range(n):
        out[i] = x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@njit(cache=True, nogil=True)
def rk4(x0, t0, dt, n_steps, stride, y_limit, v, s):
    """Classical fixed-step fourth-order Runge-Kutta.

    Parameters
    ----------
    x0 : numpy.ndarray
        Initial state.
    t0, dt : float
        Start time and step (s).
    n_steps : int
        Number of steps.
    stride : int
        Store every ``stride``-th state (the first is always stored).
    y_limit : float
        Derailment limit on a wheelset's lateral displacement relative to the track (m).
    v : float
        Forward speed (m/s).
    s : SystemArrays
        The model's arrays (:class:`railhunt.kernel.layout.SystemArrays`).

    Returns
    -------
    t : numpy.ndarray
        Stored times (s).
    x : numpy.ndarray
        Stored states, one row per time.
    status : int
        Status code (:data:`STATUS_NAMES`).
    """
    n = x0.shape[0]
    n_out = n_steps // stride + 1
    ts = np.empty(n_out)
    xs = np.empty((n_out, n))
    x = x0.copy()
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    ts[0] = t0
    xs[0] = x
    j = 1
    status = OK
    t = t0
    for step in range(1, n_steps + 1):
        rk4_step(t, x, dt, v, s, k1, k2, k3, k4, tmp, x)
        t = t0 + step * dt
        status = check_state(t, x, y_limit, v, s)
        if step % stride == 0 or status != OK:
            ts[j] = t
            xs[j] = x
            j += 1
        if status != OK:
            break
    return ts[:j], xs[:j], status


# Dormand-Prince 5(4) tableau.
_C2, _C3, _C4, _C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
_A21 = 1 / 5
_A31, _A32 = 3 / 40, 9 / 40
_A41, _A42, _A43 = 44 / 45, -56 / 15, 32 / 9
_A51, _A52, _A53, _A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
_A61, _A62, _A63, _A64, _A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
_B1, _B3, _B4, _B5, _B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
# Error coefficients: b - b_hat.
_E1, _E3, _E4, _E5, _E6, _E7 = (
    71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40,
)  # fmt: skip


@njit(cache=True, nogil=True)
def dopri5(x0, t0, t_end, dt_out, rtol, atol, h0, h_max, max_steps, y_limit, v, s):
    """Adaptive Dormand-Prince 5(4) with PI step-size control and dense output.

    Parameters
    ----------
    x0 : numpy.ndarray
        Initial state.
    t0, t_end : float
        Time span (s).
    dt_out : float
        Output step (s): states on ``t0 + k*dt_out`` by cubic Hermite interpolation between
        accepted steps (fourth-order accurate); ``<= 0`` stores every accepted step.
    rtol : float
        Relative tolerance.
    atol : numpy.ndarray
        Absolute tolerance per state (state units).
    h0, h_max : float
        First and largest step (s).
    max_steps : int
        Largest number of accepted steps.
    y_limit : float
        Derailment limit (m).
    v : float
        Forward speed (m/s).
    s : SystemArrays
        The model's arrays (:class:`railhunt.kernel.layout.SystemArrays`).

    Returns
    -------
    t, x : numpy.ndarray
        Output times and states.
    status : int
        Status code.
    n_accepted, n_rejected : int
        Step counts.
    """
    n = x0.shape[0]
    if dt_out > 0:
        n_out = int(np.floor((t_end - t0) / dt_out + 1e-9)) + 1
    else:
        n_out = max_steps + 1
    ts = np.empty(n_out)
    xs = np.empty((n_out, n))
    x = x0.copy()
    xn = np.empty(n)
    tmp = np.empty(n)
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    k5 = np.empty(n)
    k6 = np.empty(n)
    k7 = np.empty(n)
    rhs(t0, x, v, s, k1)
    ts[0] = t0
    xs[0] = x
    j = 1
    t = t0
    h = min(h0, h_max, t_end - t0)
    err_prev = 1e-4
    status = OK
    n_acc = 0
    n_rej = 0
    h_min = 1e-12 * max(1.0, abs(t_end))
    while t < t_end and n_acc < max_steps:
        if t + h > t_end:
            h = t_end - t
        for i in range(n):
            tmp[i] = x[i] + h * _A21 * k1[i]
        rhs(t + _C2 * h, tmp, v, s, k2)
        for i in range(n):
            tmp[i] = x[i] + h * (_A31 * k1[i] + _A32 * k2[i])
        rhs(t + _C3 * h, tmp, v, s, k3)
        for i in range(n):
            tmp[i] = x[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
        rhs(t + _C4 * h, tmp, v, s, k4)
        for i in range(n):
            tmp[i] = x[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
        rhs(t + _C5 * h, tmp, v, s, k5)
        for i in range(n):
            tmp[i] = x[i] + h * (
                _A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i]
            )
        rhs(t + h, tmp, v, s, k6)
        for i in range(n):
            xn[i] = x[i] + h * (
                _B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B5 * k5[i] + _B6 * k6[i]
            )
        rhs(t + h, xn, v, s, k7)
        err = 0.0
        for i in range(n):
            e = h * (
                _E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i]
            )
            sc = atol[i] + rtol * max(abs(x[i]), abs(xn[i]))
            err += (e / sc) ** 2
        err = np.sqrt(err / n)
        if not np.isfinite(err):
            err = 1e10
        if err <= 1.0:
            t_new = t + h
            # Dense output on the fixed grid by cubic Hermite interpolation.
            if dt_out > 0:
                while j < n_out and t0 + j * dt_out <= t_new + 1e-12:
                    tau = (t0 + j * dt_out - t) / h
                    tau = min(max(tau, 0.0), 1.0)
                    h00 = (1 + 2 * tau) * (1 - tau) ** 2
                    h10 = tau * (1 - tau) ** 2
                    h01 = tau * tau * (3 - 2 * tau)
                    h11 = tau * tau * (tau - 1)
                    ts[j] = t0 + j * dt_out
                    for i in range(n):
                        xs[j, i] = (
                            h00 * x[i] + h10 * h * k1[i] + h01 * xn[i] + h11 * h * k7[i]
                        )
                    j += 1
            else:
                ts[j] = t_new
                xs[j] = xn
                j += 1
            t = t_new
            for i in range(n):
                x[i] = xn[i]
                k1[i] = k7[i]
            n_acc += 1
            status = check_state(t, x, y_limit, v, s)
            if status != OK:
                if dt_out > 0 and j < n_out:
                    ts[j] = t
                    xs[j] = x
                    j += 1
                break
            # PI controller (Hairer & Wanner II.4).
            fac = 0.9 * err ** (-0.7 / 5.0) * err_prev ** (0.4 / 5.0) if err > 0 else 5.0
            fac = min(5.0, max(0.2, fac))
            err_prev = max(err, 1e-4)
            h = min(h * fac, h_max)
        else:
            n_rej += 1
            h = h * max(0.2, 0.9 * err ** (-0.2))
            if h < h_min:
                status = STEP_FAILED
                break
    return ts[:j], xs[:j], status, n_acc, n_rej


def _run_rk4(x0, t0, duration, v, s, *, dt, output_dt, rtol, atol, y_limit):
    """:func:`rk4` over ``duration`` s at step ``dt``; output every ``output_dt`` s."""
    n_steps = int(round(duration / dt))
    stride = 1 if output_dt is None else max(1, int(round(output_dt / dt)))
    t, x, status = rk4(x0, t0, dt, n_steps, stride, y_limit, v, s)
    return t, x, status, {"steps": n_steps, "rhs_calls": 4 * n_steps}


def _run_dopri5(x0, t0, duration, v, s, *, dt, output_dt, rtol, atol, y_limit):
    """:func:`dopri5` over ``duration`` s; dense output every ``output_dt`` s."""
    n = x0.shape[0]
    if atol is None:
        n_dof, n_damper = s.linear.shape[0], s.damper.shape[0]
        atol_v = default_atol(n_dof, n_damper)
    else:
        atol_v = np.broadcast_to(atol, (n,)).copy()
    out_dt = -1.0 if output_dt is None else float(output_dt)
    max_steps = int(max(1000, duration / DOPRI5_MEAN_STEP))
    t, x, status, n_acc, n_rej = dopri5(
        x0, t0, t0 + duration, out_dt, rtol, atol_v, 1e-4, 0.01, max_steps, y_limit, v, s
    )
    last_output = t0 + duration - max(out_dt, 0.0)
    if status == OK and n_acc >= max_steps and t[-1] < last_output - 1e-12:
        status = STEP_LIMIT
    stats = {"steps": n_acc, "rejected": n_rej, "rhs_calls": 6 * (n_acc + n_rej) + 1}
    return t, x, status, stats


#: Integrators by name: ``"rk4"`` (classical fixed-step Runge-Kutta, the paper's) and
#: ``"dopri5"`` (adaptive Dormand-Prince 5(4)); see the module docstring for the signature.
METHODS: dict[str, Callable[..., tuple]] = {"rk4": _run_rk4, "dopri5": _run_dopri5}
