"""The wheel/rail forces on one wheelset (the paper's Eqs. 25-33).

Creepages of both wheels, Kalker's linear creep forces, their saturation, and the
transformation into track coordinates, plus the lateral components of the normal loads
(gravitational stiffness) and the gravitational yaw moment. On straight track both wheels
carry the static load ``N = W g / 2`` and the creep coefficients are the vehicle's; in a
curve each wheel has its own quasi-static load ``Q`` and the coefficients follow it
(Hertz: ``f11, f22 ~ Q^(2/3)``, ``f23 ~ Q``, ``f33 ~ Q^(4/3)``). A wheel/rail vector with
per-point contact mechanics (:mod:`railhunt.kernel.point_contact`) takes each contact's own
ellipse, coefficients and normal force instead; one with two-point contact
(:mod:`railhunt.kernel.two_point`) up to two patches per wheel, at their own points.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from railhunt.kernel.contact import wheel_geometry
from railhunt.kernel.creep import CreepLaw, heuristic_saturation, polach_saturation
from railhunt.kernel.layout import NO_CREEP_TABLE, WR
from railhunt.kernel.point_contact import point_wheelset_contact, uses_per_point
from railhunt.kernel.two_point import two_point_wheelset_contact, uses_two_point


@njit(cache=True)
def wheelset_contact(
    y_rel: float, dy: float, psi: float, psi_rel: float, dpsi: float, yaw_rate: float,
    v: float, wr: np.ndarray, q_left: float, q_right: float, table: np.ndarray | None = None,
) -> tuple[float, float, float, float]:  # fmt: skip
    """Forces of the rails on one wheelset, in total and wheel by wheel.

    Parameters
    ----------
    y_rel : float
        Lateral displacement of the wheelset relative to the rails (m), + left.
    dy : float
        Lateral velocity relative to the track centre line (m/s).
    psi : float
        Yaw angle relative to the track's direction (rad) (sets the lateral creepage).
    psi_rel : float
        Yaw angle relative to the local rail direction (rad) (sets the gravitational
        moment; differs from ``psi`` by the slope of a track irregularity).
    dpsi : float
        Yaw rate relative to the track (rad/s).
    yaw_rate : float
        Absolute yaw rate (rad/s): ``dpsi`` plus the track's own ``v * kappa`` in a curve.
        It sets the longitudinal and spin creepages (the outer wheel's longer path).
    v : float
        Forward speed (m/s), > 0.
    wr : numpy.ndarray
        Wheel/rail parameter vector (slots :class:`railhunt.kernel.layout.WR`).
    q_left, q_right : float
        Normal loads of the left and right wheel (N); ``wr[WR.N]`` both on straight track.
        (With per-point contact mechanics: the vertical loads.)
    table : numpy.ndarray, optional
        Creep table of the ``"exact-table"`` law (``SystemArrays.creep_table``).

    Returns
    -------
    tuple of float
        ``(F_y, M_z, F_left, F_right)``: lateral force (N) and yaw moment (N*m) on the
        wheelset in track coordinates, and the lateral force on each wheel (N, + left),
        creep plus normal load, whose sum is ``F_y``.
    """
    if uses_per_point(wr):
        tab = NO_CREEP_TABLE if table is None else table
        fy, mz, f_l, f_r, _, _ = point_wheelset_contact(y_rel, dy, psi, psi_rel, yaw_rate, v,
                                                        wr, q_left, q_right, tab)
        return fy, mz, f_l, f_r
    if uses_two_point(wr):
        tab = NO_CREEP_TABLE if table is None else table
        return two_point_wheelset_contact(y_rel, dy, psi, yaw_rate, v, wr, q_left, q_right,
                                          tab)  # fmt: skip
    a = wr[WR.A]
    r_l, r_r, d_l, d_r = wheel_geometry(y_rel, wr)
    cdl, sdl = math.cos(d_l), math.sin(d_l)
    cdr, sdr = math.cos(d_r), math.sin(d_r)
    cpsi, spsi = math.cos(psi), math.sin(psi)
    fxl, fyl, mzl, fxr, fyr, mzr, _, _, _, _, _, _ = wheel_creep(
        r_l, r_r, cdl, sdl, cdr, sdr, cpsi, spsi, dy, yaw_rate, v, wr, q_left, q_right)
    # Into track coordinates (Eqs. 29-30); normal loads split into mean and difference so
    # that equal loads give the paper's N (tan delta_R - tan delta_L) exactly.
    f_lat = (fyl * cdl + fyr * cdr) * cpsi + (fxl + fxr) * spsi
    m_yaw = (fxr - fxl) * a + mzl * cdl + mzr * cdr
    tl = sdl / cdl
    tr = sdr / cdr
    q_mean = 0.5 * (q_left + q_right)
    q_half = 0.5 * (q_right - q_left)
    f_grav = q_mean * (tr - tl)
    m_grav = q_mean * a * math.sin(psi_rel) * (tl + tr)
    if q_half != 0.0:
        f_grav += q_half * (tr + tl)
        m_grav += q_half * a * math.sin(psi_rel) * (tr - tl)
    f_left = fyl * cdl * cpsi + fxl * spsi - q_left * tl
    f_right = fyr * cdr * cpsi + fxr * spsi + q_right * tr
    return f_lat + f_grav, m_yaw + m_grav, f_left, f_right


@njit(cache=True)
def wheel_creep(
    r_l: float, r_r: float, cdl: float, sdl: float, cdr: float, sdr: float, cpsi: float,
    spsi: float, dy: float, yaw_rate: float, v: float, wr: np.ndarray, q_left: float,
    q_right: float,
) -> tuple[float, ...]:
    """Creepages and saturated creep forces of both wheels of a wheelset (Eqs. 25-28).

    Parameters
    ----------
    r_l, r_r : float
        Rolling radii of the left and right wheel (m).
    cdl, sdl, cdr, sdr : float
        Cosine and sine of the left and right contact angles.
    cpsi, spsi : float
        Cosine and sine of the yaw angle relative to the track's direction.
    dy : float
        Lateral velocity relative to the track centre line (m/s).
    yaw_rate : float
        Absolute yaw rate (rad/s).
    v : float
        Forward speed (m/s), > 0.
    wr : numpy.ndarray
        Wheel/rail parameter vector (slots :class:`railhunt.kernel.layout.WR`).
    q_left, q_right : float
        Normal loads of the left and right wheel (N).

    Returns
    -------
    tuple of float
        ``(Fx_L, Fy_L, Mz_L, Fx_R, Fy_R, Mz_R, xi_x_L, xi_y_L, phi_L, xi_x_R, xi_y_R,
        phi_R)``: creep forces (N) and spin moments (N*m) in each contact's plane, after
        saturation, and the longitudinal, lateral and spin creepages (-, -, 1/m).
    """
    f11, f22, f23, f33 = wr[WR.F11], wr[WR.F22], wr[WR.F23], wr[WR.F33]
    a, r0 = wr[WR.A], wr[WR.R0]
    n_load = wr[WR.N]
    omega = v / r0
    inv_v = 1.0 / v
    # Creepages (Eq. 25); the yaw rate is the absolute one (the track turns in a curve).
    base = v * cpsi + dy * spsi
    xl = (base - a * yaw_rate - r_l * omega) * inv_v
    xr = (base + a * yaw_rate - r_r * omega) * inv_v
    lat = (dy * cpsi - v * spsi) * inv_v
    yl = lat * cdl
    yr = lat * cdr
    sl = (yaw_rate * cdl - omega * sdl) * inv_v
    sr = (yaw_rate * cdr + omega * sdr) * inv_v
    # Kalker's linear forces (Eq. 26), coefficients following each wheel's load.
    # (cyl, cyr: the lateral forces of the lateral creepage alone, without spin.)
    if q_left == n_load and q_right == n_load:
        fxl = -f11 * xl
        fxr = -f11 * xr
        cyl = -f22 * yl
        cyr = -f22 * yr
        fyl = cyl - f23 * sl
        fyr = cyr - f23 * sr
        mzl = f23 * yl - f33 * sl
        mzr = f23 * yr - f33 * sr
    else:
        rl = q_left / n_load
        rr = q_right / n_load
        pl = rl ** (2.0 / 3.0)
        pr = rr ** (2.0 / 3.0)
        fxl = -f11 * pl * xl
        fxr = -f11 * pr * xr
        cyl = -f22 * pl * yl
        cyr = -f22 * pr * yr
        fyl = cyl - f23 * rl * sl
        fyr = cyr - f23 * rr * sr
        mzl = f23 * rl * yl - f33 * rl * pl * sl
        mzr = f23 * rr * yr - f33 * rr * pr * sr
    # Saturation (Eqs. 27-28), each wheel against its own mu * Q.
    law = int(wr[WR.CREEP_LAW])
    if law == CreepLaw.VERMEULEN_JOHNSON:
        # The resultant of the creepage forces alone (f11 xi_x, f22 xi_y: Vermeulen and
        # Johnson's theory has no spin), per wheel; every force follows with its factor.
        mu = wr[WR.MU]
        al = heuristic_saturation(math.sqrt(fxl * fxl + cyl * cyl) / (mu * q_left))
        ar = heuristic_saturation(math.sqrt(fxr * fxr + cyr * cyr) / (mu * q_right))
        fxl *= al
        fyl *= al
        fxr *= ar
        fyr *= ar
    elif law != CreepLaw.LINEAR:
        mu = wr[WR.MU]
        bl = math.sqrt(fxl * fxl + fyl * fyl) / (mu * q_left)
        br = math.sqrt(fxr * fxr + fyr * fyr) / (mu * q_right)
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
    return fxl, fyl, mzl, fxr, fyr, mzr, xl, yl, sl, xr, yr, sr


@njit(cache=True)
def wheelset_forces(
    y_rel: float, dy: float, psi: float, psi_rel: float, dpsi: float, v: float, wr: np.ndarray
) -> tuple[float, float]:
    """Lateral force (N) and yaw moment (N*m) of the rails on a wheelset on straight track.

    :func:`wheelset_contact` with both wheels at the static load ``N`` and the yaw rate
    ``dpsi`` (see there for the parameters).
    """
    n_load = wr[WR.N]
    fy, mz, _, _ = wheelset_contact(y_rel, dy, psi, psi_rel, dpsi, dpsi, v, wr, n_load, n_load)
    return fy, mz
