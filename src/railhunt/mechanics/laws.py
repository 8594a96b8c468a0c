"""Creep forces and the spin moment of one Hertzian patch, by any of railhunt's laws.

:func:`creep_forces` takes the creepages of the wheel relative to the rail (``xi``
longitudinal, ``eta`` lateral, ``phi`` spin in 1/m), the patch (semi-axes ``a`` along the
rolling direction and ``b`` across it), the friction coefficient and the normal force, and
returns the forces ``F_x``, ``F_y`` (N) and the spin moment ``M_z`` (N*m) on the wheel, in
the signs of Kalker's linear theory and of railhunt's model (for small creepages, with
``c = sqrt(a b)`` and Kalker's coefficients at ``a/b``):

    F_x = -G c^2 C11 xi,   F_y = -G c^2 (C22 eta + c C23 phi),   M_z = G c^3 (C23 eta - c C33 phi).

Laws (``LAWS``):

``"exact"``
    Kalker's exact theory of steady rolling on the half-space
    (:mod:`railhunt.mechanics.exact`): a 40 x 40 grid and its half, extrapolated.
``"fastsim-modified"``
    FASTSIM with three blended flexibilities (Vollebregt and Wilders 2011; Vollebregt and
    Voltr 2023; :mod:`railhunt.mechanics.fastsim`), parabolic traction bound.
``"fastsim"``
    Kalker's FASTSIM (1982): one creepage-weighted flexibility, parabolic traction bound.
``"polach"``
    Polach's closed form with his spin term (1999; Wear 258, 2005): :mod:`railhunt.kernel.polach`.
    Polach gives no spin moment: ``M_z`` is Kalker's linear one. Where Polach's spin
    force added to his creepage force would exceed ``mu N`` (combined spin and lateral
    creepage), the resultant is scaled back to ``mu N``.
``"heuristic"``
    The paper's law (its Eq. 28) on this patch alone: Kalker's linear ``F_x, F_y`` scaled
    by ``alpha(beta)``, ``beta = |F_linear| / (mu N)``; ``M_z`` linear (as in the model).
``"vermeulen-johnson"``
    Vermeulen and Johnson's cubic on the creepage forces ``(f11 xi, f22 eta)``; the spin
    part of ``F_y`` is scaled by the same factor and ``M_z`` stays linear, exactly as in
    railhunt's model (so the spin force is not bounded by ``mu N``).
``"linear"``
    Kalker's linear theory, no saturation.

The FASTSIM laws and ``"exact"`` take ``grid`` (elements along and across the rolling
direction; one number for both): FASTSIM's default is 50 x 50, the exact solver's 40 x 40
(with its extrapolation from 20 x 20).

Batches: every argument may be an array (they broadcast). FASTSIM and Polach loop over
the patches in compiled code (about 0.1 ms per patch); the exact theory solves the
patches of one ``a/b`` in one compiled loop, each started from the previous one (about
50 ms of CPU per patch; :mod:`railhunt.mechanics.exact`): to tabulate it, group the cases
by ``a/b``, sort each group along a creepage, and run groups in separate processes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit

from railhunt.kernel.fastsim import ELLIPTIC, PARABOLIC, fastsim_batch
from railhunt.kernel.polach import polach_forces
from railhunt.mechanics._checks import check_array, check_range
from railhunt.mechanics.coefficients import A_OVER_B_RANGE, kalker_coefficients
from railhunt.mechanics.exact import DEFAULT_GRID as EXACT_GRID
from railhunt.mechanics.exact import exact_creep_forces
from railhunt.mechanics.fastsim import (
    kalker_flexibilities,
    modified_flexibilities,
    weighted_flexibility,
)
from railhunt.results import Columns, ResultDisplay, Row

__all__ = ["LAWS", "CreepForces", "creep_forces"]

#: The laws :func:`creep_forces` knows, most exact first.
LAWS = ("exact", "fastsim-modified", "fastsim", "polach", "heuristic", "vermeulen-johnson",
        "linear")
FASTSIM_GRID = (50, 50)
_BOUNDS = {"parabolic": PARABOLIC, "elliptic": ELLIPTIC}


@dataclass(frozen=True, repr=False)
class CreepForces(ResultDisplay):
    """Creep forces and spin moment on the wheel, from :func:`creep_forces`.

    Attributes
    ----------
    fx, fy : float or ndarray
        Longitudinal and lateral creep force (N).
    mz : float or ndarray
        Spin moment about the patch's normal (N*m).
    law : str
        The law that computed them.
    mu_n : float or ndarray
        Friction coefficient times normal force (N), the saturation limit.
    """

    fx: Any
    fy: Any
    mz: Any
    law: str
    mu_n: Any

    @property
    def resultant(self) -> Any:
        """``sqrt(F_x^2 + F_y^2)`` (N)."""
        return np.hypot(self.fx, self.fy)

    def _summary(self) -> list[Row]:
        rows: list[Row] = [("law", self.law, "")]
        if np.ndim(self.fx) == 0:
            rows += [("F_x", float(self.fx), "N"), ("F_y", float(self.fy), "N"),
                     ("M_z", float(self.mz), "N*m"),
                     ("|F| / (mu N)", float(self.resultant / self.mu_n), "")]
        else:
            rows += [("patches", int(np.size(self.fx)), ""),
                     ("largest |F| / (mu N)", float(np.max(self.resultant / self.mu_n)), "")]
        return rows

    def _columns(self) -> Columns:
        return {"fx": (np.ravel(self.fx), "N"), "fy": (np.ravel(self.fy), "N"),
                "mz": (np.ravel(self.mz), "N*m"),
                "mu_n": (np.ravel(np.broadcast_to(self.mu_n, np.shape(self.fx))), "N")}


def _grid(value: Any, default: tuple[int, int]) -> tuple[int, int]:
    if value is None:
        return default
    pair = (value, value) if np.ndim(value) == 0 else tuple(value)
    if len(pair) != 2 or not all(isinstance(v, int | np.integer) and not isinstance(v, bool)
                                 and 4 <= v <= 400 for v in pair):  # fmt: skip
        raise ValueError(f"grid = {value!r} is invalid: must be an integer or a pair of "
                         "integers in [4, 400] (elements along and across the rolling "
                         "direction)")
    return int(pair[0]), int(pair[1])


@njit(cache=True)
def _polach_batch(xi, eta, phi, a, b, mu_n, g, c11, c22, c23):
    n = xi.shape[0]
    fx = np.empty(n)
    fy = np.empty(n)
    for i in range(n):
        fx[i], fy[i] = polach_forces(xi[i], eta[i], phi[i], a[i], b[i], mu_n[i], g, c11[i],
                                     c22[i], c23[i])
    return fx, fy


def _cubic_factor(beta: np.ndarray) -> np.ndarray:
    """The paper's Eq. 28 factor ``alpha(beta)``, as
    :func:`railhunt.kernel.creep.heuristic_saturation`."""
    with np.errstate(divide="ignore"):
        return np.where(beta <= 3.0, 1.0 - beta / 3.0 + beta * beta / 27.0,
                        1.0 / np.maximum(beta, 3.0))


def creep_forces(xi, eta, phi, *, a, b, mu, normal_force, law: str = "fastsim-modified",
                 shear_modulus: float = 8.2e10, poisson: float = 0.28, grid=None,
                 traction_bound: str | None = None) -> CreepForces:
    """Creep forces and spin moment of elliptical contact patches.

    Parameters
    ----------
    xi, eta : float or array_like
        Longitudinal and lateral creepage of the wheel relative to the rail (-).
    phi : float or array_like
        Spin creepage (1/m).
    a, b : float or array_like
        Semi-axes along and across the rolling direction (m), > 0, ``a/b`` in
        ``[0.05, 20]``.
    mu : float or array_like
        Friction coefficient, > 0.
    normal_force : float or array_like
        Normal force (N), > 0.
    law : str
        One of ``LAWS`` (module docstring).
    shear_modulus : float
        ``G`` of wheel and rail (Pa).
    poisson : float
        Poisson's ratio, in ``[0, 0.5)``.
    grid : int or (int, int), optional
        Elements along and across the rolling direction for ``"fastsim"``,
        ``"fastsim-modified"`` and ``"exact"`` (defaults 50 x 50, 50 x 50, 40 x 40).
    traction_bound : {"parabolic", "elliptic"}, optional
        The FASTSIM laws' traction bound (default ``"parabolic"``, Kalker's).

    Returns
    -------
    CreepForces
        ``fx``, ``fy`` (N) and ``mz`` (N*m): floats for scalar arguments, else arrays of
        the arguments' broadcast shape.

    Raises
    ------
    ValueError
        One line naming the argument: a semi-axis, the load or ``mu`` not positive, ``a/b``
        outside ``[0.05, 20]``, a creepage not finite, an unknown law.
    """
    if law not in LAWS:
        raise ValueError(f"law = {law!r} is invalid: must be one of "
                         + ", ".join(repr(n) for n in LAWS))
    g = check_range("shear_modulus", shear_modulus, 0.0, 1e13, "Pa", low_open=True)
    nu = check_range("poisson", poisson, 0.0, 0.5, high_open=True)
    xi_a = check_array("xi", xi)
    eta_a = check_array("eta", eta)
    phi_a = check_array("phi", phi, unit="1/m")
    a_a = check_array("a", a, 0.0, unit="m", low_open=True, what="finite and > 0 (m)")
    b_a = check_array("b", b, 0.0, unit="m", low_open=True, what="finite and > 0 (m)")
    mu_a = check_array("mu", mu, 0.0, low_open=True, what="finite and > 0")
    n_a = check_array("normal_force", normal_force, 0.0, unit="N", low_open=True,
                      what="finite and > 0 (N)")
    scalar = all(np.ndim(v) == 0 for v in (xi, eta, phi, a, b, mu, normal_force))
    try:
        arrays = np.broadcast_arrays(xi_a, eta_a, phi_a, a_a, b_a, mu_a, n_a)
    except ValueError:
        shapes = ", ".join(str(np.shape(v)) for v in (xi, eta, phi, a, b, mu, normal_force))
        raise ValueError(f"xi, eta, phi, a, b, mu, normal_force have shapes {shapes}, which "
                         "do not broadcast to one shape") from None
    shape = arrays[0].shape
    xi_f, eta_f, phi_f, a_f, b_f, mu_f, n_f = (np.ascontiguousarray(v.ravel())
                                                for v in arrays)  # fmt: skip
    ratio = a_f / b_f
    lo, hi = A_OVER_B_RANGE
    bad = (ratio < lo) | (ratio > hi)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise ValueError(f"a/b = {ratio[k]:.6g} (a = {a_f[k]:.6g} m, b = {b_f[k]:.6g} m) is "
                         f"invalid: must be in [{lo:g}, {hi:g}] (Kalker's coefficients)")
    if traction_bound is not None and (law not in ("fastsim", "fastsim-modified")
                                       or traction_bound not in _BOUNDS):  # fmt: skip
        raise ValueError(f"traction_bound = {traction_bound!r} is invalid: must be "
                         "'parabolic' or 'elliptic', for the laws 'fastsim' and "
                         "'fastsim-modified'")
    mu_n = mu_f * n_f
    fx, fy, mz = _forces(law, xi_f, eta_f, phi_f, a_f, b_f, mu_n, g, nu, grid, traction_bound)
    if scalar:
        return CreepForces(float(fx[0]), float(fy[0]), float(mz[0]), law, float(mu_n[0]))
    return CreepForces(fx.reshape(shape), fy.reshape(shape), mz.reshape(shape), law,
                       mu_n.reshape(shape))


def _forces(law, xi, eta, phi, a, b, mu_n, g, nu, grid, bound_name):
    if law == "exact":
        return exact_creep_forces(xi, eta, phi, a, b, mu_n, g, nu, _grid(grid, EXACT_GRID))
    if law in ("fastsim", "fastsim-modified") or grid is not None:
        mx, my = _grid(grid, FASTSIM_GRID)
        if law not in ("fastsim", "fastsim-modified"):
            raise ValueError(f"grid = {grid!r} is invalid for law = {law!r}: only the laws "
                             "'exact', 'fastsim' and 'fastsim-modified' are discretised")
    c11, c22, c23, c33 = kalker_coefficients(a / b, nu)
    c2 = a * b
    f11, f22, f23, f33 = g * c2 * c11, g * c2 * c22, g * c2**1.5 * c23, g * c2 * c2 * c33
    mz_linear = f23 * eta - f33 * phi
    if law in ("fastsim", "fastsim-modified"):
        if law == "fastsim":
            l1, l2, l3 = kalker_flexibilities(a, b, g, c11, c22, c23)
            lw = weighted_flexibility(xi, eta, phi, a, b, l1, l2, l3)
            flex = (lw, lw, lw)
            bound = _BOUNDS[bound_name or "parabolic"]
        else:
            flex = modified_flexibilities(xi, eta, phi, a, b, mu_n, g, c11, c22, c23)
            bound = _BOUNDS[bound_name or "parabolic"]
        return fastsim_batch(xi, eta, phi, a, b, *(np.ascontiguousarray(f) for f in flex),
                             mu_n, bound, mx, my)
    fx_lin = -f11 * xi
    fy_lin = -f22 * eta - f23 * phi
    if law == "linear":
        return fx_lin, fy_lin, mz_linear
    if law == "heuristic":
        alpha = _cubic_factor(np.hypot(fx_lin, fy_lin) / mu_n)
        return alpha * fx_lin, alpha * fy_lin, mz_linear
    if law == "vermeulen-johnson":
        alpha = _cubic_factor(np.hypot(fx_lin, f22 * eta) / mu_n)
        return alpha * fx_lin, alpha * fy_lin, mz_linear
    # Polach, his spin term included; the resultant capped at mu N
    fx, fy = _polach_batch(xi, eta, phi, a, b, mu_n, g, np.ascontiguousarray(c11),
                           np.ascontiguousarray(c22), np.ascontiguousarray(c23))
    resultant = np.hypot(fx, fy)
    scale = np.where(resultant > mu_n, mu_n / np.maximum(resultant, 1e-300), 1.0)
    return fx * scale, fy * scale, mz_linear
