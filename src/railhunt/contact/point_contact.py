"""Contact mechanics at each contact point of a profile contact table.

For each lateral position ``y`` of a :class:`~railhunt.contact.geometry.ContactGeometry`
and each wheel: the relative curvatures at its contact point, the Hertz ellipse per unit
load, its ``a/b`` and Kalker's coefficients, and the columns the compiled right-hand side
interpolates (:class:`railhunt.kernel.layout.PointColumn`).

Curvatures (1/m, Hertz's sign, convex positive). Along the rolling direction the wheel's
normal section at a contact of angle ``delta`` on rolling radius ``r`` has curvature
``cos(delta) / r`` (Meusnier: the section's normal leans by ``delta`` from the wheel's
radius), the rail none (straight track); across it the profiles' own curvatures at the
contact points (:mod:`railhunt.contact.curvature`). The relative curvatures are
``A = cos(delta) / (2 r)``, ``B = (k_wheel + k_rail) / 2``. A conformal contact
(``B <= 0``, a worn wheel in a worn rail) or one beyond the coefficients' range is kept at
the nearest Hertz ellipse with ``a/b`` in ``[0.05, 20]`` (:data:`AB_RANGE`): the contact is
then not Hertzian, and railhunt does not model it otherwise.

The ellipse scales as ``N^(1/3)``: ``a = a1 N^(1/3)``, ``b = b1 N^(1/3)`` with ``a1, b1``
the semi-axes under 1 N; ``a/b`` depends on the curvatures only. Kalker's coefficients
follow: ``f11 = G a b C11 ~ N^(2/3)``, ``f22 ~ N^(2/3)``, ``f23 = G (ab)^(3/2) C23 ~ N``,
``f33 = G (ab)^2 C33 ~ N^(4/3)``.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from railhunt.kernel.layout import PER_POINT, PointColumn
from railhunt.mechanics.coefficients import kalker_coefficients
from railhunt.mechanics.hertz import hertz_contact
from railhunt.results import Columns, ResultDisplay, Row

__all__ = ["AB_RANGE", "PointContact", "point_contact"]

#: The semi-axis ratios a/b (rolling over lateral) the per-point model covers.
AB_RANGE = (0.05, 20.0)
#: Default shear modulus (Pa) and Poisson's ratio of wheel and rail steel: E = 210 GPa,
#: nu = 0.3, the values of the shipped vehicles' centred coefficients.
SHEAR_MODULUS = 2.1e11 / 2.6
POISSON = 0.3


def _young(shear_modulus: float, poisson: float) -> float:
    return 2.0 * shear_modulus * (1.0 + poisson)


@functools.lru_cache(maxsize=32)
def _ratio_bounds(poisson: float) -> tuple[float, float]:
    """Curvature ratios ``B/A`` whose Hertz ellipses have ``a/b`` = 0.05 and 20."""
    def ab(log_ratio: float) -> float:
        h = hertz_contact(1.0, 1.0, math.exp(log_ratio), 2.1e11, poisson)
        return math.log(h.a / h.b)

    lo = brentq(lambda x: ab(x) - math.log(AB_RANGE[0]), -9.0, 0.0, xtol=1e-12)
    hi = brentq(lambda x: ab(x) - math.log(AB_RANGE[1]), 0.0, 9.0, xtol=1e-12)
    return math.exp(lo), math.exp(hi)


def contact_coefficients(a_over_b: float, poisson: float) -> tuple[float, float, float, float]:
    """Kalker's ``(C11, C22, C23, C33)`` at ``a/b`` in :data:`AB_RANGE`
    (:func:`railhunt.mechanics.coefficients.kalker_coefficients`: Table E.3, extended to
    0.05 ... 20 by the exact theory's linear limit)."""
    c = kalker_coefficients(min(max(a_over_b, AB_RANGE[0]), AB_RANGE[1]), poisson)
    return float(c[0]), float(c[1]), float(c[2]), float(c[3])


@dataclass(frozen=True, repr=False)
class PointContact(ResultDisplay):
    """Hertz ellipse and Kalker's coefficients at each contact point of a contact table.

    Arrays have shape ``(2, n)``: row 0 the left wheel, row 1 the right, along
    :attr:`y`.

    Attributes
    ----------
    y : numpy.ndarray
        Lateral wheelset displacement (m), the contact table's grid.
    delta, radius : numpy.ndarray
        Contact angle (rad) and rolling radius (m).
    curvature_x, curvature_y : numpy.ndarray
        Relative curvatures ``A`` (rolling direction) and ``B`` (lateral), 1/m, as used
        (``B`` after the limit to :data:`AB_RANGE`).
    wheel_curvature, rail_curvature : numpy.ndarray
        Transverse curvatures of the wheel's and rail's surfaces at the contact (1/m).
    a1, b1 : numpy.ndarray
        Semi-axes under a normal force of 1 N (m / N^(1/3)), ``a`` along the rolling
        direction.
    c11, c22, c23, c33 : numpy.ndarray
        Kalker's coefficients at each ``a/b``.
    shear_modulus, poisson : float
        Material (Pa, -).
    jump : numpy.ndarray of bool
        The table's contact-point jumps.
    """

    y: np.ndarray
    delta: np.ndarray
    radius: np.ndarray
    curvature_x: np.ndarray
    curvature_y: np.ndarray
    wheel_curvature: np.ndarray
    rail_curvature: np.ndarray
    a1: np.ndarray
    b1: np.ndarray
    c11: np.ndarray
    c22: np.ndarray
    c23: np.ndarray
    c33: np.ndarray
    shear_modulus: float
    poisson: float
    jump: np.ndarray

    @property
    def a_over_b(self) -> np.ndarray:
        """Semi-axis ratio ``a/b`` (rolling over lateral)."""
        return self.a1 / self.b1

    def normal_force(self, load: float) -> np.ndarray:
        """Normal force ``N = Q / cos(delta)`` (N) of each contact under the vertical load
        ``Q`` (N) without creep forces (the per-point model adds their vertical part)."""
        return load / np.cos(self.delta)

    def ellipse(self, load: float) -> tuple[np.ndarray, np.ndarray]:
        """Semi-axes ``(a, b)`` (m) under the vertical load ``load`` (N)."""
        scale = np.cbrt(self.normal_force(load))
        return self.a1 * scale, self.b1 * scale

    def coefficients(self, load: float) -> tuple[np.ndarray, ...]:
        """Kalker's ``(f11, f22, f23, f33)`` (N, N, N*m, N*m^2) under the vertical load (N)."""
        a, b = self.ellipse(load)
        g = self.shear_modulus
        ab = a * b
        return (g * ab * self.c11, g * ab * self.c22, g * ab**1.5 * self.c23,
                g * ab**2 * self.c33)  # fmt: skip

    def kernel_tail(self, static_load: float, ab_grid: tuple[float, float] | None) -> np.ndarray:
        """The per-point block that follows the geometry in the wheel/rail vector.

        Parameters
        ----------
        static_load : float
            The wheel's static vertical load (N) (its cube root is stored).
        ab_grid : tuple of float, optional
            ``(ln(a/b) of the first slice, step)`` of the creep table; None: no table.

        Returns
        -------
        numpy.ndarray
            ``[PER_POINT, N^(1/3), columns of the left wheel, of the right wheel]``.
        """
        cd = np.cos(self.delta)
        g = self.shear_modulus
        ab1 = self.a1 * self.b1
        cols = np.empty((2, len(PointColumn), self.y.size))
        cols[:, PointColumn.C1] = np.sqrt(ab1) * cd ** (-1.0 / 3.0)
        cols[:, PointColumn.K11] = g * ab1 * self.c11 * cd ** (-2.0 / 3.0)
        cols[:, PointColumn.K22] = g * ab1 * self.c22 * cd ** (-2.0 / 3.0)
        cols[:, PointColumn.K23] = g * ab1**1.5 * self.c23 / cd
        cols[:, PointColumn.K33] = g * ab1**2 * self.c33 * cd ** (-4.0 / 3.0)
        if ab_grid is None:
            cols[:, PointColumn.AB] = 0.0
        else:
            # The nearest slice of each grid point: between two points of one slice the
            # compiled law reads that slice alone (one stencil, not two).
            cols[:, PointColumn.AB] = np.round((np.log(self.a_over_b) - ab_grid[0])
                                               / ab_grid[1])  # fmt: skip
        blocks = np.transpose(cols, (2, 0, 1)).ravel()  # per grid point: left, then right
        return np.concatenate([[float(PER_POINT), float(np.cbrt(static_load))], blocks])

    def _summary(self) -> list[Row]:
        ab = self.a_over_b
        return [("lateral displacement", f"{self.y[0] * 1e3:.4g} to {self.y[-1] * 1e3:.4g}",
                 "mm"),
                ("a/b, centred (left wheel)", float(ab[0, self.y.size // 2]), ""),
                ("a/b range", f"{ab.min():.3g} to {ab.max():.3g}", ""),
                ("shear modulus", self.shear_modulus, "Pa"),
                ("Poisson's ratio", self.poisson, "")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row per lateral displacement ``y``, left and right wheel."""
        out: Columns = {"y": (self.y, "m")}
        for k, side in enumerate(("left", "right")):
            out[f"delta_{side}"] = (self.delta[k], "rad")
            out[f"a1_{side}"] = (self.a1[k], "m/N^(1/3)")
            out[f"b1_{side}"] = (self.b1[k], "m/N^(1/3)")
            out[f"a_over_b_{side}"] = (self.a_over_b[k], "")
            for name in ("c11", "c22", "c23", "c33"):
                out[f"{name}_{side}"] = (getattr(self, name)[k], "")
        return out


def point_contact(geometry: object, shear_modulus: float = SHEAR_MODULUS,
                  poisson: float = POISSON) -> PointContact:  # fmt: skip
    """The per-point ellipses and coefficients of a contact table.

    Parameters
    ----------
    geometry : railhunt.contact.geometry.ContactGeometry
        A table with the profiles' curvatures (computed by
        :func:`railhunt.contact.geometry.contact_geometry`).
    shear_modulus : float
        Shear modulus of wheel and rail (Pa), in [1e10, 1e12].
    poisson : float
        Poisson's ratio, in [0, 0.5).

    Returns
    -------
    PointContact
    """
    if not (math.isfinite(shear_modulus) and 1e10 <= shear_modulus <= 1e12):
        raise ValueError(f"shear_modulus = {shear_modulus!r} Pa is invalid: must be in "
                         "[1e+10, 1e+12] Pa")  # fmt: skip
    if not (math.isfinite(poisson) and 0.0 <= poisson < 0.5):
        raise ValueError(f"poisson = {poisson!r} is invalid: must be in [0, 0.5)")
    curv_w = getattr(geometry, "wheel_curvature_left", None)
    if curv_w is None:
        raise ValueError("the contact geometry has no profile curvatures: compute it with "
                         "railhunt.contact_geometry (a table of r and delta alone cannot "
                         "give the contact ellipses)")  # fmt: skip
    y = np.asarray(geometry.y, dtype=np.float64)
    delta = np.vstack([geometry.delta_left, geometry.delta_right])
    radius = np.vstack([geometry.r_left, geometry.r_right])
    k_wheel = np.vstack([geometry.wheel_curvature_left, geometry.wheel_curvature_right])
    k_rail = np.vstack([geometry.rail_curvature_left, geometry.rail_curvature_right])
    young = _young(shear_modulus, poisson)
    lo, hi = _ratio_bounds(poisson)
    cx = np.cos(delta) / (2.0 * radius)
    cy = 0.5 * (k_wheel + k_rail)
    cy = np.clip(np.where(cy > 0.0, cy, lo * cx), lo * cx, hi * cx)
    a1 = np.empty(delta.shape)
    b1 = np.empty(delta.shape)
    coef = np.empty((4,) + delta.shape)
    cache: dict[tuple[float, float], tuple[float, float, tuple[float, ...]]] = {}
    for idx in np.ndindex(delta.shape):
        key = (float(cx[idx]), float(cy[idx]))
        if key not in cache:  # the right wheel repeats the left one's mirror points
            h = hertz_contact(1.0, key[0], key[1], young, poisson)
            cache[key] = (h.a, h.b, contact_coefficients(h.a / h.b, poisson))
        a1[idx], b1[idx], c = cache[key]
        coef[(slice(None),) + idx] = c
    return PointContact(
        y=y, delta=delta, radius=radius, curvature_x=cx, curvature_y=cy,
        wheel_curvature=k_wheel, rail_curvature=k_rail, a1=a1, b1=b1, c11=coef[0],
        c22=coef[1], c23=coef[2], c33=coef[3], shear_modulus=float(shear_modulus),
        poisson=float(poisson), jump=np.asarray(geometry.jump, dtype=bool),
    )
