"""The one right-hand side of the vehicle's equations of motion, and its Jacobian.

``M q'' = -(K + G) q - C q' - B_d^T F_d - B_s^T F_s + Q_wheel/rail (+ curve terms)``, with
``K``, ``C`` assembled from the suspension elements, ``G`` the gravitational roll terms,
``B_d`` the yaw damper elongation rows, ``B_s`` the bump stops' rows (a stop to the track,
a flange, deforms by ``B_s q`` minus the rails' alignment at its wheelset) and ``Q_wheel/rail``
the creep and gravitational forces on the wheelsets. Each damper force obeys
``dF/dt = K_d (B_d q' - v_d(F))`` (Maxwell element). In a curve every coordinate is
measured from the track at its body's own position; the suspension then deforms by
``B (q + q_geo)`` and each body feels the unbalanced lateral acceleration of the curve
(:func:`curve_geometry`); the wheels carry their own quasi-static loads
(:func:`wheel_loads`).

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

from railhunt.kernel.bumpstop import bump_stop_force
from railhunt.kernel.creep_batch import table_creep_batch
from railhunt.kernel.damper import damper_velocity
from railhunt.kernel.layout import NO_REFCOUNT, WR, DamperParam, StopParam, SystemArrays
from railhunt.kernel.point_contact import (
    StageSlot,
    stage_point_contact,
    unstage_point_contact,
    uses_staged_table,
)
from railhunt.kernel.route import route_point
from railhunt.kernel.track import alignment
from railhunt.kernel.wheelset import wheelset_contact, wheelset_forces

__all__ = [
    "curve_geometry", "curve_offsets", "derived", "jacobian", "rhs", "track_stop_force",
    "wheel_loads", "wheelset_forces", "wheelset_track_forces",
]  # fmt: skip


@njit(cache=True, **NO_REFCOUNT)
def wheel_loads(s_track: float, v: float, wr: np.ndarray,
                route: np.ndarray) -> tuple[float, float, float]:  # fmt: skip
    """Quasi-static wheel loads (N) and the track's yaw rate (rad/s) at track position ``s``.

    On straight track (no route) both loads are the static ``N`` and the yaw rate is 0.
    In a curve of curvature ``kappa`` and cant angle ``phi`` an axle of mass ``W`` presses
    on the track plane with ``W (g cos phi + v^2 kappa sin phi)``, shared equally; the
    unbalanced lateral acceleration ``a = v^2 kappa cos phi - g sin phi`` acting on the
    masses above the rail (``MH = sum m H``) moves ``MH a / 2a_c`` from the inner to the
    outer wheel (``2 a_c``: the distance between the contact points). A load is kept at
    1 % of ``N`` or more (a wheel that lifts has no creep forces left to compute).

    Returns
    -------
    tuple of float
        ``(Q_left, Q_right, v * kappa)``.
    """
    n_load = wr[WR.N]
    if route.shape[0] == 0:
        return n_load, n_load, 0.0
    kappa, _, _, cant, _, _ = route_point(s_track, route)
    if kappa == 0.0 and cant == 0.0:
        return n_load, n_load, 0.0
    c, sn = math.cos(cant), math.sin(cant)
    g = wr[WR.G]
    q_mean = 0.5 * wr[WR.W] * (g * c + v * v * kappa * sn)
    shift = wr[WR.MH] * (v * v * kappa * c - g * sn) / (2.0 * wr[WR.A])
    floor = 0.01 * n_load
    return max(q_mean - shift, floor), max(q_mean + shift, floor), v * kappa


@njit(cache=True, **NO_REFCOUNT)
def wheelset_track_forces(
    j: int, t: float, x: np.ndarray, v: float, s: SystemArrays
) -> tuple[float, float, float, float, float, float]:
    """Forces of the rails on wheelset ``j`` at state ``x`` and time ``t``.

    The wheelset meets the track at position ``v t - delay_j``: the track input there
    (its displacement relative to the rails sets the contact geometry, its yaw relative to
    the local rail direction the gravitational moment) and, in a curve, its wheel loads
    and the track's yaw rate.

    Returns
    -------
    tuple of float
        ``(F_y, M_z, F_left, F_right, Q_left, Q_right)`` in N and N*m (see
        :func:`railhunt.kernel.wheelset.wheelset_contact`).
    """
    nq = s.linear.shape[0]  # rates start at x[nq] (layout.py)
    iy = s.wheelsets[j, 0]
    ip = s.wheelsets[j, 1]
    pos = v * t - s.wheelset_delay[j]
    yr, slope = alignment(pos, s.track, s.track_samples)
    wr = s.wheel_rail[j]
    q_l, q_r, track_rate = wheel_loads(pos, v, wr, s.route)
    fy, mz, f_l, f_r = wheelset_contact(x[iy] - yr, x[nq + iy], x[ip], x[ip] - slope,
                                        x[nq + ip], x[nq + ip] + track_rate, v, wr,
                                        q_l, q_r, s.creep_table)  # fmt: skip
    return fy, mz, f_l, f_r, q_l, q_r


@njit(cache=True, **NO_REFCOUNT)
def track_stop_force(k: int, t: float, x: np.ndarray, v: float, s: SystemArrays) -> float:
    """Force (N) of stop ``k``, a stop to the track (a flange: ``s.stop_wheelset[k] >= 0``),
    at state ``x`` and time ``t``: the law of :func:`~railhunt.kernel.bumpstop.
    bump_stop_force` at the deformation :func:`rhs` gives it, ``stop_rows[k] @ q`` minus
    the rails' lateral alignment under its wheelset. Positive when the deformation is; the
    stop pushes the wheelset back with ``-f`` times its row, and so the wheelset presses on
    its rails with ``f * stop_rows[k, y]`` laterally (+ left).
    """
    nq = s.linear.shape[0]
    dist = 0.0
    for i in range(nq):
        dist += s.stop_rows[k, i] * x[i]
    j = s.stop_wheelset[k]
    dist -= alignment(v * t - s.wheelset_delay[j], s.track, s.track_samples)[0]
    return bump_stop_force(dist, s.stop[k, StopParam.GAP], s.stop[k, StopParam.K1],
                           s.stop[k, StopParam.K3])  # fmt: skip


@njit(cache=True, **NO_REFCOUNT)
def curve_offsets(t: float, v: float, wr: np.ndarray, route: np.ndarray, bodies: np.ndarray,
                  body_delay: np.ndarray, geo: np.ndarray) -> None:  # fmt: skip
    """Geometric offsets a curve imposes on the suspension, and the track frames' inertia.

    Each body's coordinates are measured from the track at its own position
    ``v t - delay_b``. Seen from the first body's track frame (the car body's), the track
    frame of body ``b`` is turned by ``theta_b - theta_0``, rolled by ``cant_b - cant_0``
    and shifted laterally by the offset of its track point from the tangent at the first
    body (the versine ``kappa d^2 / 2`` in a constant curve). Writes, for ``n`` coordinates,
    these offsets and their rates into ``geo[:2n]`` (``[q_geo, dq_geo/dt]``: every
    suspension element deforms by ``B (q + q_geo)``), and into ``geo[2n:3n]`` the
    accelerations that following the track adds to each body: ``-a`` laterally, with
    ``a = v^2 kappa cos phi - g sin phi`` the unbalanced (cant-deficient) lateral
    acceleration, and ``-v^2 dkappa/ds`` in yaw (the track frame's angular acceleration in
    a transition). Entries of absent coordinates stay 0.
    """
    n = geo.shape[0] // 3
    for i in range(geo.shape[0]):
        geo[i] = 0.0
    g = wr[WR.G]
    s_ref = v * t - body_delay[0]
    k_r, th_r, ph_r, c_r, _, dc_r = route_point(s_ref, route)
    for b in range(bodies.shape[0]):
        pos = v * t - body_delay[b]
        kappa, theta, phi, cant, dkappa, dcant = route_point(pos, route)
        ds = pos - s_ref
        iy, ip, ir = bodies[b, 0], bodies[b, 1], bodies[b, 2]
        geo[iy] = phi - ph_r - th_r * ds
        geo[n + iy] = v * (theta - th_r - k_r * ds)
        geo[ip] = theta - th_r
        geo[n + ip] = v * (kappa - k_r)
        geo[2 * n + iy] = -(v * v * kappa * math.cos(cant) - g * math.sin(cant))
        geo[2 * n + ip] = -v * v * dkappa
        if ir >= 0:
            geo[ir] = cant - c_r
            geo[n + ir] = v * (dcant - dc_r)


@njit(cache=True)
def curve_geometry(t: float, v: float, s: SystemArrays) -> np.ndarray:
    """:func:`curve_offsets` of the bundle at time ``t``: ``[q_geo, dq_geo/dt, body_acc]``
    (a new array of length ``3 n_dof``), for the analyses."""
    geo = np.zeros(3 * s.linear.shape[0])
    curve_offsets(t, v, s.wheel_rail[0], s.route, s.bodies, s.body_delay, geo)
    return geo


@njit(cache=True, **NO_REFCOUNT)
def rhs(t: float, x: np.ndarray, v: float, s: SystemArrays, out: np.ndarray) -> None:
    """Time derivative of the state (writes ``out``, allocates nothing).

    Parameters
    ----------
    t : float
        Time (s); the track input and the route depend on it.
    x : numpy.ndarray, shape (n_state,)
        State (:mod:`railhunt.kernel.layout`).
    v : float
        Forward speed (m/s).
    s : SystemArrays
        The model's arrays, the track input and the route.
    out : numpy.ndarray, shape (n_state,)
        Receives dx/dt.
    """
    # Compiled without numba's reference counting (NO_REFCOUNT, layout.py): rhs allocates
    # nothing, and counting the bundle's arrays at every call cost more than the physics
    # (measured per call on straight track: 600 ns counted, 420 ns not).
    lin, bd, dd, dpar = s.linear, s.damper_rows, s.damper_acc, s.damper
    wr, ws, delay, trk, trs = s.wheel_rail, s.wheelsets, s.wheelset_delay, s.track, s.track_samples
    stop_rows, stop_acc, stop, route = s.stop_rows, s.stop_acc, s.stop, s.route
    geo, susp, bodies, body_delay = s.scratch, s.suspension, s.bodies, s.body_delay
    creep = s.creep_table
    nq = lin.shape[0]  # coordinates x[:nq], rates x[nq:2nq], damper forces after
    fz = 2 * nq
    curved = route.shape[0] > 0

    # Suspension: rates, linear springs and dampers with gravity's roll terms.
    # Column by column: each acceleration sums the same products in the same order as a
    # row-by-row dot product (so the same bits), but the inner loop over the rows runs
    # down a column of the Fortran-ordered matrix (Model.system) and vectorises.
    for i in range(nq):
        out[i] = x[nq + i]
        out[nq + i] = 0.0
    for k in range(2 * nq):
        xk = x[k]
        for i in range(nq):
            out[nq + i] += lin[i, k] * xk
    # Yaw dampers (Maxwell elements): the force is a state.
    for d in range(dpar.shape[0]):
        f = x[fz + d]
        rate = 0.0
        for k in range(nq):
            rate += bd[d, k] * x[nq + k]
        v_damp = damper_velocity(f, dpar[d, DamperParam.C_D1], dpar[d, DamperParam.C_D2],
                                 dpar[d, DamperParam.F_U])  # fmt: skip
        out[fz + d] = dpar[d, DamperParam.K_D] * (rate - v_damp)
        for i in range(nq):
            out[nq + i] += dd[i, d] * f
    # Bump stops (in a curve corrected below for the geometric offsets); a stop to the
    # track (a flange) deforms by its wheelset's displacement relative to the rails there.
    n_track_stop = s.stop_wheelset.shape[0]
    for k in range(stop.shape[0]):
        dist = 0.0
        for i in range(nq):
            dist += stop_rows[k, i] * x[i]
        if k < n_track_stop and s.stop_wheelset[k] >= 0:
            dist -= alignment(v * t - delay[s.stop_wheelset[k]], trk, trs)[0]
        f = bump_stop_force(dist, stop[k, StopParam.GAP], stop[k, StopParam.K1],
                            stop[k, StopParam.K3])  # fmt: skip
        if f != 0.0:
            for i in range(nq):
                out[nq + i] += stop_acc[i, k] * f

    # Wheel/rail forces: wheelset j meets the track at v t - delay_j (the track input there,
    # and in a curve its wheel loads and the track's yaw rate).
    work = s.contact_work
    staged = work.shape[1] > 0
    n_staged = 0
    for j in range(ws.shape[0]):
        row = wr[j]  # this wheelset's own parameters (mass, load, radius, contact, creep)
        n_load = row[WR.N]
        iy = ws[j, 0]
        ip = ws[j, 1]
        pos = v * t - delay[j]
        yr, slope = alignment(pos, trk, trs)
        if curved:
            q_l, q_r, track_rate = wheel_loads(pos, v, row, route)
        else:
            q_l, q_r, track_rate = n_load, n_load, 0.0
        if staged and uses_staged_table(row, creep):
            # Per-point contact with the tabulated law: its creep forces are computed below
            # for all such wheelsets at once (the same bits as wheelset_contact's).
            stage_point_contact(x[iy] - yr, x[nq + iy], x[ip], x[ip] - slope,
                                x[nq + ip] + track_rate, v, row, q_l, q_r, work, n_staged)
            work[StageSlot.WHEELSET, n_staged] = j
            n_staged += 2
            continue
        fy, mz, _, _ = wheelset_contact(x[iy] - yr, x[nq + iy], x[ip], x[ip] - slope,
                                        x[nq + ip], x[nq + ip] + track_rate, v, row, q_l, q_r,
                                        creep)
        out[nq + iy] += fy * row[WR.INV_MW]
        out[nq + ip] += mz * row[WR.INV_JW]
    if n_staged > 0:
        table_creep_batch(work, n_staged, creep)
        for k in range(0, n_staged, 2):
            j = int(work[StageSlot.WHEELSET, k])
            row = wr[j]
            fy, mz, _, _, _, _ = unstage_point_contact(row, work, k)
            out[nq + ws[j, 0]] += fy * row[WR.INV_MW]
            out[nq + ws[j, 1]] += mz * row[WR.INV_JW]

    if not curved:
        return
    # A curve: the suspension's forces from the geometric offsets of the bodies' track
    # frames, the unbalanced lateral acceleration and the frames' angular acceleration
    # (curve_offsets), the yaw dampers' stroke rate from the frames' relative motion (the
    # Maxwell element's force rate is linear in it), the bump stops at B_s (q + q_geo).
    curve_offsets(t, v, wr[0], route, bodies, body_delay, geo)
    for i in range(nq):
        acc = geo[fz + i]
        for k in range(2 * nq):
            acc += susp[i, k] * geo[k]
        out[nq + i] += acc
    for d in range(dpar.shape[0]):
        rate = 0.0
        for k in range(nq):
            rate += bd[d, k] * geo[nq + k]
        out[fz + d] += dpar[d, DamperParam.K_D] * rate
    for k in range(stop.shape[0]):
        if k < n_track_stop and s.stop_wheelset[k] >= 0:
            continue  # a flange: the wheelset's coordinates already follow its own rails
        dist = 0.0
        shift = 0.0
        for i in range(nq):
            dist += stop_rows[k, i] * x[i]
            shift += stop_rows[k, i] * geo[i]
        gap, k1, k3 = stop[k, StopParam.GAP], stop[k, StopParam.K1], stop[k, StopParam.K3]
        df = bump_stop_force(dist + shift, gap, k1, k3) - bump_stop_force(dist, gap, k1, k3)
        if df != 0.0:
            for i in range(nq):
                out[nq + i] += stop_acc[i, k] * df


@njit(cache=True)
def jacobian(x: np.ndarray, v: float, s: SystemArrays, t: float) -> np.ndarray:
    """Jacobian d(rhs)/dx at time ``t`` by central differences of :func:`rhs`.

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
        rhs(t, xp, v, s, fp)
        xp[k] = x[k] - h
        rhs(t, xp, v, s, fm)
        xp[k] = x[k]
        for i in range(n):
            jac[i, k] = (fp[i] - fm[i]) / (2.0 * h)
    return jac


