"""Contact patches of a yawed wheelset: every point where a wheel touches its rail.

:func:`contact_patches` places a wheelset at lateral displacement ``y`` and yaw ``psi`` on
its rails, rolls it until both wheels touch (as :func:`railhunt.contact_geometry` does at
zero yaw) and returns, per wheel, every patch: the lowest point of the wheel's gap
function and each other valley of it within the wheel's elastic approach (or
``penetration``), more than ``separation`` away along the wheel.

**The contact locus of a yawed wheel.** A wheel is a body of revolution: the section at
axle coordinate ``s`` (track-lateral along the axle, + left) has radius ``r(s)``. Its
surface point at angle ``theta`` from the bottom of the section is

    P = c + s e_a + r(s) (sin(theta) e_f - cos(theta) e_n),

with ``e_a`` the axle, ``e_f`` the wheel's rolling direction and ``e_n`` the wheelset's
"up" (the track's axes rolled by ``phi`` about ``x``, then yawed by ``psi`` about ``z``).
The rail is a prism along the track's ``x``, so the wheel's lowest point above any rail
line ``Y = const`` is where the wheel's surface normal ``e_r - r'(s) e_a`` (``r' = dr/ds``)
has no ``x`` component:

    sin(theta) cos(psi) - cos(theta) sin(phi) sin(psi) = -r'(s) cos(phi) sin(psi).

Without roll that is ``sin(theta) = -r'(s) tan(psi)``. These points (one per section) are
the wheel's *contact locus*; the gap function is the locus's height above the rail at
the locus's own lateral position, and its minima are the contact points. At ``psi = 0``
the locus is the section's bottom (``theta = 0``) and this is the rigid contact of
:func:`railhunt.contact_geometry` exactly.

**The contact lead.** ``ContactPatch.x`` is the distance of the contact point ahead of
the axle, along the track at the contact's lateral position: ``x = r sin(theta) /
cos(psi)`` without roll. On the left wheel ``r' = -tan(delta)`` (its radius grows toward
the flange, inward), so ``x = r tan(delta) tan(psi) / cos(psi)``: a wheelset yawed nose-left
(``psi > 0``) has its left wheel's contact *ahead* of the axle and its right wheel's
behind; a flange at 70 degrees leads by ``r tan(70 deg) psi`` = 6.3 mm at 5 mrad on a
0.46 m wheel, a tread at 2 degrees by 0.08 mm.

**Load sharing.** Under a vertical wheel load ``Q`` the wheel sinks by its elastic
approach ``Delta`` (vertical); a patch whose vertical gap is ``g_i`` is pressed by the
normal approach ``(Delta - g_i) cos(delta_i)`` and carries the Hertz normal force
``N_i = K_i ((Delta - g_i) cos(delta_i))^(3/2)`` (``K_i`` from its ellipse). ``Delta``
solves ``sum N_i cos(delta_i) = Q``, so the patches' vertical shares sum to the wheel
load. Each wheel sinks on its own (the wheelset's roll stays the rigid one).

Frames: track ``x`` forward, ``y`` left, ``z`` up; the wheelset's roll as in
:mod:`railhunt.contact.geometry` (positive when the left wheel drops). Profile
coordinates ``wheel_y``, ``rail_y`` positive toward the field side.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from railhunt.contact.curvature import surface_curvature
from railhunt.contact.locus import (
    _axes,
    distinct,
    ellipse_constants,
    patch_search,
    raw_patches,
    share_load,
)
from railhunt.contact.profiles import Profile
from railhunt.results import Columns, ResultDisplay, Row

__all__ = ["ContactPatch", "WheelsetContact", "contact_patches", "contact_patches_along"]

#: Valleys of the gap function more than this above the lowest one are never patches (m).
_CANDIDATE_DEPTH = 1e-3


@dataclass(frozen=True)
class ContactPatch:
    """One contact patch of a wheel (SI units; module docstring for the frames).

    Attributes
    ----------
    x, y, z : float
        Position of the contact point in the track frame (m): ``x`` the lead ahead of the
        axle, ``y`` lateral (+ left) and ``z`` height, on the wheel.
    rolling_radius : float
        Radius of the wheel's profile at the contact (m).
    contact_angle : float
        Inclination of the contact plane (rad), + when the normal on the wheel leans
        toward the track centre.
    wheel_y, rail_y : float
        Lateral profile coordinates of the contact on the wheel and the rail (m), + toward
        the field side.
    gap : float
        Vertical gap of the rigid wheel over the rail there (m); 0 for the first patch.
    wheel_curvature, rail_curvature : float
        Transverse curvatures of the surfaces there (1/m, Hertz's sign: convex positive).
    a, b : float
        Hertz semi-axes under the patch's normal force (m), ``a`` along the rolling
        direction; 0 without a load (or a patch not pressed).
    normal_force : float
        Normal force of the patch (N); 0 without a load.
    vertical_load : float
        Its vertical part ``N cos(delta)`` (N): the patch's share of the wheel load.
    """

    x: float
    y: float
    z: float
    rolling_radius: float
    contact_angle: float
    wheel_y: float
    rail_y: float
    gap: float
    wheel_curvature: float = math.nan
    rail_curvature: float = math.nan
    a: float = 0.0
    b: float = 0.0
    normal_force: float = 0.0
    vertical_load: float = 0.0


@dataclass(frozen=True, repr=False)
class WheelsetContact(ResultDisplay):
    """The contact patches of a wheelset at one lateral displacement and yaw.

    Attributes
    ----------
    y, yaw : float
        Lateral displacement (m, + left) and yaw (rad, + counter-clockwise from above).
    roll : float
        Wheelset roll (rad), positive when the left wheel drops (``< 0`` for ``y > 0``).
    height : float
        Height of the wheelset's centre above the rails' reference (m), rigid contact.
    left, right : tuple of ContactPatch
        Each wheel's patches, lowest gap first.
    params : dict
        The inputs (profiles' names, track and wheelset parameters).
    """

    y: float
    yaw: float
    roll: float
    height: float
    left: tuple[ContactPatch, ...]
    right: tuple[ContactPatch, ...]
    params: dict = field(default_factory=dict)

    def creepages(self, speed: float, omega: float, lateral_velocity: float = 0.0,
                  yaw_rate: float = 0.0) -> dict[str, list[tuple[float, float, float]]]:
        """Creepages of every patch from the rigid-body slip at its own point.

        The wheelset's centre moves at ``(speed, lateral_velocity, 0)`` over the rails and
        turns at ``omega`` about its axle (forward rolling positive) and ``yaw_rate`` about
        the vertical. The slip velocity of the wheel's material point at the contact,
        ``v = v_c + Omega x (P - c)``, is resolved in the contact plane: ``xi`` along the
        track's ``x`` (the locus makes it a tangent), ``eta`` along the plane's lateral
        direction (``(cos d, sin d)`` on the left wheel, ``(cos d, -sin d)`` on the
        right, in track ``(y, z)``), both over ``speed``; the spin ``phi = Omega . n /
        speed`` (1/m), ``n`` the rail's normal. Signs as the model's (Eq. 25).

        Parameters
        ----------
        speed : float
            Forward speed (m/s), > 0.
        omega : float
            Wheelset angular velocity about its axle (rad/s).
        lateral_velocity : float
            Lateral velocity of the wheelset (m/s).
        yaw_rate : float
            Yaw rate (rad/s).

        Returns
        -------
        dict
            ``{"left": [(xi, eta, phi), ...], "right": [...]}``, one triple per patch in
            the order of :attr:`left` and :attr:`right`.
        """
        for name, value in (("speed", speed), ("omega", omega),
                            ("lateral_velocity", lateral_velocity), ("yaw_rate", yaw_rate)):
            if not math.isfinite(value):
                raise ValueError(f"{name} = {value!r} is invalid: must be finite")
        if not speed > 0.0:
            raise ValueError(f"speed = {speed!r} m/s is invalid: must be > 0")
        phi = -self.roll  # the axes' roll: positive when the left wheel rises
        ea = _axes(phi, self.yaw)[0]
        om = omega * ea + np.array([0.0, 0.0, yaw_rate])
        vc = np.array([speed, lateral_velocity, 0.0])
        out: dict[str, list[tuple[float, float, float]]] = {}
        for side, patches, sign in (("left", self.left, 1.0), ("right", self.right, -1.0)):
            rows = []
            for p in patches:
                x_track = p.x + ea[0] * (p.y - self.y) / ea[1]
                d = np.array([x_track, p.y - self.y, p.z - self.height])
                slip = vc + np.cross(om, d)
                sd, cd = math.sin(p.contact_angle), math.cos(p.contact_angle)
                normal = np.array([0.0, -sign * sd, cd])
                lateral = np.array([0.0, cd, sign * sd])
                rows.append((float(slip[0] / speed), float(slip @ lateral / speed),
                             float(om @ normal / speed)))  # fmt: skip
            out[side] = rows
        return out

    def _summary(self) -> list[Row]:
        rows: list[Row] = [
            ("wheel / rail", f"{self.params.get('wheel', '?')} / "
                             f"{self.params.get('rail', '?')}", ""),
            ("lateral displacement", self.y * 1e3, "mm"),
            ("yaw", self.yaw * 1e3, "mrad"),
            ("roll", self.roll * 1e3, "mrad")]  # fmt: skip
        for side in ("left", "right"):
            for k, p in enumerate(getattr(self, side)):
                text = (f"x {p.x * 1e3:+.2f} mm, wheel {p.wheel_y * 1e3:+.2f} mm, r "
                        f"{p.rolling_radius * 1e3:.3f} mm, delta "
                        f"{math.degrees(p.contact_angle):.2f} deg, gap {p.gap * 1e6:.1f} um")
                if p.normal_force > 0.0:
                    text += f", N {p.normal_force * 1e-3:.3g} kN"
                rows.append((f"{side} patch {k + 1}", text, ""))
        return rows

    def _columns(self) -> Columns:
        """One row per patch: the left wheel's, then the right wheel's."""
        items = [(side, k, p) for side in ("left", "right")
                 for k, p in enumerate(getattr(self, side))]  # fmt: skip
        out: Columns = {
            "wheel": (np.array([s for s, _, _ in items]), ""),
            "patch": (np.array([k + 1 for _, k, _ in items]), ""),
        }
        for name, unit in (("x", "m"), ("y", "m"), ("z", "m"), ("rolling_radius", "m"),
                           ("contact_angle", "rad"), ("wheel_y", "m"), ("rail_y", "m"),
                           ("gap", "m"), ("a", "m"), ("b", "m"), ("normal_force", "N"),
                           ("vertical_load", "N")):  # fmt: skip
            out[name] = (np.array([getattr(p, name) for _, _, p in items]), unit)
        return out


def _pair(value: object, name: str, low: float, high: float) -> tuple[float, float]:
    vals = tuple(value) if isinstance(value, tuple | list) else (value, value)
    if len(vals) != 2:
        raise ValueError(f"{name} = {value!r} is invalid: must be a float or a (left, right) "
                         "pair")  # fmt: skip
    for v in vals:
        if not (isinstance(v, int | float) and math.isfinite(v) and low <= v <= high):
            raise ValueError(f"{name} = {value!r} is invalid: must be in [{low:g}, {high:g}]")
    return float(vals[0]), float(vals[1])


def contact_patches(
    wheel: Profile, rail: Profile, y: float, yaw: float = 0.0, *,
    rail_inclination: float = 0.0, gauge: float = 1.435, back_to_back: float = 1.360,
    flange_back: float = 0.070, r0: float = 0.46, gauge_depth: float = 0.014,
    penetration: float | tuple[float, float] = 0.0, separation: float = 1e-3,
    normal_load: float | tuple[float, float] | None = None,
    shear_modulus: float = 2.1e11 / 2.6, poisson: float = 0.3, sample_step: float = 1e-5,
    curvature_window: float = 2e-3,
) -> WheelsetContact:  # fmt: skip
    """The contact patches of a wheelset at lateral displacement ``y`` and yaw ``yaw``.

    Parameters
    ----------
    wheel, rail : Profile
        Wheel profile and *upright* rail profile (:func:`railhunt.read_profile`).
    y : float
        Lateral wheelset displacement (m), + left, in [-0.03, 0.03].
    yaw : float
        Wheelset yaw (rad), + counter-clockwise seen from above, in [-0.05, 0.05].
    rail_inclination, gauge, back_to_back, flange_back, r0, gauge_depth : float
        As :func:`railhunt.contact_geometry` (m; the inclination a tangent).
    penetration : float or (float, float)
        Depth (m) within which a second valley of a wheel's gap function is a patch of its
        own, per wheel (left, right) or both; in [0, 1e-3]. With ``normal_load`` each
        wheel's elastic approach counts as well (the larger of the two).
    separation : float
        Smallest distance along the wheel between two patches (m), in [1e-4, 0.02].
    normal_load : float or (float, float), optional
        Vertical load of each wheel (N): the patches' ellipses and normal forces, the load
        shared by their elastic approach (module docstring).
    shear_modulus, poisson : float
        Material of wheel and rail (Pa, -), for the ellipses.
    sample_step : float
        Sampling step of the profiles (m).
    curvature_window : float
        Half-width of the profiles' curvature fits (m of arc).

    Returns
    -------
    WheelsetContact
    """
    for name, value, lo, hi in (("y", y, -0.03, 0.03), ("yaw", yaw, -0.05, 0.05),
                                ("separation", separation, 1e-4, 0.02)):  # fmt: skip
        if not (isinstance(value, int | float) and math.isfinite(value) and lo <= value <= hi):
            raise ValueError(f"{name} = {value!r} is invalid: must be in [{lo:g}, {hi:g}]")
    pens = _pair(penetration, "penetration", 0.0, 1e-3)
    loads = None if normal_load is None else _pair(normal_load, "normal_load", 0.0, 1e7)
    search = patch_search(wheel, rail, rail_inclination=rail_inclination, gauge=gauge,
                          back_to_back=back_to_back, flange_back=flange_back, r0=r0,
                          gauge_depth=gauge_depth, sample_step=sample_step)  # fmt: skip
    return _place(search, wheel, float(y), float(yaw), pens, loads, separation,
                  shear_modulus, poisson, curvature_window)  # fmt: skip


def contact_patches_along(wheel: Profile, rail: Profile, ys: np.ndarray, yaw: float = 0.0,
                          **options: object) -> list[WheelsetContact]:  # fmt: skip
    """:func:`contact_patches` at each lateral displacement of ``ys`` (m), one yaw (rad);
    the profiles are sampled once. ``options``: the keywords of :func:`contact_patches`."""
    ys = np.asarray(ys, dtype=np.float64)
    if ys.ndim != 1 or ys.size == 0:
        raise ValueError("ys must be a non-empty 1-D array of lateral displacements (m)")
    contact_patches(wheel, rail, float(ys[0]), yaw, **options)  # checks every argument
    names = ("rail_inclination", "gauge", "back_to_back", "flange_back", "r0", "gauge_depth",
             "sample_step")  # fmt: skip
    search = patch_search(wheel, rail, **{k: options[k] for k in names if k in options})
    pens = _pair(options.get("penetration", 0.0), "penetration", 0.0, 1e-3)
    load = options.get("normal_load")
    loads = None if load is None else _pair(load, "normal_load", 0.0, 1e7)
    out = []
    for y in ys:
        if not (math.isfinite(y) and abs(y) <= 0.03):
            raise ValueError(f"y = {y!r} is invalid: must be in [-0.03, 0.03]")
        out.append(_place(search, wheel, float(y), float(yaw), pens, loads,
                          float(options.get("separation", 1e-3)),
                          float(options.get("shear_modulus", 2.1e11 / 2.6)),
                          float(options.get("poisson", 0.3)),
                          float(options.get("curvature_window", 2e-3))))  # fmt: skip
    return out


def _place(search: object, wheel: Profile, y: float, yaw: float, pens: tuple[float, float],
           loads: tuple[float, float] | None, separation: float, shear_modulus: float,
           poisson: float, curvature_window: float) -> WheelsetContact:  # fmt: skip
    """The patches of the wheelset ``search`` at ``(y, yaw)`` (:func:`contact_patches`)."""
    phi = search.roll(y, yaw)
    young = 2.0 * shear_modulus * (1.0 + poisson)
    sides = []
    g_low = 0.0
    for k, locus in enumerate((search.left, search.right)):
        g_low, raw, gap = raw_patches(locus, y, phi, yaw, _CANDIDATE_DEPTH, separation)
        kw = surface_curvature(wheel, np.array([p["u"] for p in raw]), curvature_window)
        kr = surface_curvature(search.rail, np.array([p["t"] for p in raw]),
                               curvature_window)  # fmt: skip
        keep = distinct(gap, raw, pens[k]) if pens[k] > 0.0 else [0]
        forces = np.zeros(len(raw))
        axes = [(0.0, 0.0)] * len(raw)
        if loads is not None and loads[k] > 0.0:
            keep = list(range(len(raw)))
            for _ in range(len(raw) + 1):  # the approach sets the patches, and they it
                sel = [raw[i] for i in keep]
                f, ax, approach = _loaded(sel, kw[keep], kr[keep], young, poisson, loads[k])
                new = distinct(gap, raw, max(approach, pens[k]))
                if new == keep:
                    break
                keep = new
            for i, fi, ai in zip(keep, f, ax, strict=True):
                forces[i], axes[i] = fi, ai
        sides.append(tuple(
            ContactPatch(x=p["x"], y=p["y"], z=p["z"], rolling_radius=p["r"],
                         contact_angle=p["delta"], wheel_y=p["u"], rail_y=p["t"], gap=p["gap"],
                         wheel_curvature=float(kw[i]), rail_curvature=float(kr[i]),
                         a=axes[i][0], b=axes[i][1], normal_force=float(forces[i]),
                         vertical_load=float(forces[i] * math.cos(p["delta"])))
            for i, p in ((i, raw[i]) for i in keep)))  # fmt: skip
    params = dict(search.params, penetration=pens, separation=separation,
                  normal_load=loads)  # fmt: skip
    return WheelsetContact(y=y, yaw=yaw, roll=-phi, height=-g_low, left=sides[0],
                           right=sides[1], params=params)


def _loaded(raw: list[dict], kw: np.ndarray, kr: np.ndarray, young: float, poisson: float,
            load: float) -> tuple[np.ndarray, list[tuple[float, float]], float]:  # fmt: skip
    """Normal forces and semi-axes of a wheel's candidate patches under ``load``, and its
    vertical approach (m)."""
    consts = [ellipse_constants(p["delta"], p["r"], float(kw[i]), float(kr[i]), young, poisson)
              for i, p in enumerate(raw)]  # fmt: skip
    gaps = np.array([p["gap"] for p in raw])
    cosd = np.cos([p["delta"] for p in raw])
    stiff = np.array([c[2] ** -1.5 for c in consts])
    forces, approach = share_load(gaps, cosd, stiff, load)
    axes = [(c[0] * f ** (1 / 3), c[1] * f ** (1 / 3)) if f > 0 else (0.0, 0.0)
            for c, f in zip(consts, forces, strict=True)]  # fmt: skip
    return forces, axes, approach

