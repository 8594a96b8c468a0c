"""Kalker's creep coefficients ``C11, C22, C23, C33`` of the linear theory of rolling contact.

For two bodies of one elastic material (shear modulus ``G``, Poisson's ratio ``nu``) and
an elliptical patch with semi-axes ``a`` (rolling direction) and ``b``, ``c = sqrt(a b)``,
Kalker's linear theory gives, for small creepages ``xi, eta`` and spin ``phi``,

    F_x = -G c^2 C11 xi,   F_y = -G c^2 (C22 eta + c C23 phi),   M_z = G c^3 (C23 eta - c C33 phi)

on the body whose creepages they are (J. J. Kalker, *Three-dimensional elastic bodies in
rolling contact*, Kluwer 1990, Sec. 1.5 and Table E.3).

The table shipped in ``railhunt/data/creep/kalker_coefficients.csv`` holds, for
``nu = 0, 0.25, 0.5``:

* ``a/b = 0.1 ... 10`` (``g = a/b`` or ``b/a`` = 0.1, 0.2, ... 1.0): Kalker's Table E.3
  (C11, C22, C23 as printed there and in CONTACT's ``linrol``; C33 from Kalker's 1967
  thesis table as commonly reproduced);
* ``a/b = 0.05 ... 0.1`` and ``10 ... 20``: railhunt's exact steady-rolling solver in its
  linear limit (full adhesion), extrapolated to a vanishing element size, written by
  ``python -m railhunt.mechanics.build_tables`` (which says how, and checks itself against
  the printed table at ``g = 0.1`` and against Kalker's slender-ellipse asymptotes).

Interpolation: between the printed rows linearly in ``g`` (as railhunt always did, so the
coefficients of existing vehicles do not move); between the extension's rows linearly in
``(log g, log C)`` (the coefficients follow powers of ``g`` there); in Poisson's ratio
quadratically (Lagrange through ``nu = 0, 0.25, 0.5``).
"""

from __future__ import annotations

import csv
import math
from functools import cache
from importlib import resources

import numpy as np

from railhunt.mechanics._checks import check_array, check_range

__all__ = ["A_OVER_B_RANGE", "kalker_coefficients", "kalker_table"]

#: Range of semi-axis ratios ``a/b`` the coefficients cover.
A_OVER_B_RANGE = (0.05, 20.0)
_NU = (0.0, 0.25, 0.5)
_TABLE_FILE = "kalker_coefficients.csv"


@cache
def kalker_table() -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[str, ...]]:
    """The shipped table: ``(a_over_b, nu, C, source)`` with ``C`` of shape (n, 4)."""
    text = resources.files("railhunt.data").joinpath("creep", _TABLE_FILE).read_text(
        encoding="utf-8")
    rows = [r for r in csv.DictReader(line for line in text.splitlines()
                                      if line and not line.startswith("#"))]
    ab = np.array([float(r["a_over_b"]) for r in rows])
    nu = np.array([float(r["nu"]) for r in rows])
    c = np.array([[float(r[k]) for k in ("c11", "c22", "c23", "c33")] for r in rows])
    return ab, nu, c, tuple(r["source"] for r in rows)


@cache
def _tables() -> tuple[np.ndarray, list[tuple[np.ndarray, np.ndarray]]]:
    """The printed table as ``[case][row][coefficient][nu]`` (case 0: ``a <= b``, rows
    ``g = 0.1 .. 1.0``) and, per case, the extension's ``(log g, log C[nu, coef])``."""
    ab, nu, c, _ = kalker_table()
    printed = np.empty((2, 10, 4, 3))
    ext: list[tuple[list[float], list[np.ndarray]]] = [([], []), ([], [])]
    for case in (0, 1):
        g_all = ab if case == 0 else 1.0 / ab
        side = (ab <= 1.0) if case == 0 else (ab >= 1.0)
        gs = sorted({round(float(g), 12) for g in g_all[side]})
        for g in gs:
            sel = side & np.isclose(g_all, g, rtol=0, atol=1e-9)
            block = np.empty((3, 4))
            for k, n in enumerate(_NU):
                row = sel & np.isclose(nu, n)
                if row.sum() != 1:
                    raise RuntimeError(f"{_TABLE_FILE}: {row.sum()} rows at g = {g}, nu = {n}")
                block[k] = c[row][0]
            x = 10.0 * g - 1.0
            if g >= 0.1 - 1e-9 and abs(x - round(x)) < 1e-6:
                printed[case, int(round(x))] = block.T
            if g <= 0.1 + 1e-9:
                ext[case][0].append(math.log(g))
                ext[case][1].append(np.log(block))
    out = []
    for lg, lc in ext:
        order = np.argsort(lg)
        out.append((np.asarray(lg)[order], np.asarray(lc)[order]))
    return printed, out


