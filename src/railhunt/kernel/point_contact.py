"""Contact mechanics at each contact point: the ellipse, the coefficients and the normal
force of each wheel where it touches its rail.

With a profile contact table that carries the per-point columns (:class:`PointColumn`,
after the geometry in the wheel/rail vector), each wheel gets, at its lateral position,
its own Hertz ellipse (from the profiles' curvatures there), its own Kalker coefficients
and a normal force from its equilibrium with the contact angle instead of the static load.

**Normal force.** The rail acts on the wheel with the normal force ``N`` along the contact
normal (left wheel ``n = (-sin d, cos d)``, right wheel ``(sin d, cos d)`` in the track's
``(y, z)``) and the creep force ``T`` in the contact plane, whose lateral direction is
``(cos d, sin d)`` on the left and ``(cos d, -sin d)`` on the right (the kernel's
``T cos d`` is the force's track-lateral part). The wheel's vertical load ``Q`` (static,
or quasi-static in a curve) is carried by both:

    left:  N cos d_L + T_L sin d_L = Q_L,      right: N cos d_R - T_R sin d_R = Q_R.

``T`` itself depends on ``N`` (the saturation at ``mu N``, the ellipse ``~ N^(1/3)``). One
fixed-point step solves it: the creep law is evaluated at ``N0 = Q / cos d`` (``T = 0``),
giving ``T = t N0``; then ``N = Q / (cos d + t sin d)`` (right: ``- t sin d``) and all of the
contact's forces are scaled by ``N / N0``, so that the vertical balance holds exactly and
``|T| <= mu N`` stays true. Where friction would lift the wheel over its flange
(``cos d - mu sin d -> 0``, Nadal's limit; the model has no wheel lift) the denominator is
kept above 0.025 by a smooth floor from 0.05 down: ``N <= 40 Q``.

The lateral force on the wheelset is ``T cos d -+ N sin d`` per wheel (the static model's
``Q tan d`` is ``N sin d`` with ``N = Q / cos d``), the gravitational yaw moment
``a sin(psi_rel) (N_L sin d_L + N_R sin d_R)``.
"""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
from numba import njit

from railhunt.kernel.creep import CreepLaw, heuristic_saturation, polach_saturation
from railhunt.kernel.creep_batch import N_BATCH_SLOTS, BatchSlot
from railhunt.kernel.creep_table import table_creep
from railhunt.kernel.layout import N_POINT_COLUMNS, PER_POINT, WR

__all__ = ["N_STAGE_SLOTS", "StageSlot", "normal_force_ratio", "point_columns",
           "point_wheel_creep", "point_wheelset_contact", "stage_point_contact",
           "unstage_point_contact", "uses_per_point", "uses_staged_table"]

#: Below this the equilibrium's denominator ``cos d +- t sin d`` is floored smoothly ...
_DEN_KNEE = 0.05
#: ... toward this (never reached): ``N < Q / _DEN_MIN``.
_DEN_MIN = 0.025


@njit(cache=True)
def mechanics_marker(wr: np.ndarray) -> float:
    """The contact-mechanics marker after the wheel/rail vector's contact table (e.g.
    ``PER_POINT``, ``TWO_POINT``), or -1 when there is no table or nothing after it."""
    if wr.shape[0] <= WR.TABLE:
        return -1.0
    n = int(wr[WR.TABLE])
    if n < 2:
        return -1.0
    p = WR.TABLE + 3 + 4 * n
    return wr[p] if wr.shape[0] > p else -1.0


@njit(cache=True)
def uses_per_point(wr: np.ndarray) -> bool:
    """Whether the wheel/rail vector carries per-point contact mechanics."""
    return mechanics_marker(wr) == PER_POINT


