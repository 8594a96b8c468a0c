"""Hertz contact ellipse and Kalker's linear creep coefficients.

Hertz (Johnson, *Contact Mechanics*, 1985, Sec. 4.2): two bodies of the same elastic
material with relative curvatures ``A`` (rolling direction ``x``) and ``B`` (lateral
``y``), ``A = (1/r_wheel + 1/R_rail_x)/2``, ``B = (1/R_wheel_y + 1/R_rail_y)/2``, pressed
by ``N``. With ``m = e^2 = 1 - (b_s/a_l)^2`` (``a_l`` the longer, ``b_s`` the shorter
semi-axis, the longer one along the smaller curvature):

    C_big / C_small = (E(m)/(1 - m) - K(m)) / (K(m) - E(m)),
    a_l^3 = 3 N (K(m) - E(m)) / (2 pi E* m C_small),    1/E* = 2 (1 - nu^2) / E,

with ``K``, ``E`` the complete elliptic integrals (``scipy.special.ellipk/ellipe``, argument
``m``). For ``A = B`` this is the circle ``a^3 = 3 N R / (4 E*)``, ``R = 1/(2A)``.

Kalker's coefficients ``C11, C22, C23, C33`` of the linear theory of rolling contact come
from :func:`railhunt.mechanics.coefficients.kalker_coefficients` (Kalker's Table E.3 for
``a/b`` in ``[0.1, 10]``, extended to ``[0.05, 20]``). Then (``G`` shear modulus, ``a`` the
semi-axis in the rolling direction):

    f11 = G a b C11,  f22 = G a b C22,  f23 = G (a b)^1.5 C23,  f33 = G (a b)^2 C33.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from railhunt.mechanics._checks import check_range
from railhunt.mechanics.coefficients import kalker_coefficients

__all__ = [
    "CreepCoefficients",
    "HertzContact",
    "creep_coefficients",
    "hertz_contact",
    "kalker_coefficients",
]


def _check(name: str, value: float, low: float, high: float, unit: str = "",
           low_open: bool = False) -> float:
    return check_range(name, value, low, high, unit, low_open=low_open)


@dataclass(frozen=True)
class HertzContact:
    """Hertz contact ellipse.

    Attributes
    ----------
    a : float
        Semi-axis in the rolling direction (m).
    b : float
        Lateral semi-axis (m).
    p0 : float
        Peak pressure (Pa).
    """

    a: float
    b: float
    p0: float


def _ratio_of_curvatures(m: float) -> float:
    k, e = ellipk(m), ellipe(m)
    return (e / (1.0 - m) - k) / (k - e)


def _k_minus_e_over_m(m: float) -> float:
    if m < 1e-6:  # series: (K - E)/m = pi/4 (1 + 3m/8 + ...)
        return math.pi / 4.0 * (1.0 + 0.375 * m)
    return (ellipk(m) - ellipe(m)) / m


def hertz_contact(normal_load: float, curvature_x: float, curvature_y: float,
                  young: float = 2.1e11, nu: float = 0.3) -> HertzContact:
    """Hertz ellipse of two bodies of one elastic material.

    Parameters
    ----------
    normal_load : float
        Normal force ``N`` (N), > 0.
    curvature_x, curvature_y : float
        Relative curvatures ``A`` (rolling direction) and ``B`` (lateral) (1/m), > 0:
        half the sums of the principal curvatures of both bodies (convex positive).
    young : float
        Young's modulus (Pa).
    nu : float
        Poisson's ratio.

    Returns
    -------
    HertzContact
    """
    _check("normal_load", normal_load, 0.0, 1e8, "N", low_open=True)
    _check("curvature_x", curvature_x, 0.0, 1e6, "1/m", low_open=True)
    _check("curvature_y", curvature_y, 0.0, 1e6, "1/m", low_open=True)
    _check("young", young, 0.0, 1e13, "Pa", low_open=True)
    _check("nu", nu, 0.0, 0.5)
    e_star = young / (2.0 * (1.0 - nu * nu))
    small, big = sorted((curvature_x, curvature_y))
    ratio = big / small
    if ratio - 1.0 < 1e-12:
        m = 0.0
    else:
        if ratio > 1e4:
            raise ValueError(f"curvature ratio B/A = {ratio:.4g} is invalid: must be <= 1e4")
        m_lo = 1e-6  # below, K - E loses digits: ratio - 1 is linear in m there
        r_lo = _ratio_of_curvatures(m_lo)
        if ratio <= r_lo:
            m = m_lo * (ratio - 1.0) / (r_lo - 1.0)
        else:
            m = brentq(lambda mm: _ratio_of_curvatures(mm) - ratio, m_lo, 1.0 - 1e-15,
                       xtol=1e-16, rtol=1e-14, maxiter=500)
    long_axis = (3.0 * normal_load * _k_minus_e_over_m(m) / (2.0 * math.pi * e_star * small)
                 ) ** (1.0 / 3.0)
    short_axis = long_axis * math.sqrt(1.0 - m)
    a, b = (long_axis, short_axis) if curvature_x <= curvature_y else (short_axis, long_axis)
    p0 = 3.0 * normal_load / (2.0 * math.pi * a * b)
    return HertzContact(float(a), float(b), float(p0))


@dataclass(frozen=True)
class CreepCoefficients:
    """Kalker's linear creep coefficients of one wheel/rail contact.

    Attributes
    ----------
    f11, f22 : float
        Longitudinal and lateral coefficients (N).
    f23 : float
        Lateral/spin coefficient (N*m).
    f33 : float
        Spin coefficient (N*m^2).
    a, b : float
        Hertz semi-axes (m), rolling direction and lateral.
    c11, c22, c23, c33 : float
        Kalker's dimensionless coefficients used.
    """

    f11: float
    f22: float
    f23: float
    f33: float
    a: float
    b: float
    c11: float
    c22: float
    c23: float
    c33: float


def creep_coefficients(
    normal_load: float,
    wheel_radius: float,
    wheel_transverse_radius: float = math.inf,
    rail_transverse_radius: float = 0.3,
    rail_longitudinal_radius: float = math.inf,
    young: float = 2.1e11,
    nu: float = 0.3,
) -> CreepCoefficients:
    """Kalker's ``f11, f22, f23, f33`` from the load, the curvatures and the material.

    Parameters
    ----------
    normal_load : float
        Wheel normal load (N).
    wheel_radius : float
        Rolling radius (m).
    wheel_transverse_radius : float
        Radius of the wheel profile at the contact point (m), positive convex, negative
        concave (hollow tread), ``inf`` for a straight (conical) tread.
    rail_transverse_radius : float
        Radius of the rail head profile at the contact point (m), e.g. 0.3 on the UIC60
        crown.
    rail_longitudinal_radius : float
        Rail radius along the track (m), ``inf`` on straight track.
    young, nu : float
        Young's modulus (Pa) and Poisson's ratio of wheel and rail steel.

    Returns
    -------
    CreepCoefficients
    """
    _check("wheel_radius", wheel_radius, 0.0, 5.0, "m", low_open=True)
    curv_x = 0.5 * (1.0 / wheel_radius + 1.0 / rail_longitudinal_radius)
    curv_y = 0.5 * (1.0 / wheel_transverse_radius + 1.0 / rail_transverse_radius)
    if not curv_y > 0:
        raise ValueError(
            f"wheel_transverse_radius = {wheel_transverse_radius!r} m and "
            f"rail_transverse_radius = {rail_transverse_radius!r} m are invalid: the "
            "lateral relative curvature 1/R_wheel + 1/R_rail must be > 0 (non-conformal)"
        )
    h = hertz_contact(normal_load, curv_x, curv_y, young, nu)
    c11, c22, c23, c33 = kalker_coefficients(h.a / h.b, nu)
    g = young / (2.0 * (1.0 + nu))
    ab = h.a * h.b
    return CreepCoefficients(
        f11=g * ab * c11, f22=g * ab * c22, f23=g * ab**1.5 * c23, f33=g * ab**2 * c33,
        a=h.a, b=h.b, c11=c11, c22=c22, c23=c23, c33=c33,
    )
