"""The tabulated creep law: Kalker's exact rolling-contact theory, interpolated smoothly.

Inputs are the creepages normalised by Kalker's linear theory and the friction limit,

    u_x = f11 xi / (mu N),   u_y = f22 eta / (mu N),   u_s = f23 phi / (mu N),

(``f_ij`` the contact's own coefficients), and the ellipse's ``a/b``. Outputs are the
normalised creep forces ``t_x = F_x / (mu N)``, ``t_y = F_y / (mu N)`` and spin moment
``t_m = M_z / (mu N c)``, ``c = sqrt(a b)``, written as an analytic saturation plus a
tabulated correction:

    t = L A(rho) + q(rho) D(s_x, s_y, s_s; a/b),
    L = (-u_x, -(u_y + u_s), m_y u_y - m_s u_s),
    rho^2 = u_x^2 + u_y^2 + u_s^2 + L_m^2,   A = 1 / sqrt(1 + rho^2),   q = rho^2 A^2,

with ``m_y = f23 / (f22 c)``, ``m_s = f33 / (f23 c)`` (Kalker's moment coefficients). ``L`` is
Kalker's linear law, so the linear limit is Kalker's exactly (``q = O(rho^2)``), whatever the
table holds; every component of ``L A`` stays below 1 in magnitude (the moment's too:
``rho`` includes it) and the correction ``D`` is bounded everywhere, the full-slip limit
included. ``D`` is tabulated on a uniform grid of ``s = sign(u) (1 - (1 + |u|)^(-p))``
(the whole real line in ``[-1, 1]``, decades spread evenly) for ``u_x``, the lateral
linear force ``u_y + u_s`` (``p = 1/2``: where lateral creepage and spin cancel, the
lateral force changes sign along a plane of these coordinates, not across a diagonal of
the grid) and the spin's full linear strength ``w = u_s sqrt(1 + m_s^2)`` (force and
moment; ``p = 1/4``: the spin acts over four decades, its moment saturating long before
its lateral force on a wide ellipse), and interpolated by tensor-product quadratic
B-splines through the nodes (continuous first derivatives in all three creepages: Newton,
continuation and the Jacobians get smooth forces). In ``a/b`` the slices are uniform in
``ln(a/b)``; a fractional slice index blends two slices linearly. The per-point model
gives each point of its contact table the slice nearest its ellipse and interpolates
that index in ``y`` (the ellipse varies with the lateral position only): between two
points of one slice one stencil is read, between points of two slices they are blended
linearly in ``y`` like every other per-point quantity. Symmetry
``F_x(-xi) = -F_x(xi)``, ``F_y, M_z`` even in ``xi``, holds exactly: the table keeps
``u_x >= 0`` and ghost nodes of the right parity. Finally ``|(t_x, t_y)|`` is kept below 1
smoothly (above 0.98 it is compressed by a tanh; the exact theory gives at most 1).

Layout of the flat array (:class:`TableHeader`): a header, then the B-spline control
points ``(n_ab, n_x + 2, n_y + 2, n_s + 2, 3)`` in C order (one ghost node at each end of
each creepage axis; the outputs ``D_x, D_y, D_m`` last). Built by
:mod:`railhunt.contact.creep_table` (``python -m railhunt.data.creep.build_creep_table``),
shipped in the package.
"""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
from numba import njit

__all__ = ["TableHeader", "table_creep"]


class TableHeader(IntEnum):
    """Header slots of a creep table (the control points follow at ``DATA``)."""

    N_AB = 0  # slices in ln(a/b)
    N_X = 1  # nodes of s_x on [0, 1]
    N_Y = 2  # nodes of s_y on [-1, 1]
    N_S = 3  # nodes of s_s on [-1, 1]
    LOG_AB0 = 4  # ln(a/b) of the first slice
    DLOG_AB = 5  # step of ln(a/b)
    POISSON = 6  # Poisson's ratio the table was built for
    DATA = 8  # first control point


#: |(t_x, t_y)| above this is compressed smoothly toward (never to) 1.
_CAP = 0.98


@njit(cache=True, inline="always")
def _weights(p: float, n: int) -> tuple[int, float, float, float]:
    """Quadratic B-spline stencil at grid coordinate ``p`` in ``[0, n - 1]``: the first of
    its three control points (padded index) and their weights."""
    if p < 0.0:
        p = 0.0
    elif p > n - 1.0:
        p = n - 1.0
    i = int(p + 0.5)
    t = p - i
    w0 = 0.5 * (0.5 - t) * (0.5 - t)
    w2 = 0.5 * (0.5 + t) * (0.5 + t)
    return i, w0, 1.0 - w0 - w2, w2


@njit(cache=True, inline="always")
def _z3(table: np.ndarray, k: int, w: float, z0: float, z1: float,
        z2: float) -> tuple[float, float, float]:  # fmt: skip
    """``w`` times the three outputs summed over three consecutive spin nodes from ``k``."""
    a0 = w * z0
    a1 = w * z1
    a2 = w * z2
    return (a0 * table[k] + a1 * table[k + 3] + a2 * table[k + 6],
            a0 * table[k + 1] + a1 * table[k + 4] + a2 * table[k + 7],
            a0 * table[k + 2] + a1 * table[k + 5] + a2 * table[k + 8])


