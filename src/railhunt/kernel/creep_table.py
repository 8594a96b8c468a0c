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

Cost: below ``rho = 0.005`` the table is not read (its correction ``q D`` is below 2e-5
of mu N there, ``|D| <= 0.5`` near the origin: 0.3 % of the force), between 0.005 and
0.01 its weight rises smoothly; the 27 control points of a stencil are read as 4-wide
vectors (:func:`slice_stencil`), and the four reciprocal square roots of the coordinates
come from one division.

Layout of the flat array (:class:`TableHeader`): a header, then the B-spline control
points ``(n_ab, n_x + 2, n_y + 2, n_s + 2, LANES)`` in C order (one ghost node at each end
of each creepage axis; the outputs ``D_x, D_y, D_m`` and a zero last: :data:`LANES`).
Built by :mod:`railhunt.contact.creep_table` (``python -m railhunt.data.creep.build_creep_table``),
shipped in the package.
"""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic, overload

ir = cgutils.ir  # numba's LLVM IR builder (llvmlite.ir), for the vector stencil

__all__ = ["LANES", "TableHeader", "slice_stencil", "table_correction", "table_creep"]


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
#: Below ``rho = 0.005`` the table is not read (its correction, ``q D = O(rho^2)``, is
#: below 2e-5 of mu N there), from ``rho = 0.01`` it is read in full; in between its
#: weight rises as a cubic smoothstep in ``rho^2`` (continuous first derivatives).
_RHO2_TABLE_FROM = 0.005**2
_RHO2_TABLE_FULL = 0.01**2


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


#: Values per control point: ``D_x, D_y, D_m`` and a zero, so that one control point is one
#: contiguous 4-wide block (the stencil's arithmetic runs on all four at once).
LANES = 4


def slice_stencil(t: np.ndarray, k0: int, sx: int, sy: int, x0: float, x1: float,
                  x2: float, y0: float, y1: float, y2: float, z0: float, z1: float,
                  z2: float) -> tuple[float, float, float]:  # fmt: skip
    """The quadratic B-spline stencil of one ``a/b`` slice: the 27 control points from
    ``t[k0]`` (strides ``sx``, ``sy`` between rows; three contiguous spin nodes of
    :data:`LANES` values in each) weighted by the 1-D weights, ``(D_x, D_y, D_m)``.

    This is the reference (pure Python); compiled code uses :func:`_stencil_vector`, the
    same sums on 4-wide vectors with fused multiply-adds."""
    xw, yw, zw = (x0, x1, x2), (y0, y1, y2), (z0, z1, z2)
    out = [0.0, 0.0, 0.0]
    for i in range(3):
        for j in range(3):
            for k in range(3):
                w = xw[i] * yw[j] * zw[k]
                base = k0 + i * sx + j * sy + LANES * k
                for m in range(3):
                    out[m] += w * t[base + m]
    return out[0], out[1], out[2]


@intrinsic
def _stencil_vector(typingctx, t, k0, sx, sy, x0, x1, x2, y0, y1, y2, z0, z1, z2):
    """:func:`slice_stencil` in LLVM vector code: each control point is one 4-wide load
    (its :data:`LANES` values); a row of three spin nodes is contracted with the spin
    weights, then added with its weight ``x_i y_j`` (fused multiply-adds throughout)."""
    ret = types.UniTuple(types.float64, 3)
    sig = ret(t, k0, sx, sy, x0, x1, x2, y0, y1, y2, z0, z1, z2)

    def codegen(context, builder, signature, args):
        data = context.make_array(signature.args[0])(context, builder, args[0]).data
        dbl, i32, i64 = ir.DoubleType(), ir.IntType(32), ir.IntType(64)
        vty = ir.VectorType(dbl, LANES)
        fma = cgutils.get_or_insert_function(builder.module, ir.FunctionType(vty, [vty] * 3),
                                             "llvm.fma.v4f64")  # fmt: skip
        splat = ir.Constant(ir.VectorType(i32, LANES), [0] * LANES)

        def broadcast(x):
            v = builder.insert_element(ir.Constant(vty, None), x, ir.Constant(i32, 0))
            return builder.shuffle_vector(v, ir.Constant(vty, None), splat)

        k0v, sxv, syv = args[1], args[2], args[3]
        xs, ys, zs = args[4:7], args[7:10], [broadcast(z) for z in args[10:13]]
        parts = []  # one sum per x node (three short dependency chains)
        for i in range(3):
            acc = None
            for j in range(3):
                off = builder.add(k0v, builder.add(builder.mul(sxv, ir.Constant(i64, i)),
                                                   builder.mul(syv, ir.Constant(i64, j))))
                row = None
                for k in range(3):
                    p = builder.gep(data, [builder.add(off, ir.Constant(i64, LANES * k))],
                                    inbounds=True, source_etype=dbl)  # fmt: skip
                    v = builder.load(p, typ=vty, align=8)
                    row = builder.fmul(v, zs[k]) if row is None else builder.call(
                        fma, [v, zs[k], row])
                w = broadcast(builder.fmul(xs[i], ys[j]))
                acc = builder.fmul(row, w) if acc is None else builder.call(fma, [row, w, acc])
            parts.append(acc)
        acc = builder.fadd(builder.fadd(parts[0], parts[1]), parts[2])
        out = [builder.extract_element(acc, ir.Constant(i32, m)) for m in range(3)]
        return context.make_tuple(builder, ret, out)

    return sig, codegen


@overload(slice_stencil, inline="always")
def _slice_stencil_compiled(t, k0, sx, sy, x0, x1, x2, y0, y1, y2, z0, z1, z2):
    def impl(t, k0, sx, sy, x0, x1, x2, y0, y1, y2, z0, z1, z2):  # pragma: no cover
        return _stencil_vector(t, k0, sx, sy, x0, x1, x2, y0, y1, y2, z0, z1, z2)

    return impl


@njit(cache=True, inline="always")
def table_correction(sx: float, sy: float, ss: float, ab_index: float,
                     table: np.ndarray) -> tuple[float, float, float]:  # fmt: skip
    """The tabulated correction ``(D_x, D_y, D_m)`` at ``s_x >= 0``, ``s_y``, ``s_s`` and
    the fractional ``a/b`` slice ``ab_index``: one slice's stencil
    (:func:`slice_stencil`) at an integer index, two blended linearly between."""
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
        ia, wa = n_ab - 1, 0.0
    else:
        ia = int(ab_index)
        wa = ab_index - ia
    sy_stride = (ns + 2) * LANES
    sx_stride = (ny + 2) * sy_stride
    sa_stride = (nx + 2) * sx_stride
    k = TableHeader.DATA + ia * sa_stride + ix * sx_stride + iy * sy_stride + iz * LANES
    d0, d1, d2 = slice_stencil(table, k, sx_stride, sy_stride, x0, x1, x2, y0, y1, y2, z0,
                               z1, z2)  # fmt: skip
    if wa > 0.0:
        e0, e1, e2 = slice_stencil(table, k + sa_stride, sx_stride, sy_stride, x0, x1, x2,
                                   y0, y1, y2, z0, z1, z2)  # fmt: skip
        d0 += wa * (e0 - d0)
        d1 += wa * (e1 - d1)
        d2 += wa * (e2 - d2)
    return d0, d1, d2


@njit(cache=True, inline="always")
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
    if rho2 <= _RHO2_TABLE_FROM:  # Kalker's linear law, saturated: the table is skipped
        inv = 1.0 / math.sqrt(1.0 + rho2)
        tx = -ux * inv
        ty = -(uy + us) * inv
        tm = lm * inv
    else:
        w = us * (math.sqrt(1.0 + ms * ms) if ks < 0.0 else ks)
        uf = uy + us
        # The four reciprocal square roots from one division.
        r0 = math.sqrt(1.0 + rho2)
        r1 = math.sqrt(1.0 + ux)
        r2 = math.sqrt(1.0 + abs(uf))
        r3 = math.sqrt(math.sqrt(1.0 + abs(w)))
        r01 = r0 * r1
        r23 = r2 * r3
        ip = 1.0 / (r01 * r23)
        inv = ip * r1 * r23
        tx = -ux * inv
        ty = -uf * inv
        tm = lm * inv
        sx = 1.0 - ip * r0 * r23 if ux > 0.0 else 0.0  # exactly 0 at xi = 0: F_x = 0
        sy = 1.0 - ip * r01 * r3
        if uf < 0.0:
            sy = -sy
        ss = 1.0 - ip * r01 * r2
        if w < 0.0:
            ss = -ss
        q = rho2 * inv * inv
        if rho2 < _RHO2_TABLE_FULL:  # C1 blend from the linear law into the table's
            h = (rho2 - _RHO2_TABLE_FROM) / (_RHO2_TABLE_FULL - _RHO2_TABLE_FROM)
            q *= h * h * (3.0 - 2.0 * h)
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
