"""The assembled 17-DOF vehicle model and its one compiled right-hand side.

State vector (38 entries, SI units)::

    x[0:17]   generalised coordinates q (see railhunt.suspension.DOF_NAMES), m and rad
    x[17:34]  their rates dq/dt, m/s and rad/s
    x[34:38]  yaw damper forces F_d1..F_d4 (front left, front right, rear left, rear right), N

The right-hand side :func:`rhs` is the only place where the equations of motion are
written. Simulation, the Jacobian (linear stability), the critical-speed search and
continuation all call it.

``M q'' = -(K + G) q - C q' - B_d^T F_d + Q_wheel/rail``, with ``K``, ``C`` assembled from
the suspension elements, ``G`` the gravitational roll terms, ``B_d`` the yaw damper
elongation rows, and ``Q_wheel/rail`` the creep and gravitational forces on the wheelsets.
Each damper force obeys ``dF/dt = K_d (B_d q' - v_d(F))`` (Maxwell element).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from railhunt import track as _track
from railhunt.contact.polynomial import contact_angle, rolling_radius
from railhunt.creep import CREEP_LAWS, heuristic_saturation, polach_saturation
from railhunt.suspension import (
    DAMPER_NAMES,
    DOF_NAMES,
    N_DAMPER,
    N_DOF,
    assemble,
    damper_velocity,
    gravity_stiffness,
    mass_matrix_diagonal,
    suspension_elements,
    yaw_damper_rows,
)
from railhunt.vehicle import Vehicle

N_STATE = 2 * N_DOF + N_DAMPER
#: Names of the 38 states.
STATE_NAMES: tuple[str, ...] = (
    DOF_NAMES + tuple("d" + n for n in DOF_NAMES) + tuple("F_" + n for n in DAMPER_NAMES)
)
#: Index of the leading wheelset's lateral displacement in the state vector.
Y_W1 = DOF_NAMES.index("y_w1")
#: Indices of the wheelsets' lateral displacements.
WHEELSET_Y = np.array([DOF_NAMES.index(f"y_w{j}") for j in range(1, 5)])

# Layout of the wheel/rail parameter vector ``wr``.
(_F11, _F22, _F23, _F33, _MU, _N, _A, _R0, _L1, _L2, _L3, _L4, _L5, _D0, _D1, _D4, _D5,
 _DMAX, _LAW, _INV_MW, _INV_JW, _OFF) = range(22)  # fmt: skip
N_WR = _OFF + 4
#: Index of the first wheelset offset in the wheel/rail vector.
WR_OFFSET = _OFF
#: Tail of ``wr`` from this index: tabulated contact geometry ``[n, y0, dy, r_L[n],
#: r_R[n], delta_L[n], delta_R[n]]`` on a uniform ``y`` grid; ``n = 0``: polynomials.
WR_TABLE = N_WR


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
        Wheel/rail parameter vector (see :meth:`Model.wheel_rail_vector`).

    Returns
    -------
    tuple of float
        Lateral force (N) and yaw moment (N*m) on the wheelset in track coordinates:
        creep forces after saturation plus the gravitational (normal-force) terms.
    """
    f11, f22, f23, f33 = wr[_F11], wr[_F22], wr[_F23], wr[_F33]
    a, r0 = wr[_A], wr[_R0]
    n_load = wr[_N]
    n_tab = int(wr[WR_TABLE]) if wr.shape[0] > WR_TABLE else 0
    if n_tab > 1:
        # Tabulated geometry: linear interpolation, clamped at the table's ends.
        s = (y_rel - wr[WR_TABLE + 1]) / wr[WR_TABLE + 2]
        if s <= 0.0:
            i, w = 0, 0.0
        elif s >= n_tab - 1:
            i, w = n_tab - 2, 1.0
        else:
            i = int(s)
            w = s - i
        k = WR_TABLE + 3 + i
        r_l = wr[k] + w * (wr[k + 1] - wr[k])
        k += n_tab
        r_r = wr[k] + w * (wr[k + 1] - wr[k])
        k += n_tab
        d_l = wr[k] + w * (wr[k + 1] - wr[k])
        k += n_tab
        d_r = wr[k] + w * (wr[k + 1] - wr[k])
    else:
        # Paper's polynomials, wheel by wheel (u = displacement toward the wheel's flange).
        r_l = rolling_radius(y_rel, r0, wr[_L1], wr[_L2], wr[_L3], wr[_L4], wr[_L5])
        r_r = rolling_radius(-y_rel, r0, wr[_L1], wr[_L2], wr[_L3], wr[_L4], wr[_L5])
        d_l = contact_angle(y_rel, wr[_D0], wr[_D1], wr[_D4], wr[_D5], wr[_DMAX])
        d_r = contact_angle(-y_rel, wr[_D0], wr[_D1], wr[_D4], wr[_D5], wr[_DMAX])
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
    law = int(wr[_LAW])
    if law != 2:
        mun = wr[_MU] * n_load
        bl = math.sqrt(fxl * fxl + fyl * fyl) / mun
        br = math.sqrt(fxr * fxr + fyr * fyr) / mun
        if law == 0:
            al = heuristic_saturation(0.5 * (bl + br))
            ar = al
        elif law == 3:
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
def rhs(
    t: float,
    x: np.ndarray,
    v: float,
    lin: np.ndarray,
    bd: np.ndarray,
    dd: np.ndarray,
    dpar: np.ndarray,
    wr: np.ndarray,
    trk: np.ndarray,
    trs: np.ndarray,
    out: np.ndarray,
) -> None:
    """Time derivative of the state (writes ``out``, allocates nothing).

    Parameters
    ----------
    t : float
        Time (s); only the track input depends on it.
    x : numpy.ndarray, shape (38,)
        State.
    v : float
        Forward speed (m/s).
    lin : numpy.ndarray, shape (17, 34)
        ``-M^-1 [K + G, C]``: accelerations from the linear suspension.
    bd : numpy.ndarray, shape (4, 17)
        Yaw damper elongation rows.
    dd : numpy.ndarray, shape (17, 4)
        ``-M^-1 B_d^T``: accelerations per unit damper force.
    dpar : numpy.ndarray, shape (4, 4)
        Per damper ``[K_d, C_d1, C_d2, F_u]``.
    wr : numpy.ndarray
        Wheel/rail parameters.
    trk, trs : numpy.ndarray
        Track description (see :func:`railhunt.track.encode`).
    out : numpy.ndarray, shape (38,)
        Receives dx/dt.
    """
    nq = 17
    for i in range(nq):
        out[i] = x[nq + i]
    for i in range(nq):
        acc = 0.0
        for k in range(2 * nq):
            acc += lin[i, k] * x[k]
        out[nq + i] = acc
    for d in range(4):
        f = x[2 * nq + d]
        rate = 0.0
        for k in range(nq):
            rate += bd[d, k] * x[nq + k]
        v_damp = damper_velocity(f, dpar[d, 1], dpar[d, 2], dpar[d, 3])
        out[2 * nq + d] = dpar[d, 0] * (rate - v_damp)
        for i in range(nq):
            out[nq + i] += dd[i, d] * f
    inv_mw = wr[_INV_MW]
    inv_jw = wr[_INV_JW]
    for j in range(4):
        iy = 9 + 2 * j
        ip = iy + 1
        yr, slope = _track.alignment(v * t - wr[_OFF + j], trk, trs)
        fy, mz = wheelset_forces(
            x[iy] - yr, x[nq + iy], x[ip], x[ip] - slope, x[nq + ip], v, wr
        )
        out[nq + iy] += fy * inv_mw
        out[nq + ip] += mz * inv_jw