@njit(cache=True)
def point_columns(y_rel: float, wr: np.ndarray) -> tuple[float, ...]:
    """Rolling radii, contact angles and per-point columns of both wheels at ``y_rel``.

    Linear interpolation on the table's uniform grid, constant beyond its ends (the same
    as :func:`railhunt.kernel.contact.wheel_geometry`). At a contact-point jump the two
    neighbouring rows hold two different contact points (tread and flange); between them
    the ellipse's columns are blended linearly as r and delta are, a smooth stand-in for
    the two-point contact the table does not resolve.

    Returns
    -------
    tuple of float
        ``(r_L, r_R, delta_L, delta_R, C1_L, K11_L, K22_L, K23_L, K33_L, AB_L, C1_R, ...,
        AB_R)`` (:class:`~railhunt.kernel.layout.PointColumn`).
    """
    n = int(wr[WR.TABLE])
    s = (y_rel - wr[WR.TABLE + 1]) / wr[WR.TABLE + 2]
    if s <= 0.0:
        i, w = 0, 0.0
    elif s >= n - 1:
        i, w = n - 2, 1.0
    else:
        i = int(s)
        w = s - i
    k = WR.TABLE + 3 + i
    r_l = wr[k] + w * (wr[k + 1] - wr[k])
    k += n
    r_r = wr[k] + w * (wr[k + 1] - wr[k])
    k += n
    d_l = wr[k] + w * (wr[k + 1] - wr[k])
    k += n
    d_r = wr[k] + w * (wr[k + 1] - wr[k])
    # Per-point columns: one block of 2 x N_POINT_COLUMNS values per grid point.
    k = WR.TABLE + 3 + 4 * n + 2 + 2 * N_POINT_COLUMNS * i
    j = k + 2 * N_POINT_COLUMNS
    v0 = wr[k] + w * (wr[j] - wr[k])
    v1 = wr[k + 1] + w * (wr[j + 1] - wr[k + 1])
    v2 = wr[k + 2] + w * (wr[j + 2] - wr[k + 2])
    v3 = wr[k + 3] + w * (wr[j + 3] - wr[k + 3])
    v4 = wr[k + 4] + w * (wr[j + 4] - wr[k + 4])
    v5 = wr[k + 5] + w * (wr[j + 5] - wr[k + 5])
    k += N_POINT_COLUMNS  # the right wheel's block
    j += N_POINT_COLUMNS
    u0 = wr[k] + w * (wr[j] - wr[k])
    u1 = wr[k + 1] + w * (wr[j + 1] - wr[k + 1])
    u2 = wr[k + 2] + w * (wr[j + 2] - wr[k + 2])
    u3 = wr[k + 3] + w * (wr[j + 3] - wr[k + 3])
    u4 = wr[k + 4] + w * (wr[j + 4] - wr[k + 4])
    u5 = wr[k + 5] + w * (wr[j + 5] - wr[k + 5])
    return (r_l, r_r, d_l, d_r, v0, v1, v2, v3, v4, v5, u0, u1, u2, u3, u4, u5)


@njit(cache=True)
def normal_force_ratio(cd: float, sd: float, t_lat: float, side: float) -> float:
    """``N / N0`` (``N0 = Q / cos(delta)``) of a wheel whose in-plane lateral creep force
    is ``t_lat`` times ``N0``: the normal force that balances its vertical load (module
    docstring); ``side`` +1 for the left wheel, -1 for the right."""
    den = cd + side * t_lat * sd
    if den < _DEN_KNEE:
        den = _DEN_MIN + (_DEN_KNEE - _DEN_MIN) * math.exp(
            (den - _DEN_KNEE) / (_DEN_KNEE - _DEN_MIN))
    return cd / den


@njit(cache=True)
def _linear(q: float, qth: float, cd: float, c1: float, k11: float, k22: float, k23: float,
            k33: float) -> tuple[float, float, float, float, float, float]:  # fmt: skip
    """``(f11, f22, f23, f33, c, N0)`` of one wheel at vertical load ``q`` (``qth``: its
    cube root)."""
    q23 = qth * qth
    return k11 * q23, k22 * q23, k23 * q, k33 * q * qth, c1 * qth, q / cd


