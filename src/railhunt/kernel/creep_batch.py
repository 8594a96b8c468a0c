"""The tabulated creep law for many contacts at once, with the same bits as one by one.

:func:`railhunt.kernel.creep_table.table_creep` evaluates one contact: a chain of square
roots, a division, the stencil's weights, the stencil and the cap, each step waiting for
the one before. In a right-hand side the contacts of all wheelsets are independent, so
:func:`table_creep_batch` runs each step for all of them before the next: the arithmetic
before the stencil is written as loops over the contacts without branches (the compiler
turns them into vector instructions: one vector square root serves four or eight
contacts), then the stencils are read one contact after the other (independent loads the
processor overlaps), then the cap. Every operation is the one ``table_creep`` performs, in
the same order, on the same values (vector square roots and divisions are correctly rounded
like scalar ones; selects replace branches), so a contact gets the same bits either way
(tests/test_creep_batch.py).

The work array has one row per :class:`BatchSlot` and one column per contact: the inputs
are each contact's linear-theory coefficients, friction limit, creepages and ``a/b``
index, the outputs its creep forces and spin moment in N and N*m.
"""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
from numba import njit

from railhunt.kernel.creep_table import (
    _CAP,
    _RHO2_TABLE_FROM,
    _RHO2_TABLE_FULL,
    LANES,
    TableHeader,
    slice_stencil,
)

__all__ = ["BatchSlot", "N_BATCH_SLOTS", "table_creep_batch"]


class BatchSlot(IntEnum):
    """Rows of the work array of :func:`table_creep_batch` (columns: contacts)."""

    # Inputs.
    F11 = 0  # Kalker's f11 = G c^2 C11 (N)
    F22 = 1  # f22 (N)
    F23 = 2  # f23 (N*m)
    F33 = 3  # f33 (N*m^2)
    C = 4  # sqrt(a b) (m)
    MU_N = 5  # friction limit mu N (N)
    XI = 6  # longitudinal creepage (-)
    ETA = 7  # lateral creepage (-)
    PHI = 8  # spin (1/m)
    AB = 9  # a/b as a fractional slice index of the table
    # Outputs.
    FX = 10  # longitudinal creep force (N)
    FY = 11  # lateral creep force (N)
    MZ = 12  # spin moment (N*m)
    # Intermediate values.
    TX = 13  # normalised forces before the correction
    TY = 14
    TM = 15
    Q = 16  # the correction's weight; -1: Kalker's saturated linear law, table not read
    SIGN = 17  # sign of xi
    INDEX = 18  # first control point of the stencil
    WA = 19  # weight of the next a/b slice
    X0 = 20
    X1 = 21
    X2 = 22
    Y0 = 23
    Y1 = 24
    Y2 = 25
    Z0 = 26
    Z1 = 27
    Z2 = 28


#: Rows of the work array.
N_BATCH_SLOTS = len(BatchSlot)


@njit(cache=True, inline="always", error_model="numpy")
def _weights(p: float, n: int) -> tuple[int, float, float, float]:
    """:func:`railhunt.kernel.creep_table._weights` with selects for its branches."""
    p = 0.0 if p < 0.0 else (n - 1.0 if p > n - 1.0 else p)
    i = int(p + 0.5)
    t = p - i
    w0 = 0.5 * (0.5 - t) * (0.5 - t)
    w2 = 0.5 * (0.5 + t) * (0.5 + t)
    return i, w0, 1.0 - w0 - w2, w2


@njit(cache=True, error_model="numpy")
def _saturate(w: np.ndarray, n: int) -> None:
    """``table_creep`` up to the stencil's coordinates, branch-free (module docstring),
    from the creepages normalised as its callers do."""
    for k in range(n):
        inv = 1.0 / w[BatchSlot.MU_N, k]
        f22 = w[BatchSlot.F22, k]
        f23 = w[BatchSlot.F23, k]
        c = w[BatchSlot.C, k]
        ux = w[BatchSlot.F11, k] * w[BatchSlot.XI, k] * inv
        uy = f22 * w[BatchSlot.ETA, k] * inv
        us = f23 * w[BatchSlot.PHI, k] * inv
        my = f23 / (f22 * c)
        ms = w[BatchSlot.F33, k] / (f23 * c)
        neg = ux < 0.0
        ux = -ux if neg else ux
        lm = my * uy - ms * us
        rho2 = ux * ux + uy * uy + us * us + lm * lm
        r0 = math.sqrt(1.0 + rho2)
        ws = us * math.sqrt(1.0 + ms * ms)
        uf = uy + us
        r1 = math.sqrt(1.0 + ux)
        r2 = math.sqrt(1.0 + abs(uf))
        r3 = math.sqrt(math.sqrt(1.0 + abs(ws)))
        r01 = r0 * r1
        r23 = r2 * r3
        ip = 1.0 / (r01 * r23)
        linear = rho2 <= _RHO2_TABLE_FROM
        inv = 1.0 / r0 if linear else ip * r1 * r23
        w[BatchSlot.TX, k] = -ux * inv
        w[BatchSlot.TY, k] = (-(uy + us) if linear else -uf) * inv
        w[BatchSlot.TM, k] = lm * inv
        sy = 1.0 - ip * r01 * r3
        ss = 1.0 - ip * r01 * r2
        # The stencil's coordinates wait in the weights' rows (_stencil_weights).
        w[BatchSlot.X0, k] = 1.0 - ip * r0 * r23 if ux > 0.0 else 0.0
        w[BatchSlot.Y0, k] = -sy if uf < 0.0 else sy
        w[BatchSlot.Z0, k] = -ss if ws < 0.0 else ss
        q = rho2 * inv * inv
        h = (rho2 - _RHO2_TABLE_FROM) / (_RHO2_TABLE_FULL - _RHO2_TABLE_FROM)
        q = q * (h * h * (3.0 - 2.0 * h)) if rho2 < _RHO2_TABLE_FULL else q
        w[BatchSlot.Q, k] = -1.0 if linear else q
        w[BatchSlot.SIGN, k] = -1.0 if neg else 1.0


