"""The contact locus of a yawed wheel and the search for its patches.

The machinery of :func:`railhunt.contact.patches.contact_patches` (whose docstring derives
the locus, the lead and the load sharing): each wheel sampled with its rail
(:class:`WheelLocus`), the roll that puts both wheels on their rails
(:class:`PatchSearch`), the valleys of a gap function and which of them are patches of
their own (:func:`valleys`, :func:`distinct`), and the Hertz constants and load sharing of
the patches (:func:`hertz_per_newton`, :func:`share_load`). The two-point contact table of
the kernel (:mod:`railhunt.contact.patch_table`) runs on the same functions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from railhunt.contact.geometry import _check_fit, _gauge_point, _refine
from railhunt.contact.profiles import Profile, ProfileError

__all__ = ["PatchSearch", "WheelLocus", "distinct", "ellipse_constants", "hertz_per_newton",
           "patch_search", "raw_patches", "share_load", "valleys"]

_NO_RAIL = 1.0  # depth (m) assigned outside the rail's lateral range: never in contact


def _axes(phi: float, psi: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The wheelset's axle ``e_a``, rolling direction ``e_f`` and up ``e_n`` in the track
    frame: rolled by ``phi`` (left wheel up) about ``x``, then yawed by ``psi``."""
    cf, sf, cp, sp = math.cos(phi), math.sin(phi), math.cos(psi), math.sin(psi)
    return (np.array([-cf * sp, cf * cp, sf]), np.array([cp, sp, 0.0]),
            np.array([sf * sp, -sf * cp, cf]))  # fmt: skip


class WheelLocus:
    """One wheel and its rail, sampled: the contact locus and the gap function.

    Parameters
    ----------
    wheel, rail : Profile
        Wheel profile and the rail *as laid* (inclined).
    y_tape, y_rail : float
        Lateral position of the tape circle from the wheelset centre and of the rail's
        profile origin from the track centre (m).
    r0 : float
        Radius at the tape circle (m).
    step : float
        Sampling step (m).
    sign : float
        +1 for the left wheel, -1 for the right (its mirror).
    """

    def __init__(self, wheel: Profile, rail: Profile, y_tape: float, y_rail: float,
                 r0: float, step: float, sign: float) -> None:  # fmt: skip
        w = wheel.resampled(step)
        self.u = w.y
        self.r = r0 + w.z
        self.s = sign * (y_tape + w.y)
        self.r_s = sign * np.gradient(w.z, w.y)  # dr/ds along the axle
        r = rail.resampled(step)
        self.ry = r.y
        self.rz = r.z
        self.rslope = np.gradient(r.z, r.y)
        self.y_rail = y_rail
        self.sign = sign

    def locus(self, y: float, phi: float, psi: float) -> tuple[np.ndarray, ...]:
        """``(X, Y, Z, gap)`` of the locus (m), wheelset centre at ``(0, y, 0)``;
        ``phi`` the roll with the left wheel up positive, ``psi`` the yaw."""
        ea, ef, en = _axes(phi, psi)
        if psi == 0.0:
            st, ct = 0.0, 1.0
        else:
            big_a, big_b = ef[0], -en[0]
            rad = math.hypot(big_a, big_b)
            alpha = math.atan2(big_b, big_a)
            theta = np.arcsin(np.clip(self.r_s * ea[0] / rad, -1.0, 1.0)) - alpha
            st, ct = np.sin(theta), np.cos(theta)
        rs, rc = self.r * st, self.r * ct
        x = self.s * ea[0] + rs * ef[0] - rc * en[0]
        yy = y + self.s * ea[1] + rs * ef[1] - rc * en[1]
        z = self.s * ea[2] - rc * en[2]
        t = self.sign * yy - self.y_rail
        gap = z + np.interp(t, self.ry, self.rz, left=_NO_RAIL, right=_NO_RAIL)
        return x, yy, z, gap

    def lowest(self, y: float, phi: float, psi: float) -> float:
        """The refined minimum of the gap function (m)."""
        return _refine(self.locus(y, phi, psi)[3])[2]


def valleys(gap: np.ndarray, u: np.ndarray, depth: float, separation: float) -> list[int]:
    """Indices of the gap function's valleys less than ``depth`` above its lowest point,
    the lowest first, each more than ``separation`` along the wheel from every lower one.

    A valley is a point whose gap is the least within ``separation / 2`` along the wheel
    on either side (the ripples of a measured tread do not count), as
    :func:`railhunt.contact.bands.patch_count` counts them.
    """
    from scipy.ndimage import minimum_filter1d

    step = float(u[1] - u[0])
    half = max(1, int(round(0.5 * separation / step)))
    low = minimum_filter1d(gap, 2 * half + 1, mode="nearest")
    cand = np.flatnonzero(gap[1:-1] <= low[1:-1]) + 1
    g0 = float(gap.min())
    cand = cand[gap[cand] < g0 + depth]
    cand = cand[np.argsort(gap[cand], kind="stable")]
    out: list[int] = [int(np.argmin(gap))]
    for i in cand:
        if all(abs(u[i] - u[j]) > separation for j in out):
            out.append(int(i))
    return out


