"""Creep laws: Kalker's linear theory with the paper's heuristic saturation or Polach's.

Kalker's linear law (Eq. 26) gives the creep forces of one wheel from its creepages;
the heuristic (Johnson-Vermeulen type) saturation of Eqs. 27-28 scales the
longitudinal and lateral forces so that their resultant never exceeds ``mu * N``.

Polach's method (O. Polach, "A fast wheel-rail forces calculation computer code",
Vehicle System Dynamics 33 (suppl.), 1999, 728-739) gives the resultant tangential force
``F = (2 mu N / pi) (eps / (1 + eps^2) + atan(eps))`` with the gradient of the
tangential stress ``eps = (2/3) C pi a^2 b s / (mu N)``, ``C = (3/8) (G/a) c_jj``
(Kalker's coefficients). Since ``(2/3) C pi a^2 b s = (pi/4) |F_Kalker|``, this is
``eps = (pi/4) beta`` with ``beta = |F_Kalker| / (mu N)``, the same input as the
heuristic law: :func:`polach_saturation` returns ``alpha = F / (mu N beta)``.
Vermeulen and Johnson (J. Appl. Mech. 31 (1964) 338-340) saturate the resultant of the
longitudinal and lateral creepages: with ``u = sqrt((xi_x/phi)^2 + (xi_y/psi)^2)`` and
``beta = G pi a b u / (mu N)``, ``F_R / (mu N) = beta - beta^2/3 + beta^3/27`` for
``beta < 3`` and 1 beyond, each component following its creepage. With the creep
coefficients ``f11 = G pi a b / phi``, ``f22 = G pi a b / psi`` this is
``beta = |(f11 xi_x, f22 xi_y)| / (mu N)`` and every component scaled by the factor
:func:`heuristic_saturation` gives (the same cubic as Eq. 28), wheel by wheel. Their
theory has no spin: ``beta`` is formed without the spin terms, which (if ``f23`` is not
0) are scaled by the same factor.

Departure: Polach's separate spin term (``F_yS`` with ``K_M``) needs the ellipse
semi-axes, which the model does not carry; the spin part of Kalker's lateral force is
saturated together with the creepage part, as in the heuristic law.
"""

from __future__ import annotations

import math
from enum import IntEnum

from numba import njit


class CreepLaw(IntEnum):
    """Creep-law codes understood by the compiled right-hand side (slot ``WR.CREEP_LAW``)."""

    HEURISTIC = 0  # the paper's Eq. 28, one factor per wheelset from the wheels' mean beta
    HEURISTIC_PER_WHEEL = 1  # Eq. 28 with one factor per wheel
    LINEAR = 2  # Kalker's linear law, no saturation
    POLACH = 3  # Polach's saturation per wheel
    VERMEULEN_JOHNSON = 4  # Vermeulen-Johnson: Eq. 28's cubic per wheel on f11 xi_x, f22 xi_y
    EXACT_TABLE = 5  # Kalker's exact theory, tabulated (per-point contact mechanics only)


#: Creep-law names (as users write them) -> codes.
CREEP_LAWS: dict[str, int] = {
    law.name.lower().replace("_", "-"): int(law) for law in CreepLaw
}


@njit(cache=True)
def heuristic_saturation(beta: float) -> float:
    """Saturation factor ``alpha(beta)`` of Eq. 28 (dimensionless).

    Parameters
    ----------
    beta : float
        Unsaturated resultant creep force over ``mu * N`` (>= 0).

    Returns
    -------
    float
        ``1 - beta/3 + beta**2/27`` for ``beta <= 3`` (the printed
        ``(beta - beta**2/3 + beta**3/27) / beta`` without the 0/0 at ``beta = 0``),
        ``1 / beta`` above. Continuous with a continuous derivative at ``beta = 3``;
        ``alpha * beta`` rises monotonically to 1.
    """
    if beta <= 3.0:
        return 1.0 - beta / 3.0 + beta * beta / 27.0
    return 1.0 / beta


@njit(cache=True)
def polach_saturation(beta: float) -> float:
    """Polach's saturation factor ``alpha(beta)`` (dimensionless), per wheel.

    Parameters
    ----------
    beta : float
        Unsaturated (Kalker) resultant creep force over ``mu * N`` (>= 0).

    Returns
    -------
    float
        ``(2 / (pi beta)) (eps / (1 + eps^2) + atan(eps))`` with ``eps = pi beta / 4``;
        1 at ``beta = 0`` (Kalker's slope), ``alpha * beta -> 1`` as ``beta -> inf``.
    """
    if beta < 1e-9:
        return 1.0 - (math.pi * beta / 4.0) ** 2 * (2.0 / 3.0)
    eps = 0.25 * math.pi * beta
    return 2.0 / (math.pi * beta) * (eps / (1.0 + eps * eps) + math.atan(eps))


@njit(cache=True)
def kalker_linear(
    xi_x: float, xi_y: float, xi_sp: float, f11: float, f22: float, f23: float, f33: float
) -> tuple[float, float, float]:
    """Kalker's linear creep forces and spin moment on a wheel (Eq. 26).

    Parameters
    ----------
    xi_x, xi_y : float
        Longitudinal and lateral creepage (dimensionless).
    xi_sp : float
        Spin creepage (1/m).
    f11, f22 : float
        Longitudinal and lateral creep coefficients (N).
    f23 : float
        Lateral/spin coefficient (N*m).
    f33 : float
        Spin coefficient (N*m^2).

    Returns
    -------
    tuple of float
        ``(F_x, F_y, M_z)`` in N, N, N*m, in the contact plane, acting on the wheel.
    """
    fx = -f11 * xi_x
    fy = -f22 * xi_y - f23 * xi_sp
    mz = f23 * xi_y - f33 * xi_sp
    return fx, fy, mz
