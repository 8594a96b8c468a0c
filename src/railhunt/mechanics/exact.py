"""Kalker's exact theory of steady rolling on the half-space, for Hertzian patches.

The patch ``x^2/a^2 + y^2/b^2 < 1`` is covered by a uniform ``mx * my`` grid of rectangular
elements (those whose centres lie inside the ellipse are in contact); the traction bound
is ``mu`` times the Hertz pressure ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)`` at the element
centres, scaled so that it sums to exactly ``mu N``; the influence coefficients are those
of uniform tractions on rectangles (Boussinesq-Cerruti, two bodies of one material, so the
normal and tangential problems decouple: :mod:`railhunt.kernel.halfspace`); the
tangential problem of steady rolling, with its adhesion and slip areas, is solved by the
compiled block Gauss-Seidel solver of :mod:`railhunt.kernel.rolling`.

Lengths are scaled by ``c = sqrt(a b)`` and tractions by ``G``, so one patch (its ``a/b``,
``nu`` and grid) serves every size and load: its influence table is built once and
cached (:func:`exact_patch`).

The solver's discretisation error is of first order in the element size, largest for the
spin moment (the linear theory's ``C33`` at ``a/b = 2.5`` comes out 21 % high on a
40 x 40 grid). :func:`exact_creep_forces` therefore returns, by default, Richardson's
extrapolation ``F = 2 F(m) - F(m/2)`` from the grid and the grid of half as many elements
each way (which costs about a sixteenth of the fine one), and scales a resultant above
``mu N`` (a few parts in a thousand at most, near saturation) back to ``mu N``.

Batches: all arguments broadcast; cases that share ``a/b`` (to 1e-12) are solved in one
compiled loop: on the coarse grid each case starts from the previous case's tractions
(sort a sweep by creepage for the best starts), on the fine grid from its own coarse
solution. Measured costs are in ``benchmarks/run.py`` (``--only creep``).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from railhunt.kernel.halfspace import tangential_influence
from railhunt.kernel.rolling import refine_tractions, rolling_batch
from railhunt.mechanics.linear_theory import PatchGrid, patch_grid

__all__ = ["DEFAULT_GRID", "ExactPatch", "exact_creep_forces", "exact_patch"]

#: Elements along and across the rolling direction of the finer grid.
DEFAULT_GRID = (40, 40)
TOLERANCE = 1e-5
MAX_SWEEPS = 2000


@dataclass(frozen=True)
class ExactPatch:
    """One discretised patch in units of ``c`` (lengths) and ``G`` (tractions)."""

    grid: PatchGrid
    table: np.ndarray  # influence coefficients, (3, 2 mx + 1, 2 my - 1)
    shape: np.ndarray  # Hertz bound shape at the element centres, 0 outside
    shape_sum: float  # sum of shape * element area


@lru_cache(maxsize=64)
def exact_patch(a_over_b: float, nu: float, mx: int, my: int) -> ExactPatch:
    """The discretised patch of ``a/b``, Poisson's ratio ``nu`` and an ``mx * my`` grid."""
    grid = patch_grid(a_over_b, mx, my)
    table = tangential_influence(mx, my - 1, grid.dx, grid.dy, nu)
    r = 1.0 - (grid.x / grid.a) ** 2 - (grid.y / grid.b) ** 2
    shape = np.where(grid.inside, np.sqrt(np.clip(r, 0.0, None)), 0.0)
    return ExactPatch(grid, table, shape, float(shape.sum() * grid.dx * grid.dy))


def _solve(patch: ExactPatch, xi, eta, phi_c, bound, start=None, keep=False):
    g = patch.grid
    if start is None:
        start = np.zeros((0, 2, *g.inside.shape))
    fx, fy, mz, sweeps, tractions = rolling_batch(
        g.inside, patch.shape, g.x, g.y, g.dx, g.dy, patch.table, xi, eta, phi_c,
        bound / patch.shape_sum, TOLERANCE, MAX_SWEEPS, 0.9, 1.0, start, keep)
    if np.any(sweeps < 0):
        raise RuntimeError(f"exact creep forces: the solver did not converge in {MAX_SWEEPS} "
                           f"sweeps (a/b = {g.a / g.b:g}, grid {g.inside.shape})")
    return np.array([fx, fy, mz]), tractions


def exact_creep_forces(xi, eta, phi, a, b, mu_n, shear_modulus, nu,
                       grid: tuple[int, int] = DEFAULT_GRID, extrapolate: bool = True):
    """Creep forces and spin moment by Kalker's exact theory of steady rolling.

    Parameters
    ----------
    xi, eta : array_like
        Longitudinal and lateral creepage.
    phi : array_like
        Spin creepage (1/m).
    a, b : array_like
        Semi-axes along and across the rolling direction (m).
    mu_n : array_like
        Friction coefficient times normal force (N); ``inf`` gives the linear theory.
    shear_modulus : float
        ``G`` (Pa).
    nu : float
        Poisson's ratio.
    grid : (int, int)
        Elements of the (finer) grid along and across the rolling direction.
    extrapolate : bool
        Richardson's extrapolation from ``grid`` and half of it (default), or the
        discrete solution on ``grid`` alone.

    Returns
    -------
    fx, fy, mz : ndarray
        Forces (N) and moment (N*m) on the body whose creepages they are, shaped as the
        broadcast arguments.

    Raises
    ------
    RuntimeError
        If the solver did not converge (it always has, in railhunt's tests).
    """
    xi, eta, phi, a, b, mu_n = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (
        xi, eta, phi, a, b, mu_n)))
    shape = xi.shape
    xi, eta, phi, a, b, mu_n = (v.ravel() for v in (xi, eta, phi, a, b, mu_n))
    c = np.sqrt(a * b)
    ratio = a / b
    # dimensionless: tractions / G, lengths / c
    bound = mu_n / (shear_modulus * c * c)
    phi_c = phi * c
    mx, my = grid
    out = np.zeros((2, 3, xi.size))
    for key in np.unique(np.round(ratio, 12)):
        sel = np.flatnonzero(np.round(ratio, 12) == key)
        fine = exact_patch(float(key), float(nu), mx, my)
        start = None
        if extrapolate:  # the coarse grid first: its tractions start the fine grid's
            coarse = exact_patch(float(key), float(nu), max(2, mx // 2), max(2, my // 2))
            out[1][:, sel], tractions = _solve(coarse, xi[sel], eta[sel], phi_c[sel],
                                               bound[sel], keep=True)
            start = refine_tractions(tractions, fine.grid.inside)
        out[0][:, sel], _ = _solve(fine, xi[sel], eta[sel], phi_c[sel], bound[sel], start)
    res = 2.0 * out[0] - out[1] if extrapolate else out[0]
    if extrapolate:
        limit = mu_n / (shear_modulus * c * c)
        resultant = np.hypot(res[0], res[1])
        over = np.isfinite(limit) & (resultant > limit)
        scale = np.where(over, limit / np.where(over, resultant, 1.0), 1.0)
        res[0] *= scale
        res[1] *= scale
    g = shear_modulus
    fx = (g * c * c * res[0]).reshape(shape)
    fy = (g * c * c * res[1]).reshape(shape)
    mz = (g * c**3 * res[2]).reshape(shape)
    return fx, fy, mz
