"""Two-point contact: up to two patches per wheel, each with its own normal force,
ellipse and creep forces, from a table over the lateral displacement and the yaw.

A wheel/rail vector whose block after the contact table starts with
:data:`~railhunt.kernel.layout.TWO_POINT` (:class:`~railhunt.kernel.layout.TwoPointHeader`)
holds, on a uniform grid of ``(y, psi)``, two *slots* per wheel
(:class:`~railhunt.kernel.layout.PatchColumn`): the share ``W`` of the wheel's vertical
load each patch carries, its rolling radius, contact angle, lead ahead of the axle, axle
coordinate and Hertz/Kalker columns (:mod:`railhunt.contact.patch_table` builds them).
They are interpolated by Catmull-Rom cubics in ``y`` (continuous first derivatives: the
Jacobians and the continuation see smooth forces) and linearly in ``psi``, held at the
grid's edges beyond it; the share ``W`` and the ellipse's and coefficients' columns by the
same cubic Hermite with its slopes limited so that it stays >= 0 and sets in from 0 with
zero slope (a patch's load and coefficients grow from nothing smoothly). A slot whose
``W`` is 0 there is skipped.

**Creepages** (each patch's rigid-body slip, :meth:`railhunt.WheelsetContact.creepages`
with the roll's tilt of the axle neglected, as in Eq. 25): the patch's point relative to
the wheelset centre is ``f = X cos(psi)`` ahead of the axle in the wheel's plane, ``s``
along the axle and ``h = sqrt(r^2 - f^2)`` below it; in the track frame ``d = (f cos psi -
s sin psi, f sin psi + s cos psi, -h)``. With ``Omega = (-omega sin psi, omega cos psi,
psi')`` and the centre's velocity ``(V, y', 0)``, the slip ``v = v_c + Omega x d`` is

    v_x = V - omega h cos(psi) - psi' d_y,   v_y = y' + psi' d_x - omega h sin(psi),
    v_z = -omega f,

and ``xi = v_x / V``, ``eta = (v_y cos d +- v_z sin d) / V`` (+ left), ``phi = (psi' cos d
-+ omega cos(psi) sin d) / V`` (the contact plane's longitudinal axis is the track's ``x``:
the contact locus makes it a tangent). On a flange at 5 mrad ``eta`` is about
``-psi / cos(delta)``, three times Eq. 25's ``-psi cos(delta)``.

**Forces.** Each patch's creep law is the per-point one
(:mod:`railhunt.kernel.point_contact`) at ``N0 = W Q / cos(delta)``; its normal force then
balances its share of the vertical load, ``N cos d +- T sin d = W Q``
(:func:`railhunt.kernel.point_contact.normal_force_ratio`). The heuristic law's one factor
per wheelset comes from the mean of the wheels' ``beta``, each wheel's the load-weighted
mean of its patches'. Into track coordinates: ``F_y = T cos d -+ N sin d`` and the yaw
moment ``d_x F_y - d_y F_x + M_spin cos d`` of every patch at its own point (the normal
forces' moment about the leading contact points replaces Eq. 30's gravitational yaw
moment ``a sin(psi) (N_L sin d_L + N_R sin d_R)``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from railhunt.kernel.creep import CreepLaw, heuristic_saturation, polach_saturation
from railhunt.kernel.creep_table import table_creep
from railhunt.kernel.layout import (
    N_PATCH_COLUMNS,
    TWO_POINT,
    WR,
    PatchColumn,
    TwoPointHeader,
)
from railhunt.kernel.point_contact import mechanics_marker, normal_force_ratio

__all__ = ["two_point_wheelset_contact", "uses_two_point"]

_NODE = 4 * N_PATCH_COLUMNS  # values per grid node: two wheels, two slots each


@njit(cache=True)
def uses_two_point(wr: np.ndarray) -> bool:
    """Whether the wheel/rail vector carries the two-point contact table."""
    return mechanics_marker(wr) == TWO_POINT


@njit(cache=True)
def _stencil(y: float, y0: float, dy: float,
             n: int) -> tuple[int, int, int, int, float, float, float, float, float]:
    """Catmull-Rom nodes and weights at ``y`` on ``n`` uniform nodes (clamped at the ends,
    constant beyond them), and the fraction ``t`` of the cell."""
    s = (y - y0) / dy
    if s <= 0.0:
        i, t = 0, 0.0
    elif s >= n - 1:
        i, t = n - 2, 1.0
    else:
        i = int(s)
        t = s - i
    i0 = i - 1 if i > 0 else 0
    i3 = i + 2 if i + 2 < n else n - 1
    t2 = t * t
    t3 = t2 * t
    return (i0, i, i + 1, i3, 0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2), t)  # fmt: skip


@njit(cache=True)
def _positive(v0: float, v1: float, v2: float, v3: float, h: tuple[float, float, float,
                                                                  float]) -> float:
    """A share between nodes 1 and 2: a cubic Hermite whose node slopes are the central
    differences limited to ``3 v`` (Fritsch and Carlson's bound), so that it never falls
    below 0 and meets 0 flat where a patch sets in (continuous slope everywhere)."""
    m1 = min(max(0.5 * (v2 - v0), -3.0 * v1), 3.0 * v1)
    m2 = min(max(0.5 * (v3 - v1), -3.0 * v2), 3.0 * v2)
    return h[0] * v1 + h[1] * m1 + h[2] * v2 + h[3] * m2


@njit(cache=True)
def _hermite(t: float) -> tuple[float, float, float, float]:
    """The cubic Hermite basis ``(h00, h10, h01, h11)`` at ``t`` in ``[0, 1]``."""
    t2 = t * t
    t3 = t2 * t
    return 2.0 * t3 - 3.0 * t2 + 1.0, t3 - 2.0 * t2 + t, 3.0 * t2 - 2.0 * t3, t3 - t2


@njit(cache=True)
def _share(wr: np.ndarray, k: int, a0: int, a1: int, a2: int, a3: int, b0: int, b1: int,
           t: tuple[float, float, float, float], p0: float, p1: float) -> float:  # fmt: skip
    """A column that is never negative (offset ``k``: ``W``, ``C1``, ``K11`` ... ``K33``)
    interpolated: :func:`_positive` in ``y``, linear in ``psi``."""
    return (p0 * _positive(wr[k + b0 + a0], wr[k + b0 + a1], wr[k + b0 + a2], wr[k + b0 + a3],
                           t)
            + p1 * _positive(wr[k + b1 + a0], wr[k + b1 + a1], wr[k + b1 + a2],
                             wr[k + b1 + a3], t))  # fmt: skip


@njit(cache=True)
def _value(wr: np.ndarray, k: int, a0: int, a1: int, a2: int, a3: int, b0: int, b1: int,
           w0: float, w1: float, w2: float, w3: float, p0: float, p1: float) -> float:  # fmt: skip
    """One column interpolated: ``k`` its offset in a node, ``a*`` the lateral nodes' and
    ``b*`` the yaw nodes' offsets, ``w*`` and ``p*`` their weights."""
    return (p0 * (w0 * wr[k + b0 + a0] + w1 * wr[k + b0 + a1] + w2 * wr[k + b0 + a2]
                  + w3 * wr[k + b0 + a3])
            + p1 * (w0 * wr[k + b1 + a0] + w1 * wr[k + b1 + a1] + w2 * wr[k + b1 + a2]
                    + w3 * wr[k + b1 + a3]))  # fmt: skip


@njit(cache=True)
def _patch(wr: np.ndarray, k: int, a0: int, a1: int, a2: int, a3: int, b0: int, b1: int,
           w0: float, w1: float, w2: float, w3: float, t: tuple[float, float, float, float],
           p0: float, p1: float, side: float, cpsi: float, spsi: float, dy: float,
           yaw_rate: float, v: float, omega: float, q: float, qth: float, mu: float, law: int,
           table: np.ndarray) -> tuple[float, float, float, float, float, float, float,
                                       float, float, float]:  # fmt: skip
    """One patch's unsaturated forces and saturation measures.

    Returns ``(W, F_x, F_y, M_z, F_y of the creepages alone, N0, cos(delta), sin(delta),
    d_x, d_y)``; for
    the exact-table law the forces are the table's (saturated), ``F_y`` of the creepages
    alone then 0. ``W = 0``: no patch, every other value 0.
    """
    big_w = _share(wr, k + PatchColumn.W, a0, a1, a2, a3, b0, b1, t, p0, p1)
    if big_w <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0
    r = _value(wr, k + PatchColumn.R, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, p0, p1)
    d = _value(wr, k + PatchColumn.D, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, p0, p1)
    lead = _value(wr, k + PatchColumn.X, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, p0, p1)
    s = _value(wr, k + PatchColumn.S, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, p0, p1)
    k11 = _share(wr, k + PatchColumn.K11, a0, a1, a2, a3, b0, b1, t, p0, p1)
    k22 = _share(wr, k + PatchColumn.K22, a0, a1, a2, a3, b0, b1, t, p0, p1)
    k23 = _share(wr, k + PatchColumn.K23, a0, a1, a2, a3, b0, b1, t, p0, p1)
    k33 = _share(wr, k + PatchColumn.K33, a0, a1, a2, a3, b0, b1, t, p0, p1)
    cd, sd = math.cos(d), math.sin(d)
    # The patch's point and its slip (module docstring).
    f = lead * cpsi
    h = math.sqrt(r * r - f * f)
    d_x = f * cpsi - s * spsi
    d_y = f * spsi + s * cpsi
    inv_v = 1.0 / v
    xi = (v - omega * h * cpsi - yaw_rate * d_y) * inv_v
    eta = ((dy + yaw_rate * d_x - omega * h * spsi) * cd - side * omega * f * sd) * inv_v
    phi = (yaw_rate * cd - side * omega * cpsi * sd) * inv_v
    q23 = qth * qth
    f11 = k11 * q23
    f22 = k22 * q23
    f23 = k23 * q
    f33 = k33 * q * qth
    n0 = big_w * q / cd
    if law == CreepLaw.EXACT_TABLE and table.shape[0] > 0:
        c = _share(wr, k + PatchColumn.C1, a0, a1, a2, a3, b0, b1, t, p0, p1) * qth
        m = mu * n0
        inv = 1.0 / m
        ab = _value(wr, k + PatchColumn.AB, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, p0, p1)
        tx, ty, tm = table_creep(f11 * xi * inv, f22 * eta * inv, f23 * phi * inv,
                                 f23 / (f22 * c), f33 / (f23 * c), ab, table)  # fmt: skip
        return big_w, m * tx, m * ty, m * c * tm, 0.0, n0, cd, sd, d_x, d_y
    fx = -f11 * xi
    cy = -f22 * eta
    return big_w, fx, cy - f23 * phi, f23 * eta - f33 * phi, cy, n0, cd, sd, d_x, d_y


@njit(cache=True)
def _factor(law: int, mu: float, n0: float, fx: float, fy: float, cy: float) -> float:
    """Saturation factor of one patch (per-patch laws), or its ``beta`` (heuristic)."""
    if n0 <= 0.0 or law == CreepLaw.LINEAR or law == CreepLaw.EXACT_TABLE:
        return 1.0
    if law == CreepLaw.VERMEULEN_JOHNSON:
        return heuristic_saturation(math.sqrt(fx * fx + cy * cy) / (mu * n0))
    beta = math.sqrt(fx * fx + fy * fy) / (mu * n0)
    if law == CreepLaw.HEURISTIC:
        return beta
    if law == CreepLaw.POLACH:
        return polach_saturation(beta)
    return heuristic_saturation(beta)


@njit(cache=True)
def two_point_wheelset_contact(
    y_rel: float, dy: float, psi: float, yaw_rate: float, v: float, wr: np.ndarray,
    q_left: float, q_right: float, table: np.ndarray,
) -> tuple[float, float, float, float]:  # fmt: skip
    """Forces of the rails on one wheelset with two-point contact.

    Parameters as :func:`railhunt.kernel.wheelset.wheelset_contact` (``psi`` the yaw
    relative to the track, which also reads the table).

    Returns
    -------
    tuple of float
        ``(F_y, M_z, F_left, F_right)``: lateral force (N) and yaw moment (N*m) on the
        wheelset, and the lateral force on each wheel (N, + left).
    """
    p = WR.TABLE + 3 + 4 * int(wr[WR.TABLE])
    n_y = int(wr[p + TwoPointHeader.N_Y])
    n_p = int(wr[p + TwoPointHeader.N_PSI])
    i0, i1, i2, i3, w0, w1, w2, w3, t_y = _stencil(y_rel, wr[p + TwoPointHeader.Y0],
                                              wr[p + TwoPointHeader.DY], n_y)  # fmt: skip
    s = (psi - wr[p + TwoPointHeader.PSI0]) / wr[p + TwoPointHeader.DPSI]
    if s <= 0.0:
        j, t = 0, 0.0
    elif s >= n_p - 1:
        j, t = n_p - 2, 1.0
    else:
        j = int(s)
        t = s - j
    b0 = j * n_y * _NODE
    b1 = b0 + n_y * _NODE
    a0, a1, a2, a3 = i0 * _NODE, i1 * _NODE, i2 * _NODE, i3 * _NODE
    p0, p1 = 1.0 - t, t
    ty = _hermite(t_y)
    base = p + TwoPointHeader.DATA
    cpsi, spsi = math.cos(psi), math.sin(psi)
    omega = v / wr[WR.R0]
    mu = wr[WR.MU]
    law = int(wr[WR.CREEP_LAW])
    n_load = wr[WR.N]
    qth0 = wr[p + TwoPointHeader.QTH]
    qth_l = qth0 if q_left == n_load else np.cbrt(q_left)
    qth_r = qth0 if q_right == n_load else np.cbrt(q_right)
    nc = N_PATCH_COLUMNS
    wl0, fxl0, fyl0, mzl0, cyl0, nl0, cl0, sl0, xl0, yl0 = _patch(
        wr, base, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, ty, p0, p1, 1.0, cpsi, spsi, dy,
        yaw_rate, v, omega, q_left, qth_l, mu, law, table)
    wl1, fxl1, fyl1, mzl1, cyl1, nl1, cl1, sl1, xl1, yl1 = _patch(
        wr, base + nc, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, ty, p0, p1, 1.0, cpsi, spsi, dy,
        yaw_rate, v, omega, q_left, qth_l, mu, law, table)
    wr0, fxr0, fyr0, mzr0, cyr0, nr0, cr0, sr0, xr0, yr0 = _patch(
        wr, base + 2 * nc, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, ty, p0, p1, -1.0, cpsi, spsi,
        dy, yaw_rate, v, omega, q_right, qth_r, mu, law, table)
    wr1, fxr1, fyr1, mzr1, cyr1, nr1, cr1, sr1, xr1, yr1 = _patch(
        wr, base + 3 * nc, a0, a1, a2, a3, b0, b1, w0, w1, w2, w3, ty, p0, p1, -1.0, cpsi, spsi,
        dy, yaw_rate, v, omega, q_right, qth_r, mu, law, table)
    gl0 = _factor(law, mu, nl0, fxl0, fyl0, cyl0)
    gl1 = _factor(law, mu, nl1, fxl1, fyl1, cyl1)
    gr0 = _factor(law, mu, nr0, fxr0, fyr0, cyr0)
    gr1 = _factor(law, mu, nr1, fxr1, fyr1, cyr1)
    if law == CreepLaw.HEURISTIC:
        beta = 0.5 * ((wl0 * gl0 + wl1 * gl1) / max(wl0 + wl1, 1e-12)
                      + (wr0 * gr0 + wr1 * gr1) / max(wr0 + wr1, 1e-12))  # fmt: skip
        gl0 = gl1 = gr0 = gr1 = heuristic_saturation(beta)
    fy_l = 0.0
    fy_r = 0.0
    m_z = 0.0
    for w_, fx, fy, mz, n0, cd, sd, d_x, d_y, g, side in (
            (wl0, fxl0, fyl0, mzl0, nl0, cl0, sl0, xl0, yl0, gl0, 1.0),
            (wl1, fxl1, fyl1, mzl1, nl1, cl1, sl1, xl1, yl1, gl1, 1.0),
            (wr0, fxr0, fyr0, mzr0, nr0, cr0, sr0, xr0, yr0, gr0, -1.0),
            (wr1, fxr1, fyr1, mzr1, nr1, cr1, sr1, xr1, yr1, gr1, -1.0)):  # fmt: skip
        if w_ <= 0.0:
            continue
        fx *= g
        fy *= g
        # the normal force that balances the patch's share of the vertical load
        ratio = normal_force_ratio(cd, sd, fy / n0, side)
        fx *= ratio
        fy *= ratio
        mz *= ratio
        lateral = fy * cd - side * ratio * n0 * sd
        if side > 0.0:
            fy_l += lateral
        else:
            fy_r += lateral
        m_z += d_x * lateral - d_y * fx + mz * cd
    return fy_l + fy_r, m_z, fy_l, fy_r
