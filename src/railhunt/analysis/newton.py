"""Newton's method with step halving, for the square systems of railhunt's analyses.

Shooting for limit cycles (:mod:`railhunt.analysis.periodic`), pseudo-arclength
continuation (:mod:`railhunt.analysis.continuation`) and steady curving
(:mod:`railhunt.analysis.curving`) all solve ``r(u) = 0`` with it.
"""

from __future__ import annotations

import math

import numpy as np


def newton(
    fun, jac_fun, u0: np.ndarray, tol: float = 1e-8, max_iter: int = 12,
    jac: np.ndarray | None = None, halvings: int = 6,
) -> tuple[np.ndarray, float, int, bool, np.ndarray | None]:
    """Newton's method on a square system with damping by step halving.

    ``fun(u)`` returns the residual, ``jac_fun(u, r)`` its Jacobian. When ``jac`` is given
    it is used first (chord step) and recomputed only if convergence stalls. A step that
    does not lower the residual's largest entry is halved up to ``halvings`` times.

    Returns
    -------
    u, residual_norm, iterations, converged, last_jacobian
    """
    u = u0.copy()
    r = fun(u)
    norm = float(np.max(np.abs(r)))
    if not math.isfinite(norm):
        return u, norm, 0, False, jac
    for it in range(1, max_iter + 1):
        if norm < tol:
            return u, norm, it - 1, True, jac
        fresh = jac is None
        if fresh:
            jac = jac_fun(u, r)
        try:
            du = np.linalg.solve(jac, -r)
        except np.linalg.LinAlgError:
            return u, norm, it, False, jac
        step = halved_step(fun, u, du, norm, halvings)
        if step is None:
            if not fresh:
                jac = None  # stalled with an old Jacobian: refresh and retry
                continue
            return u, norm, it, False, jac
        _, un, rn, nn = step
        ratio = nn / norm
        u, r, norm = un, rn, nn
        if ratio > 0.25:
            jac = None  # slow (chord) convergence: refresh the Jacobian
    return u, norm, max_iter, norm < tol, jac


def halved_step(fun, u: np.ndarray, du: np.ndarray, norm: float,
                halvings: int) -> tuple[float, np.ndarray, np.ndarray, float] | None:  # fmt: skip
    """The Newton step ``du`` from ``u``, halved up to ``halvings`` times until the
    residual's largest entry falls below ``norm``: ``(lam, u_new, r_new, norm_new)``, or
    None when no step of those lowers it."""
    lam = 1.0
    for _ in range(halvings):
        un = u + lam * du
        rn = fun(un)
        nn = float(np.max(np.abs(rn)))
        if math.isfinite(nn) and nn < norm:
            return lam, un, rn, nn
        lam *= 0.5
    return None
