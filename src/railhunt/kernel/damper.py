"""The yaw damper's two-stage viscous law (the paper's Fig. 4b and Eqs. 35-37).

The yaw damper is a Maxwell element: a spring ``K_d`` in series with a viscous damper
whose damping drops from ``C_d1`` to ``C_d2`` above the blow-off force ``F_u``. Its force
is a state; the right-hand side integrates ``dF/dt = K_d (elongation rate - v_d(F))``
with :func:`damper_velocity` the inverse of the force-velocity characteristic.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def damper_velocity(force: float, c1: float, c2: float, f_u: float) -> float:
    """Velocity of the two-stage viscous damper carrying ``force`` (inverse of Fig. 4b).

    Parameters
    ----------
    force : float
        Damper force (N), positive in tension.
    c1, c2 : float
        First- and second-stage damping (N*s/m).
    f_u : float
        Blow-off force (N); the blow-off velocity is ``f_u / c1``.

    Returns
    -------
    float
        Elongation rate of the viscous part (m/s): ``force / c1`` below blow-off,
        ``sign(force) * (f_u / c1 + (|force| - f_u) / c2)`` above. Odd in ``force``.
    """
    af = abs(force)
    if af <= f_u:
        return force / c1
    vel = f_u / c1 + (af - f_u) / c2
    return vel if force > 0.0 else -vel


@njit(cache=True)
def damper_force_steady(velocity: float, c1: float, c2: float, f_u: float) -> float:
    """Steady two-stage damper force at a constant velocity (Fig. 4b), N.

    ``c1 * v`` for ``|v| <= v_u = f_u / c1``, then ``sign(v) * (f_u + c2 * (|v| - v_u))``.
    """
    v_u = f_u / c1
    av = abs(velocity)
    if av <= v_u:
        return c1 * velocity
    f = f_u + c2 * (av - v_u)
    return f if velocity > 0.0 else -f


@njit(cache=True)
def damper_velocity_array(force: np.ndarray, c1: float, c2: float, f_u: float) -> np.ndarray:
    """:func:`damper_velocity` of every entry of a 1-D array of forces (N) -> m/s."""
    out = np.empty(force.shape[0])
    for i in range(force.shape[0]):
        out[i] = damper_velocity(force[i], c1, c2, f_u)
    return out
