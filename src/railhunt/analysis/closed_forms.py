"""Closed forms of railway dynamics that the numerical analyses are checked against.

Pure Python, SI units. Derivations in docs/model.md ("Closed forms used as checks"). All
three concern conical wheels (rolling radii ``r0 +- lambda y``) on knife-edge rails (no
gravitational stiffness, no spin) with Kalker's linear creep law; ``f11`` and ``f22`` are
the longitudinal and lateral creep coefficients of one wheel (N), ``a`` half the distance
between the contact points (m).

* :func:`klingel_wavelength`: a free wheelset's kinematic oscillation,
  ``2 pi sqrt(r0 a / lambda)``;
* :func:`rigid_truck_wavelength`: two wheelsets held rigidly in one frame at ``+-b``,
  ``2 pi sqrt((r0 a / lambda) (1 + (f22 / f11) b^2 / a^2))``;
* :func:`sprung_wheelset_quartic` and :func:`sprung_wheelset_critical_speed`: a wheelset
  on lateral and yaw springs to a fixed frame, its characteristic quartic and the speed
  where Routh-Hurwitz's condition fails (the Hopf point), with the frequency there.
"""

from __future__ import annotations

import math
from typing import NamedTuple

__all__ = [
    "SprungWheelsetStability", "klingel_wavelength", "rigid_truck_wavelength",
    "sprung_wheelset_critical_speed", "sprung_wheelset_quartic",
]  # fmt: skip


def _check(low_open: bool, **values: float) -> None:
    for name, value in values.items():
        try:
            x = float(value)
        except (TypeError, ValueError):
            x = math.nan
        if not (math.isfinite(x) and (x > 0 if low_open else x >= 0)):
            bound = "> 0" if low_open else ">= 0"
            raise ValueError(f"{name} = {value!r} is invalid: must be finite and {bound}")


def _positive(**values: float) -> None:
    _check(True, **values)


def _non_negative(**values: float) -> None:
    _check(False, **values)


def klingel_wavelength(r0: float, a: float, conicity: float) -> float:
    """Klingel's wavelength of a free wheelset's kinematic oscillation (m).

    Parameters
    ----------
    r0 : float
        Centred rolling radius (m).
    a : float
        Half the distance between the contact points (m).
    conicity : float
        Cone slope ``lambda`` of the treads (dimensionless).

    Returns
    -------
    float
        ``2 pi sqrt(r0 a / lambda)``.
    """
    _positive(r0=r0, a=a, conicity=conicity)
    return 2.0 * math.pi * math.sqrt(r0 * a / conicity)


def rigid_truck_wavelength(r0: float, a: float, conicity: float, b: float,
                           f11: float = 1.0, f22: float = 1.0) -> float:  # fmt: skip
    """Kinematic wavelength of a rigid two-axle truck (m).

    Two wheelsets at ``+-b`` held rigidly in one frame, inertia neglected (low speed):
    ``2 pi sqrt((r0 a / lambda) (1 + (f22 / f11) (b / a)^2))``; with equal creep
    coefficients ``2 pi sqrt((r0 a / lambda) (1 + b^2 / a^2))``, and Klingel's wavelength
    for ``b = 0``.

    Parameters
    ----------
    r0, a, conicity : float
        As :func:`klingel_wavelength`.
    b : float
        Half the wheelbase (m), >= 0.
    f11, f22 : float
        Longitudinal and lateral creep coefficients of one wheel (N); only their ratio
        matters.

    Returns
    -------
    float
        The wavelength (m).
    """
    _positive(r0=r0, a=a, conicity=conicity, f11=f11, f22=f22)
    _non_negative(b=b)
    return klingel_wavelength(r0, a, conicity) * math.sqrt(1.0 + (f22 / f11) * (b / a) ** 2)


