"""Polach's creep forces with his spin term (the closed form, per contact patch).

O. Polach, "A fast wheel-rail forces calculation computer code", Vehicle System Dynamics
33 (suppl.) (1999) 728-739; the same method in O. Polach, "Creep forces in simulations of
traction vehicles running on adhesion limit", Wear 258 (2005) 992-1000 (Eqs. 1-11 there,
whose reduction factors ``k_A``, ``k_S`` and slip-velocity-dependent friction reduce to
the method of 1999 for ``k_A = k_S = 1`` and constant ``mu``, as here).

With the lateral creepage that the spin enlarges, ``s_yC = eta + phi a`` if
``|eta + phi a| > |eta|``, else ``eta``, and ``s_C = sqrt(xi^2 + s_yC^2)``:

    C_jj   = sqrt((c11 xi / s)^2 + (c22 eta / s)^2),   s = sqrt(xi^2 + eta^2),
    eps    = pi G a b C_jj s_C / (4 mu N),
    F      = (2 mu N / pi) (eps / (1 + eps^2) + atan(eps)),
    K_S    = 1 + 6.3 (1 - exp(-a/b)),
    eps_M  = (8/3) G b sqrt(a b) c23 s_C / (mu N K_S),
    delta  = (eps_M^2 - 1) / (eps_M^2 + 1),
    K_M    = |eps_M| (delta^3/3 - delta^2/2 + 1/6) - sqrt((1 - delta^2)^3) / 3,
    F_yS   = -(9/16) a mu N K_M K_S phi / s_C,

and the forces on the wheel ``F_x = -F xi / s_C``, ``F_y = -F eta / s_C - F_yS`` (signs of
Kalker's linear theory: for small creepages these are ``-f11 xi`` and
``-f22 eta - f23 phi``). Polach gives no spin moment.
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def polach_forces(xi, eta, phi, a, b, mu_n, shear_modulus, c11, c22, c23):
    """Polach's ``(F_x, F_y)`` (N) on one patch.

    Parameters
    ----------
    xi, eta : float
        Longitudinal and lateral creepage.
    phi : float
        Spin creepage (1/m).
    a, b : float
        Semi-axes along and across the rolling direction (m).
    mu_n : float
        Friction coefficient times normal force (N).
    shear_modulus : float
        ``G`` (Pa).
    c11, c22, c23 : float
        Kalker's coefficients at ``a/b``.

    Returns
    -------
    fx, fy : float
    """
    syc = eta + phi * a
    if abs(syc) <= abs(eta):
        syc = eta
    sc = math.sqrt(xi * xi + syc * syc)
    if sc == 0.0:
        return 0.0, 0.0
    s = math.sqrt(xi * xi + eta * eta)
    if s > 0.0:
        cjj = math.sqrt((c11 * xi / s) ** 2 + (c22 * eta / s) ** 2)
    else:
        cjj = c22
    eps = math.pi * shear_modulus * a * b * cjj * sc / (4.0 * mu_n)
    force = 2.0 * mu_n / math.pi * (eps / (1.0 + eps * eps) + math.atan(eps))
    ks = 1.0 + 6.3 * (1.0 - math.exp(-a / b))
    eps_m = 8.0 / 3.0 * shear_modulus * b * math.sqrt(a * b) * c23 * sc / (mu_n * ks)
    delta = (eps_m * eps_m - 1.0) / (eps_m * eps_m + 1.0)
    km = abs(eps_m) * (delta**3 / 3.0 - delta * delta / 2.0 + 1.0 / 6.0) - math.sqrt(
        max(0.0, 1.0 - delta * delta) ** 3) / 3.0
    fys = -9.0 / 16.0 * a * mu_n * km * ks * phi / sc
    return -force * xi / sc, -force * eta / sc - fys
