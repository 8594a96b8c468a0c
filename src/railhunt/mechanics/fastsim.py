"""FASTSIM's flexibilities: Kalker's single weighted one, and three blended ones.

The simplified theory's flexibilities are chosen so that it reproduces Kalker's linear
theory for small creepages (Kalker 1982):

    L1 = 8 a / (3 G C11),   L2 = 8 a / (3 G C22),   L3 = pi a^2 / (4 G c C23).

``"fastsim"`` (Kalker, Vehicle System Dynamics 11 (1982) 1-13) uses one flexibility, the
creepage-weighted mean ``L = (|xi| L1 + |eta| L2 + c |phi| L3) / sqrt(xi^2 + eta^2 +
c^2 phi^2)``, and the parabolic traction bound.

``"fastsim-modified"`` uses the three flexibilities separately (Vollebregt and Wilders,
Comput. Mech. 47 (2011) 105-116), blended towards one at large creepage as Vollebregt and
Voltr propose ("Improved accuracy for FASTSIM using one or three flexibility values",
Vehicle System Dynamics 61 (2023) 309-317; CONTACT's ``M = 3``): with the one value
``L_c = (xi^2 + eta^2 + (k phi)^2) / (xi^2/L1 + eta^2/L2 + (k phi)^2/L3)``,
``k = 3 pi a / 32``, and the weight ``w = min(1, f/3)`` of the creepage relative to the
one that saturates the linear theory, ``f = sqrt((xi^2 + eta^2) / (x1^2 + x2^2))``,
``x1 = mu N / (G c^2 C11)``, ``x2 = mu N / (G c^2 C22)``, each flexibility becomes
``(1 - w) L_i + w L_c``. Its traction bound is Kalker's parabolic one by default: measured
against the exact theory (docs/creep.md) it keeps the forces within 8 % of mu N on every
patch, the flange's included, where the elliptical (Hertz) bound, which CONTACT
recommends and which gives the spin moment of round patches more closely, is 17 % off.
"""

from __future__ import annotations

import numpy as np

__all__ = ["kalker_flexibilities", "modified_flexibilities", "weighted_flexibility"]


def kalker_flexibilities(a, b, shear_modulus, c11, c22, c23):
    """``(L1, L2, L3)`` (m/Pa) of Kalker's simplified theory (arrays broadcast)."""
    c = np.sqrt(a * b)
    l1 = 8.0 * a / (3.0 * shear_modulus * c11)
    l2 = 8.0 * a / (3.0 * shear_modulus * c22)
    l3 = np.pi * a * a / (4.0 * shear_modulus * c * c23)
    return l1, l2, l3


def weighted_flexibility(xi, eta, phi, a, b, l1, l2, l3):
    """Kalker's (1982) single flexibility, the creepage-weighted mean of ``L1, L2, L3``;
    ``L1`` where every creepage is zero (the forces are zero there anyway)."""
    c = np.sqrt(a * b)
    norm = np.sqrt(xi * xi + eta * eta + (c * phi) ** 2)
    num = np.abs(xi) * l1 + np.abs(eta) * l2 + c * np.abs(phi) * l3
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(norm > 0.0, num / np.where(norm > 0.0, norm, 1.0), l1)


def modified_flexibilities(xi, eta, phi, a, b, mu_n, shear_modulus, c11, c22, c23):
    """Vollebregt and Voltr's (2023) blended three flexibilities ``(L1, L2, L3)`` (m/Pa)."""
    l1, l2, l3 = kalker_flexibilities(a, b, shear_modulus, c11, c22, c23)
    c2g = a * b * shear_modulus
    x1 = mu_n / (c2g * c11)
    x2 = mu_n / (c2g * c22)
    k = 3.0 * np.pi * a / 32.0
    s3 = (k * phi) ** 2
    num = xi * xi + eta * eta + s3
    den = xi * xi / l1 + eta * eta / l2 + s3 / l3
    with np.errstate(invalid="ignore", divide="ignore"):
        lc = np.where(den > 0.0, num / np.where(den > 0.0, den, 1.0), l1)
    f = np.sqrt((xi * xi + eta * eta) / (x1 * x1 + x2 * x2))
    w = np.clip(f / 3.0, 0.0, 1.0)
    return (1.0 - w) * l1 + w * lc, (1.0 - w) * l2 + w * lc, (1.0 - w) * l3 + w * lc