@njit(cache=True, error_model="numpy")
def _stencil_weights(w: np.ndarray, n: int, table: np.ndarray) -> None:
    """Each contact's first control point and its 1-D weights (``table_correction``'s)."""
    n_ab = int(table[TableHeader.N_AB])
    nx = int(table[TableHeader.N_X])
    ny = int(table[TableHeader.N_Y])
    ns = int(table[TableHeader.N_S])
    sy_stride = (ns + 2) * LANES
    sx_stride = (ny + 2) * sy_stride
    sa_stride = (nx + 2) * sx_stride
    for k in range(n):
        ix, x0, x1, x2 = _weights(w[BatchSlot.X0, k] * (nx - 1), nx)
        iy, y0, y1, y2 = _weights((w[BatchSlot.Y0, k] + 1.0) * 0.5 * (ny - 1), ny)
        iz, z0, z1, z2 = _weights((w[BatchSlot.Z0, k] + 1.0) * 0.5 * (ns - 1), ns)
        ab = w[BatchSlot.AB, k]
        low = n_ab == 1 or ab <= 0.0
        high = ab >= n_ab - 1.0
        ia = 0 if low else (n_ab - 1 if high else int(ab))
        w[BatchSlot.WA, k] = 0.0 if (low or high) else ab - int(ab)
        w[BatchSlot.INDEX, k] = (TableHeader.DATA + ia * sa_stride + ix * sx_stride
                                 + iy * sy_stride + iz * LANES)  # fmt: skip
        w[BatchSlot.X0, k] = x0
        w[BatchSlot.X1, k] = x1
        w[BatchSlot.X2, k] = x2
        w[BatchSlot.Y0, k] = y0
        w[BatchSlot.Y1, k] = y1
        w[BatchSlot.Y2, k] = y2
        w[BatchSlot.Z0, k] = z0
        w[BatchSlot.Z1, k] = z1
        w[BatchSlot.Z2, k] = z2


@njit(cache=True)
def _correct(w: np.ndarray, n: int, table: np.ndarray) -> None:
    """The stencils, the correction, the cap and the forces, contact by contact."""
    nx = int(table[TableHeader.N_X])
    ny = int(table[TableHeader.N_Y])
    ns = int(table[TableHeader.N_S])
    sy_stride = (ns + 2) * LANES
    sx_stride = (ny + 2) * sy_stride
    sa_stride = (nx + 2) * sx_stride
    for k in range(n):
        tx = w[BatchSlot.TX, k]
        ty = w[BatchSlot.TY, k]
        tm = w[BatchSlot.TM, k]
        q = w[BatchSlot.Q, k]
        if q >= 0.0:
            i0 = int(w[BatchSlot.INDEX, k])
            x0, x1, x2 = w[BatchSlot.X0, k], w[BatchSlot.X1, k], w[BatchSlot.X2, k]
            y0, y1, y2 = w[BatchSlot.Y0, k], w[BatchSlot.Y1, k], w[BatchSlot.Y2, k]
            z0, z1, z2 = w[BatchSlot.Z0, k], w[BatchSlot.Z1, k], w[BatchSlot.Z2, k]
            d0, d1, d2 = slice_stencil(table, i0, sx_stride, sy_stride, x0, x1, x2, y0, y1,
                                       y2, z0, z1, z2)  # fmt: skip
            wa = w[BatchSlot.WA, k]
            if wa > 0.0:
                e0, e1, e2 = slice_stencil(table, i0 + sa_stride, sx_stride, sy_stride, x0,
                                           x1, x2, y0, y1, y2, z0, z1, z2)  # fmt: skip
                d0 += wa * (e0 - d0)
                d1 += wa * (e1 - d1)
                d2 += wa * (e2 - d2)
            tx += q * d0
            ty += q * d1
            tm += q * d2
        r2 = tx * tx + ty * ty
        if r2 > _CAP * _CAP:
            r = math.sqrt(r2)
            scale = (_CAP + (1.0 - _CAP) * math.tanh((r - _CAP) / (1.0 - _CAP))) / r
            tx *= scale
            ty *= scale
        m = w[BatchSlot.MU_N, k]
        w[BatchSlot.FX, k] = m * (w[BatchSlot.SIGN, k] * tx)
        w[BatchSlot.FY, k] = m * ty
        w[BatchSlot.MZ, k] = m * w[BatchSlot.C, k] * tm


@njit(cache=True)
def table_creep_batch(w: np.ndarray, n: int, table: np.ndarray) -> None:
    """Creep forces and spin moments of contacts ``0..n-1`` from the creep table.

    Parameters
    ----------
    w : numpy.ndarray, shape (N_BATCH_SLOTS, >= n)
        Work array (rows :class:`BatchSlot`): the inputs ``F11 .. AB`` are read, the
        outputs ``FX, FY, MZ`` (N, N, N*m; signs of Kalker's linear law) written, the other
        rows overwritten.
    n : int
        Number of contacts.
    table : numpy.ndarray
        The creep table (:mod:`railhunt.kernel.creep_table`).

    Notes
    -----
    Contact ``k`` gets exactly ``mu N * table_creep(f11 xi / (mu N), f22 eta / (mu N),
    f23 phi / (mu N), f23 / (f22 c), f33 / (f23 c), ab, table)`` (the moment times ``c``).
    """
    _saturate(w, n)
    _stencil_weights(w, n, table)
    _correct(w, n, table)
