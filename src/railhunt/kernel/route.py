"""Track geometry along the route: curvature, heading, lateral offset integral and cant.

The route is a table of segments (:class:`railhunt.kernel.layout.RouteColumn`) in which
the curvature and the cant angle vary linearly with the track position ``s`` (a tangent,
a clothoid transition, a constant curve). Before the first segment the track is straight
with heading 0. :func:`railhunt.curve.Curve` builds the table.

From the heading ``theta(s)`` and its integral ``Phi(s)`` the geometric offsets of one
track frame relative to another follow without cancellation problems for the distances
of one vehicle: the heading difference ``theta(s_b) - theta(s_a)`` and the lateral offset
of the track point ``s_b`` from the tangent at ``s_a``,
``Phi(s_b) - Phi(s_a) - theta(s_a) (s_b - s_a)`` (the versine ``kappa d^2 / 2`` in a
constant curve).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from railhunt.kernel.layout import RouteColumn as C


@njit(cache=True)
def route_point(s: float, route: np.ndarray) -> tuple[float, float, float, float, float, float]:
    """Geometry of the track at position ``s`` (m).

    Returns
    -------
    tuple of float
        ``(kappa, theta, Phi, cant, dkappa, dcant)``: curvature (1/m, + left), heading
        (rad), integral of the heading (m), cant angle (rad), and the derivatives of
        curvature (1/m^2) and cant (rad/m) along the track.
    """
    n = route.shape[0]
    if n == 0 or s <= route[0, C.S0]:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    i = 0
    while i + 1 < n and route[i + 1, C.S0] <= s:
        i += 1
    u = s - route[i, C.S0]
    k0 = route[i, C.KAPPA0]
    dk = route[i, C.DKAPPA]
    th0 = route[i, C.THETA0]
    kappa = k0 + dk * u
    theta = th0 + u * (k0 + 0.5 * dk * u)
    phi = route[i, C.PHI0] + u * (th0 + u * (0.5 * k0 + dk * u / 6.0))
    cant = route[i, C.CANT0] + route[i, C.DCANT] * u
    return kappa, theta, phi, cant, dk, route[i, C.DCANT]
