"""Influence coefficients of the elastic half-space for piecewise-constant surface tractions.

Two bodies of one elastic material (quasi-identity: the normal and the tangential problems
decouple) are pressed together over a uniform grid of rectangular elements of size
``dx * dy``; each element carries a uniform traction. The displacement difference of the
two surfaces at the centre of element ``I`` due to a unit traction on element ``J`` depends
only on the offset ``(k, l)`` between them (a Toeplitz structure), so one table per
displacement/traction pair holds every coefficient.

Boussinesq-Cerruti (Johnson, *Contact Mechanics*, 1985, Eq. 3.86a): a tangential point
force ``Q_x`` on the surface of one half-space displaces its surface by

    u_x = Q_x / (2 pi G) [(1 - nu)/rho + nu x^2/rho^3],    u_y = Q_x / (2 pi G) nu x y/rho^3,

so the displacement *difference* of two equal bodies under equal and opposite tractions
has ``1 / (pi G)`` in front. Integrated over a rectangle, with the antiderivatives
(``d^2 F / dx dy = f``)

    1/rho     : x asinh(y/|x|) + y asinh(x/|y|)
    x^2/rho^3 : y asinh(x/|y|)
    y^2/rho^3 : x asinh(y/|x|)
    x y/rho^3 : -rho

(Kalker, *Three-dimensional elastic bodies in rolling contact*, 1990, Sec. 5.3 writes the
same integrals with logarithms). Plane strain (the 2-D problem of Carter): a uniform
tangential line load ``q`` over an interval displaces the surfaces' difference by
``-2 (1 - nu)/(pi G) q int ln|x - s| ds`` (``x`` direction) and ``-2/(pi G) q int ln|x - s|
ds`` (anti-plane, ``y``), up to a constant that the rolling problem never sees.

Everything is unit-free: ``G = 1``, lengths in any unit (the element sizes set it).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def _xasinh(x: float, y: float) -> float:
    """``x * asinh(y / |x|)``, 0 at ``x = 0``."""
    if x == 0.0:
        return 0.0
    return x * math.asinh(y / abs(x))


@njit(cache=True)
def _rect(x1: float, x2: float, y1: float, y2: float, kind: int) -> float:
    """Integral over the rectangle ``[x1, x2] x [y1, y2]`` of ``1/rho`` (kind 0),
    ``x^2/rho^3`` (1), ``y^2/rho^3`` (2) or ``x y/rho^3`` (3)."""
    total = 0.0
    for xs, ys, sign in ((x2, y2, 1.0), (x1, y2, -1.0), (x2, y1, -1.0), (x1, y1, 1.0)):
        if kind == 0:
            v = _xasinh(xs, ys) + _xasinh(ys, xs)
        elif kind == 1:
            v = _xasinh(ys, xs)
        elif kind == 2:
            v = _xasinh(xs, ys)
        else:
            v = -math.sqrt(xs * xs + ys * ys)
        total += sign * v
    return total


@njit(cache=True)
def tangential_influence(nk: int, nl: int, dx: float, dy: float, nu: float) -> np.ndarray:
    """Table of the tangential influence coefficients for offsets ``k = -nk..nk`` (along
    ``x``) and ``l = -nl..nl`` (along ``y``), in element counts.

    Parameters
    ----------
    nk, nl : int
        Largest offsets tabulated.
    dx, dy : float
        Element size (length unit of the problem).
    nu : float
        Poisson's ratio.

    Returns
    -------
    ndarray, shape (3, 2 nk + 1, 2 nl + 1)
        ``[:, k + nk, l + nl]`` holds ``(A_xx, A_xy, A_yy)``: the displacement difference
        (``G = 1``) at the centre of an element offset by ``(k, l)`` from an element
        carrying a unit traction; ``A_xy`` is ``u_x`` from ``p_y`` (= ``u_y`` from ``p_x``).
        (One plane per pair, contiguous along ``l``, for the solver's vectorised loops.)
    """
    a = np.empty((3, 2 * nk + 1, 2 * nl + 1))
    hx, hy = 0.5 * dx, 0.5 * dy
    scale = 1.0 / math.pi
    for k in range(-nk, nk + 1):
        x = k * dx
        for m in range(-nl, nl + 1):
            y = m * dy
            x1, x2, y1, y2 = x - hx, x + hx, y - hy, y + hy
            i1 = _rect(x1, x2, y1, y2, 0)
            ixx = _rect(x1, x2, y1, y2, 1)
            iyy = _rect(x1, x2, y1, y2, 2)
            ixy = _rect(x1, x2, y1, y2, 3)
            a[0, k + nk, m + nl] = scale * ((1.0 - nu) * i1 + nu * ixx)
            a[1, k + nk, m + nl] = scale * nu * ixy
            a[2, k + nk, m + nl] = scale * ((1.0 - nu) * i1 + nu * iyy)
    return a


@njit(cache=True)
def normal_influence(nk: int, nl: int, dx: float, dy: float, nu: float) -> np.ndarray:
    """Table of the normal influence coefficients (Boussinesq, both bodies, ``G = 1``):
    ``(1 - nu)/pi`` times the rectangle's integral of ``1/rho``; ``[k + nk, l + nl]`` for
    the offset ``(k, l)``."""
    azz = np.empty((2 * nk + 1, 2 * nl + 1))
    hx, hy = 0.5 * dx, 0.5 * dy
    for k in range(-nk, nk + 1):
        for m in range(-nl, nl + 1):
            x, y = k * dx, m * dy
            azz[k + nk, m + nl] = (1.0 - nu) / math.pi * _rect(x - hx, x + hx, y - hy,
                                                                y + hy, 0)
    return azz


@njit(cache=True)
def _xlogx(x: float) -> float:
    return 0.0 if x == 0.0 else x * math.log(abs(x)) - x


@njit(cache=True)
def plane_strain_influence(nk: int, dx: float, nu: float) -> np.ndarray:
    """The 2-D (line contact) table: offsets ``k = -nk..nk`` along ``x``, one row in ``y``.

    Returns
    -------
    ndarray, shape (3, 2 nk + 1, 1)
        ``-2 (1 - nu)/pi`` (``A_xx``) and ``-2/pi`` (anti-plane, ``A_yy``) times
        ``int ln|x - s| ds`` over an element, ``A_xy = 0``; layout of
        :func:`tangential_influence` with ``nl = 0``.
    """
    a = np.zeros((3, 2 * nk + 1, 1))
    h = 0.5 * dx
    for k in range(-nk, nk + 1):
        x = k * dx
        integral = _xlogx(x + h) - _xlogx(x - h)
        a[0, k + nk, 0] = -2.0 * (1.0 - nu) / math.pi * integral
        a[2, k + nk, 0] = -2.0 / math.pi * integral
    return a