@njit(cache=True, inline="always")
def _slice(table: np.ndarray, k: int, sx_stride: int, sy_stride: int, x0: float, x1: float,
           x2: float, y0: float, y1: float, y2: float, z0: float, z1: float,
           z2: float) -> tuple[float, float, float]:  # fmt: skip
    """The 27-node stencil of one ``a/b`` slice from its first node ``k``."""
    a0, b0, c0 = _z3(table, k, x0 * y0, z0, z1, z2)
    a1, b1, c1 = _z3(table, k + sy_stride, x0 * y1, z0, z1, z2)
    a2, b2, c2 = _z3(table, k + 2 * sy_stride, x0 * y2, z0, z1, z2)
    k += sx_stride
    a3, b3, c3 = _z3(table, k, x1 * y0, z0, z1, z2)
    a4, b4, c4 = _z3(table, k + sy_stride, x1 * y1, z0, z1, z2)
    a5, b5, c5 = _z3(table, k + 2 * sy_stride, x1 * y2, z0, z1, z2)
    k += sx_stride
    a6, b6, c6 = _z3(table, k, x2 * y0, z0, z1, z2)
    a7, b7, c7 = _z3(table, k + sy_stride, x2 * y1, z0, z1, z2)
    a8, b8, c8 = _z3(table, k + 2 * sy_stride, x2 * y2, z0, z1, z2)
    return (((a0 + a1) + (a2 + a3)) + ((a4 + a5) + (a6 + a7)) + a8,
            ((b0 + b1) + (b2 + b3)) + ((b4 + b5) + (b6 + b7)) + b8,
            ((c0 + c1) + (c2 + c3)) + ((c4 + c5) + (c6 + c7)) + c8)


@njit(cache=True)
def table_correction(sx: float, sy: float, ss: float, ab_index: float,
                     table: np.ndarray) -> tuple[float, float, float]:  # fmt: skip
    """The tabulated correction ``(D_x, D_y, D_m)`` at ``s_x >= 0``, ``s_y``, ``s_s`` and
    the fractional ``a/b`` slice ``ab_index``."""
    n_ab = int(table[TableHeader.N_AB])
    nx = int(table[TableHeader.N_X])
    ny = int(table[TableHeader.N_Y])
    ns = int(table[TableHeader.N_S])
    ix, x0, x1, x2 = _weights(sx * (nx - 1), nx)
    iy, y0, y1, y2 = _weights((sy + 1.0) * 0.5 * (ny - 1), ny)
    iz, z0, z1, z2 = _weights((ss + 1.0) * 0.5 * (ns - 1), ns)
    if n_ab == 1 or ab_index <= 0.0:
        ia, wa = 0, 0.0
    elif ab_index >= n_ab - 1.0:
        ia, wa = n_ab - 2, 1.0
    else:
        ia = int(ab_index)
        wa = ab_index - ia
    sy_stride = (ns + 2) * 3
    sx_stride = (ny + 2) * sy_stride
    sa_stride = (nx + 2) * sx_stride
    k = TableHeader.DATA + ia * sa_stride + ix * sx_stride + iy * sy_stride + iz * 3
    dx, dy, dm = 0.0, 0.0, 0.0
    if wa < 1.0:
        dx, dy, dm = _slice(table, k, sx_stride, sy_stride, (1.0 - wa) * x0,
                            (1.0 - wa) * x1, (1.0 - wa) * x2, y0, y1, y2, z0, z1, z2)
    if wa > 0.0:
        a, b, c = _slice(table, k + sa_stride, sx_stride, sy_stride, wa * x0, wa * x1,
                         wa * x2, y0, y1, y2, z0, z1, z2)
        dx += a
        dy += b
        dm += c
    return dx, dy, dm


@njit(cache=True)
def table_creep(ux: float, uy: float, us: float, my: float, ms: float, ab_index: float,
                table: np.ndarray, ks: float = -1.0) -> tuple[float, float, float]:  # fmt: skip
    """Normalised creep forces and spin moment of one contact from the creep table.

    Parameters
    ----------
    ux, uy, us : float
        Normalised creepages ``f11 xi / (mu N)``, ``f22 eta / (mu N)``,
        ``f23 phi / (mu N)``.
    my, ms : float
        Moment coefficients ``f23 / (f22 c)`` and ``f33 / (f23 c)``.
    ab_index : float
        ``a/b`` as a fractional slice index of the table.
    table : numpy.ndarray
        The creep table (module docstring).
    ks : float, optional
        ``sqrt(1 + m_s^2)`` if known (default: computed).

    Returns
    -------
    tuple of float
        ``(F_x / (mu N), F_y / (mu N), M_z / (mu N c))``, signs of Kalker's linear law.
    """
    sign = 1.0
    if ux < 0.0:
        ux = -ux
        sign = -1.0
    lm = my * uy - ms * us
    rho2 = ux * ux + uy * uy + us * us + lm * lm
    inv = 1.0 / math.sqrt(1.0 + rho2)
    tx = -ux * inv
    ty = -(uy + us) * inv
    tm = lm * inv
    if rho2 > 0.0:
        q = rho2 * inv * inv
        w = us * (math.sqrt(1.0 + ms * ms) if ks < 0.0 else ks)
        sx = 1.0 - 1.0 / math.sqrt(1.0 + ux)
        uf = uy + us
        sy = 1.0 - 1.0 / math.sqrt(1.0 + abs(uf))
        if uf < 0.0:
            sy = -sy
        ss = 1.0 - 1.0 / math.sqrt(math.sqrt(1.0 + abs(w)))
        if w < 0.0:
            ss = -ss
        dx, dy, dm = table_correction(sx, sy, ss, ab_index, table)
        tx += q * dx
        ty += q * dy
        tm += q * dm
    r2 = tx * tx + ty * ty
    if r2 > _CAP * _CAP:
        r = math.sqrt(r2)
        scale = (_CAP + (1.0 - _CAP) * math.tanh((r - _CAP) / (1.0 - _CAP))) / r
        tx *= scale
        ty *= scale
    return sign * tx, ty, tm
