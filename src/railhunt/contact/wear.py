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

__all__ = ["MEASURED_LIKE", "WORN_S1002_COMMENT", "hollow_wear_depth", "hollow_worn",
           "measured_like", "worn_s1002", "write_measured_like"]

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


#: The measured-like worn wheels shipped in MiniProf format: file name -> (hollow depth,
#: band centre, band width) in m, and the seed of their measurement noise.
MEASURED_LIKE = {
    "worn_hollow_1mm.whl": (1.0e-3, 5e-3, 60e-3, 101),
    "worn_hollow_2mm.whl": (2.0e-3, 5e-3, 60e-3, 102),
}
#: RMS (m) of the measurement noise of :func:`measured_like`, normal to the profile.
MEASURED_NOISE = 5e-6
#: Point spacing (m of arc) of :func:`measured_like`, as a MiniProf gauge records.
MEASURED_SPACING = 0.25e-3


def measured_like(depth: float, centre: float, width: float, seed: int,
                  noise: float = MEASURED_NOISE, name: str = "") -> str:  # fmt: skip
    """A MiniProf wheel file (text) of a hollow-worn S1002 as a gauge would measure it.

    ``hollow_worn(s1002(), depth, centre, width)`` sampled every
    :data:`MEASURED_SPACING` of arc from its flange back to its field-side edge, each point
    moved normal to the profile by Gaussian noise of RMS ``noise`` (seeded), after a run of
    points down the wheel's back face (``X`` = 0 with the same noise, 15 mm below the
    tape line up to the flange), in MiniProf's axes and layout
    (:mod:`railhunt.contact.miniprof`). Generated, not measured: for examples and tests.
    """
    from railhunt.contact.miniprof import miniprof_text
    from railhunt.contact.profiles import s1002

    worn = hollow_worn(s1002(step=1e-5), depth, centre, width)
    seg = np.hypot(np.diff(worn.y), np.diff(worn.z))
    s = np.concatenate([[0.0], np.cumsum(seg)])
    at = np.arange(0.0, s[-1], MEASURED_SPACING)
    y, z = np.interp(at, s, worn.y), np.interp(at, s, worn.z)
    ty, tz = np.gradient(y), np.gradient(z)
    norm = np.hypot(ty, tz)
    rng = np.random.default_rng(seed)
    e = rng.normal(0.0, noise, y.size)
    y, z = y - e * tz / norm, z + e * ty / norm
    face = np.arange(-15e-3, z[0], MEASURED_SPACING)
    y_face = -0.070 + rng.normal(0.0, noise, face.size)
    comment = (f"railhunt: a measured-like worn wheel (generated, not measured): S1002 with "
               f"hollow wear depth {depth * 1e3:g} mm, centre {centre * 1e3:+g} mm, width "
               f"{width * 1e3:g} mm\nnoise {noise * 1e6:g} um RMS normal to the profile, "
               f"seed {seed}; railhunt.contact.wear.measured_like")  # fmt: skip
    return miniprof_text(np.concatenate([y_face, y]), np.concatenate([face, z]), "wheel",
                         name=name, comment=comment)  # fmt: skip


def write_measured_like(folder: str) -> list[str]:
    """Write the shipped measured-like wheels (:data:`MEASURED_LIKE`) into ``folder``."""
    from pathlib import Path

    paths = []
    for name, (depth, centre, width, seed) in MEASURED_LIKE.items():
        path = Path(folder) / name
        path.write_text(measured_like(depth, centre, width, seed, name=name), encoding="utf-8")
        paths.append(str(path))
    return paths
