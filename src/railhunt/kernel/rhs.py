"""The one right-hand side of the vehicle's equations of motion, and its Jacobian.

``M q'' = -(K + G) q - C q' - B_d^T F_d + Q_wheel/rail``, with ``K``, ``C`` assembled from
the suspension elements, ``G`` the gravitational roll terms, ``B_d`` the yaw damper
elongation rows, and ``Q_wheel/rail`` the creep and gravitational forces on the wheelsets.
Each damper force obeys ``dF/dt = K_d (B_d q' - v_d(F))`` (Maxwell element).

:func:`rhs` is the only place where these equations are written. Simulation, the Jacobian
(linear stability), the shooting flow (limit cycles, continuation) and the derived output
channels all call it. Its inputs come in one bundle,
:class:`railhunt.kernel.layout.SystemArrays`, whose sizes set the state layout (see
:mod:`railhunt.kernel.layout`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from railhunt.kernel.contact import wheel_geometry
from railhunt.kernel.creep import CreepLaw, heuristic_saturation, polach_saturation
from railhunt.kernel.damper import damper_velocity
from railhunt.kernel.layout import WR, DamperParam, SystemArrays
from railhunt.kernel.track import alignment


@njit(cache=True)
def wheelset_forces(
    y_rel: float, dy: float, psi: float, psi_rel: float, dpsi: float, v: float, wr: np.ndarray
) -> tuple[float, float]:
    """Lateral force and yaw moment of the rails on one wheelset (Eqs. 25-33).

    Parameters
    ----------
    y_rel : float
        Lateral displacement of the wheelset relative to the track (m), + left.
    dy : float
        Lateral velocity (m/s).
    psi : float
        Yaw angle (rad) in the absolute frame (sets the lateral creepage).
    psi_rel : float
        Yaw angle relative to the local rail direction (rad) (sets the gravitational moment).
    dpsi : float
        Yaw rate (rad/s).
    v : float
        Forward speed (m/s), > 0.
    wr : numpy.ndarray
        Wheel/rail parameter vector (slots :class:`railhunt.kernel.layout.WR`).

    Returns
    -------
    tuple of float
        Lateral force (N) and yaw moment (N*m) on the wheelset in track coordinates:
        creep forces after saturation plus the gravitational (normal-force) terms.
    """
    f11, f22, f23, f33 = wr[WR.F11], wr[WR.F22], wr[WR.F23], wr[WR.F33]
    a, r0 = wr[WR.A], wr[WR.R0]
    n_load = wr[WR.N]
    r_l, r_r, d_l, d_r = wheel_geometry(y_rel, wr)
    cdl, sdl = math.cos(d_l), math.sin(d_l)
    cdr, sdr = math.cos(d_r), math.sin(d_r)
    cpsi, spsi = math.cos(psi), math.sin(psi)
    omega = v / r0
    inv_v = 1.0 / v
    # Creepages (Eq. 25).
    base = v * cpsi + dy * spsi
    xl = (base - a * dpsi - r_l * omega) * inv_v
    xr = (base + a * dpsi - r_r * omega) * inv_v
    lat = (dy * cpsi - v * spsi) * inv_v
    yl = lat * cdl
    yr = lat * cdr
    sl = (dpsi * cdl - omega * sdl) * inv_v
    sr = (dpsi * cdr + omega * sdr) * inv_v
    # Kalker's linear forces (Eq. 26).
    fxl = -f11 * xl
    fxr = -f11 * xr
    fyl = -f22 * yl - f23 * sl
    fyr = -f22 * yr - f23 * sr
    mzl = f23 * yl - f33 * sl
    mzr = f23 * yr - f33 * sr
    # Saturation (Eqs. 27-28).
    law = int(wr[WR.CREEP_LAW])
    if law != CreepLaw.LINEAR:
        mun = wr[WR.MU] * n_load
        bl = math.sqrt(fxl * fxl + fyl * fyl) / mun
        br = math.sqrt(fxr * fxr + fyr * fyr) / mun
        if law == CreepLaw.HEURISTIC:
            al = heuristic_saturation(0.5 * (bl + br))
            ar = al
        elif law == CreepLaw.POLACH:
            al = polach_saturation(bl)
            ar = polach_saturation(br)
        else:
            al = heuristic_saturation(bl)
            ar = heuristic_saturation(br)
        fxl *= al
        fyl *= al
        fxr *= ar
        fyr *= ar
    # Into track coordinates (Eqs. 29-30).
    f_lat = (fyl * cdl + fyr * cdr) * cpsi + (fxl + fxr) * spsi
    m_yaw = (fxr - fxl) * a + mzl * cdl + mzr * cdr
    tl = sdl / cdl
    tr = sdr / cdr
    f_grav = n_load * (tr - tl)
    m_grav = n_load * a * math.sin(psi_rel) * (tl + tr)
    return f_lat + f_grav, m_yaw + m_grav


@njit(cache=True)
def wheelset_track_forces(
    j: int, t: float, x: np.ndarray, v: float, s: SystemArrays
) -> tuple[float, float]:
    """Lateral force (N) and yaw moment (N*m) of the rails on wheelset ``j`` at state ``x``.

    The wheelset meets the track input at track position ``v t - delay_j``; its
    displacement relative to the rails sets the contact geometry, its yaw relative to
    the local rail direction the gravitational moment.
    """
    nq = s.linear.shape[0]  # rates start at x[nq] (layout.py)
    iy = s.wheelsets[j, 0]
    ip = s.wheelsets[j, 1]
    yr, slope = alignment(v * t - s.wheelset_delay[j], s.track, s.track_samples)
    return wheelset_forces(x[iy] - yr, x[nq + iy], x[ip], x[ip] - slope, x[nq + ip], v,
                           s.wheel_rail)  # fmt: skip


@njit(cache=True)
def rhs(t: float, x: np.ndarray, v: float, s: SystemArrays, out: np.ndarray) -> None:
    """Time derivative of the state (writes ``out``, allocates nothing).

    Parameters
    ----------
    t : float
        Time (s); only the track input depends on it.
    x : numpy.ndarray, shape (n_state,)
        State (:mod:`railhunt.kernel.layout`).
    v : float
        Forward speed (m/s).
    s : SystemArrays
        The model's arrays and the track input.
    out : numpy.ndarray, shape (n_state,)
        Receives dx/dt.
    """
    nq = s.linear.shape[0]  # coordinates x[:nq], rates x[nq:2nq], damper forces after
    nd = s.damper.shape[0]
    fz = 2 * nq
    for i in range(nq):
        out[i] = x[nq + i]
    for i in range(nq):
        acc = 0.0
        for k in range(2 * nq):
            acc += s.linear[i, k] * x[k]
        out[nq + i] = acc
    for d in range(nd):
        f = x[fz + d]
        rate = 0.0
        for k in range(nq):
            rate += s.damper_rows[d, k] * x[nq + k]
        v_damp = damper_velocity(f, s.damper[d, DamperParam.C_D1], s.damper[d, DamperParam.C_D2],
                                 s.damper[d, DamperParam.F_U])  # fmt: skip
        out[fz + d] = s.damper[d, DamperParam.K_D] * (rate - v_damp)
        for i in range(nq):
            out[nq + i] += s.damper_acc[i, d] * f
    inv_mw = s.wheel_rail[WR.INV_MW]
    inv_jw = s.wheel_rail[WR.INV_JW]
    for j in range(s.wheelsets.shape[0]):
        fy, mz = wheelset_track_forces(j, t, x, v, s)
        out[nq + s.wheelsets[j, 0]] += fy * inv_mw
        out[nq + s.wheelsets[j, 1]] += mz * inv_jw


@njit(cache=True)
def jacobian(x: np.ndarray, v: float, s: SystemArrays) -> np.ndarray:
    """Jacobian d(rhs)/dx at ``t = 0`` by central differences of :func:`rhs`.

    Steps are 1e-7 in displacements, angles and rates and 1e-3 N in damper forces (the
    states' natural scales times about 1e-5).
    """
    n = x.shape[0]
    fz = 2 * s.linear.shape[0]  # first damper force (layout.py)
    jac = np.empty((n, n))
    xp = x.copy()
    fp = np.empty(n)
    fm = np.empty(n)
    for k in range(n):
        h = 1e-3 if k >= fz else 1e-7
        xp[k] = x[k] + h
        rhs(0.0, xp, v, s, fp)
        xp[k] = x[k] - h
        rhs(0.0, xp, v, s, fm)
        xp[k] = x[k]
        for i in range(n):
            jac[i, k] = (fp[i] - fm[i]) / (2.0 * h)
    return jac


@njit(cache=True)
def derived(t: np.ndarray, x: np.ndarray, v: float, s: SystemArrays,
            acc_index: np.ndarray) -> np.ndarray:  # fmt: skip
    """Guiding forces and accelerations along a run (see :mod:`railhunt.channels`).

    Returns an array with one row per time: ``-F_y`` of each wheelset (the sum of its
    guiding forces on the track, N), then ``d(rate)/dt`` of each coordinate in
    ``acc_index`` (m/s^2 or rad/s^2).
    """
    nq = s.linear.shape[0]
    nw = s.wheelsets.shape[0]
    n = t.shape[0]
    res = np.empty((n, nw + acc_index.shape[0]))
    out = np.empty(x.shape[1])
    for i in range(n):
        xi = x[i]
        rhs(t[i], xi, v, s, out)
        for j in range(nw):
            fy, _ = wheelset_track_forces(j, t[i], xi, v, s)
            res[i, j] = -fy
        for k in range(acc_index.shape[0]):
            res[i, nw + k] = out[nq + acc_index[k]]
    return res
