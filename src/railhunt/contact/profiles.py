"""Wheel and rail cross-section profiles: file readers and the standard analytic profiles.

Profile coordinates (SI, metres), the same for wheels and rails:

* ``y`` lateral, positive toward the *field side* (away from the wheel's flange / the
  rail's gauge face, i.e. away from the track centre);
* ``z`` vertical, positive *downward*. For a wheel, ``z`` is the radius increase over
  the nominal rolling radius at the tape circle (``z = 0`` at ``y = 0``); for a rail it is
  the depth below the top of the (un-inclined) rail head.

The standard S1002 wheel (EN 13715, the piecewise polynomials and arcs of the standard's
sections A-H, coefficients as published with the standard) and the UIC60 / 60E1 rail head
(EN 13674-1: crown R300, R80, R13 corner, 1:20 head flank) are generated analytically.
Three file formats are read (:func:`read_profile`): SIMPACK profile files (``.prw``
wheel, ``.prr`` rail), whose header's unit factor, shifts, rotation and mirroring flags are
applied, which brings them into the convention above; MiniProf exports (``.whl`` wheel,
``.ban`` rail, :mod:`railhunt.contact.miniprof`), turned from MiniProf's axes (``X`` from
the flange back, ``Y`` up) into it and smoothed (:mod:`railhunt.contact.smoothing`); and
two-column ``y z`` text/CSV files (mm), already in it.
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np

__all__ = [
    "Profile",
    "ProfileError",
    "read_profile",
    "smoothed",
    "write_profile",
    "s1002",
    "shipped_profile",
    "normal_distance",
    "uic60",
]

#: Shipped profiles (name -> file in railhunt/data/profiles).
SHIPPED = {
    "S1002": "MBench_S1002_v3.prw",
    "UIC60": "MBench_UIC60_v3.prr",
    "S1002_worn": "worn_s1002.prw",
    "worn_hollow_1mm": "worn_hollow_1mm.whl",
    "worn_hollow_2mm": "worn_hollow_2mm.whl",
}


class ProfileError(ValueError):
    """An unreadable or invalid profile (file, values or parameters)."""


@dataclass(frozen=True)
class Profile:
    """A wheel or rail cross-section, SI units (see the module docstring for the axes).

    Parameters
    ----------
    y, z : numpy.ndarray
        Lateral and vertical coordinates (m), ``y`` strictly increasing.
    kind : {"wheel", "rail"}
        What the profile describes.
    name : str
        Label (file name or standard name).
    source : str
        Where the points come from.
    meta : dict
        Header values of a SIMPACK file (``type``, ``mirror.y``, ...) and the
        ``inclination`` applied, if any.
    """

    y: np.ndarray
    z: np.ndarray
    kind: str
    name: str = ""
    source: str = ""
    meta: dict = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        y = np.ascontiguousarray(self.y, dtype=np.float64)
        z = np.ascontiguousarray(self.z, dtype=np.float64)
        if self.kind not in ("wheel", "rail"):
            raise ProfileError(f"kind = {self.kind!r} is invalid: must be 'wheel' or 'rail'")
        if y.ndim != 1 or y.shape != z.shape or y.size < 4:
            raise ProfileError(
                f"profile {self.name!r}: y and z must be 1-D of equal length >= 4, "
                f"got shapes {y.shape} and {z.shape}"
            )
        if not (np.all(np.isfinite(y)) and np.all(np.isfinite(z))):
            raise ProfileError(f"profile {self.name!r}: coordinates must be finite")
        order = np.argsort(y, kind="stable")
        y, z = y[order], z[order]
        keep = np.concatenate([[True], np.diff(y) > 1e-9])
        object.__setattr__(self, "y", y[keep])
        object.__setattr__(self, "z", z[keep])

    def height(self, y: np.ndarray) -> np.ndarray:
        """``z`` at lateral positions ``y`` (m), by linear interpolation of the points."""
        return np.interp(y, self.y, self.z)

    def resampled(self, step: float = 1e-5) -> Profile:
        """The profile on a uniform ``y`` grid of ``step`` (m), by monotone cubic interpolation.

        PCHIP keeps the shape of measured points (no overshoot between them), so a finely
        sampled profile is smooth enough for slopes yet never rings.
        """
        from scipy.interpolate import PchipInterpolator

        if not (step > 0.0):
            raise ProfileError(f"step = {step!r} m is invalid: must be > 0")
        n = int(math.floor((self.y[-1] - self.y[0]) / step)) + 1
        yy = self.y[0] + step * np.arange(n)
        return Profile(yy, PchipInterpolator(self.y, self.z)(yy), self.kind, self.name,
                       self.source, dict(self.meta))

    def inclined(self, inclination: float) -> Profile:
        """A rail profile rotated by its inclination (cant) toward the track centre.

        Parameters
        ----------
        inclination : float
            Tangent of the cant angle, e.g. ``1/40`` (0 for none). The head leans toward
            the gauge side (negative ``y``); the top of the result is at ``z = 0``.
        """
        if self.kind != "rail":
            raise ProfileError("only rail profiles are inclined")
        if not (math.isfinite(inclination) and 0.0 <= inclination <= 0.1):
            raise ProfileError(
                f"rail_inclination = {inclination!r} is invalid: must be in [0, 0.1] "
                "(tangent of the cant angle, e.g. 1/40)"
            )
        th = math.atan(inclination)
        c, s = math.cos(th), math.sin(th)
        y = c * self.y + s * self.z
        z = -s * self.y + c * self.z
        z = z - z.min()
        return Profile(y, z, "rail", self.name, self.source,
                       {**self.meta, "inclination": inclination})


# --------------------------------------------------------------------------- readers


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?"


def read_profile(
    path: str | Path, kind: str | None = None, *, mirror_y: bool = False, repair: bool = False,
    smooth: float | str | None = None, flange_back: float = 0.070,
) -> Profile:
    """Read a profile file: SIMPACK ``.prw``/``.prr``, MiniProf ``.whl``/``.ban`` or two
    columns ``y z`` in mm.

    Parameters
    ----------
    path : str or pathlib.Path
        The file. SIMPACK files are recognised by ``point.begin``/``point.end``; MiniProf
        files by their extension, their first lines (``#MINIWHEELPROF``, ``MINIPROF``) or
        their header keywords (``ColumnDef=``, ``XYPoints=`` ...,
        :mod:`railhunt.contact.miniprof`); other files are read as whitespace-, comma- or
        semicolon-separated ``y z`` pairs in mm (lines starting with ``#``, ``!`` or
        ``%`` and non-numeric header lines skipped).
    kind : {"wheel", "rail"}, optional
        Default: from the SIMPACK header's ``type`` (1 wheel, 0 rail), a MiniProf file's
        ``#MINIWHEELPROF`` mark, or the extension (``.prw``/``.whe``/``.whl`` wheel,
        ``.prr``/``.rai``/``.ban`` rail).
    mirror_y : bool
        Mirror ``y`` (field side at negative ``y``); a MiniProf file's ``X`` is negated
        before it is put into railhunt's axes.
    repair : bool
        Sort the points of a profile whose ``y`` is not monotonic (with a warning naming
        the file and the first offending point) instead of refusing it; in a MiniProf
        file, drop the points that fold back.
    smooth : float or "auto", optional
        Smoothing-spline tolerance (m, RMS normal distance; 0 none; ``"auto"`` the noise
        estimated, :mod:`railhunt.contact.smoothing`). Default ``"auto"`` for MiniProf
        files, none for SIMPACK and text files.
    flange_back : float
        A MiniProf wheel's tape circle from its flange back (m), EN 13715: 70 mm.

    Returns
    -------
    Profile
        In metres, in the convention of the module docstring (smoothed: ``meta``'s
        ``smoothing`` and ``noise``, m).

    Raises
    ------
    ProfileError
        An unreadable file, points whose ``y`` goes back and forth (without ``repair``;
        the first named), a file that cannot be the profile it is given as
        (:mod:`.profile_checks`); a MiniProf file names its line (:mod:`.miniprof`).
    """
    from railhunt.contact import miniprof, profile_checks

    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig", errors="replace")
    except OSError as exc:
        raise ProfileError(f"profile file {str(path)!r} cannot be read: {exc}") from exc
    meta: dict = {}
    suffix = path.suffix.lower()
    measured = False
    if re.search(r"^\s*point\.begin", text, flags=re.MULTILINE):
        y, z, meta = _parse_simpack(text, str(path))
        if kind is None and "type" in meta:
            kind = "wheel" if int(meta["type"]) == 1 else "rail"
    elif miniprof.is_miniprof(text, suffix):
        measured = True
        if kind is None:
            kind = miniprof.EXTENSIONS.get(suffix)
        if kind is None and "#miniwheelprof" in text[:200].lower():
            kind = "wheel"
        if kind is None:
            raise ProfileError(f"profile file {str(path)!r} is a MiniProf file, but its "
                               f"extension {suffix!r} says not whether a wheel (.whl) or a "
                               "rail (.ban); pass kind='wheel' or kind='rail'")  # fmt: skip
        _check_kind(kind)
        try:
            y, z, meta = miniprof.parse_miniprof(text, kind, str(path), mirror_y=mirror_y,
                                                 repair=repair, flange_back=flange_back)
        except ValueError as exc:
            raise ProfileError(str(exc)) from None
        mirror_y = False  # applied to X above
    else:
        _checked(profile_checks.check_decimal_commas, text, str(path))
        y, z = _parse_columns(text, str(path))
        y, z = y * 1e-3, z * 1e-3
    if not measured:
        _check_monotonic(y, str(path), repair)
    if kind is None:
        if suffix in (".prw", ".whe"):
            kind = "wheel"
        elif suffix in (".prr", ".rai"):
            kind = "rail"
        else:
            raise ProfileError(
                f"profile file {str(path)!r}: kind cannot be inferred from the extension "
                f"{suffix!r}; pass kind='wheel' or kind='rail'"
            )
    _check_kind(kind)
    _checked(profile_checks.check_kind, meta, kind, str(path))
    _checked(profile_checks.check_shape, y, z, kind, str(path))
    if mirror_y:
        y = -y
    profile = Profile(y, z, kind, path.name, str(path), meta)
    if smooth is None:
        smooth = "auto" if measured else 0.0
    return smoothed(profile, smooth, str(path)) if smooth != 0.0 else profile


def _check_kind(kind: str) -> None:  # noqa: D103 - a kind's check
    if kind not in ("wheel", "rail"):
        raise ProfileError(f"kind = {kind!r} is invalid: must be 'wheel' or 'rail'")


def smoothed(profile: Profile, tolerance: float | str = "auto", where: str = "") -> Profile:
    """The profile smoothed by a cubic smoothing spline, sampled every 0.1 mm
    (:func:`railhunt.contact.smoothing.smooth_profile_points`: ``tolerance`` in m, or
    ``"auto"``); ``meta["smoothing"]`` the tolerance used, ``meta["noise"]`` the noise
    estimated (m)."""
    from railhunt.contact.smoothing import smooth_profile_points

    try:
        y, z, used, noise = smooth_profile_points(profile.y, profile.z, profile.kind,
                                                  tolerance, where or profile.name)
    except ValueError as exc:
        raise ProfileError(str(exc)) from None
    meta = {**profile.meta, "smoothing": used, "noise": noise}
    return Profile(y, z, profile.kind, profile.name, profile.source, meta)


def _checked(check, *args) -> None:  # noqa: ANN001 - a check of profile_checks
    """Run a check of :mod:`railhunt.contact.profile_checks`, its refusal a ProfileError."""
    try:
        check(*args)
    except ValueError as exc:
        raise ProfileError(str(exc)) from None


def write_profile(profile: Profile, path: str | Path, comment: str = "") -> Path:
    """Write a profile as a SIMPACK file (``.prw``/``.prr``), a MiniProf file
    (``.whl``/``.ban``) or two columns ``y z`` in mm.

    The inverse of :func:`read_profile`: reading the file back gives the same points to
    1e-10 m, in the convention of the module docstring (no shift, rotation or mirroring);
    a MiniProf file's points are written as MiniProf writes them, with four decimals in
    mm (0.05 um), in MiniProf's axes (:func:`railhunt.contact.miniprof.miniprof_text`,
    the tape circle 70 mm from the flange back); read it back with ``smooth=0`` for the
    same points.

    Parameters
    ----------
    profile : Profile
        The profile (SI).
    path : str or pathlib.Path
        The file: ``.prw`` or ``.prr`` for SIMPACK format (the header's ``type`` from
        ``profile.kind``), any other suffix for two whitespace-separated columns in mm.
    comment : str
        Lines written at the top of the file as ``!`` (SIMPACK) or ``#`` comments.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    path = Path(path)
    if path.suffix.lower() in (".whl", ".ban"):
        from railhunt.contact.miniprof import miniprof_text

        path.write_text(miniprof_text(profile.y, profile.z, profile.kind, name=path.name,
                                      comment=comment), encoding="utf-8")  # fmt: skip
        return path
    simpack = path.suffix.lower() in (".prw", ".prr")
    mark = "!" if simpack else "#"
    lines = [f"{mark} {line}".rstrip() for line in comment.splitlines()]
    points = [f"{y:+.7f} {z:+.7f}" for y, z in zip(profile.y * 1e3, profile.z * 1e3, strict=True)]
    if simpack:
        lines += ["  header.begin", "    version = 1",
                  f"    type = {1 if profile.kind == 'wheel' else 0}"
                  "    ! 0=rail profile, 1=wheel profile", "  header.end",
                  "  spline.begin", "    units.len.f = +1.000000000000000e+03   ! mm",
                  "    mirror.y = 0", "    mirror.z = 0", "    point.begin",
                  "    ! y (mm), positive toward the field side   z (mm), positive downward",
                  *points, "    point.end", "  spline.end"]  # fmt: skip
    else:
        lines += [f"# {profile.kind} profile: y (mm, positive toward the field side), "
                  "z (mm, positive downward)", *points]  # fmt: skip
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _check_monotonic(y: np.ndarray, where: str, repair: bool) -> None:
    """Refuse (or, with ``repair``, warn about) points whose ``y`` goes back and forth.

    Points may run either way (rising or falling ``y``; repeats are dropped later); the
    first point against the direction of the first step is named (1-based, in the order
    of the file's points).
    """
    d = np.diff(y)
    steps = d[d != 0.0]
    if steps.size == 0:
        return
    direction = np.sign(steps[0])
    against = np.flatnonzero(np.sign(d) == -direction)
    if against.size == 0:
        return
    k = int(against[0]) + 1  # 0-based index of the point out of order
    way = "rising" if direction > 0 else "falling"
    text = (f"profile file {where!r}: y is not monotonic: point {k + 1} (y = {y[k] * 1e3:.4g} "
            f"mm) goes back from point {k} (y = {y[k - 1] * 1e3:.4g} mm) while y was {way}")
    if not repair:
        raise ProfileError(text + "; fix the file, or read it with repair=True to sort the "
                           "points")  # fmt: skip
    warnings.warn(text + "; the points were sorted by y (repair=True)", stacklevel=3)