@njit(cache=True)
def derived(t: np.ndarray, x: np.ndarray, v: float, s: SystemArrays,
            acc_index: np.ndarray) -> np.ndarray:  # fmt: skip
    """Wheel/rail forces and accelerations along a run (see :mod:`railhunt.channels`).

    Returns an array with one row per time and, for ``n`` wheelsets, the columns: ``ΣY``
    of each wheelset (``-F_y``: the lateral force it puts on the track, N, + left, its
    flanges' forces included: :func:`track_stop_force`); the guiding force ``Y`` of each
    left wheel, then of each right wheel (the force of the wheel on its rail, N, positive
    outward from the track centre; a flange's force on the wheel whose flange touches its
    rail: the left one when the wheelset presses toward +y); the wheel loads ``Q``
    of the left wheels, then of the right wheels (N); then ``d(rate)/dt`` of each
    coordinate in ``acc_index`` (m/s^2 or rad/s^2). With ``acc_index`` empty the whole
    right-hand side is not evaluated (the wheel/rail forces alone: half the cost).
    """
    nq = s.linear.shape[0]
    nw = s.wheelsets.shape[0]
    n = t.shape[0]
    res = np.empty((n, 5 * nw + acc_index.shape[0]))
    out = np.empty(x.shape[1])
    for i in range(n):
        xi = x[i]
        if acc_index.shape[0] > 0:
            rhs(t[i], xi, v, s, out)
        for j in range(nw):
            fy, _, f_l, f_r, q_l, q_r = wheelset_track_forces(j, t[i], xi, v, s)
            res[i, j] = -fy
            res[i, nw + j] = -f_l
            res[i, 2 * nw + j] = f_r
            res[i, 3 * nw + j] = q_l
            res[i, 4 * nw + j] = q_r
        # Flanges (stops to the track): the force of the wheelset on its rails belongs in
        # its guiding forces, on the wheel whose flange is in contact.
        for k in range(s.stop_wheelset.shape[0]):
            j = s.stop_wheelset[k]
            if j < 0:
                continue
            f = track_stop_force(k, t[i], xi, v, s) * s.stop_rows[k, s.wheelsets[j, 0]]
            res[i, j] += f
            if f > 0.0:
                res[i, nw + j] += f
            else:
                res[i, 2 * nw + j] -= f
        for k in range(acc_index.shape[0]):
            res[i, 5 * nw + k] = out[nq + acc_index[k]]
    return res
