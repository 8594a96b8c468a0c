"""Rigid wheel/rail contact geometry of a wheelset on straight track, from profiles.

For each lateral wheelset displacement ``y`` the wheelset is lowered onto the rails and
rolled (about the track's longitudinal axis) until *both* wheels touch their rails:
the vertical gap between each wheel and its rail, minimised over the lateral position,
is zero on both sides. At a touching configuration the minimum of the vertical gap lies
where wheel and rail are tangent, so the gap minimum is the rigid contact point (exact
for rigid bodies, any contact angle below 90 degrees). Wheelset yaw is neglected (the
usual 2-D contact table of vehicle dynamics).

Track frame: ``Y`` lateral, positive to the left; ``Z`` upward. A wheelset displaced by
``y > 0`` moves toward the left rail, so the left wheel runs toward its flange:
``r_L`` grows and ``delta_r = r_L - r_R > 0``. The reported roll follows the model's body
roll (``docs/model.md``): positive when a point above the axle moves toward +y, i.e. when
the left wheel *drops*; a wheelset displaced to the left lifts its left wheel (larger
radius), so there ``roll < 0``. (Internally the search works with the opposite angle,
positive when the left wheel rises.)
Contact angles ``delta_L``, ``delta_R`` are the inclinations of the contact planes,
positive when the contact normal on the wheel leans toward the track centre (the usual
tread and flange case), as in the paper's Eq. 33.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from railhunt.contact.conicity import ConicityError, equivalent_conicity
from railhunt.contact.curvature import surface_curvature
from railhunt.contact.profiles import Profile, ProfileError, s1002, uic60
from railhunt.results import Columns, ResultDisplay, Row

__all__ = ["ContactGeometry", "contact_geometry", "default_profiles"]

_NO_RAIL = 1.0  # depth (m) assigned outside the rail's lateral range: never in contact


@dataclass(frozen=True, repr=False)
class ContactGeometry(ResultDisplay):
    """Contact geometry of a wheelset versus its lateral displacement (SI units).

    Attributes
    ----------
    y : numpy.ndarray
        Lateral wheelset displacement (m), positive to the left.
    r_left, r_right : numpy.ndarray
        Rolling radii (m).
    delta_left, delta_right : numpy.ndarray
        Contact angles (rad).
    roll : numpy.ndarray
        Wheelset roll angle (rad), the model's sign: positive when the left wheel drops
        (a point above the axle moves toward +y); negative for ``y > 0``.
    contact_left, contact_right : numpy.ndarray, shape (n, 2)
        Contact points in the track frame, ``(Y, Z)`` (m).
    wheel_left, wheel_right, rail_left, rail_right : numpy.ndarray
        Lateral profile coordinate (m) of the contact point on each wheel and rail
        profile (profile axes: positive toward the field side).
    jump : numpy.ndarray of bool
        True where the contact point on either wheel jumps (two-point contact between
        this ``y`` and the previous one).
    r0 : float
        Nominal rolling radius (m) (wheel radius at the tape circle).
    params : dict
        Track/wheelset parameters used.
    wheel_curvature_left, wheel_curvature_right : numpy.ndarray or None
        Transverse curvature of each wheel's surface at its contact point (1/m), Hertz's
        sign: positive convex, negative for a hollow tread, 0 on a straight flank
        (:func:`railhunt.contact.curvature.surface_curvature`, smoothed over +-2 mm of
        arc).
    rail_curvature_left, rail_curvature_right : numpy.ndarray or None
        The same for each rail (the crown positive).
    """

    y: np.ndarray
    r_left: np.ndarray
    r_right: np.ndarray
    delta_left: np.ndarray
    delta_right: np.ndarray
    roll: np.ndarray
    contact_left: np.ndarray
    contact_right: np.ndarray
    wheel_left: np.ndarray
    wheel_right: np.ndarray
    rail_left: np.ndarray
    rail_right: np.ndarray
    jump: np.ndarray
    r0: float
    params: dict = field(default_factory=dict)
    wheel_curvature_left: np.ndarray | None = None
    wheel_curvature_right: np.ndarray | None = None
    rail_curvature_left: np.ndarray | None = None
    rail_curvature_right: np.ndarray | None = None

    @property
    def delta_r(self) -> np.ndarray:
        """Rolling-radius difference ``r_L - r_R`` (m)."""
        return self.r_left - self.r_right

    @property
    def contact_distance(self) -> np.ndarray:
        """Lateral distance between the two contact points (m)."""
        return self.contact_left[:, 0] - self.contact_right[:, 0]

    def flange_contact_y(self, angle: float = math.radians(45.0)) -> tuple[float, float]:
        """Smallest ``|y|`` (m) at which a contact angle exceeds ``angle``, per side.

        Returns ``(y_left, y_right)`` (positive and negative ``y``); ``nan`` if not reached.
        """
        yl = self.y[(self.y > 0) & (self.delta_left > angle)]
        yr = self.y[(self.y < 0) & (self.delta_right > angle)]
        return (float(yl.min()) if yl.size else math.nan,
                float(yr.max()) if yr.size else math.nan)

    def _summary(self) -> list[Row]:
        try:
            conicity: float | str = equivalent_conicity(self.y, self.delta_r, 3e-3)
        except ConicityError as exc:
            conicity = f"not defined ({exc})"
        centre = int(np.argmin(np.abs(self.y)))
        flange = self.flange_contact_y()
        return [("wheel / rail", f"{self.params.get('wheel', '?')} / "
                 f"{self.params.get('rail', '?')}", ""),
                ("lateral displacement", f"{self.y[0] * 1e3:.4g} to {self.y[-1] * 1e3:.4g}",
                 "mm"),
                ("points", self.y.size, ""),
                ("rolling radius, centred", float(self.r_left[centre]), "m"),
                ("equivalent conicity at 3 mm (EN 15302 B)", conicity, ""),
                ("flange contact from y", f"{flange[0] * 1e3:+.1f}, {flange[1] * 1e3:+.1f}", "mm"),
                ("contact-point jumps", int(np.count_nonzero(self.jump)), "")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row per lateral displacement ``y``."""
        return {"y": (self.y, "m"), "r_left": (self.r_left, "m"), "r_right": (self.r_right, "m"),
                "delta_r": (self.delta_r, "m"), "delta_left": (self.delta_left, "rad"),
                "delta_right": (self.delta_right, "rad"), "roll": (self.roll, "rad"),
                "jump": (self.jump, "")}  # fmt: skip


