"""Transverse curvature of a wheel or rail profile at given points, smoothed over a window.

Hertz's theory needs the principal curvatures of both surfaces at the contact point. In
the transverse plane these are the curvatures of the profiles themselves. A profile
point list (a measured profile, or the analytic S1002 with its jumps of curvature where
its arcs meet) has no usable second derivative point by point, so the curvature at a
point is taken from least-squares quadratics ``y(s)``, ``z(s)`` in the arc length ``s``
over ``|s - s0| <= half_width`` (default 2 mm, about half the lateral semi-axis of a
tread contact: the averaging a Hertz patch of that width feels):

    kappa = (y' z'' - z' y'') / (y'^2 + z'^2)^(3/2)

in the arc length, which holds at any slope (a flange flank at 70 degrees as well as the
tread). Signs (profile axes of :mod:`railhunt.contact.profiles`, ``z`` downward):
:func:`surface_curvature` returns the curvature of the *surface* as Hertz counts it,
positive where the body is convex toward its partner: ``-kappa`` for a wheel (whose
material lies above its profile), ``+kappa`` for a rail (material below).
"""

from __future__ import annotations

import math

import numpy as np

from railhunt.contact.profiles import Profile, ProfileError

__all__ = ["profile_curvature", "surface_curvature"]


def profile_curvature(y: np.ndarray, z: np.ndarray, at: np.ndarray,
                      half_width: float = 2e-3) -> np.ndarray:  # fmt: skip
    """Signed curvature ``d(angle)/ds`` (1/m) of the curve ``(y, z)`` at lateral ``at``.

    Parameters
    ----------
    y, z : numpy.ndarray
        Profile points (m), ``y`` increasing.
    at : numpy.ndarray
        Lateral positions (m) of the points wanted (within the profile's range).
    half_width : float
        Half-width of the arc-length window of the quadratic fits (m), > 0.

    Returns
    -------
    numpy.ndarray
        Curvature (1/m), positive where ``z`` is convex from below (``z'' > 0`` for a
        graph ``z(y)``), the shape of ``at``.
    """
    if not (math.isfinite(half_width) and 1e-5 <= half_width <= 0.02):
        raise ProfileError(f"half_width = {half_width!r} m is invalid: must be in "
                           "[1e-05, 0.02] m")  # fmt: skip
    y = np.asarray(y, dtype=np.float64)
    z = np.asarray(z, dtype=np.float64)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(y), np.diff(z)))])
    at = np.asarray(at, dtype=np.float64)
    s_at = np.interp(at, y, s)
    out = np.empty(at.shape)
    for k, s0 in np.ndenumerate(s_at):
        m = np.abs(s - s0) <= half_width
        if np.count_nonzero(m) < 5:
            # Too few points in the window (a sparse measured profile): the 5 nearest.
            m = np.zeros(s.size, dtype=bool)
            m[np.argsort(np.abs(s - s0))[:5]] = True
        u = s[m] - s0
        cy = np.polyfit(u, y[m], 2)
        cz = np.polyfit(u, z[m], 2)
        dy, ddy = cy[1], 2.0 * cy[0]
        dz, ddz = cz[1], 2.0 * cz[0]
        out[k] = (dy * ddz - dz * ddy) / (dy * dy + dz * dz) ** 1.5
    return out


def surface_curvature(profile: Profile, at: np.ndarray, half_width: float = 2e-3) -> np.ndarray:
    """Transverse curvature of the surface (1/m) at lateral profile positions ``at``,
    positive where the body is convex toward its partner (Hertz's sign).

    A wheel's hollow (concave) tread is negative, a rail crown positive, a straight
    flange flank 0.
    """
    kappa = profile_curvature(profile.y, profile.z, at, half_width)
    return -kappa if profile.kind == "wheel" else kappa
