"""The switching-aware flow: RK4 on a uniform grid with yaw-damper blow-off located.

Used for shooting (limit cycles, continuation; :mod:`railhunt.analysis.periodic`). The
yaw damper's two-stage law has a kink at ``|F_d| = F_u`` (blow-off); the vector field is
continuous but its derivative jumps there. A fixed-step Runge-Kutta step across the kink
is only first-order accurate and makes the discrete flow map non-smooth in ``x0``, which
slows or stalls Newton. :func:`flow` locates each crossing of ``|F_d| = F_u`` inside a
step (regula falsi on the step fraction, to ``1e-9 F_u``), ends the step there and
restarts on the other side, so every Runge-Kutta step sees a smooth vector field. Other
kinks (contact angle limited to the flange angle, the heuristic saturation at
``beta = 3``, which is C1) are not located.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from railhunt.kernel.integrators import rk4_step
from railhunt.kernel.layout import DamperParam


@njit(cache=True, nogil=True)
def flow(x0, horizon, n_steps, locate, v, s, samples):
    """State after ``horizon`` seconds: RK4 on a uniform grid, damper switchings located.

    Parameters
    ----------
    x0 : numpy.ndarray, shape (n_state,)
        Initial state.
    horizon : float
        Integration time (s).
    n_steps : int
        Number of grid steps (step ``horizon / n_steps``).
    locate : bool
        End a step where a yaw damper force crosses ``|F| = F_u`` (module docstring).
    v : float
        Forward speed (m/s).
    s : SystemArrays
        The model's arrays (:class:`railhunt.kernel.layout.SystemArrays`).
    samples : numpy.ndarray, shape (n_steps + 1, k)
        Receives states ``0..k-1`` at every grid point (``k = 0`` for none).

    Returns
    -------
    x : numpy.ndarray
        State at ``t = horizon``.
    n_switch : int
        Number of located switchings.
    """
    n = x0.shape[0]
    fz = 2 * s.linear.shape[0]  # first damper force (layout.py)
    nd = s.damper.shape[0]
    ns = samples.shape[1]
    x = x0.copy()
    xn = np.empty(n)
    xt = np.empty(n)
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    h = horizon / n_steps
    n_switch = 0
    for j in range(ns):
        samples[0, j] = x[j]
    for step in range(n_steps):
        t = step * h
        remaining = h
        sub = 0
        while remaining > 1e-12 * h:
            rk4_step(t, x, remaining, v, s, k1, k2, k3, k4, tmp, xn)
            crossing = -1
            theta = 1.0
            b_hi = 1.0
            b_shi = 0.0
            if locate and sub < 16:  # after 16 switchings in one step: finish it plainly
                for d in range(nd):
                    fu = s.damper[d, DamperParam.F_U]
                    f0 = x[fz + d]
                    f1 = xn[fz + d]
                    s0 = abs(f0) - fu
                    s1 = abs(f1) - fu
                    if abs(s0) <= 1e-9 * fu:
                        continue  # starts on the switching surface
                    if s0 * s1 < 0.0:
                        th, hi_d, shi_d = s0 / (s0 - s1), 1.0, s1
                    elif s0 > 0.0 and s1 > 0.0 and f0 * f1 < 0.0:
                        # Through the whole band |F| < F_u within the step (tiny F_u): the
                        # first crossing lies before F = 0, where |F| - F_u = -F_u.
                        hi_d = f0 / (f0 - f1)
                        th, shi_d = hi_d * s0 / (s0 + fu), -fu
                    else:
                        continue
                    if th < theta:
                        theta, crossing, b_hi, b_shi = th, d, hi_d, shi_d
            if crossing < 0:
                for i in range(n):
                    x[i] = xn[i]
                break
            # Regula falsi (Illinois) for the step fraction where |F| = F_u.
            fu = s.damper[crossing, DamperParam.F_U]
            lo, slo = 0.0, abs(x[fz + crossing]) - fu
            hi, shi = b_hi, b_shi
            th = theta
            side = 0
            for it in range(30):
                rk4_step(t, x, th * remaining, v, s, k1, k2, k3, k4, tmp, xt)
                st = abs(xt[fz + crossing]) - fu
                if abs(st) <= 1e-9 * fu or it == 29:
                    break  # th is the fraction xt was computed with
                if st * slo < 0.0:
                    hi, shi = th, st
                    if side == -1:
                        slo *= 0.5
                    side = -1
                else:
                    lo, slo = th, st
                    if side == 1:
                        shi *= 0.5
                    side = 1
                th = lo + (hi - lo) * slo / (slo - shi)
            for i in range(n):
                x[i] = xt[i]
            n_switch += 1
            sub += 1
            t += th * remaining
            remaining *= 1.0 - th
        for j in range(ns):
            samples[step + 1, j] = x[j]
    return x, n_switch
