"""The secondary lateral bump stop: free play, then a progressive rubber spring.

Between the car body and each bogie frame, at the level of the secondary suspension.
Inside its free play it carries nothing; beyond it the force grows with the compression
``u = |d| - gap`` as ``K1 u + K3 u^3`` (a progressive rubber stop). It limits how far the
car body can swing out on the soft air springs in a curve, and the amplitude of car body
motion on straight track when the vehicle hunts violently.

The same law with the track as the second body is a flange: a wheelset's lateral
displacement relative to the rails, free inside the flange clearance ``gap``, then the
rail's lateral stiffness (Cooperrider's dead-band spring ``k0 (y - delta)`` beyond
``+-delta``: ``k1 = k0``, ``k3 = 0``); ``SystemArrays.stop_wheelset`` says which stops
these are.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def bump_stop_force(deformation: float, gap: float, k1: float, k3: float) -> float:
    """Force of a bump stop at ``deformation`` (m), N, positive when ``deformation`` is.

    ``0`` for ``|deformation| <= gap``; ``sign(d) (k1 u + k3 u^3)`` with
    ``u = |d| - gap`` beyond. ``k1 = k3 = 0`` switches the stop off.
    """
    ad = abs(deformation)
    if ad <= gap:
        return 0.0
    u = ad - gap
    f = u * (k1 + k3 * u * u)
    return f if deformation > 0.0 else -f
