"""The paper's polynomial contact geometry (Eqs. 32-33): coefficients consistent with it.

The polynomials themselves are evaluated in the compiled kernel
(:func:`railhunt.kernel.contact.rolling_radius`, :func:`~railhunt.kernel.contact.contact_angle`,
re-exported here).

Each wheel is described as a function of ``u``, its lateral displacement toward its own
flange (m): ``u = +y`` for the left wheel and ``u = -y`` for the right wheel when the
wheelset is displaced by ``y`` (positive to the left). A wheel moving toward its flange
(``u > 0``) runs on a larger rolling radius and a steeper contact angle.

The paper prints the contact-angle coefficients ``d0, d1, d4, d5`` for the opposite
sense of ``y`` (its polynomial steepens for negative ``y``, see its Fig. 3); they are
used here unchanged with ``u = -y_paper``:
``delta(u) = d0 - d1*u + d4*u**4 - d5*u**5``, capped at ``delta_max`` (the flange angle).
"""

from __future__ import annotations

from railhunt.kernel.contact import contact_angle, rolling_radius

__all__ = ["contact_angle", "radius_coefficients_from_contact_angle", "rolling_radius"]


def radius_coefficients_from_contact_angle(
    kappa: float,
    d0: float,
    d1: float,
    d4: float,
    d5: float,
    delta_max: float,
    u_max: float = 0.008,
    n: int = 4001,
) -> tuple[float, float, float, float, float]:
    """Rolling-radius coefficients ``lambda1..lambda5`` consistent with a contact-angle law.

    At the contact point the wheel profile's slope is ``tan(delta)``, so the rolling radius
    grows as ``dr/du = kappa * tan(delta(u))``, with ``kappa = ds/du`` the ratio between the
    contact point's travel across the wheel tread and the wheelset's displacement (taken
    constant). Integrating from ``u = 0`` and fitting a quintic by least squares over
    ``[-u_max, u_max]`` gives Eq. 32's coefficients (``lambda1 = kappa * tan(d0)`` to
    within the fit).

    Parameters
    ----------
    kappa : float
        Contact-point travel ratio (dimensionless, > 0).
    d0, d1, d4, d5, delta_max : float
        Contact-angle law (see :func:`contact_angle`).
    u_max : float
        Half-width of the fitting range (m).
    n : int
        Number of integration points.

    Returns
    -------
    tuple of float
        ``(lambda1, lambda2, lambda3, lambda4, lambda5)`` in SI units (1, 1/m, ... 1/m^4).
    """
    import numpy as np

    u = np.linspace(-u_max, u_max, n)
    slope = np.tan(
        np.clip(d0 - d1 * u + d4 * u**4 - d5 * u**5, -delta_max, delta_max)
    )
    du = u[1] - u[0]
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (slope[1:] + slope[:-1]) * du)])
    integral -= integral[n // 2]
    basis = np.vstack([u**k for k in range(1, 6)]).T
    coef, *_ = np.linalg.lstsq(basis, kappa * integral, rcond=None)
    return tuple(float(c) for c in coef)