def hertz_per_newton(curvature_x: float, curvature_y: float, young: float,
                     poisson: float) -> tuple[float, float, float]:  # fmt: skip
    """Semi-axes ``a1, b1`` (m) and normal approach ``d1`` (m) of a Hertz contact under
    1 N (``a ~ N^(1/3)``, ``d ~ N^(2/3)``). The approach (Johnson, Eq. 4.36):
    ``d = p0 b_s K(m) / E*``, ``b_s`` the shorter semi-axis, ``m = 1 - (b_s/a_l)^2``."""
    from scipy.special import ellipk

    from railhunt.mechanics.hertz import hertz_contact

    h = hertz_contact(1.0, curvature_x, curvature_y, young, poisson)
    short, long_ = sorted((h.a, h.b))
    e_star = young / (2.0 * (1.0 - poisson * poisson))
    return h.a, h.b, h.p0 * short * float(ellipk(1.0 - (short / long_) ** 2)) / e_star


def share_load(gaps: np.ndarray, cos_delta: np.ndarray, stiffness: np.ndarray,
               load: float) -> tuple[np.ndarray, float]:
    """Normal forces (N) of patches with vertical gaps ``gaps`` (m) under the wheel's
    vertical load ``load`` (N), ``N_i = K_i ((Delta - g_i) cos d_i)^(3/2)``, and the
    vertical approach ``Delta`` (m) that gives ``sum N_i cos d_i = load`` (module
    docstring)."""
    if load <= 0.0:
        return np.zeros(gaps.size), float(gaps.min())

    def vertical(delta: float) -> np.ndarray:
        pen = np.clip((delta - gaps) * cos_delta, 0.0, None)
        return stiffness * pen**1.5

    def residual(delta: float) -> float:
        return float(vertical(delta) @ cos_delta) - load

    lo = float(gaps.min())
    hi = lo + (load / float(stiffness[0] * cos_delta[0] ** 2.5)) ** (2.0 / 3.0)
    delta = brentq(residual, lo, hi, xtol=1e-15, rtol=1e-13) if residual(hi) > 0 else hi
    return vertical(delta), delta


@dataclass
class PatchSearch:
    """A wheelset's two wheel loci on their rails, and the roll search (SI units).

    Built once per wheel/rail pair (:func:`patch_search`); :meth:`solve` places the
    wheelset at one ``(y, psi)``.
    """

    left: WheelLocus
    right: WheelLocus
    rail: Profile
    params: dict

    def roll(self, y: float, psi: float, guess: float | None = None) -> float:
        """The roll (left wheel up positive) that brings both wheels onto their rails."""
        def f(phi: float) -> float:
            return self.left.lowest(y, phi, psi) - self.right.lowest(y, phi, psi)

        if guess is not None:
            lo, hi = guess - 2e-4, guess + 2e-4
            if f(lo) * f(hi) < 0:
                return brentq(f, lo, hi, xtol=1e-12, rtol=1e-12)
        lo, hi = -0.05, 0.05
        if f(lo) * f(hi) > 0:
            raise ProfileError(f"no wheelset roll in [-0.05, 0.05] rad brings both wheels "
                               f"onto the rails at y = {y * 1e3:.2f} mm, yaw "
                               f"{psi * 1e3:.2f} mrad: check gauge, back_to_back and the "
                               "profiles")  # fmt: skip
        return brentq(f, lo, hi, xtol=1e-12, rtol=1e-12)