def _parse_columns(text: str, where: str) -> tuple[np.ndarray, np.ndarray]:
    rows = []
    for line in text.splitlines():
        s = line.strip()
        if not s or s[0] in "#!%":
            continue
        parts = [p for p in re.split(r"[,;\s]+", s) if p]
        try:
            values = [float(p) for p in parts[:2]]
        except ValueError:
            continue
        if len(values) == 2:
            rows.append(values)
    if len(rows) < 4:
        raise ProfileError(f"profile file {where!r}: fewer than 4 numeric 'y z' rows found")
    arr = np.array(rows)
    return arr[:, 0], arr[:, 1]


def _parse_simpack(text: str, where: str) -> tuple[np.ndarray, np.ndarray, dict]:
    meta: dict[str, float] = {}
    in_points = False
    section = ""
    rows = []
    for line in text.splitlines():
        s = line.split("!", 1)[0].strip()
        if not s:
            continue
        if s.endswith(".begin") and s != "point.begin":
            section = s[: -len(".begin")]
            continue
        if s.endswith(".end") and s != "point.end":
            section = ""
            continue
        if s.startswith("point.begin"):
            in_points = True
            continue
        if s.startswith("point.end"):
            in_points = False
            continue
        if in_points:
            parts = re.findall(_NUMBER, s)
            if len(parts) >= 2:
                rows.append([float(parts[0].replace("d", "e").replace("D", "e")),
                             float(parts[1].replace("d", "e").replace("D", "e"))])
            continue
        m = re.match(r"^([A-Za-z_.]+)\s*=\s*(" + _NUMBER + r")\s*$", s)
        if m:
            key = "type" if (section == "header" and m.group(1) == "type") else m.group(1)
            if m.group(1) == "type" and section != "header":
                key = section + ".type"
            meta[key] = float(m.group(2).replace("d", "e").replace("D", "e"))
    if len(rows) < 4:
        raise ProfileError(f"profile file {where!r}: fewer than 4 points between "
                           "point.begin and point.end")
    pts = np.array(rows)
    y, z = pts[:, 0].copy(), pts[:, 1].copy()
    # SIMPACK processing order: shift, rotate, mirror; lengths in user units.
    y += meta.get("shift.y", 0.0)
    z += meta.get("shift.z", 0.0)
    ang = meta.get("rotate", 0.0) / meta.get("units.ang.f", 1.0)
    if ang:
        c, s_ = math.cos(ang), math.sin(ang)
        y, z = c * y - s_ * z, s_ * y + c * z
    if int(meta.get("mirror.y", 0)) == 1:
        y = -y
    if int(meta.get("mirror.z", 0)) == 1:
        z = -z
    factor = meta.get("units.len.f", 1000.0)  # user length units per metre
    if not (factor > 0):
        raise ProfileError(f"profile file {where!r}: units.len.f = {factor!r} must be > 0")
    return y / factor, z / factor, meta