def sprung_wheelset_quartic(speed: float, mass: float, yaw_inertia: float,
                            k_lateral: float, k_yaw: float, f11: float, f22: float,
                            r0: float, a: float, conicity: float,
                            ) -> tuple[float, float, float, float, float]:  # fmt: skip
    """Characteristic polynomial of a wheelset on springs to a fixed frame.

    ``m y'' + 2 f22 (y'/V - psi) + k_y y = 0`` and
    ``J psi'' + 2 f11 a (a psi'/V + lambda y / r0) + k_psi psi = 0`` give
    ``det = (m s^2 + c_y s + k_y)(J s^2 + c_psi s + k_psi) + P`` with ``c_y = 2 f22 / V``,
    ``c_psi = 2 f11 a^2 / V`` and ``P = 4 f11 f22 a lambda / r0``.

    Parameters
    ----------
    speed : float
        Forward speed ``V`` (m/s).
    mass, yaw_inertia : float
        Wheelset mass (kg) and yaw inertia (kg m^2).
    k_lateral, k_yaw : float
        Lateral stiffness (N/m) and yaw stiffness (N m/rad) to the frame, in total.
    f11, f22 : float
        Creep coefficients of one wheel (N).
    r0, a, conicity : float
        As :func:`klingel_wavelength`.

    Returns
    -------
    tuple of float
        ``(a4, a3, a2, a1, a0)``: ``a4 s^4 + a3 s^3 + a2 s^2 + a1 s + a0``.
    """
    _positive(speed=speed, mass=mass, yaw_inertia=yaw_inertia, f11=f11, f22=f22, r0=r0,
              a=a, conicity=conicity)  # fmt: skip
    _non_negative(k_lateral=k_lateral, k_yaw=k_yaw)
    c_y = 2.0 * f22 / speed
    c_psi = 2.0 * f11 * a * a / speed
    coupling = 4.0 * f11 * f22 * a * conicity / r0
    return (
        mass * yaw_inertia,
        mass * c_psi + yaw_inertia * c_y,
        mass * k_yaw + yaw_inertia * k_lateral + c_y * c_psi,
        c_y * k_yaw + c_psi * k_lateral,
        k_lateral * k_yaw + coupling,
    )


class SprungWheelsetStability(NamedTuple):
    """The Hopf point of a wheelset on springs (:func:`sprung_wheelset_critical_speed`)."""

    #: Critical speed (m/s): stable below; 0 if unstable at every speed, inf if never.
    critical_speed: float
    #: Frequency of the oscillation at the critical speed (Hz): ``sqrt(a1/a3) / 2 pi``.
    frequency: float


def sprung_wheelset_critical_speed(mass: float, yaw_inertia: float, k_lateral: float,
                                   k_yaw: float, f11: float, f22: float, r0: float, a: float,
                                   conicity: float) -> SprungWheelsetStability:  # fmt: skip
    """Critical speed of a wheelset on springs to a fixed frame, by Routh-Hurwitz.

    Every coefficient of :func:`sprung_wheelset_quartic` is positive; the quartic is stable
    while ``H = a3 a2 a1 - a4 a1^2 - a0 a3^2 > 0``. The damping terms scale as ``1/V``:
    with ``A3 = V a3``, ``A1 = V a1``, ``B = m k_psi + J k_y`` and
    ``C = (2 f22)(2 f11 a^2)``, ``V^2 H = A3 A1 (B + C / V^2) - m J A1^2 - a0 A3^2``, so
    ``V_c^2 = A3 A1 C / (m J A1^2 + a0 A3^2 - A3 A1 B)`` if the denominator is positive
    (else stable at every speed). At ``V_c`` the roots ``+-i omega`` have
    ``omega^2 = a1 / a3 = A1 / A3``. Without springs ``A1 = 0``: unstable at every speed.

    Parameters
    ----------
    mass, yaw_inertia, k_lateral, k_yaw, f11, f22, r0, a, conicity : float
        As :func:`sprung_wheelset_quartic`.

    Returns
    -------
    SprungWheelsetStability
        Critical speed (m/s) and frequency (Hz) there.
    """
    a4, a3, a2, a1, a0 = sprung_wheelset_quartic(1.0, mass, yaw_inertia, k_lateral, k_yaw,
                                                 f11, f22, r0, a, conicity)  # fmt: skip
    big_c = (2.0 * f22) * (2.0 * f11 * a * a)
    big_b = a2 - big_c  # the speed-free part of a2 (a2 at V = 1 holds C once)
    denominator = a4 * a1 * a1 + a0 * a3 * a3 - a3 * a1 * big_b
    omega = math.sqrt(a1 / a3)
    if a1 == 0.0:
        return SprungWheelsetStability(0.0, 0.0)
    if denominator <= 0.0:
        return SprungWheelsetStability(math.inf, omega / (2.0 * math.pi))
    speed = math.sqrt(a3 * a1 * big_c / denominator)
    return SprungWheelsetStability(speed, omega / (2.0 * math.pi))