def _lagrange(nu: np.ndarray) -> np.ndarray:
    n0, n1, n2 = _NU
    l0 = (nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2))
    l1 = (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2))
    l2 = (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1))
    return np.stack([l0, l1, l2], axis=-1)


def _coefficients(a_over_b: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """``(..., 4)`` coefficients for validated arrays (``nu`` broadcast to ``a_over_b``)."""
    printed, ext = _tables()
    r = a_over_b.ravel()
    l0, l1, l2 = np.moveaxis(_lagrange(np.broadcast_to(nu, a_over_b.shape).ravel()), -1, 0)
    case = (r > 1.0).astype(int)
    g = np.where(case == 0, r, 1.0 / r)
    out = np.empty((r.size, 4))
    tab = g >= 0.1
    if tab.any():
        x = 10.0 * g[tab] - 1.0
        i = np.minimum(np.floor(x).astype(int), 8)
        w = (x - i)[:, None, None]
        cs = case[tab]
        row = (1.0 - w) * printed[cs, i] + w * printed[cs, i + 1]  # (n, 4, 3)
        out[tab] = (row[..., 0] * l0[tab, None] + row[..., 1] * l1[tab, None]
                    + row[..., 2] * l2[tab, None])
    for cs in (0, 1):
        sel = ~tab & (case == cs)
        if not sel.any():
            continue
        lg, lc = ext[cs]
        t = np.log(g[sel])
        j = np.clip(np.searchsorted(lg, t) - 1, 0, lg.size - 2)
        w = ((t - lg[j]) / (lg[j + 1] - lg[j]))[:, None, None]
        block = np.exp((1.0 - w) * lc[j] + w * lc[j + 1])  # (n, 3 nu, 4)
        out[sel] = (block[:, 0] * l0[sel, None] + block[:, 1] * l1[sel, None]
                    + block[:, 2] * l2[sel, None])
    return out.reshape(a_over_b.shape + (4,))


def kalker_coefficients(a_over_b, nu: float):
    """Kalker's ``(C11, C22, C23, C33)`` for semi-axis ratio ``a/b`` and Poisson's ratio.

    Parameters
    ----------
    a_over_b : float or array_like
        Semi-axis in the rolling direction over the lateral one, in ``[0.05, 20]``.
    nu : float
        Poisson's ratio, in ``[0, 0.5]``.

    Returns
    -------
    tuple of float (or of ndarray, for an array ``a_over_b``)
        Dimensionless coefficients. For ``a/b`` in ``[0.1, 10]`` Kalker's Table E.3
        interpolated linearly in ``g``; beyond, the shipped extension (module docstring).

    Raises
    ------
    ValueError
        ``a_over_b`` or ``nu`` outside the ranges, not finite.
    """
    nu = check_range("nu", nu, 0.0, 0.5)
    lo, hi = A_OVER_B_RANGE
    if np.ndim(a_over_b) == 0:
        r = check_range("a_over_b", a_over_b, lo, hi)
        c = _coefficients(np.array([r]), np.array(nu))[0]
        return float(c[0]), float(c[1]), float(c[2]), float(c[3])
    arr = check_array("a_over_b", a_over_b, lo, hi)
    c = _coefficients(arr, np.array(nu))
    return c[..., 0], c[..., 1], c[..., 2], c[..., 3]