@njit(cache=True)
def jacobian(
    x: np.ndarray,
    v: float,
    lin: np.ndarray,
    bd: np.ndarray,
    dd: np.ndarray,
    dpar: np.ndarray,
    wr: np.ndarray,
    trk: np.ndarray,
    trs: np.ndarray,
) -> np.ndarray:
    """Jacobian d(rhs)/dx at ``t = 0`` by central differences of :func:`rhs` (38 x 38).

    Steps are 1e-7 in displacements, angles and rates and 1e-3 N in damper forces (the
    states' natural scales times about 1e-5).
    """
    n = x.shape[0]
    jac = np.empty((n, n))
    xp = x.copy()
    fp = np.empty(n)
    fm = np.empty(n)
    for k in range(n):
        h = 1e-3 if k >= 34 else 1e-7
        xp[k] = x[k] + h
        rhs(0.0, xp, v, lin, bd, dd, dpar, wr, trk, trs, fp)
        xp[k] = x[k] - h
        rhs(0.0, xp, v, lin, bd, dd, dpar, wr, trk, trs, fm)
        xp[k] = x[k]
        for i in range(n):
            jac[i, k] = (fp[i] - fm[i]) / (2.0 * h)
    return jac


class Model:
    """The vehicle's equations of motion in the arrays the compiled code needs.

    Parameters
    ----------
    vehicle : Vehicle
        Validated vehicle description (SI).
    creep_law : {"heuristic", "heuristic-per-wheel", "linear", "polach"}
        ``"heuristic"``: the paper's Eq. 28 with one factor per wheelset from the mean of
        both wheels' ``beta``; ``"heuristic-per-wheel"``: one factor per wheel;
        ``"linear"``: Kalker's linear law without saturation; ``"polach"``: Polach's
        saturation per wheel (see :mod:`railhunt.creep`).
    contact : railhunt.contact.geometry.ContactGeometry, optional
        Tabulated contact geometry (uniform ``y`` grid) used instead of the vehicle's
        polynomials (Eqs. 32-33): ``r_L, r_R, delta_L, delta_R`` interpolated linearly in
        the compiled right-hand side, held constant beyond the table. The vehicle's ``r0``
        (creepage reference) and ``a`` are still used. Default: the geometry of the
        vehicle's :class:`railhunt.vehicle.ContactSpec` (its ``[contact]`` section) if it
        has one, else the polynomials.

    Attributes
    ----------
    mass : numpy.ndarray
        Mass matrix diagonal (kg, kg*m^2).
    K, C : numpy.ndarray
        Suspension stiffness (incl. gravitational roll terms) and damping matrices.
    """

    def __init__(
        self, vehicle: Vehicle, creep_law: str = "heuristic", contact: object = None
    ) -> None:
        if creep_law not in CREEP_LAWS:
            raise ValueError(
                f"creep_law = {creep_law!r} is invalid: must be one of {sorted(CREEP_LAWS)}"
            )
        self.vehicle = vehicle
        self.creep_law = creep_law
        if contact is None and vehicle.contact is not None:
            contact = vehicle.contact.geometry()
        if contact is not None:
            # The creepages are measured from r0: a centred wheelset on a table whose
            # radius differs from r0 would carry a steady longitudinal creepage that eats
            # into the saturation of every creep force.
            r_centre = float(np.interp(0.0, contact.y, contact.r_left))
            if abs(r_centre - vehicle.r0) > 1e-6:
                raise ValueError(
                    f"r0 = {vehicle.r0!r} m is invalid with this contact geometry: must "
                    f"equal its centred rolling radius {r_centre:.9f} m within 1 um "
                    f"(set r0 = {r_centre!r})"
                )
        self.contact = contact
        self.mass = mass_matrix_diagonal(vehicle)
        k_susp, self.C = assemble(suspension_elements(vehicle))
        self.K = k_susp + gravity_stiffness(vehicle)
        inv_m = 1.0 / self.mass
        self.lin = np.ascontiguousarray(-inv_m[:, None] * np.hstack([self.K, self.C]))
        self.bd = np.ascontiguousarray(yaw_damper_rows(vehicle))
        self.dd = np.ascontiguousarray(-inv_m[:, None] * self.bd.T)
        self.dpar = np.tile([vehicle.K_d, vehicle.C_d1, vehicle.C_d2, vehicle.F_u], (N_DAMPER, 1))
        self.wr = self.wheel_rail_vector()

    def wheel_rail_vector(self) -> np.ndarray:
        """Wheel/rail parameters packed for :func:`wheelset_forces`."""
        v = self.vehicle
        wr = np.zeros(N_WR + 3)
        wr[_F11], wr[_F22], wr[_F23], wr[_F33] = v.f11, v.f22, v.f23, v.f33
        wr[_MU], wr[_N], wr[_A], wr[_R0] = v.mu, v.N, v.a, v.r0
        wr[_L1:_L5 + 1] = [v.lambda1, v.lambda2, v.lambda3, v.lambda4, v.lambda5]
        wr[_D0], wr[_D1], wr[_D4], wr[_D5], wr[_DMAX] = v.d0, v.d1, v.d4, v.d5, v.delta_max
        wr[_LAW] = CREEP_LAWS[self.creep_law]
        wr[_INV_MW], wr[_INV_JW] = 1.0 / v.M_w, 1.0 / v.J_wz
        wr[_OFF:_OFF + 4] = self.wheelset_offsets()
        if self.contact is not None:
            wr = np.concatenate([wr[:N_WR], _contact_table(self.contact)])
        return wr

    def wheelset_offsets(self) -> np.ndarray:
        """Distance of each wheelset behind the leading one (m): 0, 2*l1, 2*l, 2*l + 2*l1."""
        v = self.vehicle
        return np.array([0.0, 2 * v.l1, 2 * v.l, 2 * v.l + 2 * v.l1])

    def args(self, speed: float, excitation: object = None) -> tuple:
        """Arguments that follow ``(t, x)`` in every call of :func:`rhs`.

        Parameters
        ----------
        speed : float
            Forward speed (m/s), > 0.
        excitation : object, optional
            Track input (:class:`railhunt.track.SingleDefect`, ``SampledTrack``); ideal
            track otherwise.
        """
        if not (math.isfinite(speed) and speed > 0.0):
            raise ValueError(f"speed = {speed!r} m/s is invalid: must be finite and > 0")
        trk, trs = _track.encode(excitation)
        return (float(speed), self.lin, self.bd, self.dd, self.dpar, self.wr, trk, trs)

    def derivative(
        self, x: np.ndarray, speed: float, t: float = 0.0, excitation: object = None
    ) -> np.ndarray:
        """dx/dt at state ``x`` (convenience wrapper of :func:`rhs`)."""
        out = np.empty(N_STATE)
        rhs(t, np.ascontiguousarray(x, dtype=np.float64), *self.args(speed, excitation), out)
        return out

    def jacobian(self, speed: float, x: np.ndarray | None = None) -> np.ndarray:
        """Jacobian of the autonomous system (ideal track) at ``x`` (default: centred)."""
        x0 = np.zeros(N_STATE) if x is None else np.ascontiguousarray(x, dtype=np.float64)
        return jacobian(x0, *self.args(speed))

    def damper_velocities(self, damper_forces: np.ndarray) -> np.ndarray:
        """Velocities of the viscous parts of the yaw dampers (m/s) for given forces (N)."""
        f = np.asarray(damper_forces, dtype=np.float64)
        out = np.empty_like(f)
        flat_f, flat_o = f.reshape(-1, N_DAMPER), out.reshape(-1, N_DAMPER)
        for d in range(N_DAMPER):
            k_d, c1, c2, fu = self.dpar[d]
            flat_o[:, d] = _damper_velocity_array(flat_f[:, d], c1, c2, fu)
        return out