def shipped_profile(name: str) -> Profile:
    """A profile shipped with railhunt: ``"S1002"`` (wheel), ``"UIC60"`` (rail, as filed) or
    ``"S1002_worn"`` (S1002 with 2 mm of hollow wear, :func:`railhunt.contact.wear.worn_s1002`).

    The files are the Manchester contact benchmark's profiles (from the examples of the
    CONTACT library by E. Vollebregt, Apache License 2.0). Note that the UIC60 file is
    *already inclined 1:40* (see :func:`uic60` and ``docs/contact.md``).
    """
    if name not in SHIPPED:
        raise ProfileError(f"no shipped profile named {name!r}; available: {sorted(SHIPPED)}")
    ref = resources.files("railhunt") / "data" / "profiles" / SHIPPED[name]
    with resources.as_file(ref) as path:
        return read_profile(path)


# --------------------------------------------------------------------------- S1002

# EN 13715 S1002, sections A (field side) ... H (flange back); S in mm from the tape
# circle, positive toward the field side; F(S) in mm, positive downward (larger radius).
_S1002_BOUNDS = (-70.0, -62.764705882, -49.662510381, -39.764473993, -38.426669071,
                 -35.0, -26.0, 32.15796, 60.0)
_B = (0.0, -3.358537058e-02, 1.565681624e-03, -2.810427944e-05, 5.844240864e-08,
      -1.562379023e-08, 5.309217349e-15, -5.957839843e-12, 2.646656573e-13)
