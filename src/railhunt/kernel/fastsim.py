"""FASTSIM: Kalker's simplified theory of rolling contact on an elliptical patch, strip by strip.

Kalker's simplified theory (J. J. Kalker, "A fast algorithm for the simplified theory of
rolling contact", Vehicle System Dynamics 11 (1982) 1-13) replaces the half-space by
independent springs: the displacement difference is ``u = L p``. In steady rolling (in
``+x``, material flowing through the patch in ``-x``) a particle entering at the leading
edge ``x = A(y) = a sqrt(1 - y^2/b^2)`` carries no traction; while it adheres its traction
changes as ``dp/dx = w / L`` with the rigid slip ``w = (xi - phi y, eta + phi x)``, so

    p(x - h) = p(x) - (1/L) int_{x-h}^{x} w dx'

and wherever ``|p|`` would exceed the traction bound ``g = mu p_n`` the particle slips and
``p`` is scaled back onto the bound (the direction kept, as in Kalker's algorithm).

With three flexibilities (Vollebregt and Wilders, "FASTSIM2: a second order accurate
frictional rolling contact algorithm", Comput. Mech. 47 (2011) 105-116; Vollebregt and
Voltr, "Improved accuracy for FASTSIM using one or three flexibility values", Vehicle
System Dynamics 61 (2023) 309-317) the slip terms are divided by their own flexibility:
``w / L -> (xi/L1 - phi y/L3, eta/L2 + phi x/L3)``. One flexibility is the special case
``L1 = L2 = L3``.

Discretisation: ``my`` strips of width ``2b/my`` (their centre lines at ``y_j``), each cut
into ``mx`` elements of length ``2 A(y_j)/mx``; the traction is evaluated at the element
centres, the rigid slip integrated exactly over each step (it is linear in ``x``), and the
forces are the midpoint sums. The traction bound is parabolic,
``g = mu (2N/(pi a b)) (1 - x^2/a^2 - y^2/b^2)`` (Kalker's, consistent with the simplified
theory's own pressure) or elliptical (Hertz, ``mu (3N/(2 pi a b)) sqrt(...)``), scaled so
that its discrete sum is exactly ``mu N`` (full sliding gives ``|F| = mu N``).

Everything is unit-free: creepages, ``phi`` in 1/length, semi-axes in length, the
flexibilities in length per traction, ``mu N`` in force.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

PARABOLIC, ELLIPTIC = 0, 1


@njit(cache=True)
def _bound_shape(x: float, y: float, a: float, b: float, bound: int) -> float:
    r = 1.0 - (x / a) ** 2 - (y / b) ** 2
    if r <= 0.0:
        return 0.0
    return r if bound == PARABOLIC else math.sqrt(r)


@njit(cache=True)
def fastsim_patch(xi, eta, phi, a, b, l1, l2, l3, mu_n, bound, mx, my):
    """Creep forces and spin moment of one elliptical patch by FASTSIM.

    Parameters
    ----------
    xi, eta : float
        Longitudinal and lateral creepage.
    phi : float
        Spin creepage (1/length).
    a, b : float
        Semi-axes along and across the rolling direction (length), > 0.
    l1, l2, l3 : float
        Flexibilities for the longitudinal, lateral and spin creepages (length/traction).
    mu_n : float
        Friction coefficient times normal force (force), > 0.
    bound : int
        ``PARABOLIC`` (0) or ``ELLIPTIC`` (1) traction bound.
    mx, my : int
        Elements per strip along the rolling direction, and strips across it.

    Returns
    -------
    fx, fy, mz : float
        Forces (force) and the moment about the patch centre (force*length) on the body
        whose creepages are given (opposing them).
    """
    dy = 2.0 * b / my
    # the bound's discrete sum, to scale it to exactly mu N
    total = 0.0
    for j in range(my):
        y = -b + (j + 0.5) * dy
        half = a * math.sqrt(max(0.0, 1.0 - (y / b) ** 2))
        h = 2.0 * half / mx
        for k in range(mx):
            x = half - (k + 0.5) * h
            total += _bound_shape(x, y, a, b, bound) * h * dy
    gscale = mu_n / total if total > 0.0 else 0.0
    cx, cy, cs = xi / l1, eta / l2, phi / l3
    fx = 0.0
    fy = 0.0
    mz = 0.0
    for j in range(my):
        y = -b + (j + 0.5) * dy
        half = a * math.sqrt(max(0.0, 1.0 - (y / b) ** 2))
        h = 2.0 * half / mx
        wx = cx - cs * y
        px = 0.0
        py = 0.0
        x_prev = half
        for k in range(mx):
            x = half - (k + 0.5) * h
            step = x_prev - x
            px -= step * wx
            py -= step * (cy + cs * 0.5 * (x + x_prev))
            x_prev = x
            g = gscale * _bound_shape(x, y, a, b, bound)
            pabs = math.sqrt(px * px + py * py)
            if pabs > g:
                if pabs > 0.0:
                    px *= g / pabs
                    py *= g / pabs
            da = h * dy
            fx += px * da
            fy += py * da
            mz += (x * py - y * px) * da
    return fx, fy, mz


@njit(cache=True)
def fastsim_batch(xi, eta, phi, a, b, l1, l2, l3, mu_n, bound, mx, my):
    """:func:`fastsim_patch` for 1-D arrays of equal length (one patch per entry).

    Returns
    -------
    fx, fy, mz : ndarray
    """
    n = xi.shape[0]
    fx = np.empty(n)
    fy = np.empty(n)
    mz = np.empty(n)
    for i in range(n):
        fx[i], fy[i], mz[i] = fastsim_patch(
            xi[i], eta[i], phi[i], a[i], b[i], l1[i], l2[i], l3[i], mu_n[i], bound, mx, my
        )
    return fx, fy, mz
