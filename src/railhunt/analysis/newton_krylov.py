"""Newton's method whose Jacobian refreshes are Krylov solves: for expensive Jacobians.

:func:`railhunt.analysis.newton.newton` recomputes the Jacobian after every slow step.
For shooting from the end of a run that has not settled on its cycle, Newton walks a
long way down a valley (a slowly decaying mode), each step halved, and pays a full
finite-difference Jacobian (40 flows) per step, although the Jacobian changes little
from one step to the next. :func:`newton_krylov` takes the same steps (the same
step halving, the same refresh rule) but solves each refreshed Newton system by GMRES
preconditioned with the previous Jacobian: a product of the Jacobian with a vector is a
directional finite difference of the residual (one flow), and a few of them solve the
system to ``krylov_rtol``. The products found also update the previous Jacobian
(multi-secant: it then agrees with them) for the next refresh. A full ``jac_fun``
Jacobian is computed at the start and whenever GMRES does not converge in
``krylov_dim`` products.

The steps are those of Newton's method up to the inexact solve (relative error
``krylov_rtol``); at convergence the solution satisfies the same tolerance.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import scipy.linalg as sla

from railhunt.analysis.newton import halved_step

#: Directional finite-difference step, relative to the direction's largest entry (the
#: shooting residuals' unknowns are scaled to natural units, as their FD columns' 1e-5).
DIRECTION_STEP = 1e-5


def gmres(matvec: Callable[[np.ndarray], np.ndarray], b: np.ndarray,
          precondition: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, rtol: float,
          max_dim: int) -> tuple[np.ndarray, bool]:  # fmt: skip
    """Right-preconditioned GMRES without restarts for ``A x = b``.

    Parameters
    ----------
    matvec : callable
        ``v -> A v``.
    b : numpy.ndarray
        Right-hand side.
    precondition : callable
        ``v -> P^-1 v`` for an approximation ``P`` of ``A``.
    x0 : numpy.ndarray
        Start.
    rtol : float
        Stop when ``|b - A x| <= rtol |b|`` (2-norms).
    max_dim : int
        Largest Krylov dimension (products of ``A``).

    Returns
    -------
    x : numpy.ndarray
        The solution found.
    converged : bool
        Whether it meets ``rtol``.
    """
    target = rtol * float(np.linalg.norm(b))
    r0 = b - matvec(x0)
    beta = float(np.linalg.norm(r0))
    if beta <= target:
        return x0, True
    n = b.size
    q = np.zeros((max_dim + 1, n))
    z = np.zeros((max_dim, n))
    h = np.zeros((max_dim + 1, max_dim))
    q[0] = r0 / beta
    e1 = np.zeros(max_dim + 1)
    e1[0] = beta
    for j in range(max_dim):
        z[j] = precondition(q[j])
        w = matvec(z[j])
        for i in range(j + 1):  # modified Gram-Schmidt
            h[i, j] = float(w @ q[i])
            w = w - h[i, j] * q[i]
        h[j + 1, j] = float(np.linalg.norm(w))
        y, *_ = np.linalg.lstsq(h[: j + 2, : j + 1], e1[: j + 2], rcond=None)
        res = float(np.linalg.norm(h[: j + 2, : j + 1] @ y - e1[: j + 2]))
        if res <= target or h[j + 1, j] <= 1e-14 * beta:
            return x0 + y @ z[: j + 1], res <= target
        q[j + 1] = w / h[j + 1, j]
    return x0 + y @ z[:max_dim], False


def newton_krylov(
    fun: Callable[[np.ndarray], np.ndarray],
    jac_fun: Callable[[np.ndarray, np.ndarray], np.ndarray],
    u0: np.ndarray,
    tol: float = 1e-8,
    max_iter: int = 12,
    halvings: int = 6,
    krylov_rtol: float = 1e-3,
    krylov_dim: int = 10,
    previous: np.ndarray | None = None,
) -> tuple[np.ndarray, float, int, bool, np.ndarray | None]:
    """Newton's method with step halving and Krylov Jacobian refreshes (module docstring).

    Same parameters and returns as :func:`railhunt.analysis.newton.newton` (without
    ``jac``), plus ``krylov_rtol`` (relative residual of each refreshed Newton system),
    ``krylov_dim`` (directional differences per refresh before a full ``jac_fun``) and
    ``previous``: a Jacobian of the same system near ``u0`` (an earlier solve's last one)
    that preconditions the first step too. The last Jacobian returned is the latest one
    known, also when Newton fails.
    """
    u = u0.copy()
    r = fun(u)
    norm = float(np.max(np.abs(r)))
    if not math.isfinite(norm):
        return u, norm, 0, False, previous
    jac: np.ndarray | None = None
    for it in range(1, max_iter + 1):
        if norm < tol:
            return u, norm, it - 1, True, jac
        fresh = jac is None
        du = None
        if fresh and previous is not None:
            du, jac = _krylov_step(fun, u, r, previous, krylov_rtol, krylov_dim)
        krylov = du is not None
        if du is None:
            if fresh:
                jac = jac_fun(u, r)
            try:
                du = np.linalg.solve(jac, -r)
            except np.linalg.LinAlgError:
                return u, norm, it, False, jac
        halved = halved_step(fun, u, du, norm, halvings)
        if halved is None:
            if not fresh:
                jac = None  # stalled with an old Jacobian: refresh and retry
                continue
            if krylov:
                previous = jac = None  # stalled on a Krylov step: retry with jac_fun
                continue
            return u, norm, it, False, jac
        lam, un, rn, nn = halved
        ratio = nn / norm
        step = lam * du
        # The Jacobian with Broyden's update along the step: the next refresh's start.
        previous = jac + np.outer(rn - r - jac @ step, step) / float(step @ step)
        u, r, norm = un, rn, nn
        if ratio > 0.25:
            jac = None  # slow (chord) convergence: refresh the Jacobian
    return u, norm, max_iter, norm < tol, jac if jac is not None else previous


def _krylov_step(fun, u: np.ndarray, r: np.ndarray, previous: np.ndarray, rtol: float,
                 max_dim: int) -> tuple[np.ndarray | None, np.ndarray | None]:  # fmt: skip
    """The Newton step at ``u`` by GMRES preconditioned with ``previous``, and
    ``previous`` updated to the products found; ``(None, None)`` when GMRES fails."""
    try:
        lu = sla.lu_factor(previous, check_finite=True)
    except (ValueError, np.linalg.LinAlgError):
        return None, None
    dirs, prods = [], []

    def matvec(v: np.ndarray) -> np.ndarray:
        size = float(np.max(np.abs(v)))
        if size == 0.0:
            return np.zeros_like(r)
        eps = DIRECTION_STEP / size
        out = (fun(u + eps * v) - r) / eps
        dirs.append(v)
        prods.append(out)
        return out

    du, ok = gmres(matvec, -r, lambda v: sla.lu_solve(lu, v), sla.lu_solve(lu, -r), rtol,
                   max_dim)  # fmt: skip
    if not (ok and np.all(np.isfinite(du))):
        return None, None
    v, p = np.array(dirs).T, np.array(prods).T
    return du, previous + (p - previous @ v) @ np.linalg.pinv(v)