def default_profiles() -> tuple[Profile, Profile]:
    """The analytic S1002 wheel and upright UIC60 rail (the CLI's defaults)."""
    return s1002(step=1e-5), uic60(0.0, step=1e-5)


class _Side:
    """Wheel and rail of one side, pre-sampled (left side; the right is its mirror)."""

    def __init__(self, wheel: Profile, rail: Profile, y_tape: float, y_rail: float,
                 r0: float, step: float) -> None:
        w = wheel.resampled(step)
        self.wy = w.y
        self.wz = w.z
        self.yw = y_tape + w.y              # wheelset frame, left wheel
        self.zw = -(r0 + w.z)
        r = rail.resampled(step)
        self.ry = r.y
        self.rz = r.z
        self.rslope = np.gradient(r.z, r.y)
        self.y_rail = y_rail
        self.r0 = r0

    def gaps(self, y: float, roll: float, sign: float) -> np.ndarray:
        """Vertical gap of every wheel point over its rail (m), wheelset centre at Z=0."""
        c, s = math.cos(roll), math.sin(roll)
        yw = sign * self.yw
        y_track = y + c * yw - s * self.zw
        z_track = s * yw + c * self.zw
        # Rail: Y = sign*(y_rail + t), Z = -z(t)
        t = sign * y_track - self.y_rail
        z_rail = -np.interp(t, self.ry, self.rz, left=_NO_RAIL, right=_NO_RAIL)
        return z_track - z_rail


def _refine(g: np.ndarray, i: int | None = None) -> tuple[int, float, float]:
    """Index of the minimum (or of the valley at ``i``), its fractional offset (parabola)
    and the refined value."""
    if i is None:
        i = int(np.argmin(g))
    if 0 < i < g.size - 1:
        a, b, c = g[i - 1], g[i], g[i + 1]
        den = a - 2.0 * b + c
        if den > 0:
            off = 0.5 * (a - c) / den
            return i, off, b - 0.25 * (a - c) * off
    return i, 0.0, g[i]


