"""Creep laws: Kalker's linear theory with the paper's heuristic saturation.

Kalker's linear law (Eq. 26) gives the creep forces of one wheel from its creepages;
the heuristic (Johnson-Vermeulen type) saturation of Eqs. 27-28 scales the
longitudinal and lateral forces so that their resultant never exceeds ``mu * N``.
"""

from __future__ import annotations

from numba import njit

#: Creep-law codes understood by the compiled right-hand side.
CREEP_LAWS: dict[str, int] = {"heuristic": 0, "heuristic-per-wheel": 1, "linear": 2}


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
