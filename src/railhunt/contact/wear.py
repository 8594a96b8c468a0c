"""Hollow tread wear: a worn wheel profile from a new one, by a stated wear model.

In service the wheel wears most where it runs most, a band of the tread around the tape
circle. The tread becomes concave ("hollow"), a "false flange" rises at the field side, and
the rolling-radius difference grows faster with the lateral displacement: the equivalent
conicity rises, and with it the hunting frequency, while the critical speed falls.

The model (:func:`hollow_worn`) removes material radially, with the depth

    d(y) = h cos^2(pi (y - c) / w)   for |y - c| <= w / 2,   0 elsewhere,

``h`` the hollow depth, ``c`` the centre of the worn band (positive toward the field side,
from the tape circle) and ``w`` its width. The band is smooth: its depth and slope are zero
at both edges, so the worn profile keeps a continuous slope. The profile is then referred
again to its tape circle (``z = 0`` at ``y = 0``): the worn wheel's radius measured there is
the new radius less ``d(0)``. This is an engineering idealisation for studies (a measured
worn profile is read with :func:`railhunt.read_profile`), not a wear law: it says how deep
and where, not how many kilometres.
"""

from __future__ import annotations

import math

import numpy as np

from railhunt.contact.profiles import Profile, ProfileError

__all__ = ["WORN_S1002_COMMENT", "hollow_wear_depth", "hollow_worn", "worn_s1002"]

#: Header of the shipped ``railhunt/data/profiles/worn_s1002.prw`` (see :func:`worn_s1002`).
WORN_S1002_COMMENT = """\
railhunt: S1002 wheel with hollow tread wear (a generated profile, not a measurement)
new profile: EN 13715 S1002 from its analytic sections, railhunt.s1002(step=0.25 mm)
wear model: railhunt.contact.wear.hollow_worn(depth=2 mm, centre=+5 mm, width=60 mm):
  d(y) = h cos^2(pi (y - c) / w) for |y - c| <= w / 2, removed radially;
  z referred again to the tape circle (the worn radius there is the new one less 1.866 mm)
licence: MIT, as railhunt; regenerate with railhunt.contact.wear.worn_s1002(path)"""


def hollow_wear_depth(y: np.ndarray, depth: float, centre: float, width: float) -> np.ndarray:
    """Depth of material removed (m) at lateral profile coordinates ``y`` (m)."""
    u = (np.asarray(y, dtype=np.float64) - centre) / width
    return np.where(np.abs(u) <= 0.5, depth * np.cos(math.pi * u) ** 2, 0.0)


def hollow_worn(
    wheel: Profile, depth: float = 2e-3, centre: float = 5e-3, width: float = 60e-3
) -> Profile:
    """The wheel profile after hollow tread wear (module docstring).

    Parameters
    ----------
    wheel : Profile
        New wheel profile (``kind="wheel"``), e.g. :func:`railhunt.s1002`.
    depth : float
        Hollow depth ``h`` (m), in [0, 0.005]: the largest depth of material removed.
    centre : float
        Centre ``c`` of the worn band (m), positive toward the field side, in [-0.02, 0.03].
    width : float
        Width ``w`` of the worn band (m), in [0.01, 0.09].

    Returns
    -------
    Profile
        The worn profile, ``z = 0`` at ``y = 0`` (the tape circle), named
        ``"<name> hollow-worn <h> mm"``.
    """
    if wheel.kind != "wheel":
        raise ProfileError(f"hollow wear applies to wheel profiles, not to a {wheel.kind}")
    for name, value, low, high in (("depth", depth, 0.0, 0.005),
                                   ("centre", centre, -0.02, 0.03),
                                   ("width", width, 0.01, 0.09)):  # fmt: skip
        if not (math.isfinite(value) and low <= value <= high):
            raise ProfileError(f"{name} = {value!r} m is invalid: must be in [{low:g}, {high:g}] m")
    z = wheel.z - hollow_wear_depth(wheel.y, depth, centre, width)
    z = z - np.interp(0.0, wheel.y, z)
    meta = {"hollow_depth": depth, "hollow_centre": centre, "hollow_width": width}
    return Profile(wheel.y, z, "wheel", f"{wheel.name} hollow-worn {depth * 1e3:g} mm",
                   f"{wheel.source}; hollow wear (railhunt.contact.wear.hollow_worn, "
                   f"h = {depth * 1e3:g} mm, c = {centre * 1e3:g} mm, w = {width * 1e3:g} mm)",
                   meta)  # fmt: skip


def worn_s1002(path: str | None = None) -> Profile:
    """The shipped worn wheel: S1002 with 2 mm of hollow wear, and its file.

    ``hollow_worn(s1002(step=0.25 mm))`` with the defaults (depth 2 mm, band centre 5 mm
    toward the field side, width 60 mm). With ``path``, also written there as the SIMPACK
    file shipped as ``railhunt/data/profiles/worn_s1002.prw`` (header
    :data:`WORN_S1002_COMMENT`); the tests check that the shipped file is this output.
    """
    from railhunt.contact.profiles import s1002, write_profile

    worn = hollow_worn(s1002(step=2.5e-4))
    if path is not None:
        write_profile(worn, path, WORN_S1002_COMMENT)
    return worn
