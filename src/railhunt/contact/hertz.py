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

Kalker's coefficients ``C11, C22, C23, C33`` of the linear theory of rolling contact
(J. J. Kalker, *On the rolling contact of two elastic bodies in the presence of dry
friction*, thesis, Delft 1967; tabulated again in Kalker, *Three-dimensional elastic
bodies in rolling contact*, Kluwer 1990, Table E.3) are interpolated in ``g`` (linear,
between the table's rows ``g = a/b`` or ``b/a`` = 0.1 ... 1.0) and in Poisson's ratio
(quadratic through ``nu = 0, 0.25, 0.5``). Then (``G`` shear modulus, ``a`` the semi-axis
in the rolling direction):

    f11 = G a b C11,  f22 = G a b C22,  f23 = G (a b)^1.5 C23,  f33 = G (a b)^2 C33.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

__all__ = [
    "CreepCoefficients",
    "HertzContact",
    "creep_coefficients",
    "hertz_contact",
    "kalker_coefficients",
]

# Kalker's table: [case][row][coefficient][nu]; case 0: a <= b, rows g = a/b = 0.1..1.0;
# case 1: a > b, rows g = b/a = 0.1..1.0. Coefficients C11, C22, C23, C33; nu = 0, 0.25, 0.5.
_KALKER = np.array([
    [  # a/b = 0.1 ... 1.0
        [[2.51, 3.31, 4.85], [2.51, 2.52, 2.53], [0.334, 0.473, 0.731], [6.42, 8.28, 11.7]],
        [[2.59, 3.37, 4.81], [2.59, 2.63, 2.66], [0.483, 0.603, 0.809], [3.46, 4.27, 5.66]],
        [[2.68, 3.44, 4.80], [2.68, 2.75, 2.81], [0.607, 0.715, 0.889], [2.49, 2.96, 3.72]],
        [[2.78, 3.53, 4.82], [2.78, 2.88, 2.98], [0.720, 0.823, 0.977], [2.02, 2.32, 2.77]],
        [[2.88, 3.62, 4.83], [2.88, 3.01, 3.14], [0.827, 0.929, 1.07], [1.74, 1.93, 2.22]],
        [[2.98, 3.72, 4.91], [2.98, 3.14, 3.31], [0.930, 1.03, 1.18], [1.56, 1.68, 1.86]],
        [[3.09, 3.81, 4.97], [3.09, 3.28, 3.48], [1.03, 1.14, 1.29], [1.43, 1.50, 1.60]],
        [[3.19, 3.91, 5.05], [3.19, 3.41, 3.65], [1.13, 1.25, 1.40], [1.34, 1.37, 1.42]],
        [[3.29, 4.01, 5.12], [3.29, 3.54, 3.82], [1.23, 1.36, 1.51], [1.27, 1.27, 1.27]],
        [[3.40, 4.12, 5.20], [3.40, 3.67, 3.98], [1.33, 1.47, 1.63], [1.21, 1.19, 1.16]],
    ],
    [  # b/a = 0.1 ... 1.0
        [[10.7, 11.7, 12.9], [10.7, 12.8, 16.0], [12.2, 14.6, 18.0], [0.795, 0.526, 0.228]],
        [[6.96, 7.78, 8.82], [6.96, 8.14, 9.79], [5.72, 6.63, 7.89], [0.828, 0.601, 0.341]],
        [[5.57, 6.34, 7.34], [5.57, 6.40, 7.51], [3.79, 4.32, 5.01], [0.868, 0.674, 0.446]],
        [[4.84, 5.57, 6.57], [4.84, 5.48, 6.31], [2.88, 3.24, 3.70], [0.912, 0.747, 0.549]],
        [[4.37, 5.10, 6.11], [4.37, 4.90, 5.56], [2.35, 2.62, 2.96], [0.958, 0.819, 0.650]],
        [[4.06, 4.78, 5.80], [4.06, 4.50, 5.04], [2.01, 2.23, 2.50], [1.01, 0.892, 0.751]],
        [[3.82, 4.54, 5.58], [3.82, 4.21, 4.67], [1.76, 1.95, 2.18], [1.05, 0.965, 0.852]],
        [[3.65, 4.36, 5.42], [3.65, 3.99, 4.39], [1.58, 1.75, 1.94], [1.10, 1.04, 0.954]],
        [[3.51, 4.22, 5.30], [3.51, 3.81, 4.16], [1.44, 1.59, 1.77], [1.16, 1.11, 1.06]],
        [[3.40, 4.12, 5.20], [3.40, 3.67, 3.98], [1.33, 1.47, 1.63], [1.21, 1.19, 1.16]],
    ],
])
_NU = (0.0, 0.25, 0.5)


def _check(name: str, value: float, low: float, high: float, unit: str = "",
           low_open: bool = False) -> float:
    ok = isinstance(value, int | float) and math.isfinite(value)
    ok = ok and (value > low if low_open else value >= low) and value <= high
    if not ok:
        lb = "(" if low_open else "["
        raise ValueError(f"{name} = {value!r}{(' ' + unit) if unit else ''} is invalid: "
                         f"must be in {lb}{low:g}, {high:g}]")
    return float(value)


def kalker_coefficients(a_over_b: float, nu: float) -> tuple[float, float, float, float]:
    """Kalker's ``(C11, C22, C23, C33)`` for semi-axis ratio ``a/b`` and Poisson's ratio.

    Parameters
    ----------
    a_over_b : float
        Semi-axis in the rolling direction over the lateral one, in ``[0.1, 10]``.
    nu : float
        Poisson's ratio, in ``[0, 0.5]``.

    Returns
    -------
    tuple of float
        Dimensionless coefficients.
    """
    _check("a_over_b", a_over_b, 0.1, 10.0)
    _check("nu", nu, 0.0, 0.5)
    case, g = (0, a_over_b) if a_over_b <= 1.0 else (1, 1.0 / a_over_b)
    x = 10.0 * g - 1.0  # row index, 0..9
    i = min(int(math.floor(x)), 8)
    w = x - i
    row = (1.0 - w) * _KALKER[case, i] + w * _KALKER[case, i + 1]  # (4, 3)
    n0, n1, n2 = _NU
    l0 = (nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2))
    l1 = (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2))
    l2 = (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1))
    c = row[:, 0] * l0 + row[:, 1] * l1 + row[:, 2] * l2
    return float(c[0]), float(c[1]), float(c[2]), float(c[3])


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