_C = (-4.320221063e03, -1.038384026e03, -1.065501873e02, -6.051367875,
      -2.054332446e-01, -4.169739389e-03, -4.687195829e-05, -2.252755540e-07)


def _s1002_mm(s: np.ndarray) -> np.ndarray:
    s = np.asarray(s, dtype=np.float64)
    b = _S1002_BOUNDS
    out = np.full(s.shape, np.nan)

    def arc(a: float, r: float, c: float, x: np.ndarray, sign: float) -> np.ndarray:
        return a + sign * np.sqrt(np.maximum(r * r - (x + c) ** 2, 0.0))

    sections = [
        (b[0], b[1], lambda x: arc(9.519259302, 20.5, 49.5, x, 1.0)),        # H
        (b[1], b[2], lambda x: arc(16.0, 12.0, 55.0, x, 1.0)),               # G
        (b[2], b[3], lambda x: arc(8.834924130, 20.0, 58.558326413, x, 1.0)),  # F
        (b[3], b[4], lambda x: -93.576667419 - 2.747477419 * x),             # E
        (b[4], b[5], lambda x: arc(16.446, 13.0, 26.210665, x, -1.0)),       # D
        (b[5], b[6], lambda x: np.polynomial.polynomial.polyval(x, _C)),     # C
        (b[6], b[7], lambda x: np.polynomial.polynomial.polyval(x, _B)),     # B
        (b[7], b[8], lambda x: 1.364323640 - 0.066666667 * x),               # A
    ]
    for lo, hi, f in sections:
        m = (s >= lo) & (s <= hi)
        out[m] = f(s[m])
    return out


