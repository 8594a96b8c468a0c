"""Write ``railhunt/data/creep/kalker_coefficients.csv``: Kalker's table and its extension.

Run as ``python -m railhunt.mechanics.build_tables [--out FILE] [--grid 64]``.

The rows ``a/b = 0.1 ... 10`` are Kalker's Table E.3 (*Three-dimensional elastic bodies
in rolling contact*, Kluwer 1990), typed in below (C33 from Kalker's 1967 thesis table as
it is commonly reproduced). The extension to ``a/b = 0.05`` and ``20`` (``g = a/b`` or
``b/a`` down to 0.05) comes from the linear limit of railhunt's exact steady-rolling solver
(:mod:`railhunt.mechanics.linear_theory`). The discretisation error of the solver is of
first order in the element size (the spin coefficient's most: ``C33`` at ``a/b = 10`` is
1.26 on a 64 x 64 grid, 0.53 printed), so each coefficient is extrapolated from two grids,
``C = 2 C(h) - C(2h)`` (Richardson); then the extension is the printed value at
``g = 0.1`` times the ratio ``C(g) / C(0.1)`` of the extrapolated values, which joins the
printed table continuously. The grids: ``m x m`` and ``m/2 x m/2`` elements for
``a <= b``; twice as many along the rolling direction for ``a > b`` (``2m x m``), where
the first-order error grows with ``sqrt(a/b) / m_x``. The script prints, at ``g = 0.1``,
the extrapolated values over the printed ones (the solver's agreement with Kalker's
table) and, at every node, the deviation from Kalker's slender-ellipse asymptotes (as in
CONTACT's ``linrol``).

It takes about ten minutes on one core with the default ``m = 64``.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

from railhunt.mechanics.linear_theory import linear_coefficients

# Kalker (1990) Table E.3 [case][row][coefficient][nu]; case 0: g = a/b = 0.1 .. 1.0;
# case 1: g = b/a = 0.1 .. 1.0; coefficients C11, C22, C23, C33; nu = 0, 0.25, 0.5.
PRINTED = (
    (  # a/b = 0.1 ... 1.0
        ((2.51, 3.31, 4.85), (2.51, 2.52, 2.53), (0.334, 0.473, 0.731), (6.42, 8.28, 11.7)),
        ((2.59, 3.37, 4.81), (2.59, 2.63, 2.66), (0.483, 0.603, 0.809), (3.46, 4.27, 5.66)),
        ((2.68, 3.44, 4.80), (2.68, 2.75, 2.81), (0.607, 0.715, 0.889), (2.49, 2.96, 3.72)),
        ((2.78, 3.53, 4.82), (2.78, 2.88, 2.98), (0.720, 0.823, 0.977), (2.02, 2.32, 2.77)),
        ((2.88, 3.62, 4.83), (2.88, 3.01, 3.14), (0.827, 0.929, 1.07), (1.74, 1.93, 2.22)),
        ((2.98, 3.72, 4.91), (2.98, 3.14, 3.31), (0.930, 1.03, 1.18), (1.56, 1.68, 1.86)),
        ((3.09, 3.81, 4.97), (3.09, 3.28, 3.48), (1.03, 1.14, 1.29), (1.43, 1.50, 1.60)),
        ((3.19, 3.91, 5.05), (3.19, 3.41, 3.65), (1.13, 1.25, 1.40), (1.34, 1.37, 1.42)),
        ((3.29, 4.01, 5.12), (3.29, 3.54, 3.82), (1.23, 1.36, 1.51), (1.27, 1.27, 1.27)),
        ((3.40, 4.12, 5.20), (3.40, 3.67, 3.98), (1.33, 1.47, 1.63), (1.21, 1.19, 1.16)),
    ),
    (  # b/a = 0.1 ... 1.0
        ((10.7, 11.7, 12.9), (10.7, 12.8, 16.0), (12.2, 14.6, 18.0), (0.795, 0.526, 0.228)),
        ((6.96, 7.78, 8.82), (6.96, 8.14, 9.79), (5.72, 6.63, 7.89), (0.828, 0.601, 0.341)),
        ((5.57, 6.34, 7.34), (5.57, 6.40, 7.51), (3.79, 4.32, 5.01), (0.868, 0.674, 0.446)),
        ((4.84, 5.57, 6.57), (4.84, 5.48, 6.31), (2.88, 3.24, 3.70), (0.912, 0.747, 0.549)),
        ((4.37, 5.10, 6.11), (4.37, 4.90, 5.56), (2.35, 2.62, 2.96), (0.958, 0.819, 0.650)),
        ((4.06, 4.78, 5.80), (4.06, 4.50, 5.04), (2.01, 2.23, 2.50), (1.01, 0.892, 0.751)),
        ((3.82, 4.54, 5.58), (3.82, 4.21, 4.67), (1.76, 1.95, 2.18), (1.05, 0.965, 0.852)),
        ((3.65, 4.36, 5.42), (3.65, 3.99, 4.39), (1.58, 1.75, 1.94), (1.10, 1.04, 0.954)),
        ((3.51, 4.22, 5.30), (3.51, 3.81, 4.16), (1.44, 1.59, 1.77), (1.16, 1.11, 1.06)),
        ((3.40, 4.12, 5.20), (3.40, 3.67, 3.98), (1.33, 1.47, 1.63), (1.21, 1.19, 1.16)),
    ),
)
NU = (0.0, 0.25, 0.5)
#: The extension's nodes g (log-spaced from the table's last row 0.1 down to 0.05).
EXTENSION_G = (0.0794, 0.0630, 0.05)
DEFAULT_GRID = 64
HEADER = "a_over_b,nu,c11,c22,c23,c33,source"


def asymptotes(case: int, g: float, nu: float) -> tuple[float, ...]:
    """Kalker's slender-ellipse asymptotes (``g -> 0``): ``(C11, C22, C23[, C33])``.

    ``a << b`` (case 0, ``g = a/b``): ``C11 = pi^2/(4(1-nu))``, ``C22 = pi^2/4``,
    ``C23 = pi sqrt(g)/(3(1-nu)) (1 + nu (ln(16/g) - 5))``, ``C33 = pi^2/(16(1-nu) g)``.
    ``a >> b`` (case 1, ``g = b/a``, ``L = ln(16/g^2)``): ``C11 = 2 pi/((L - 2 nu) g)
    (1 + (3 - ln 4)/(L - 2 nu))``, ``C22 = 2 pi/g (1 + (1-nu)(3 - ln 4)/((1-nu) L + 2 nu))
    / ((1-nu) L + 2 nu)``, ``C23 = 2 pi/(3 g^1.5 ((1-nu) L - 2 + 4 nu))``.
    """
    pi = math.pi
    if case == 0:
        return (pi**2 / (4 * (1 - nu)), pi**2 / 4,
                pi * math.sqrt(g) / (3 * (1 - nu)) * (1 + nu * (math.log(16 / g) - 5)),
                pi**2 / (16 * (1 - nu) * g))
    big = math.log(16 / g**2)
    c11 = 2 * pi / ((big - 2 * nu) * g) * (1 + (3 - math.log(4)) / (big - 2 * nu))
    d = (1 - nu) * big + 2 * nu
    c22 = 2 * pi / g * (1 + (1 - nu) * (3 - math.log(4)) / d) / d
    c23 = 2 * pi / (3 * g**1.5 * ((1 - nu) * big - 2 + 4 * nu))
    return c11, c22, c23


def printed_rows() -> list[tuple[float, float, tuple[float, ...], str]]:
    rows = []
    for case in (0, 1):
        for r in range(10):
            g = round(0.1 * (r + 1), 10)
            ab = g if case == 0 else 1.0 / g
            if case == 1 and r == 9:
                continue  # a/b = 1 appears once
            for k, nu in enumerate(NU):
                coef = tuple(PRINTED[case][r][i][k] for i in range(4))
                rows.append((ab, nu, coef, "Kalker 1990 Table E.3"))
    return rows


def _fmt(x: float) -> str:
    return f"{x:.10g}"


def _grid(case: int, m: int) -> tuple[int, int]:
    return (m, m) if case == 0 else (2 * m, m)


def extrapolated(case: int, g: float, nu: float, m: int) -> np.ndarray:
    """``2 C(h) - C(2h)`` of ``(C11, C22, C23, C33)`` on the grids of ``m`` and ``m/2``."""
    ab = g if case == 0 else 1.0 / g
    values = []
    for mm in (m // 2, m):
        mx, my = _grid(case, mm)
        s = linear_coefficients(ab, nu, mx, my)
        values.append(np.array([s.c11, s.c22, s.c23, s.c33]))
    return 2.0 * values[1] - values[0]


def extension_rows(m: int, log=print):
    rows = []
    for case in (0, 1):
        for k, nu in enumerate(NU):
            t0 = time.perf_counter()
            table01 = np.array([PRINTED[case][0][i][k] for i in range(4)])
            at01 = extrapolated(case, 0.1, nu, m)
            mx, my = _grid(case, m)
            log(f"case {'a<=b' if case == 0 else 'a>b'}, nu = {nu:g}, grids {mx} x {my} and "
                f"half: at g = 0.1 extrapolated/printed = "
                f"{np.array2string(at01 / table01, precision=4)}")
            for g in EXTENSION_G:
                coef = table01 * extrapolated(case, g, nu, m) / at01
                asym = asymptotes(case, g, nu)
                dev = ", ".join(f"{coef[i] / asym[i] - 1:+.3f}" for i in range(len(asym)))
                log(f"  g = {g:.4f}: C = {np.array2string(coef, precision=4)}; relative to "
                    f"the asymptotes {dev}")
                ab = g if case == 0 else 1.0 / g
                rows.append((ab, nu, tuple(float(c) for c in coef),
                             f"exact solver linear limit (Richardson {mx} x {my}) scaled to "
                             "Table E.3 at g = 0.1"))
            log(f"  ({time.perf_counter() - t0:.0f} s)")
    return rows


def write_table(path: Path, rows) -> None:
    rows = sorted(rows, key=lambda r: (r[0], r[1]))
    lines = [
        "# Kalker's creep coefficients C11, C22, C23, C33 (F_x = -G c^2 C11 xi, ...,",
        "# c = sqrt(a b)) for a/b = 0.05 ... 20 and nu = 0, 0.25, 0.5.",
        "# Written by: python -m railhunt.mechanics.build_tables (see its docstring).",
        HEADER,
    ]
    for ab, nu, coef, source in rows:
        lines.append(",".join([_fmt(ab), _fmt(nu), *(_fmt(c) for c in coef), source]))
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = Path(__file__).resolve().parents[1] / "data" / "creep" / "kalker_coefficients.csv"
    parser.add_argument("--out", type=Path, default=default, help="output CSV file")
    parser.add_argument("--grid", type=int, default=DEFAULT_GRID,
                        help="elements m of the finer grid (default %(default)s)")
    args = parser.parse_args(argv)
    rows = printed_rows() + extension_rows(args.grid, log=lambda s: print(s, flush=True))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    write_table(args.out, rows)
    print(f"wrote {args.out} ({len(rows)} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
