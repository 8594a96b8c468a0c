"""The linear limit of the exact steady-rolling theory (full adhesion): Kalker's coefficients.

With an infinite traction bound every element of the patch adheres, and the discretised
steady-rolling problem of :mod:`railhunt.kernel.rolling` becomes linear:

    dx w_I + sum_J (A(I - J) - A(I - J + (1, 0))) p_J = 0   for every element I of the patch.

Written in the differences of the tractions along the rolling direction,
``q_I = p_I - p_{I+(1,0)}`` (``p`` is the sum of ``q`` from the leading edge; at the element
just behind the trailing edge of each line ``q = -p``), the operator is the plain influence
matrix ``A``, symmetric and positive definite; the products with ``A`` are convolutions,
done by FFT (``scipy.fft``) on the grid, and the system is solved by GMRES
(``scipy.sparse.linalg.gmres``) to a relative residual of ``1e-10``. The unit-creepage
solutions give the coefficients: ``C11 = -F_x / (G c^2 xi)`` and so on, the same numbers
the nonlinear solver gives with a huge friction coefficient, but in a fraction of its time,
so that grids up to a few hundred elements a side can be solved to extrapolate to a
vanishing element size (:mod:`railhunt.mechanics.build_tables`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft as sfft
from scipy.sparse.linalg import LinearOperator, gmres

from railhunt.kernel.halfspace import tangential_influence

__all__ = ["LinearSolution", "linear_coefficients", "patch_grid"]


@dataclass(frozen=True)
class PatchGrid:
    """A uniform grid over the ellipse's bounding box, lengths in units of ``c = sqrt(ab)``.

    Attributes
    ----------
    a, b : float
        Semi-axes over ``c`` (``a b = 1``).
    dx, dy : float
        Element sizes over ``c``.
    x, y : ndarray, shape (mx, my)
        Element centres.
    inside : ndarray of bool, shape (mx, my)
        Elements whose centres lie inside the ellipse.
    """

    a: float
    b: float
    dx: float
    dy: float
    x: np.ndarray
    y: np.ndarray
    inside: np.ndarray


def patch_grid(a_over_b: float, mx: int, my: int) -> PatchGrid:
    """``mx * my`` elements covering ``[-a, a] x [-b, b]``, lengths in units of ``c``."""
    a = math.sqrt(a_over_b)
    b = 1.0 / a
    dx, dy = 2.0 * a / mx, 2.0 * b / my
    x = -a + (np.arange(mx) + 0.5) * dx
    y = -b + (np.arange(my) + 0.5) * dy
    xx, yy = np.meshgrid(x, y, indexing="ij")
    inside = (xx / a) ** 2 + (yy / b) ** 2 < 1.0
    return PatchGrid(a, b, dx, dy, xx, yy, inside)


@dataclass(frozen=True)
class LinearSolution:
    """Kalker's coefficients of one discretisation, and the GMRES iterations it took."""

    c11: float
    c22: float
    c23: float
    c23_moment: float  # from M_z of the lateral creepage: equal to c23 (reciprocity)
    c33: float
    iterations: tuple[int, int, int]


def linear_coefficients(a_over_b: float, nu: float, mx: int, my: int | None = None,
                        rtol: float = 1e-10) -> LinearSolution:
    """Coefficients of the discretised linear theory on an ``mx * my`` grid.

    Parameters
    ----------
    a_over_b : float
        Semi-axis ratio, > 0.
    nu : float
        Poisson's ratio.
    mx, my : int
        Elements along and across the rolling direction (``my`` defaults to ``mx``).
    rtol : float
        GMRES's relative residual.

    Returns
    -------
    LinearSolution
    """
    my = mx if my is None else my
    grid = patch_grid(a_over_b, mx, my)
    inside = grid.inside
    table = tangential_influence(mx, my - 1, grid.dx, grid.dy, nu)  # k in -mx..mx
    n1 = sfft.next_fast_len(3 * mx + 1, real=True)
    n2 = sfft.next_fast_len(3 * my - 2, real=True)
    kf = [sfft.rfft2(table[c], s=(n1, n2)) for c in range(3)]
    idx = np.argwhere(inside)
    n = idx.shape[0]
    cols = np.flatnonzero(inside.any(axis=0))
    trailing = np.argmax(inside, axis=0)[cols]  # smallest i of each line y = y_j
    window = (slice(mx + 1, 2 * mx + 1), slice(my - 1, 2 * my - 1))

    def operator(v: np.ndarray) -> np.ndarray:
        v = v.reshape(n, 2)
        q = np.zeros((mx + 1, my, 2))  # row 0: the elements behind i = 0
        q[idx[:, 0] + 1, idx[:, 1]] = v
        for c in range(2):
            q[trailing, cols, c] -= np.bincount(idx[:, 1], v[:, c], minlength=my)[cols]
        f0 = sfft.rfft2(q[..., 0], s=(n1, n2))
        f1 = sfft.rfft2(q[..., 1], s=(n1, n2))
        ux = sfft.irfft2(kf[0] * f0 + kf[1] * f1, s=(n1, n2))[window]
        uy = sfft.irfft2(kf[1] * f0 + kf[2] * f1, s=(n1, n2))[window]
        return np.stack([ux[idx[:, 0], idx[:, 1]], uy[idx[:, 0], idx[:, 1]]], axis=1).ravel()

    op = LinearOperator((2 * n, 2 * n), matvec=operator, dtype=float)
    results = []
    iterations = []
    for xi, eta, phi in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)):
        w = np.stack([xi - phi * grid.y, eta + phi * grid.x], axis=-1)
        rhs = -grid.dx * w[idx[:, 0], idx[:, 1]].ravel()
        count = [0]

        def step(_residual: float, count: list[int] = count) -> None:
            count[0] += 1

        v, info = gmres(op, rhs, rtol=rtol, atol=0.0, restart=300, maxiter=20,
                        callback=step, callback_type="pr_norm")
        if info != 0:
            raise RuntimeError(f"linear theory: GMRES did not converge (a/b = {a_over_b:g}, "
                               f"nu = {nu:g}, grid {mx} x {my})")
        iterations.append(count[0])
        dq = np.zeros((mx, my, 2))
        dq[idx[:, 0], idx[:, 1]] = v.reshape(n, 2)
        p = np.cumsum(dq[::-1], axis=0)[::-1]
        p[~inside] = 0.0
        da = grid.dx * grid.dy
        fx = p[..., 0].sum() * da
        fy = p[..., 1].sum() * da
        mz = (grid.x * p[..., 1] - grid.y * p[..., 0]).sum() * da
        results.append((fx, fy, mz))
    (fx1, _, _), (_, fy2, mz2), (_, fy3, mz3) = results
    return LinearSolution(-fx1, -fy2, -fy3, mz2, -mz3, tuple(iterations))