def s1002(step: float = 1e-4, y_min: float = -0.070, y_max: float = 0.060) -> Profile:
    """The S1002 wheel profile of EN 13715, generated from its analytic sections.

    Parameters
    ----------
    step : float
        Sampling step in ``y`` (m).
    y_min, y_max : float
        Range (m) within the standard's ``[-0.070, 0.060]`` (flange back to outer edge).

    Returns
    -------
    Profile
        Wheel profile, ``y = 0`` at the tape circle, flange at negative ``y``.
    """
    if not (-0.070 <= y_min < y_max <= 0.060):
        raise ProfileError(
            f"y range [{y_min!r}, {y_max!r}] m is invalid: must lie in [-0.070, 0.060]"
        )
    n = int(round((y_max - y_min) / step)) + 1
    y = np.linspace(y_min, y_max, n)
    z = _s1002_mm(y * 1e3) * 1e-3
    return Profile(y, z, "wheel", "S1002", "EN 13715 analytic sections")


# --------------------------------------------------------------------------- UIC60

#: 60E1 (UIC60) head geometry, mm: crown radius, its half-width, corner radii, head
#: half-width at the flank tangent point, flank inclination.
UIC60_GEOMETRY = {
    "R_crown": 300.0,
    "crown_half_width": 10.5,
    "R_shoulder": 80.0,
    "R_corner": 13.0,
    "head_half_width": 36.0,
    "flank_inclination": 1.0 / 20.0,
}