def contact_geometry(
    wheel: Profile | None = None,
    rail: Profile | None = None,
    *,
    rail_inclination: float = 1.0 / 40.0,
    gauge: float = 1.435,
    back_to_back: float = 1.360,
    flange_back: float = 0.070,
    r0: float = 0.43,
    gauge_depth: float = 0.014,
    y_max: float = 0.012,
    y_step: float = 1e-4,
    sample_step: float = 1e-5,
    jump_threshold: float = 1e-3,
    curvature_window: float = 2e-3,
) -> ContactGeometry:
    """Rigid contact geometry of a symmetric wheelset on its rails over ``|y| <= y_max``.

    Parameters
    ----------
    wheel, rail : Profile, optional
        Wheel profile and *upright* rail profile (default: analytic S1002 and UIC60).
    rail_inclination : float
        Rail cant (tangent), e.g. ``1/40``, ``1/20``, 0 for none.
    gauge : float
        Track gauge (m), between the gauge faces at ``gauge_depth`` below the rail top.
    back_to_back : float
        Distance between the inner faces of the wheels (m).
    flange_back : float
        Distance from a wheel's inner face to its tape circle (profile ``y = 0``) (m);
        70 mm for EN 13715 profiles.
    r0 : float
        Nominal rolling radius (m): the wheel radius at the tape circle.
    gauge_depth : float
        Depth of the gauge measuring point below the rail top (m), 14 mm in Europe.
    y_max, y_step : float
        Range and step of the lateral displacement (m).
    sample_step : float
        Sampling step of the profiles in the contact search (m).
    jump_threshold : float
        Lateral travel of a contact point between two steps above which a jump
        (two-point contact) is flagged (m).
    curvature_window : float
        Half-width (m of arc) over which the profiles' transverse curvatures at the
        contact points are fitted (:mod:`railhunt.contact.curvature`).

    Returns
    -------
    ContactGeometry
    """
    checks = {
        "rail_inclination": (rail_inclination, 0.0, 0.1),
        "gauge": (gauge, 0.5, 2.0),
        "back_to_back": (back_to_back, 0.4, 2.0),
        "flange_back": (flange_back, 0.0, 0.2),
        "r0": (r0, 0.1, 1.0),
        "gauge_depth": (gauge_depth, 0.0, 0.03),
        "y_max": (y_max, 1e-4, 0.03),
        "y_step": (y_step, 1e-6, 1e-3),
        "sample_step": (sample_step, 1e-6, 1e-4),
        "jump_threshold": (jump_threshold, 1e-5, 0.05),
        "curvature_window": (curvature_window, 1e-5, 0.02),
    }
    for name, (value, lo, hi) in checks.items():
        if not (isinstance(value, int | float) and math.isfinite(value) and lo <= value <= hi):
            raise ProfileError(f"{name} = {value!r} m is invalid: must be in [{lo}, {hi}]"
                               if name != "rail_inclination" else
                               f"rail_inclination = {value!r} is invalid: must be in [0, 0.1]")
    if wheel is None or rail is None:
        dw, dr = default_profiles()
        wheel = dw if wheel is None else wheel
        rail = dr if rail is None else rail
    if wheel.kind != "wheel" or rail.kind != "rail":
        raise ProfileError(f"expected a wheel and a rail profile, got {wheel.kind!r} "
                           f"and {rail.kind!r}")
    rail_c = rail.inclined(rail_inclination) if rail_inclination else rail
    y_gauge = _gauge_point(rail_c, gauge_depth)
    y_rail = 0.5 * gauge - y_gauge
    y_tape = 0.5 * back_to_back + flange_back
    _check_fit(wheel, gauge, back_to_back, flange_back, gauge_depth)
    side = _Side(wheel, rail_c, y_tape, y_rail, r0, sample_step)

    n = int(round(y_max / y_step))
    ys = y_step * np.arange(-n, n + 1)
    out = {k: np.empty(ys.size) for k in
           ("rl", "rr", "dl", "dr", "roll", "wl", "wr", "tl", "tr", "yl", "zl", "yr", "zr")}
    for k, y in enumerate(ys):
        def f(phi: float, y: float = y) -> float:
            return _refine(side.gaps(y, phi, 1.0))[2] - _refine(side.gaps(y, phi, -1.0))[2]

        lo, hi = -0.05, 0.05
        if f(lo) * f(hi) > 0:
            raise ProfileError(f"no wheelset roll in [-0.05, 0.05] rad brings both wheels "
                               f"onto the rails at y = {y * 1e3:.2f} mm: check gauge, "
                               "back_to_back and the profiles")
        phi = brentq(f, lo, hi, xtol=1e-12, rtol=1e-12)
        out["roll"][k] = phi
        for sign, tag in ((1.0, "l"), (-1.0, "r")):
            g = side.gaps(y, phi, sign)
            i, off, gmin = _refine(g)
            j = min(max(i + (1 if off > 0 else -1), 0), g.size - 1)
            w = abs(off)
            s_w = (1 - w) * side.wy[i] + w * side.wy[j]
            z_w = (1 - w) * side.wz[i] + w * side.wz[j]
            yw = sign * (side.yw[i] * (1 - w) + side.yw[j] * w)
            zw = -(r0 + z_w)
            c, s = math.cos(phi), math.sin(phi)
            y_track = y + c * yw - s * zw
            z_track = s * yw + c * zw
            t = sign * y_track - y_rail
            slope = np.interp(t, side.ry, side.rslope)
            out["r" + tag][k] = r0 + z_w
            out["d" + tag][k] = math.atan(-slope)
            out["w" + tag][k] = s_w
            out["t" + tag][k] = t
            out["y" + tag][k] = y_track
            out["z" + tag][k] = z_track - gmin
    jump = np.zeros(ys.size, dtype=bool)
    jump[1:] = (np.abs(np.diff(out["wl"])) > jump_threshold) | (
        np.abs(np.diff(out["wr"])) > jump_threshold)
    params = {
        "wheel": wheel.name, "rail": rail.name, "rail_inclination": rail_inclination,
        "gauge": gauge, "back_to_back": back_to_back, "flange_back": flange_back,
        "r0": r0, "gauge_depth": gauge_depth,
    }
    return ContactGeometry(
        y=ys, r_left=out["rl"], r_right=out["rr"], delta_left=out["dl"],
        delta_right=out["dr"], roll=-out["roll"],
        contact_left=np.column_stack([out["yl"], out["zl"]]),
        contact_right=np.column_stack([out["yr"], out["zr"]]),
        wheel_left=out["wl"], wheel_right=out["wr"], rail_left=out["tl"],
        rail_right=out["tr"], jump=jump, r0=r0, params=params,
        wheel_curvature_left=surface_curvature(wheel, out["wl"], curvature_window),
        wheel_curvature_right=surface_curvature(wheel, out["wr"], curvature_window),
        rail_curvature_left=surface_curvature(rail_c, out["tl"], curvature_window),
        rail_curvature_right=surface_curvature(rail_c, out["tr"], curvature_window),
    )