def patch_search(wheel: Profile, rail: Profile, *, rail_inclination: float = 0.0,
                 gauge: float = 1.435, back_to_back: float = 1.360,
                 flange_back: float = 0.070, r0: float = 0.46, gauge_depth: float = 0.014,
                 sample_step: float = 1e-5) -> PatchSearch:  # fmt: skip
    """The sampled loci of a wheelset's wheels on their rails (parameters as
    :func:`contact_patches`)."""
    checks = {"rail_inclination": (rail_inclination, 0.0, 0.1), "gauge": (gauge, 0.5, 2.0),
              "back_to_back": (back_to_back, 0.4, 2.0), "flange_back": (flange_back, 0.0, 0.2),
              "r0": (r0, 0.1, 1.0), "gauge_depth": (gauge_depth, 0.0, 0.03),
              "sample_step": (sample_step, 1e-6, 1e-4)}  # fmt: skip
    for name, (value, lo, hi) in checks.items():
        if not (isinstance(value, int | float) and math.isfinite(value) and lo <= value <= hi):
            unit = "" if name == "rail_inclination" else " m"
            raise ProfileError(f"{name} = {value!r}{unit} is invalid: must be in [{lo:g}, "
                               f"{hi:g}]{unit}")  # fmt: skip
    if wheel.kind != "wheel" or rail.kind != "rail":
        raise ProfileError(f"expected a wheel and a rail profile, got {wheel.kind!r} and "
                           f"{rail.kind!r}")  # fmt: skip
    rail_c = rail.inclined(rail_inclination) if rail_inclination else rail
    y_rail = 0.5 * gauge - _gauge_point(rail_c, gauge_depth)
    y_tape = 0.5 * back_to_back + flange_back
    _check_fit(wheel, gauge, back_to_back, flange_back, gauge_depth)
    params = {"wheel": wheel.name, "rail": rail.name, "rail_inclination": rail_inclination,
              "gauge": gauge, "back_to_back": back_to_back, "flange_back": flange_back,
              "r0": r0, "gauge_depth": gauge_depth}  # fmt: skip
    return PatchSearch(WheelLocus(wheel, rail_c, y_tape, y_rail, r0, sample_step, 1.0),
                       WheelLocus(wheel, rail_c, y_tape, y_rail, r0, sample_step, -1.0),
                       rail_c, params)  # fmt: skip


def raw_patches(locus: WheelLocus, y: float, phi: float, psi: float, depth: float,
                separation: float) -> tuple[float, list[dict], np.ndarray]:  # fmt: skip
    """The lowest gap (m), the valleys within ``depth`` of it as dicts of the patch's
    geometry (``x`` the lead, ``y``, ``z`` on the lowered wheel, ``r``, ``delta``, ``u``,
    ``t``, ``gap`` above the lowest, ``i`` the sample), lowest first, and the gap
    function itself."""
    x, yy, z, gap = locus.locus(y, phi, psi)
    ea = _axes(phi, psi)[0]
    g_low = _refine(gap)[2]
    out = []
    for i0 in valleys(gap, locus.u, depth, separation):
        i, off, gmin = _refine(gap, i0)
        j = min(max(i + (1 if off > 0 else -1), 0), gap.size - 1)
        w = abs(off)

        def at(a: np.ndarray, i: int = i, j: int = j, w: float = w) -> float:
            return float((1 - w) * a[i] + w * a[j])

        y_c = at(yy)
        t = locus.sign * y_c - locus.y_rail
        slope = float(np.interp(t, locus.ry, locus.rslope))
        out.append({"x": at(x) - ea[0] * (y_c - y) / ea[1], "y": y_c, "z": at(z) - g_low,
                    "r": at(locus.r), "delta": math.atan(-slope), "u": at(locus.u), "t": t,
                    "gap": max(float(gmin) - g_low, 0.0), "i": i})  # fmt: skip
    out.sort(key=lambda p: p["gap"])
    if out:
        out[0]["gap"] = 0.0
    return g_low, out, gap - g_low


def distinct(gap: np.ndarray, patches: list[dict], level: float) -> list[int]:
    """Which of the valleys ``patches`` (lowest first) are patches of their own at the
    approach ``level`` (m above the lowest gap): those whose gap is below it and that the
    gap function separates from every lower one by a ridge above ``level / 2``. A Hertz
    contact's area is where the rigid gap is below half the approach (``a^2 = R d``): two
    valleys under a lower ridge press one area, and are one patch (the lower)."""
    kept: list[int] = []
    for k, p in enumerate(patches):
        if k and p["gap"] >= level:
            continue
        i = p["i"]
        if all(float(gap[min(i, patches[m]["i"]): max(i, patches[m]["i"]) + 1].max())
               > 0.5 * level for m in kept):  # fmt: skip
            kept.append(k)
    return kept


def ellipse_constants(delta: float, radius: float, k_wheel: float, k_rail: float,
                      young: float, poisson: float) -> tuple[float, float, float]:  # fmt: skip
    """``(a1, b1, d1)`` of a contact under 1 N (:func:`hertz_per_newton`) from its angle,
    rolling radius and transverse curvatures, with the per-point model's limits
    (:func:`railhunt.contact.point_contact.point_contact`: ``a/b`` within its range, a
    conformal contact at the nearest Hertz ellipse)."""
    from railhunt.contact.point_contact import _ratio_bounds

    lo, hi = _ratio_bounds(poisson)
    cx = math.cos(delta) / (2.0 * radius)
    cy = 0.5 * (k_wheel + k_rail)
    cy = min(max(cy if cy > 0.0 else lo * cx, lo * cx), hi * cx)
    return hertz_per_newton(cx, cy, young, poisson)