@njit(cache=True, inline="always")
def _setup(
    y_rel: float, dy: float, cpsi: float, spsi: float, yaw_rate: float, v: float,
    wr: np.ndarray, q_left: float, q_right: float,
) -> tuple[float, ...]:  # fmt: skip
    """Creepages, linear-theory coefficients and geometry of both wheels (everything
    before the creep law)."""
    a, r0 = wr[WR.A], wr[WR.R0]
    (r_l, r_r, d_l, d_r, c1l, k11l, k22l, k23l, k33l, abl,
     c1r, k11r, k22r, k23r, k33r, abr) = point_columns(y_rel, wr)  # fmt: skip
    cdl, sdl = math.cos(d_l), math.sin(d_l)
    cdr, sdr = math.cos(d_r), math.sin(d_r)
    # Creepages (Eq. 25), as in wheel_creep.
    omega = v / r0
    inv_v = 1.0 / v
    base = v * cpsi + dy * spsi
    xl = (base - a * yaw_rate - r_l * omega) * inv_v
    xr = (base + a * yaw_rate - r_r * omega) * inv_v
    lat = (dy * cpsi - v * spsi) * inv_v
    yl = lat * cdl
    yr = lat * cdr
    sl = (yaw_rate * cdl - omega * sdl) * inv_v
    sr = (yaw_rate * cdr + omega * sdr) * inv_v
    # Each contact's ellipse and coefficients at N0 = Q / cos(delta).
    p = WR.TABLE + 3 + 4 * int(wr[WR.TABLE])
    n_load = wr[WR.N]
    qth_l = wr[p + 1] if q_left == n_load else np.cbrt(q_left)
    qth_r = wr[p + 1] if q_right == n_load else np.cbrt(q_right)
    f11l, f22l, f23l, f33l, cl, n0l = _linear(q_left, qth_l, cdl, c1l, k11l, k22l, k23l, k33l)
    f11r, f22r, f23r, f33r, cr, n0r = _linear(q_right, qth_r, cdr, c1r, k11r, k22r, k23r, k33r)
    return (xl, yl, sl, xr, yr, sr, f11l, f22l, f23l, f33l, cl, n0l, f11r, f22r, f23r, f33r,
            cr, n0r, abl, abr, d_l, d_r, cdl, sdl, cdr, sdr)


@njit(cache=True)
def point_wheel_creep(
    y_rel: float, dy: float, cpsi: float, spsi: float, yaw_rate: float, v: float,
    wr: np.ndarray, q_left: float, q_right: float, table: np.ndarray,
) -> tuple[float, ...]:  # fmt: skip
    """Creepages, creep forces and normal forces of both wheels, per-point mechanics.

    Parameters as :func:`point_wheelset_contact` (``cpsi``, ``spsi``: cosine and sine of
    the yaw angle relative to the track).

    Returns
    -------
    tuple of float
        ``(Fx_L, Fy_L, Mz_L, Fx_R, Fy_R, Mz_R, xi_x_L, xi_y_L, phi_L, xi_x_R, xi_y_R,
        phi_R, N_L, N_R, delta_L, delta_R, cos delta_L, sin delta_L, cos delta_R,
        sin delta_R)``: forces (N) and spin moments (N*m) in each contact's plane,
        creepages (-, -, 1/m), normal forces (N), contact angles (rad) and their cosines
        and sines.
    """
    (xl, yl, sl, xr, yr, sr, f11l, f22l, f23l, f33l, cl, n0l, f11r, f22r, f23r, f33r, cr,
     n0r, abl, abr, d_l, d_r, cdl, sdl, cdr, sdr) = _setup(y_rel, dy, cpsi, spsi, yaw_rate,
                                                          v, wr, q_left, q_right)  # fmt: skip
    mu = wr[WR.MU]
    law = int(wr[WR.CREEP_LAW])
    if law == CreepLaw.EXACT_TABLE and table.shape[0] > 0:
        ml = mu * n0l
        mr = mu * n0r
        il = 1.0 / ml
        ir = 1.0 / mr
        txl, tyl, tml = table_creep(f11l * xl * il, f22l * yl * il, f23l * sl * il,
                                    f23l / (f22l * cl), f33l / (f23l * cl), abl, table)
        txr, tyr, tmr = table_creep(f11r * xr * ir, f22r * yr * ir, f23r * sr * ir,
                                    f23r / (f22r * cr), f33r / (f23r * cr), abr, table)
        fxl, fyl, mzl = ml * txl, ml * tyl, ml * cl * tml
        fxr, fyr, mzr = mr * txr, mr * tyr, mr * cr * tmr
    else:
        fxl = -f11l * xl
        fxr = -f11r * xr
        cyl = -f22l * yl
        cyr = -f22r * yr
        fyl = cyl - f23l * sl
        fyr = cyr - f23r * sr
        mzl = f23l * yl - f33l * sl
        mzr = f23r * yr - f33r * sr
        if law == CreepLaw.VERMEULEN_JOHNSON:
            al = heuristic_saturation(math.sqrt(fxl * fxl + cyl * cyl) / (mu * n0l))
            ar = heuristic_saturation(math.sqrt(fxr * fxr + cyr * cyr) / (mu * n0r))
        elif law == CreepLaw.LINEAR:
            al = 1.0
            ar = 1.0
        else:
            bl = math.sqrt(fxl * fxl + fyl * fyl) / (mu * n0l)
            br = math.sqrt(fxr * fxr + fyr * fyr) / (mu * n0r)
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
    # The normal forces from each wheel's vertical equilibrium; every force of the
    # contact follows (one fixed-point step, module docstring).
    gl = normal_force_ratio(cdl, sdl, fyl / n0l, 1.0)
    gr = normal_force_ratio(cdr, sdr, fyr / n0r, -1.0)
    return (fxl * gl, fyl * gl, mzl * gl, fxr * gr, fyr * gr, mzr * gr, xl, yl, sl, xr, yr,
            sr, gl * n0l, gr * n0r, d_l, d_r, cdl, sdl, cdr, sdr)


