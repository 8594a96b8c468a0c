"""Two-point bands: the lateral displacements at which a wheel touches its rail twice.

The rigid contact search (:func:`railhunt.contact_geometry`) finds the lowest point of each
wheel's gap function, the vertical distance between wheel and rail across the wheel.
Where that function has a second valley nearly as low, the wheel, pressed onto the rail by
its load, touches on two patches: the elastic approach of a loaded contact is a few
hundredths to a tenth of a millimetre. A wheel touches on two patches at a displacement
``y`` when its gap function has a second valley (local minimum) less than ``penetration``
(default 0.1 mm) above its lowest point, more than ``separation`` (default 1 mm) away from
it along the wheel. A *band* is a run of consecutive table displacements at which either
wheel does.

:func:`patch_count` is the one place that decides it, from a single gap function; a
contact routine that returns the patches themselves can take its place.
"""

from __future__ import annotations

import math

import numpy as np

from railhunt.contact.geometry import ContactGeometry, _Side
from railhunt.contact.profiles import Profile, ProfileError

__all__ = ["patch_count", "two_point_bands"]


def patch_count(gap: np.ndarray, wheel_y: np.ndarray, penetration: float = 1e-4,
                separation: float = 1e-3) -> int:  # fmt: skip
    """Number of patches of one wheel (module docstring): its lowest gap, and each other
    valley of the gap function less than ``penetration`` above it and more than
    ``separation`` away along the wheel.

    A valley is a point whose gap is the least within ``separation / 2`` along the wheel
    on either side (so that the ripples of a measured profile's flat tread do not count).

    Parameters
    ----------
    gap : numpy.ndarray
        Vertical gap (m) of each wheel point over the rail.
    wheel_y : numpy.ndarray
        Lateral profile coordinate (m) of each wheel point, evenly spaced, increasing.
    penetration : float
        Depth (m) within which a second valley touches too.
    separation : float
        Smallest distance (m) along the wheel between two patches.
    """
    from scipy.ndimage import minimum_filter1d

    step = float(wheel_y[1] - wheel_y[0])
    half = max(1, int(round(0.5 * separation / step)))
    low = minimum_filter1d(gap, 2 * half + 1, mode="nearest")
    valley = np.flatnonzero(gap[1:-1] <= low[1:-1]) + 1
    i0 = int(np.argmin(gap))
    near = gap[valley] < gap[i0] + penetration
    apart = np.abs(wheel_y[valley] - wheel_y[i0]) > separation
    others = np.sort(wheel_y[valley[near & apart]])
    # valleys of one flat stretch (equal gaps side by side) count once
    count = 1
    if others.size:
        count += 1 + int(np.count_nonzero(np.diff(others) > separation))
    return count


def two_point_bands(
    geometry: ContactGeometry, wheel: Profile, rail: Profile, *,
    penetration: float = 1e-4, separation: float = 1e-3, sample_step: float = 1e-5,
) -> list[tuple[float, float]]:  # fmt: skip
    """The bands of lateral displacement (m) where a wheel touches on two patches.

    Parameters
    ----------
    geometry : ContactGeometry
        The contact table of ``wheel`` on ``rail`` (its parameters and roll are used).
    wheel, rail : Profile
        The profiles it was computed from (the rail upright, as given to it).
    penetration, separation : float
        See :func:`patch_count` (m).
    sample_step : float
        Sampling step of the profiles (m), as in the contact search.

    Returns
    -------
    list of tuple
        ``(y_from, y_to)`` of each band (m, wheelset displacement, + left), in order; a
        symmetric wheelset has them in mirrored pairs.
    """
    for name, value, low, high in (("penetration", penetration, 1e-6, 1e-3),
                                   ("separation", separation, 1e-4, 0.02)):  # fmt: skip
        if not (math.isfinite(value) and low <= value <= high):
            raise ProfileError(f"{name} = {value!r} m is invalid: must be in [{low:g}, "
                               f"{high:g}] m")  # fmt: skip
    p = geometry.params
    from railhunt.contact.geometry import _gauge_point

    incl = float(p["rail_inclination"])
    rail_c = rail.inclined(incl) if incl else rail
    y_rail = 0.5 * p["gauge"] - _gauge_point(rail_c, p["gauge_depth"])
    y_tape = 0.5 * p["back_to_back"] + p["flange_back"]
    side = _Side(wheel, rail_c, y_tape, y_rail, p["r0"], sample_step)
    two = np.zeros(geometry.y.size, dtype=bool)
    for k, (y, roll) in enumerate(zip(geometry.y, geometry.roll, strict=True)):
        for sign in (1.0, -1.0):
            gap = side.gaps(float(y), -float(roll), sign)
            if patch_count(gap, side.wy, penetration, separation) > 1:
                two[k] = True
                break
    bands = []
    k = 0
    while k < two.size:
        if two[k]:
            j = k
            while j + 1 < two.size and two[j + 1]:
                j += 1
            bands.append((float(geometry.y[k]), float(geometry.y[j])))
            k = j + 1
        else:
            k += 1
    return bands