def _uic60_half_mm(depth_max: float, step: float) -> tuple[np.ndarray, np.ndarray]:
    """One half (y >= 0) of the un-inclined 60E1 head, mm, z downward from the top."""
    g = UIC60_GEOMETRY
    r1, r2, r3 = g["R_crown"], g["R_shoulder"], g["R_corner"]
    beta = math.atan(g["flank_inclination"])  # flank angle from the vertical
    # Crown R300: centre (0, r1); ends where y = crown_half_width.
    a1 = math.asin(g["crown_half_width"] / r1)
    c2 = ((r1 - r2) * math.sin(a1), r1 - (r1 - r2) * math.cos(a1))  # R80 centre
    # R13 centre: on the circle of radius r2 - r3 about c2, at lateral distance
    # head_half_width - r3*cos(beta) from the axis (flank tangent point at y = 36).
    yc3 = g["head_half_width"] - r3 * math.cos(beta)
    a2 = math.asin((yc3 - c2[0]) / (r2 - r3))
    c3 = (yc3, c2[1] - (r2 - r3) * math.cos(a2))
    a3 = math.pi / 2 - beta  # tangent angle at the flank
    ys, zs = [], []

    def arc(cy: float, cz: float, r: float, t0: float, t1: float) -> None:
        n = max(int(math.ceil(r * (t1 - t0) / step)), 2)
        t = np.linspace(t0, t1, n)
        ys.append(cy + r * np.sin(t))
        zs.append(cz - r * np.cos(t))

    arc(0.0, r1, r1, 0.0, a1)
    arc(c2[0], c2[1], r2, a1, a2)
    arc(c3[0], c3[1], r3, a2, a3)
    # Flank: straight line from the R13 tangent point, inclination 1:20 outward downward.
    y0, z0 = c3[0] + r3 * math.sin(a3), c3[1] - r3 * math.cos(a3)
    if depth_max > z0:
        n = max(int(math.ceil((depth_max - z0) / step)), 2)
        zz = np.linspace(z0, depth_max, n)
        ys.append(y0 + (zz - z0) * math.tan(beta))
        zs.append(zz)
    return np.concatenate(ys), np.concatenate(zs)