@njit(cache=True, inline="always")
def _track_forces(
    fxl: float, fyl: float, mzl: float, fxr: float, fyr: float, mzr: float, n_l: float,
    n_r: float, cdl: float, sdl: float, cdr: float, sdr: float, cpsi: float, spsi: float,
    a: float, sin_psi_rel: float,
) -> tuple[float, float, float, float, float, float]:  # fmt: skip
    """The contact forces in track coordinates (Eqs. 29-30 with the normal forces' lateral
    parts): ``(F_y, M_z, F_left, F_right, N_left, N_right)``."""
    nsl = n_l * sdl
    nsr = n_r * sdr
    f_left = fyl * cdl * cpsi + fxl * spsi - nsl
    f_right = fyr * cdr * cpsi + fxr * spsi + nsr
    m_yaw = (fxr - fxl) * a + mzl * cdl + mzr * cdr + a * sin_psi_rel * (nsl + nsr)
    return f_left + f_right, m_yaw, f_left, f_right, n_l, n_r


@njit(cache=True)
def point_wheelset_contact(
    y_rel: float, dy: float, psi: float, psi_rel: float, yaw_rate: float, v: float,
    wr: np.ndarray, q_left: float, q_right: float, table: np.ndarray,
) -> tuple[float, float, float, float, float, float]:  # fmt: skip
    """Forces of the rails on one wheelset with per-point contact mechanics.

    Parameters as :func:`railhunt.kernel.wheelset.wheelset_contact`; ``table`` is the creep
    table of the ``"exact-table"`` law (empty: that law falls back to the heuristic
    saturation per wheel).

    Returns
    -------
    tuple of float
        ``(F_y, M_z, F_left, F_right, N_left, N_right)``: lateral force (N) and yaw moment
        (N*m) on the wheelset, the lateral force on each wheel (N, + left) and the normal
        forces (N).
    """
    cpsi, spsi = math.cos(psi), math.sin(psi)
    (fxl, fyl, mzl, fxr, fyr, mzr, _, _, _, _, _, _, n_l, n_r, _, _, cdl, sdl, cdr,
     sdr) = point_wheel_creep(y_rel, dy, cpsi, spsi, yaw_rate, v, wr, q_left, q_right,
                              table)  # fmt: skip
    return _track_forces(fxl, fyl, mzl, fxr, fyr, mzr, n_l, n_r, cdl, sdl, cdr, sdr, cpsi,
                         spsi, wr[WR.A], math.sin(psi_rel))  # fmt: skip


class StageSlot(IntEnum):
    """Rows after the creep batch's (:class:`~railhunt.kernel.creep_batch.BatchSlot`) in
    the work array of the staged per-point contact (:func:`stage_point_contact`)."""

    N0 = N_BATCH_SLOTS  # Q / cos(delta) of the wheel (N)
    CD = N_BATCH_SLOTS + 1  # cos(delta)
    SD = N_BATCH_SLOTS + 2  # sin(delta)
    # Per wheelset, in its left wheel's column:
    CPSI = N_BATCH_SLOTS + 3  # cos(psi)
    SPSI = N_BATCH_SLOTS + 4  # sin(psi)
    SIN_PSI_REL = N_BATCH_SLOTS + 5  # sin(psi_rel)
    WHEELSET = N_BATCH_SLOTS + 6  # the wheelset's index


#: Rows of the staged per-point contact's work array.
N_STAGE_SLOTS = N_BATCH_SLOTS + len(StageSlot)


