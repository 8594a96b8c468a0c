"""Time integrators for the vehicle model: fixed-step RK4 and adaptive Dormand-Prince 5(4).

Both call :func:`railhunt.model.rhs` directly (compiled together, no Python in the loop),
stop cleanly when the run diverges, and report a status code:

* ``OK`` (0): reached the end time;
* ``DERAILED`` (1): a wheelset left the rails laterally by more than ``y_limit``;
* ``DIVERGED`` (2): a state became NaN or infinite;
* ``STEP_FAILED`` (3): the adaptive step size fell below its minimum.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from railhunt import track as _track
from railhunt.model import WR_OFFSET, rhs

OK, DERAILED, DIVERGED, STEP_FAILED = 0, 1, 2, 3
STATUS_NAMES = {OK: "ok", DERAILED: "derailed", DIVERGED: "diverged", STEP_FAILED: "step-failed"}


@njit(cache=True)
def _check_state(t, x, y_limit, v, wr, trk, trs) -> int:
    for i in range(x.shape[0]):
        if not np.isfinite(x[i]):
            return DIVERGED
    for j in range(4):
        yr, _ = _track.alignment(v * t - wr[WR_OFFSET + j], trk, trs)
        if abs(x[9 + 2 * j] - yr) > y_limit:
            return DERAILED
    return OK


@njit(cache=True)
def rk4_step(t, x, h, v, lin, bd, dd, dpar, wr, trk, trs, k1, k2, k3, k4, tmp, out):
    """One classical Runge-Kutta step of size ``h`` from ``(t, x)`` into ``out``.

    ``k1 .. k4`` and ``tmp`` are work arrays of the state's size; ``out`` may be ``x``
    itself (the update is elementwise after all stages are computed).
    """
    n = x.shape[0]
    rhs(t, x, v, lin, bd, dd, dpar, wr, trk, trs, k1)
    for i in range(n):
        tmp[i] = x[i] + 0.5 * h * k1[i]
    rhs(t + 0.5 * h, tmp, v, lin, bd, dd, dpar, wr, trk, trs, k2)
    for i in range(n):
        tmp[i] = x[i] + 0.5 * h * k2[i]
    rhs(t + 0.5 * h, tmp, v, lin, bd, dd, dpar, wr, trk, trs, k3)
    for i in range(n):
        tmp[i] = x[i] + h * k3[i]
    rhs(t + h, tmp, v, lin, bd, dd, dpar, wr, trk, trs, k4)
    for i in range(n):
        out[i] = x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@njit(cache=True)
def rk4(x0, t0, dt, n_steps, stride, y_limit, v, lin, bd, dd, dpar, wr, trk, trs):
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
    v, lin, bd, dd, dpar, wr, trk, trs
        Model arguments (see :meth:`railhunt.model.Model.args`).

    Returns
    -------
    t : numpy.ndarray
        Stored times (s).
    x : numpy.ndarray
        Stored states, one row per time.
    status : int
        Status code (module docstring).
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
        rk4_step(t, x, dt, v, lin, bd, dd, dpar, wr, trk, trs, k1, k2, k3, k4, tmp, x)
        t = t0 + step * dt
        status = _check_state(t, x, y_limit, v, wr, trk, trs)
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


@njit(cache=True)
def dopri5(
    x0, t0, t_end, dt_out, rtol, atol, h0, h_max, max_steps, y_limit,
    v, lin, bd, dd, dpar, wr, trk, trs,
):  # fmt: skip
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
    v, lin, bd, dd, dpar, wr, trk, trs
        Model arguments.

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
    rhs(t0, x, v, lin, bd, dd, dpar, wr, trk, trs, k1)
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
        rhs(t + _C2 * h, tmp, v, lin, bd, dd, dpar, wr, trk, trs, k2)
        for i in range(n):
            tmp[i] = x[i] + h * (_A31 * k1[i] + _A32 * k2[i])
        rhs(t + _C3 * h, tmp, v, lin, bd, dd, dpar, wr, trk, trs, k3)
        for i in range(n):
            tmp[i] = x[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
        rhs(t + _C4 * h, tmp, v, lin, bd, dd, dpar, wr, trk, trs, k4)
        for i in range(n):
            tmp[i] = x[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
        rhs(t + _C5 * h, tmp, v, lin, bd, dd, dpar, wr, trk, trs, k5)
        for i in range(n):
            tmp[i] = x[i] + h * (
                _A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i]
            )
        rhs(t + h, tmp, v, lin, bd, dd, dpar, wr, trk, trs, k6)
        for i in range(n):
            xn[i] = x[i] + h * (
                _B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B5 * k5[i] + _B6 * k6[i]
            )
        rhs(t + h, xn, v, lin, bd, dd, dpar, wr, trk, trs, k7)
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
            status = _check_state(t, x, y_limit, v, wr, trk, trs)
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