def uic60(inclination: float = 0.0, depth_max: float = 0.035, step: float = 1e-4) -> Profile:
    """The UIC60 (60E1) rail head built from its arcs, optionally inclined.

    Crown R300 over ``|y| <= 10.5 mm``, R80 shoulders, R13 gauge corners tangent to the
    1:20 head flanks whose tangent points are 72 mm apart (EN 13674-1 60E1).

    Parameters
    ----------
    inclination : float
        Rail cant (tangent), e.g. ``1/40``; 0 for an upright rail.
    depth_max : float
        Lowest point of the flanks generated, m below the top.
    step : float
        Point spacing (m).

    Returns
    -------
    Profile
        Rail profile, top at ``z = 0``, gauge side at negative ``y``.
    """
    if not (0.015 <= depth_max <= 0.045):
        raise ProfileError(f"depth_max = {depth_max!r} m is invalid: must be in [0.015, 0.045]")
    y, z = _uic60_half_mm(depth_max * 1e3, step * 1e3)
    y = np.concatenate([-y[::-1], y[1:]]) * 1e-3
    z = np.concatenate([z[::-1], z[1:]]) * 1e-3
    rail = Profile(y, z, "rail", "UIC60", "EN 13674-1 60E1 head arcs")
    return rail.inclined(inclination) if inclination else rail


def normal_distance(points_y: np.ndarray, points_z: np.ndarray, curve: Profile) -> np.ndarray:
    """Distance (m) from each point to the polyline of ``curve`` (shortest, not vertical)."""
    py = np.asarray(points_y, dtype=np.float64)[:, None]
    pz = np.asarray(points_z, dtype=np.float64)[:, None]
    ay, az = curve.y[:-1][None, :], curve.z[:-1][None, :]
    dy, dz = np.diff(curve.y)[None, :], np.diff(curve.z)[None, :]
    t = np.clip(((py - ay) * dy + (pz - az) * dz) / (dy * dy + dz * dz), 0.0, 1.0)
    d = np.hypot(ay + t * dy - py, az + t * dz - pz)
    return d.min(axis=1)
