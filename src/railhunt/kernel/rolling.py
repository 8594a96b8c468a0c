"""Kalker's exact theory of steady rolling, discretised: the tangential problem's solver.

The contact area is a set of elements of a uniform ``mx * my`` grid (``inside``, each grid
row ``i`` along ``x`` holding a contiguous run of ``j``); each element carries a uniform
traction ``p = (p_x, p_y)`` (arrays ``(2, mx, my)``) in ``G = 1`` units, like the influence
table ``A`` of :mod:`railhunt.kernel.halfspace`. Rolling in ``+x``, material flows through
the contact in ``-x`` and the slip of element ``I`` over the rolling distance ``dx`` is
(Kalker 1990, Sec. 5.2, the transport term taken from the element upstream, ``I + (1, 0)``)

    S_I = dx w_I + u_I - u_{I+(1,0)} = dx w_I + sum_J (A(I - J) - A(I - J + (1, 0))) p_J,

with the rigid slip ``w = (xi - phi y, eta + phi x)``. Coulomb's law with the traction
bound ``g_I = mu p_n``: ``|p_I| <= g_I``; ``S_I = 0`` where ``|p_I| < g_I`` (adhesion),
``p_I = -g_I S_I / |S_I|`` where the element slips.

The solver is a nonlinear block Gauss-Seidel method in the differences of the tractions
along the rolling direction (the idea of Vollebregt's SteadyGS, CONTACT's steady-rolling
solver): in those variables the system matrix is ``A`` itself (symmetric, positive
definite) instead of the badly conditioned transport operator, so the iteration converges.
Visiting element ``I`` (from the trailing edge to the leading edge of its line), its
traction changes by ``delta`` together with those of the adhesion elements downstream of
it up to the next element that slips or lies outside (``J``), so that the slip changes by
``(A(K - I) - A(K - J)) delta`` (a telescoping sum), and the element's own 2 x 2
complementarity problem is solved exactly: adhesion if the sticking traction lies within
the bound, else the slip direction from a scalar Newton iteration on the slip's magnitude.
Each line of elements along ``x`` is swept ``INNER`` times with the slip updated along the
line only; then the line's change of tractions goes to the slip of every element, one
vectorised pass per element with the transport table ``B(k) = A(k) - A(k + (1, 0))``, so
that a sweep of the patch costs about one dense product. Relaxation factors ``omega_h``
(adhesion) and ``omega_s`` (slip) damp the updates and are reduced when the iteration is
slow. The loop stops when the resultants (forces and moment) have settled.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

EXTERIOR, ADHESION, SLIP = 0, 1, 2
#: Sweeps along one line before its change goes to the rest of the patch.
INNER = 6
#: Sweeps after which, without convergence, the relaxation factors are reduced (again).
DAMP_AFTER = 30


@njit(cache=True)
def _slip_traction(rx: float, ry: float, g: float, cx: float, cy: float):
    """Traction on the bound ``g`` opposite to the slip ``S = diag(cx, cy) p + r``.

    Solves ``(rx/(lam + g cx))^2 + (ry/(lam + g cy))^2 = 1`` for ``lam >= 0`` (the slip's
    magnitude) by Newton's method from the left: the function is convex and decreasing,
    so the iterates rise monotonically to the root.
    """
    gx, gy = g * cx, g * cy
    lam = max(0.0, math.sqrt(rx * rx + ry * ry) - max(gx, gy))
    for _ in range(60):
        ex = rx / (lam + gx)
        ey = ry / (lam + gy)
        f = ex * ex + ey * ey - 1.0
        if f <= 0.0:
            break
        df = 2.0 * (ex * ex / (lam + gx) + ey * ey / (lam + gy))
        step = f / df
        lam += step
        if step <= 1e-15 * (lam + gx + gy):
            break
    return -g * rx / (lam + gx), -g * ry / (lam + gy)


@njit(cache=True, fastmath=True)
def _add_transport(s, i, j, dpx, dpy, lo, hi, b, mx, my):
    """``S_K += B(K - I) dp`` over the contact, ``B(k) = A(k) - A(k + (1, 0))``: the change
    ``dp`` of the traction of element ``I = (i, j)`` alone. One loop per grid row over
    slices indexed alike, which LLVM vectorises."""
    off = my - 1 - j
    for ik in range(s.shape[1]):
        j0, j1 = lo[ik], hi[ik]
        if j1 < j0:
            continue
        n = j1 - j0 + 1
        k = ik - i + mx
        c0 = j0 + off
        sx = s[0, ik, j0:j1 + 1]
        sy = s[1, ik, j0:j1 + 1]
        bx = b[0, k, c0:c0 + n]
        bc = b[1, k, c0:c0 + n]
        by = b[2, k, c0:c0 + n]
        for t in range(n):
            sx[t] += bx[t] * dpx + bc[t] * dpy
            sy[t] += bc[t] * dpx + by[t] * dpy


@njit(cache=True)
def transport_table(a):
    """``B(k, l) = A(k, l) - A(k + 1, l)``, laid out as ``a``: ``b[:, k + mx]`` for
    ``k = -mx .. mx - 1``."""
    nc, nk, nl = a.shape
    b = np.empty((nc, nk - 1, nl))
    for c in range(nc):
        for k in range(nk - 1):
            for m in range(nl):
                b[c, k, m] = a[c, k, m] - a[c, k + 1, m]
    return b


@njit(cache=True)
def rolling_slip(inside, w, dx, a, p):
    """Slip ``S = dx w + sum_J (A(I - J) - A(I - J + (1, 0))) p_J`` of every contact element.

    Parameters as :func:`steady_rolling`; returns ``S`` (shape ``(2, mx, my)``, zero
    outside the contact).
    """
    return _slip(inside, w, dx, transport_table(a), p)


@njit(cache=True)
def _slip(inside, w, dx, b, p):
    mx, my = inside.shape
    lo, hi = _row_ranges(inside)
    s = np.zeros((2, mx, my))
    for i in range(mx):
        for j in range(lo[i], hi[i] + 1):
            s[0, i, j] = dx * w[0, i, j]
            s[1, i, j] = dx * w[1, i, j]
    for i in range(mx):
        for j in range(lo[i], hi[i] + 1):
            if p[0, i, j] != 0.0 or p[1, i, j] != 0.0:
                _add_transport(s, i, j, p[0, i, j], p[1, i, j], lo, hi, b, mx, my)
    return s


@njit(cache=True)
def _row_ranges(inside):
    mx, my = inside.shape
    lo = np.full(mx, my, np.int64)
    hi = np.full(mx, -1, np.int64)
    for i in range(mx):
        for j in range(my):
            if inside[i, j]:
                lo[i] = min(lo[i], j)
                hi[i] = max(hi[i], j)
    return lo, hi


@njit(cache=True)
def _resultants(inside, x, y, p):
    """Sums of ``p_x``, ``p_y`` and ``x p_y - y p_x`` over the contact."""
    mx, my = inside.shape
    sx = 0.0
    sy = 0.0
    sm = 0.0
    for i in range(mx):
        for j in range(my):
            if inside[i, j]:
                sx += p[0, i, j]
                sy += p[1, i, j]
                sm += x[i, j] * p[1, i, j] - y[i, j] * p[0, i, j]
    return sx, sy, sm


@njit(cache=True)
def steady_rolling(inside, gbound, w, dx, a, p, tol, maxit, omega_h, omega_s, x, y):
    """Solve the discretised steady-rolling tangential problem; ``p`` is updated in place.

    Parameters
    ----------
    inside : ndarray of bool, shape (mx, my)
        Elements in contact; in each row ``i`` (fixed ``x``) a contiguous run of ``j``;
        every column ``j`` a contiguous run of ``i``.
    gbound : ndarray, shape (mx, my)
        Traction bound ``mu p_n / G`` (``inf`` for the linear theory of full adhesion).
    w : ndarray, shape (2, mx, my)
        Rigid slip per unit rolling distance (creepages and spin), ``x`` and ``y``.
    dx : float
        Element length in the rolling direction.
    a : ndarray, shape (3, 2 mx + 1, 2 my - 1)
        Influence table: ``a[:, k + mx, l + my - 1]`` holds ``(A_xx, A_xy, A_yy)`` at the
        offset ``(k, l)`` (:func:`railhunt.kernel.halfspace.tangential_influence`).
    p : ndarray, shape (2, mx, my)
        Initial tractions (set to zero outside the contact); overwritten by the solution.
    tol : float
        Stop when, in two sweeps in a row, no resultant (the sums of ``p_x``, ``p_y``
        and of ``(x p_y - y p_x) / l``, ``l = sqrt(max|x| max|y|)`` over the contact)
        changed by more than ``tol`` times the largest of them. (The iteration converges
        geometrically, about a factor 2 per sweep, so the remaining error is about the
        last change: the forces are converged long before every traction is.)
    maxit : int
        Largest number of sweeps.
    omega_h, omega_s : float
        Relaxation factors for elements in adhesion and in slip (1 = none); reduced
        every ``DAMP_AFTER`` sweeps without convergence (to at least 0.5 and 0.3).
    x, y : ndarray, shape (mx, my)
        Element centres, for the moment.

    Returns
    -------
    sweeps : int
        Sweeps made; negative if ``maxit`` was reached first.
    s : ndarray, shape (2, mx, my)
        Slip over the rolling distance ``dx``, zero in the adhesion area.
    state : ndarray of int8, shape (mx, my)
        ``EXTERIOR`` (0), ``ADHESION`` (1) or ``SLIP`` (2).
    """
    mx, my = inside.shape
    lo, hi = _row_ranges(inside)
    state = np.zeros((mx, my), np.int8)
    for i in range(mx):
        for j in range(my):
            if inside[i, j]:
                state[i, j] = ADHESION
            else:
                p[0, i, j] = 0.0
                p[1, i, j] = 0.0
    xmax = 0.0
    ymax = 0.0
    for i in range(mx):
        for j in range(my):
            if inside[i, j]:
                xmax = max(xmax, abs(x[i, j]))
                ymax = max(ymax, abs(y[i, j]))
    arm = math.sqrt(xmax * ymax) if ymax > 0.0 else max(xmax, 1e-300)
    b = transport_table(a)
    s = _slip(inside, w, dx, b, p)
    line = np.ascontiguousarray(a[:, :, my - 1])  # the offsets along one line, (3, 2 mx + 1)
    for i in range(mx):
        for j in range(lo[i], hi[i] + 1):
            g = gbound[i, j]
            if p[0, i, j] ** 2 + p[1, i, j] ** 2 >= g * g * (1.0 - 1e-12) and g < math.inf:
                state[i, j] = SLIP
    a0x, a0y = a[0, mx, my - 1], a[2, mx, my - 1]
    fx0, fy0, mz0 = _resultants(inside, x, y, p)
    quiet = 0
    pmax = 0.0
    col_lo = np.full(my, mx, np.int64)
    col_hi = np.full(my, -1, np.int64)
    for i in range(mx):
        for j in range(my):
            if inside[i, j]:
                col_lo[j] = min(col_lo[j], i)
                col_hi[j] = max(col_hi[j], i)
    save = np.empty((4, mx))
    for sweep in range(1, maxit + 1):
        # a change below this is not made (p and S stay consistent): it moves no resultant
        # by more than about a tenth of the tolerance
        skip = 0.1 * tol * pmax if sweep > 1 else 0.0
        pmax = 0.0
        for j in range(my):
            i0, i1 = col_lo[j], col_hi[j]
            if i1 < i0:
                continue
            for i in range(i0, i1 + 1):
                save[0, i] = s[0, i, j]
                save[1, i] = s[1, i, j]
                save[2, i] = p[0, i, j]
                save[3, i] = p[1, i, j]
            for _ in range(INNER):
                line_change = 0.0
                for i in range(i0, i1 + 1):  # trailing edge first
                    jx = i - 1
                    while jx >= 0 and state[jx, j] == ADHESION:
                        jx -= 1
                    cx = a0x - line[0, mx + i - jx]
                    cy = a0y - line[2, mx + i - jx]
                    ox, oy = p[0, i, j], p[1, i, j]
                    rx = s[0, i, j] - cx * ox
                    ry = s[1, i, j] - cy * oy
                    nx, ny = -rx / cx, -ry / cy
                    g = gbound[i, j]
                    if nx * nx + ny * ny > g * g:
                        state[i, j] = SLIP
                        if g > 0.0:
                            nx, ny = _slip_traction(rx, ry, g, cx, cy)
                        else:
                            nx, ny = 0.0, 0.0
                        omega = omega_s
                    else:
                        state[i, j] = ADHESION
                        omega = omega_h
                    dpx, dpy = omega * (nx - ox), omega * (ny - oy)
                    if abs(dpx) > skip or abs(dpy) > skip:
                        for ii in range(jx + 1, i + 1):
                            p[0, ii, j] += dpx
                            p[1, ii, j] += dpy
                        # the slip along this line only; the rest after the line
                        k1, k2 = mx - i, mx - jx
                        for ik in range(i0, i1 + 1):
                            cxx = line[0, ik + k1] - line[0, ik + k2]
                            cxy = line[1, ik + k1] - line[1, ik + k2]
                            cyy = line[2, ik + k1] - line[2, ik + k2]
                            s[0, ik, j] += cxx * dpx + cxy * dpy
                            s[1, ik, j] += cxy * dpx + cyy * dpy
                        line_change = max(line_change, abs(dpx), abs(dpy))
                if line_change <= skip:
                    break
            # the line's change of tractions to the slip of every element (its own line's
            # again, from its slip before: the same sum, in one pass)
            for i in range(i0, i1 + 1):
                s[0, i, j] = save[0, i]
                s[1, i, j] = save[1, i]
            for i in range(i0, i1 + 1):
                dpx = p[0, i, j] - save[2, i]
                dpy = p[1, i, j] - save[3, i]
                if dpx != 0.0 or dpy != 0.0:
                    _add_transport(s, i, j, dpx, dpy, lo, hi, b, mx, my)
                pmax = max(pmax, abs(p[0, i, j]), abs(p[1, i, j]))
        fx, fy, mz = _resultants(inside, x, y, p)
        change = max(abs(fx - fx0), abs(fy - fy0), abs(mz - mz0) / arm)
        scale = max(abs(fx), abs(fy), abs(mz) / arm)
        fx0, fy0, mz0 = fx, fy, mz
        quiet = quiet + 1 if change <= tol * scale else 0
        if quiet >= 2:
            return sweep, s, state
        if sweep % DAMP_AFTER == 0:
            # slow: slip areas that flip back and forth (large spin near saturation)
            # settle under damping
            omega_s = max(0.3, 0.7 * omega_s)
            omega_h = max(0.5, 0.85 * omega_h)
    return -maxit, s, state


@njit(cache=True)
def rolling_batch(inside, shape, x, y, dx, dy, a, xi, eta, phi, gscale, tol, maxit,
                  omega_h, omega_s, start, keep):
    """:func:`steady_rolling` for many cases on one patch.

    Parameters
    ----------
    inside, dx, a, tol, maxit, omega_h, omega_s
        As :func:`steady_rolling`.
    shape : ndarray, shape (mx, my)
        Shape of the traction bound (Hertz: ``sqrt(1 - x^2/a^2 - y^2/b^2)``).
    x, y : ndarray, shape (mx, my)
        Element centres (for the rigid slip and the moment).
    dy : float
        Element width.
    xi, eta, phi : ndarray, shape (n,)
        Creepages and spin of each case.
    gscale : ndarray, shape (n,)
        Traction bound over ``shape`` for each case (``inf``: the linear theory).
    start : ndarray, shape (n, 2, mx, my) or (0, 2, mx, my)
        Initial tractions of each case; with none (``n = 0``) each case starts from the
        previous one's solution (the first from zero), or from zero after a change of
        ``gscale``.
    keep : bool
        Return every case's tractions (else an empty array).

    Returns
    -------
    fx, fy, mz : ndarray, shape (n,)
        Sums of the tractions times the element area, and of ``x p_y - y p_x``.
    sweeps : ndarray of int, shape (n,)
        Sweeps per case (negative: not converged within ``maxit``).
    tractions : ndarray, shape (n, 2, mx, my) (``keep``) or (0, 2, mx, my)
    """
    mx, my = inside.shape
    n = xi.shape[0]
    fx = np.empty(n)
    fy = np.empty(n)
    mz = np.empty(n)
    sweeps = np.empty(n, np.int64)
    out = np.zeros((n if keep else 0, 2, mx, my))
    p = np.zeros((2, mx, my))
    w = np.zeros((2, mx, my))
    g = np.zeros((mx, my))
    da = dx * dy
    given = start.shape[0] == n and n > 0
    for k in range(n):
        for i in range(mx):
            for j in range(my):
                w[0, i, j] = xi[k] - phi[k] * y[i, j]
                w[1, i, j] = eta[k] + phi[k] * x[i, j]
                g[i, j] = gscale[k] * shape[i, j] if inside[i, j] else 0.0
        if given:
            p[:] = start[k]
        elif k > 0 and (gscale[k] != gscale[k - 1]):
            p[:] = 0.0  # another bound: the last solution is no start
        it, _, _ = steady_rolling(inside, g, w, dx, a, p, tol, maxit, omega_h, omega_s, x, y)
        sweeps[k] = it
        if keep:
            out[k] = p
        sx, sy, sm = _resultants(inside, x, y, p)
        fx[k] = sx * da
        fy[k] = sy * da
        mz[k] = sm * da
    return fx, fy, mz, sweeps, out


@njit(cache=True)
def refine_tractions(coarse, inside_fine):
    """Tractions of a grid with half the elements each way, on the full grid: each coarse
    element's traction on its (up to) 2 x 2 fine elements inside the contact.

    Parameters
    ----------
    coarse : ndarray, shape (n, 2, mx // 2, my // 2)
    inside_fine : ndarray of bool, shape (mx, my)

    Returns
    -------
    ndarray, shape (n, 2, mx, my)
    """
    n, _, cx, cy = coarse.shape
    mx, my = inside_fine.shape
    fine = np.zeros((n, 2, mx, my))
    for k in range(n):
        for i in range(mx):
            ic = min(i * cx // mx, cx - 1)
            for j in range(my):
                if inside_fine[i, j]:
                    jc = min(j * cy // my, cy - 1)
                    fine[k, 0, i, j] = coarse[k, 0, ic, jc]
                    fine[k, 1, i, j] = coarse[k, 1, ic, jc]
    return fine