def _flange_face(wheel: Profile, depth: float) -> float | None:
    """Lateral profile coordinate (m) of the flange face ``depth`` below the tread's
    tape circle (where the wheel's radius exceeds the nominal one by ``depth``); None for
    a wheel whose flange is not that high."""
    tip = int(np.argmax(wheel.z))
    if wheel.z[tip] < depth:
        return None
    face_y, face_z = wheel.y[tip:], wheel.z[tip:]
    below = np.nonzero(face_z < depth)[0]
    if below.size == 0:
        return None
    k = int(below[0])  # first point of the face under ``depth``; k - 1 is above it
    return float(np.interp(depth, [face_z[k], face_z[k - 1]], [face_y[k], face_y[k - 1]]))


def _check_fit(wheel: Profile, gauge: float, back_to_back: float, flange_back: float,
               depth: float) -> None:  # fmt: skip
    """Refuse a track too narrow for the wheelset, before any contact search: the
    distance over the two flange faces, ``depth`` below the tape circle (where the gauge
    is measured on the rails), must be less than the gauge."""
    face = _flange_face(wheel, depth)
    if face is None:
        return
    flange = flange_back + face  # flange thickness from the inner face (m)
    width = back_to_back + 2.0 * flange
    if width >= gauge:
        raise ProfileError(
            f"gauge = {gauge:g} m is too narrow for these wheels: the wheelset measures "
            f"{width:.4f} m over its flanges (back_to_back {back_to_back:g} m + 2 x "
            f"{flange * 1e3:.1f} mm of flange at {depth * 1e3:g} mm), so the gauge must exceed "
            f"{width:.4f} m (or back_to_back be below {gauge - 2.0 * flange:.4f} m)"
        )


def _gauge_point(rail: Profile, depth: float) -> float:
    """Lateral profile coordinate (m) of the gauge face at ``depth`` below the rail top."""
    top = int(np.argmin(rail.z))
    z = rail.z[: top + 1] - rail.z[top]
    y = rail.y[: top + 1]
    below = np.nonzero(z >= depth)[0]
    if below.size == 0:
        raise ProfileError(f"rail profile {rail.name!r} does not reach {depth * 1e3:g} mm "
                           "below its top on the gauge side: cannot place it at the gauge")
    i = below[-1]
    # z decreases from i to i+1 across the depth
    return float(np.interp(depth, [z[i + 1], z[i]], [y[i + 1], y[i]]))
