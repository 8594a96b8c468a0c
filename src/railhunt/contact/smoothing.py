"""Smoothing a measured profile: a cubic smoothing spline with a stated tolerance.

A measured profile carries the gauge's noise, a few micrometres to a few hundredths of a
millimetre. Its slope (the contact angle) shrugs that off, but its curvature, which sets
the Hertz ellipse of every contact point, does not: a second difference of points 0.3 mm
apart turns 10 um of noise into curvature noise of the order of 0.2 /mm, a hundred times a
tread's own. So a measured profile is smoothed before it is used.

:func:`smooth_points` fits the cubic smoothing spline ``z(y)`` (FITPACK, as
:class:`scipy.interpolate.UnivariateSpline`) of least curvature whose weighted residual

    sum_i (w_i (z_i - s(y_i)))^2 <= n tolerance^2,   w_i = cos(theta_i),

stays within the tolerance: ``w_i`` turns the vertical residual into the distance normal
to the profile (``theta_i`` the profile's inclination at the point), so ``tolerance`` is
the RMS normal distance between the points and the smoothed profile, the same on the tread
as on a 70-degree flange. By default the tolerance is the noise estimated from the points
themselves (:func:`noise_estimate`): the smoothing takes out what the gauge added, no
more. The smoothed profile is sampled on a uniform grid of :data:`STEP`.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["MIN_TOLERANCE", "STEP", "noise_estimate", "smooth_points", "smooth_profile_points"]

#: Smallest tolerance (m) used: below it a file's rounding (0.1 um) is all there is.
MIN_TOLERANCE = 0.5e-6
#: Largest tolerance (m) accepted: more would smooth away the profile itself.
MAX_TOLERANCE = 0.2e-3
#: Sampling step (m) of a smoothed profile.
STEP = 0.1e-3


def _inclination(y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """cos(theta) of the profile at each point, from the chord of its neighbours."""
    slope = np.gradient(z, y)
    return 1.0 / np.sqrt(1.0 + slope * slope)


def noise_estimate(y: np.ndarray, z: np.ndarray) -> float:
    """The points' noise (m, RMS normal to the profile), robustly from their scatter.

    Each inner point's normal distance from the chord of its two neighbours is, for white
    noise of RMS ``sigma`` on evenly spaced points, of RMS ``sigma sqrt(3/2)``, while a
    smooth profile sampled every few tenths of a millimetre contributes well under 1 um.
    The median absolute value of those distances (1.4826 times it, the RMS of a normal
    distribution), over ``sqrt(3/2)``, is the estimate; the median ignores the kinks of a
    profile's sections and a few spikes.
    """
    y = np.asarray(y, dtype=np.float64)
    z = np.asarray(z, dtype=np.float64)
    if y.size < 5:
        return 0.0
    dy0, dy1 = y[1:-1] - y[:-2], y[2:] - y[1:-1]
    t = dy0 / (dy0 + dy1)
    chord = (1.0 - t) * z[:-2] + t * z[2:]
    slope = (z[2:] - z[:-2]) / (y[2:] - y[:-2])
    dist = (z[1:-1] - chord) / np.sqrt(1.0 + slope * slope)
    return float(1.4826 * np.median(np.abs(dist)) / math.sqrt(1.5))


def smooth_points(
    y: np.ndarray, z: np.ndarray, tolerance: float | None = None, step: float = STEP
) -> tuple[np.ndarray, np.ndarray, float]:
    """The smoothing spline of a profile's points, sampled every ``step`` (module docstring).

    Parameters
    ----------
    y, z : numpy.ndarray
        The points (m), ``y`` strictly increasing.
    tolerance : float, optional
        RMS normal distance (m) allowed between the points and the smoothed profile, in
        ``[0, 0.2 mm]``; default :func:`noise_estimate` (at least :data:`MIN_TOLERANCE`).
    step : float
        Sampling step (m) of the result.

    Returns
    -------
    tuple
        ``(y, z, tolerance)``: the smoothed profile's points and the tolerance used.
    """
    from scipy.interpolate import UnivariateSpline

    y = np.asarray(y, dtype=np.float64)
    z = np.asarray(z, dtype=np.float64)
    if tolerance is None:
        tolerance = max(noise_estimate(y, z), MIN_TOLERANCE)
    if not (math.isfinite(tolerance) and 0.0 <= tolerance <= MAX_TOLERANCE):
        raise ValueError(f"smoothing tolerance = {tolerance!r} m is invalid: must be in "
                         f"[0, {MAX_TOLERANCE:g}] m (the RMS normal distance from the "
                         "points)")  # fmt: skip
    w = _inclination(y, z)
    # Scaled to mm so that FITPACK's tolerances see numbers of order one.
    spline = UnivariateSpline(y * 1e3, z * 1e3, w=w, k=3,
                              s=y.size * (tolerance * 1e3) ** 2)  # fmt: skip
    n = int(math.floor((y[-1] - y[0]) / step + 1e-9)) + 1
    yy = y[0] + step * np.arange(n)
    if yy[-1] < y[-1] - 1e-9:
        yy = np.append(yy, y[-1])
    return yy, spline(yy * 1e3) * 1e-3, float(tolerance)


def smooth_profile_points(
    y: np.ndarray, z: np.ndarray, kind: str, tolerance: float | str = "auto", where: str = ""
) -> tuple[np.ndarray, np.ndarray, float, float]:
    """:func:`smooth_points` for a wheel or rail profile: ``tolerance`` a float (m) or
    ``"auto"``; a wheel's ``z`` referred again to its tape circle (``z = 0`` at ``y = 0``),
    a rail's to its top. Returns ``(y, z, tolerance used, noise estimated)``; a
    ``ValueError`` names ``where``."""
    if isinstance(tolerance, str):
        if tolerance != "auto":
            raise ValueError(f"profile {where!r}: smooth = {tolerance!r} is invalid: must be "
                             "'auto' or a tolerance in m")  # fmt: skip
        tolerance = None
    elif isinstance(tolerance, bool) or not isinstance(tolerance, int | float):
        raise ValueError(f"profile {where!r}: smooth = {tolerance!r} is invalid: must be "
                         "'auto' or a tolerance in m")  # fmt: skip
    noise = noise_estimate(y, z)
    try:
        ys, zs, used = smooth_points(y, z, tolerance)
    except ValueError as exc:
        raise ValueError(f"profile {where!r}: {exc}") from None
    if not np.all(np.isfinite(zs)):
        raise ValueError(f"profile {where!r}: its smoothing spline is not finite: are its "
                         "points one profile?")  # fmt: skip
    if kind == "wheel" and ys[0] <= 0.0 <= ys[-1]:
        zs = zs - np.interp(0.0, ys, zs)
    elif kind == "rail":
        zs = zs - zs.min()
    return ys, zs, used, noise