def _contact_table(contact: object) -> np.ndarray:
    """Pack a contact table (``y`` uniform) into the ``wr`` tail (see :data:`WR_TABLE`)."""
    y = np.asarray(contact.y, dtype=np.float64)
    step = np.diff(y)
    if y.ndim != 1 or y.size < 2 or not np.all(step > 0):
        raise ValueError("contact.y must be strictly increasing with at least 2 points")
    if np.max(np.abs(step - step[0])) > 1e-9 * max(abs(step[0]), 1e-12) + 1e-15:
        raise ValueError("contact.y must be uniformly spaced (tabulated geometry)")
    cols = [np.asarray(getattr(contact, name), dtype=np.float64)
            for name in ("r_left", "r_right", "delta_left", "delta_right")]
    for name, col in zip(("r_left", "r_right", "delta_left", "delta_right"), cols,
                         strict=True):
        if col.shape != y.shape or not np.all(np.isfinite(col)):
            raise ValueError(f"contact.{name} must be finite with the shape of contact.y")
    return np.concatenate([[float(y.size), y[0], step[0]], *cols])


@njit(cache=True)
def _damper_velocity_array(f: np.ndarray, c1: float, c2: float, fu: float) -> np.ndarray:
    out = np.empty(f.shape[0])
    for i in range(f.shape[0]):
        out[i] = damper_velocity(f[i], c1, c2, fu)
    return out
