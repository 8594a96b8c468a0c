"""The creep table: Kalker's exact theory tabulated for the right-hand side.

The compiled law (:mod:`railhunt.kernel.creep_table`) is an analytic saturation of
Kalker's linear law plus a tabulated correction ``D`` on a grid of the normalised
creepages ``s = u / (1 + |u|)`` and of ``ln(a/b)``. This module builds ``D`` from a solver
of the steady rolling contact problem (the exact theory: ``creep_forces(...,
law="exact")``), turns node values into B-spline control points, and loads the table
shipped with railhunt (``railhunt/data/creep/exact_table.npz``, written by
``python -m railhunt.data.creep.build_creep_table``).

Each slice is normalised by the solver's *own* linear theory at that ``a/b`` (its
coefficients from a tiny creepage), so that ``D`` is bounded at small creepages whatever
the solver's discretisation; the right-hand side feeds it creepages normalised by
Kalker's coefficients, which makes its linear limit Kalker's exactly.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import resources

import numpy as np

from railhunt.kernel.creep_table import LANES, TableHeader, table_creep

__all__ = ["CreepTable", "build_creep_table", "control_points", "shipped_creep_table"]

#: A solver of the steady rolling contact problem: ``(xi, eta, phi, a, b, mu, N, G, nu)``
#: (SI, ``a`` along the rolling direction) -> ``(F_x, F_y, M_z)`` in Kalker's signs.
Solver = Callable[[float, float, float, float, float, float, float, float, float],
                  tuple[float, float, float]]

#: Where the shipped table lives (in the package data).
SHIPPED = ("data", "creep", "exact_table.npz")
#: Normalised creepage standing for "infinite" at the grid's ends (full slip).
_U_FULL_SLIP = 1e6
#: Exponents ``p`` of the grid coordinates ``s = sign(u) (1 - (1 + |u|)^(-p))``.
P_CREEPAGE = 0.5
P_SPIN = 0.25
#: Normalised creepage of the linear-limit evaluations.
_U_LINEAR = 1e-4


def _u_of_s(s: np.ndarray, p: float) -> np.ndarray:
    """Inverse of ``s = sign(u) (1 - (1 + |u|)^(-p))``; ``|s| = 1`` gives the full-slip
    stand-in."""
    s = np.asarray(s, dtype=np.float64)
    with np.errstate(divide="ignore"):
        u = np.sign(s) * ((1.0 - np.abs(s)) ** (-1.0 / p) - 1.0)
    return np.where(np.abs(s) >= 1.0, np.sign(s) * _U_FULL_SLIP, u)


def _spline_matrix(n: int, parity: int) -> np.ndarray:
    """Interpolation matrix of centred quadratic B-splines on ``n`` nodes; ghost control
    points: ``c[-1] = parity c[1]`` (``parity`` 0: linear extrapolation) and
    ``c[n] = 2 c[n-1] - c[n-2]``. Maps the ``n`` inner control points to node values."""
    m = np.zeros((n, n))
    for i in range(n):
        m[i, i] += 0.75
        for j, w in ((i - 1, 0.125), (i + 1, 0.125)):
            if j < 0:
                if parity:
                    m[i, 1] += w * parity
                else:
                    m[i, 0] += 2.0 * w
                    m[i, 1] -= w
            elif j >= n:
                m[i, n - 1] += 2.0 * w
                m[i, n - 2] -= w
            else:
                m[i, j] += w
    return m


def _solve_axis(values: np.ndarray, axis: int, parity: int) -> np.ndarray:
    """Control points along ``axis`` (inner nodes solved, one ghost added at each end)."""
    v = np.moveaxis(values, axis, -1)
    n = v.shape[-1]
    c = np.linalg.solve(_spline_matrix(n, parity), v.reshape(-1, n).T).T.reshape(v.shape)
    lo = parity * c[..., 1:2] if parity else 2.0 * c[..., :1] - c[..., 1:2]
    hi = 2.0 * c[..., -1:] - c[..., -2:-1]
    return np.moveaxis(np.concatenate([lo, c, hi], axis=-1), -1, axis)


def control_points(values: np.ndarray) -> np.ndarray:
    """B-spline control points, padded with ghosts, of node values ``D``.

    Parameters
    ----------
    values : numpy.ndarray, shape (n_ab, n_x, n_y, n_s, 3)
        ``D_x, D_y, D_m`` at the nodes (``s_x`` from 0, ``s_y`` and ``s_s`` from -1).

    Returns
    -------
    numpy.ndarray, shape (n_ab, n_x + 2, n_y + 2, n_s + 2, 3)
        ``D_x`` odd and ``D_y``, ``D_m`` even across ``s_x = 0``.
    """
    out = []
    for k, parity in enumerate((-1, 1, 1)):
        c = _solve_axis(values[..., k], 1, parity)
        c = _solve_axis(c, 2, 0)
        c = _solve_axis(c, 3, 0)
        # The parity across s_x = 0 to the bit (the later solves round each slab alike
        # only to rounding): the ghost mirrors the first inner point, D_x's node is 0.
        c[:, 0] = parity * c[:, 2]
        if parity < 0:
            c[:, 1] = 0.0
        out.append(c)
    return np.stack(out, axis=-1)


@dataclass(frozen=True)
class CreepTable:
    """A tabulated creep law (node values of the correction ``D`` and their grid).

    Attributes
    ----------
    log_ab : numpy.ndarray
        ``ln(a/b)`` of the slices (uniform).
    values : numpy.ndarray, shape (n_ab, n_x, n_y, n_s, 3)
        ``D_x, D_y, D_m`` at the nodes ``s_x`` in [0, 1], ``s_y``, ``s_s`` in [-1, 1].
    poisson : float
        Poisson's ratio of the solutions.
    coefficients : numpy.ndarray, shape (n_ab, 4)
        The solver's own linear coefficients ``C11, C22, C23, C33`` per slice.
    meta : dict
        How it was built (solver, grid, time).
    """

    log_ab: np.ndarray
    values: np.ndarray
    poisson: float
    coefficients: np.ndarray
    meta: dict = field(default_factory=dict, compare=False)

    @property
    def ab_grid(self) -> tuple[float, float]:
        """``(ln(a/b) of the first slice, step)``."""
        step = float(self.log_ab[1] - self.log_ab[0]) if self.log_ab.size > 1 else 1.0
        return float(self.log_ab[0]), step

    @functools.cached_property
    def kernel_array(self) -> np.ndarray:
        """The flat array the compiled law reads (:class:`TableHeader`)."""
        n_ab, nx, ny, ns, _ = self.values.shape
        head = np.zeros(int(TableHeader.DATA))
        head[TableHeader.N_AB], head[TableHeader.N_X] = n_ab, nx
        head[TableHeader.N_Y], head[TableHeader.N_S] = ny, ns
        head[TableHeader.LOG_AB0], head[TableHeader.DLOG_AB] = self.ab_grid
        head[TableHeader.POISSON] = self.poisson
        points = control_points(self.values)
        lanes = np.zeros((*points.shape[:-1], LANES))
        lanes[..., :3] = points
        flat = np.concatenate([head, lanes.ravel()])
        # Each control point (LANES doubles, one vector load) on a 32-byte boundary, so that
        # no load of the stencil straddles two cache lines.
        buffer = np.zeros(flat.size + 8)
        skip = (-(buffer.ctypes.data + 8 * int(TableHeader.DATA)) // 8) % 4
        aligned = buffer[skip:skip + flat.size]
        aligned[:] = flat
        return aligned

    def normalised(self, ux: float, uy: float, us: float, a_over_b: float,
                   moment: tuple[float, float] | None = None
                   ) -> tuple[float, float, float]:  # fmt: skip
        """``(F_x/(mu N), F_y/(mu N), M_z/(mu N c))`` at normalised creepages, by the compiled
        law. ``moment``: ``(m_y, m_s)``; default the table's own at that ``a/b``."""
        lo, step = self.ab_grid
        index = (math.log(a_over_b) - lo) / step
        if moment is None:
            c = np.array([np.interp(math.log(a_over_b), self.log_ab, self.coefficients[:, k])
                          for k in range(4)])  # fmt: skip
            moment = (c[2] / c[1], c[3] / c[2])
        return table_creep(float(ux), float(uy), float(us), moment[0], moment[1], index,
                           self.kernel_array)  # fmt: skip


