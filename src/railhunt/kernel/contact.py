"""Wheel/rail contact geometry in the right-hand side: rolling radii and contact angles.

Two descriptions, chosen by the wheel/rail vector (:class:`railhunt.kernel.layout.WR`):

* the paper's polynomials (Eqs. 32-33), wheel by wheel: each wheel is described as a
  function of ``u``, its lateral displacement toward its own flange (m): ``u = +y`` for
  the left wheel and ``u = -y`` for the right wheel when the wheelset is displaced by
  ``y`` (positive to the left). A wheel moving toward its flange (``u > 0``) runs on a
  larger rolling radius and a steeper contact angle. The paper prints the contact-angle
  coefficients ``d0, d1, d4, d5`` for the opposite sense of ``y`` (its polynomial
  steepens for negative ``y``, see its Fig. 3); they are used unchanged with
  ``u = -y_paper``: ``delta(u) = d0 - d1*u + d4*u**4 - d5*u**5``, capped at
  ``delta_max`` (the flange angle);
* a table of ``r_L, r_R, delta_L, delta_R`` on a uniform grid of ``y`` (from real
  profiles, :mod:`railhunt.contact.geometry`), interpolated linearly and held constant
  beyond its ends.

Conical treads (a layout's ``contact = "conical"``: rolling radii ``r0 +- lambda y``, a
constant contact angle ``gamma`` on both wheels) are the polynomials with ``lambda1 =
lambda``, ``d0 = gamma``, ``delta_max = |gamma|`` and every other coefficient 0
(:func:`conical_slots`). This is exactly, not approximately, the cone: with zero
coefficients the Horner sums return ``r0 + lambda u`` and ``gamma`` bit for bit, so no
separate code path is needed. With ``gamma = 0`` (a knife-edge rail) both contact angles
are exactly 0: the normal loads have no lateral component (no gravitational stiffness,
no gravitational yaw moment) and the spin creepage has no ``omega sin(delta)`` part.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from railhunt.kernel.layout import WR


def conical_slots(conicity: float, contact_angle: float = 0.0) -> dict[int, float]:
    """Wheel/rail slots of conical treads: rolling radii ``r0 +- conicity y``.

    Parameters
    ----------
    conicity : float
        Cone slope ``lambda`` (dimensionless, rad): ``d r / d u``.
    contact_angle : float
        Constant contact angle of both wheels (rad); 0: knife-edge rails.

    Returns
    -------
    dict
        ``{slot: value}`` for the slots :class:`~railhunt.kernel.layout.WR` ``LAMBDA1``
        ... ``DELTA_MAX`` (the polynomial slots; ``TABLE`` must be 0).
    """
    slots = dict.fromkeys((WR.LAMBDA1, WR.LAMBDA2, WR.LAMBDA3, WR.LAMBDA4, WR.LAMBDA5,
                           WR.D0, WR.D1, WR.D4, WR.D5), 0.0)  # fmt: skip
    slots[WR.LAMBDA1] = float(conicity)
    slots[WR.D0] = float(contact_angle)
    slots[WR.DELTA_MAX] = abs(float(contact_angle))
    return {int(k): v for k, v in slots.items()}


@njit(cache=True)
def rolling_radius(
    u: float, r0: float, l1: float, l2: float, l3: float, l4: float, l5: float
) -> float:
    """Rolling radius of a wheel displaced ``u`` toward its flange (Eq. 32), m.

    ``r = r0 + l1*u + l2*u**2 + l3*u**3 + l4*u**4 + l5*u**5``.
    """
    return r0 + u * (l1 + u * (l2 + u * (l3 + u * (l4 + u * l5))))


@njit(cache=True)
def contact_angle(
    u: float, d0: float, d1: float, d4: float, d5: float, delta_max: float
) -> float:
    """Contact angle of a wheel displaced ``u`` toward its flange (Eq. 33), rad.

    ``delta = d0 - d1*u + d4*u**4 - d5*u**5`` (the paper's coefficients with its sign of
    the lateral coordinate), limited to ``[-delta_max, delta_max]``.
    """
    u2 = u * u
    d = d0 - d1 * u + u2 * u2 * (d4 - d5 * u)
    if d > delta_max:
        return delta_max
    if d < -delta_max:
        return -delta_max
    return d


@njit(cache=True)
def wheel_geometry(y_rel: float, wr: np.ndarray) -> tuple[float, float, float, float]:
    """Rolling radii and contact angles of both wheels of a wheelset.

    Parameters
    ----------
    y_rel : float
        Lateral displacement of the wheelset relative to the track (m), + left.
    wr : numpy.ndarray
        Wheel/rail vector (:class:`railhunt.kernel.layout.WR`).

    Returns
    -------
    tuple of float
        ``(r_L, r_R, delta_L, delta_R)`` in m and rad.
    """
    n_tab = int(wr[WR.TABLE]) if wr.shape[0] > WR.TABLE else 0
    if n_tab > 1:
        # Tabulated geometry: linear interpolation, clamped at the table's ends.
        s = (y_rel - wr[WR.TABLE + 1]) / wr[WR.TABLE + 2]
        if s <= 0.0:
            i, w = 0, 0.0
        elif s >= n_tab - 1:
            i, w = n_tab - 2, 1.0
        else:
            i = int(s)
            w = s - i
        k = WR.TABLE + 3 + i
        r_l = wr[k] + w * (wr[k + 1] - wr[k])
        k += n_tab
        r_r = wr[k] + w * (wr[k + 1] - wr[k])
        k += n_tab
        d_l = wr[k] + w * (wr[k + 1] - wr[k])
        k += n_tab
        d_r = wr[k] + w * (wr[k + 1] - wr[k])
        return r_l, r_r, d_l, d_r
    # Paper's polynomials, wheel by wheel (u = displacement toward the wheel's flange).
    r0 = wr[WR.R0]
    l1, l2, l3 = wr[WR.LAMBDA1], wr[WR.LAMBDA2], wr[WR.LAMBDA3]
    l4, l5 = wr[WR.LAMBDA4], wr[WR.LAMBDA5]
    d0, d1, d4, d5, dmax = wr[WR.D0], wr[WR.D1], wr[WR.D4], wr[WR.D5], wr[WR.DELTA_MAX]
    r_l = rolling_radius(y_rel, r0, l1, l2, l3, l4, l5)
    r_r = rolling_radius(-y_rel, r0, l1, l2, l3, l4, l5)
    d_l = contact_angle(y_rel, d0, d1, d4, d5, dmax)
    d_r = contact_angle(-y_rel, d0, d1, d4, d5, dmax)
    return r_l, r_r, d_l, d_r