@njit(cache=True)
def uses_staged_table(wr: np.ndarray, table: np.ndarray) -> bool:
    """Whether a wheelset's per-point contact with the ``"exact-table"`` law can be staged
    (:func:`stage_point_contact`): per-point mechanics, that law and its table."""
    return (table.shape[0] > 0 and int(wr[WR.CREEP_LAW]) == CreepLaw.EXACT_TABLE
            and uses_per_point(wr))  # fmt: skip


@njit(cache=True, inline="always")
def stage_point_contact(
    y_rel: float, dy: float, psi: float, psi_rel: float, yaw_rate: float, v: float,
    wr: np.ndarray, q_left: float, q_right: float, w: np.ndarray, k: int,
) -> None:  # fmt: skip
    """First half of :func:`point_wheelset_contact` with the ``"exact-table"`` law: the
    wheels' inputs of :func:`~railhunt.kernel.creep_batch.table_creep_batch` into columns
    ``k`` (left) and ``k + 1`` (right) of the work array ``w`` (rows :class:`StageSlot`).
    After the batch, :func:`unstage_point_contact` gives the forces, the same bits as
    :func:`point_wheelset_contact`."""
    cpsi, spsi = math.cos(psi), math.sin(psi)
    (xl, yl, sl, xr, yr, sr, f11l, f22l, f23l, f33l, cl, n0l, f11r, f22r, f23r, f33r, cr,
     n0r, abl, abr, _, _, cdl, sdl, cdr, sdr) = _setup(y_rel, dy, cpsi, spsi, yaw_rate, v,
                                                       wr, q_left, q_right)  # fmt: skip
    mu = wr[WR.MU]
    for col, f11, f22, f23, f33, c, n0, xi, eta, phi, ab, cd, sd in (
            (k, f11l, f22l, f23l, f33l, cl, n0l, xl, yl, sl, abl, cdl, sdl),
            (k + 1, f11r, f22r, f23r, f33r, cr, n0r, xr, yr, sr, abr, cdr, sdr)):
        w[BatchSlot.F11, col] = f11
        w[BatchSlot.F22, col] = f22
        w[BatchSlot.F23, col] = f23
        w[BatchSlot.F33, col] = f33
        w[BatchSlot.C, col] = c
        w[BatchSlot.MU_N, col] = mu * n0
        w[BatchSlot.XI, col] = xi
        w[BatchSlot.ETA, col] = eta
        w[BatchSlot.PHI, col] = phi
        w[BatchSlot.AB, col] = ab
        w[StageSlot.N0, col] = n0
        w[StageSlot.CD, col] = cd
        w[StageSlot.SD, col] = sd
    w[StageSlot.CPSI, k] = cpsi
    w[StageSlot.SPSI, k] = spsi
    w[StageSlot.SIN_PSI_REL, k] = math.sin(psi_rel)


@njit(cache=True, inline="always")
def unstage_point_contact(
    wr: np.ndarray, w: np.ndarray, k: int
) -> tuple[float, float, float, float, float, float]:  # fmt: skip
    """Second half of :func:`point_wheelset_contact` (see :func:`stage_point_contact`):
    ``(F_y, M_z, F_left, F_right, N_left, N_right)`` from columns ``k`` and ``k + 1``."""
    n0l, n0r = w[StageSlot.N0, k], w[StageSlot.N0, k + 1]
    cdl, sdl = w[StageSlot.CD, k], w[StageSlot.SD, k]
    cdr, sdr = w[StageSlot.CD, k + 1], w[StageSlot.SD, k + 1]
    fyl = w[BatchSlot.FY, k]
    fyr = w[BatchSlot.FY, k + 1]
    gl = normal_force_ratio(cdl, sdl, fyl / n0l, 1.0)
    gr = normal_force_ratio(cdr, sdr, fyr / n0r, -1.0)
    return _track_forces(w[BatchSlot.FX, k] * gl, fyl * gl, w[BatchSlot.MZ, k] * gl,
                         w[BatchSlot.FX, k + 1] * gr, fyr * gr, w[BatchSlot.MZ, k + 1] * gr,
                         gl * n0l, gr * n0r, cdl, sdl, cdr, sdr, w[StageSlot.CPSI, k],
                         w[StageSlot.SPSI, k], wr[WR.A], w[StageSlot.SIN_PSI_REL, k])