def _linear_coefficients(solver: Solver, a: float, b: float, poisson: float
                         ) -> np.ndarray:  # fmt: skip
    """The solver's ``C11, C22, C23, C33`` from tiny creepages (its linear limit)."""
    g, n_load, mu = 1.0e11, 1.0e4, 1.0
    c = math.sqrt(a * b)
    xi = _U_LINEAR * mu * n_load / (g * c * c)
    fx, _, _ = solver(xi, 0.0, 0.0, a, b, mu, n_load, g, poisson)
    _, fy, mz = solver(0.0, xi, 0.0, a, b, mu, n_load, g, poisson)
    phi = xi / c
    _, fy_s, mz_s = solver(0.0, 0.0, phi, a, b, mu, n_load, g, poisson)
    c11 = -fx / (g * c * c * xi)
    c22 = -fy / (g * c * c * xi)
    c23 = -fy_s / (g * c**3 * phi)
    c33 = -mz_s / (g * c**4 * phi)
    _ = mz  # the reciprocal C23 (moment of the lateral creepage) equals -fy_s's
    return np.array([c11, c22, c23, c33])


def slice_values(solver: Solver, a_over_b: float, sx: np.ndarray, sy: np.ndarray,
                 ss: np.ndarray, poisson: float, vectorised: bool = False
                 ) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Node values ``D`` of one ``a/b`` slice and the solver's coefficients there.

    ``s_y`` is the coordinate of the lateral linear force ``u_y + u_s``. Only ``s_y >= 0`` is
    solved; ``D(s_x, -s_y, -s_s) = (D_x, -D_y, -D_m)(s_x, s_y, s_s)``
    (the mirror ``y -> -y``) fills the rest (``sy`` and ``ss`` must be symmetric grids) and
    makes the plane ``s_y = 0`` symmetric (its two halves averaged); ``D_x`` is exactly 0
    at ``s_x = 0`` (``F_x`` is odd in ``xi``). ``vectorised``: the solver takes arrays of
    creepages (one call per slice, in the grid's order: each case starts from its
    neighbour's solution).
    """
    a = 5e-3 * math.sqrt(a_over_b)
    b = 5e-3 / math.sqrt(a_over_b)
    c = math.sqrt(a * b)
    g, n_load, mu = 1.0e11, 1.0e4, 1.0
    coef = _linear_coefficients(solver, a, b, poisson)
    c11, c22, c23, c33 = coef
    my, ms = c23 / c22, c33 / c23
    out = np.zeros((sx.size, sy.size, ss.size, 3))
    half = sy.size // 2
    ux_all, uf_all = _u_of_s(sx, P_CREEPAGE), _u_of_s(sy, P_CREEPAGE)
    us_all = _u_of_s(ss, P_SPIN) / math.sqrt(1.0 + ms * ms)
    # Node creepages of the solved half (s_y >= 0), index order (s_x, s_y, s_s).
    ux, uf, us = np.meshgrid(ux_all, uf_all[half:], us_all, indexing="ij")
    uy = uf - us  # the grid's s_y is the lateral linear force u_y + u_s
    lm = my * uy - ms * us
    rho2 = ux * ux + uy * uy + us * us + lm * lm
    live = rho2 > 0.0
    xi = ux[live] * mu * n_load / (g * c * c * c11)
    eta = uy[live] * mu * n_load / (g * c * c * c22)
    phi = us[live] * mu * n_load / (g * c**3 * c23)
    if vectorised:
        fx, fy, mz = (np.asarray(v, dtype=float) for v in solver(xi, eta, phi, a, b, mu,
                                                                  n_load, g, poisson))
    else:
        fx, fy, mz = np.array([solver(float(x), float(e), float(p), a, b, mu, n_load, g,
                                      poisson) for x, e, p in zip(xi, eta, phi, strict=True)]).T
    t = np.stack([fx, fy, mz / c], axis=-1) / (mu * n_load)
    inv = 1.0 / np.sqrt(1.0 + rho2[live])
    base = np.stack([-ux[live], -(uy[live] + us[live]), lm[live]], axis=-1) * inv[:, None]
    solved = np.zeros((*ux.shape, 3))
    solved[live] = (t - base) / (rho2[live] * inv * inv)[:, None]
    out[:, half:] = solved
    mirror = np.array([1.0, -1.0, -1.0])
    if sy.size % 2:  # the plane s_y = 0: symmetric under (s_s, D_y, D_m) -> -(...)
        out[:, half] = 0.5 * (out[:, half] + out[:, half, ::-1] * mirror)
    for j in range(half):
        out[:, j] = out[:, sy.size - 1 - j, ::-1] * mirror
    out[0, ..., 0] = 0.0
    return out, coef


def build_creep_table(solver: Solver, *, a_over_b: np.ndarray, n_x: int = 9, n_y: int = 17,
                      n_s: int = 17, poisson: float = 0.3,
                      map_slices: Callable | None = None,
                      vectorised: bool = False) -> CreepTable:  # fmt: skip
    """Solve the contact problem on the grid and return the table.

    Parameters
    ----------
    solver : callable
        :data:`Solver` (the exact theory).
    a_over_b : numpy.ndarray
        Slices, uniform in ``ln(a/b)``.
    n_x, n_y, n_s : int
        Nodes of ``s_x`` on [0, 1] and of ``s_y``, ``s_s`` on [-1, 1] (odd).
    poisson : float
        Poisson's ratio.
    map_slices : callable, optional
        ``map(function, iterable)`` to spread the slices over processes.
    vectorised : bool
        The solver takes arrays of creepages (one call per slice).
    """
    log_ab = np.log(np.asarray(a_over_b, dtype=np.float64))
    sx = np.linspace(0.0, 1.0, n_x)
    sy = np.linspace(-1.0, 1.0, n_y)
    ss = np.linspace(-1.0, 1.0, n_s)
    job = functools.partial(slice_values, solver, sx=sx, sy=sy, ss=ss, poisson=poisson,
                            vectorised=vectorised)
    results = list((map_slices or map)(job, np.exp(log_ab)))
    values = np.stack([r[0] for r in results])
    coefficients = np.stack([r[1] for r in results])
    return CreepTable(log_ab=log_ab, values=values, poisson=poisson,
                      coefficients=coefficients,
                      meta={"n_x": n_x, "n_y": n_y, "n_s": n_s})  # fmt: skip


def save_creep_table(table: CreepTable, path: object) -> None:
    """Write a table (npz: node values, grid, coefficients, build notes)."""
    import json

    np.savez_compressed(path, log_ab=table.log_ab, values=table.values,
                        poisson=np.array(table.poisson), coefficients=table.coefficients,
                        meta=np.array(json.dumps(table.meta)))  # fmt: skip


def load_creep_table(path: object) -> CreepTable:
    """Read a table written by :func:`save_creep_table`."""
    import json

    with np.load(path, allow_pickle=False) as data:
        return CreepTable(log_ab=data["log_ab"], values=data["values"],
                          poisson=float(data["poisson"]), coefficients=data["coefficients"],
                          meta=json.loads(str(data["meta"])))  # fmt: skip


@functools.lru_cache(maxsize=1)
def shipped_creep_table() -> CreepTable:
    """The creep table shipped with railhunt (read once)."""
    ref = resources.files("railhunt").joinpath(*SHIPPED)
    if not ref.is_file():
        raise ValueError("creep_law = 'exact-table' is not available in this installation: "
                         "its table railhunt/data/creep/exact_table.npz has not been built "
                         "(python -m railhunt.data.creep.build_creep_table, with the exact "
                         "solver); use another creep law")  # fmt: skip
    with resources.as_file(ref) as path:
        return load_creep_table(path)
