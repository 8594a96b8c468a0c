"""How far each creep law is from Kalker's exact theory: the table of docs/creep.md.

Run as ``python -m railhunt.mechanics.accuracy [--grid 40] [--reference-grid 60]``.

For three patches (a/b = 0.5, the S1002/UIC60 tread's shape; a/b = 1; a/b = 19, a flange
contact) and five sweeps of the creepages in units of the ones that saturate Kalker's
linear law (``xi_s = mu N / f11``, ``eta_s = mu N / f22``, ``phi_s = mu N / f23``) at
``t = 0.1, 0.25, 0.5, 1, 2, 4``: pure ``xi``; pure ``eta``; pure ``phi``; ``xi = eta``
(combined, ``t / sqrt 2`` each); ``eta`` with a large spin ``phi = phi_s`` beside it; it
prints, per law, the largest difference from the exact theory over each sweep, of
``F_x``, ``F_y`` over ``mu N`` and of ``M_z`` over ``mu N c``. The exact theory is the
``"exact"`` law (40 x 40 extrapolated from 20 x 20), itself checked against a finer grid
(``--reference-grid``, extrapolated from half of it): that difference is the reference's
own uncertainty, printed beside. A second table gives each law's linear coefficients
(at a thousandth of the saturating creepages) relative to Kalker's.
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

from railhunt.mechanics.coefficients import kalker_coefficients
from railhunt.mechanics.laws import LAWS, creep_forces

PATCHES = {"a/b = 0.5": (0.5, 0.0070), "a/b = 1": (1.0, 0.0050), "a/b = 19": (19.0, 0.0012)}
T = (0.1, 0.25, 0.5, 1.0, 2.0, 4.0)
SWEEPS = ("xi", "eta", "phi", "xi = eta", "eta, phi = phi_s")
N, MU, G, NU = 60e3, 0.3, 8.2e10, 0.28


def creepages(sweep: str, a: float, b: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    c11, c22, c23, _ = kalker_coefficients(a / b, NU)
    c = math.sqrt(a * b)
    xs, es, ps = MU * N / (G * c * c * c11), MU * N / (G * c * c * c22), MU * N / (G * c**3 * c23)
    t = np.asarray(T)
    zero = np.zeros_like(t)
    return {"xi": (t * xs, zero, zero), "eta": (zero, t * es, zero), "phi": (zero, zero, t * ps),
            "xi = eta": (t * xs / math.sqrt(2), t * es / math.sqrt(2), zero),
            "eta, phi = phi_s": (zero, t * es, zero + ps)}[sweep]  # fmt: skip


def table(grid: int, reference_grid: int, laws=LAWS, log=print) -> dict:
    """``{(patch, sweep, law): (dFx, dFy, dMz)}`` and the reference's own uncertainty."""
    out = {}
    for name, (ratio, b) in PATCHES.items():
        a = ratio * b
        c = math.sqrt(a * b)
        kw = dict(a=a, b=b, mu=MU, normal_force=N, shear_modulus=G, poisson=NU)
        for sweep in SWEEPS:
            t0 = time.perf_counter()
            xi, eta, phi = creepages(sweep, a, b)
            ref = creep_forces(xi, eta, phi, law="exact", grid=grid, **kw)
            fine = creep_forces(xi, eta, phi, law="exact", grid=reference_grid, **kw)
            for law in ("reference", *(x for x in laws if x != "exact")):
                r = fine if law == "reference" else creep_forces(xi, eta, phi, law=law, **kw)
                out[name, sweep, law] = (np.max(np.abs(r.fx - ref.fx)) / (MU * N),
                                         np.max(np.abs(r.fy - ref.fy)) / (MU * N),
                                         np.max(np.abs(r.mz - ref.mz)) / (MU * N * c))
            log(f"{name}, {sweep}: {time.perf_counter() - t0:.0f} s")
    return out


def coefficient_table(laws=LAWS) -> dict:
    """``{(patch, law): (C11, C22, C23 from F_y, C23 from M_z, C33)}`` of each law at a
    creepage of 1e-3 of the saturating one, over Kalker's (the table's) values, minus 1."""
    out = {}
    for name, (ratio, b) in PATCHES.items():
        a = ratio * b
        c = math.sqrt(a * b)
        kw = dict(a=a, b=b, mu=MU, normal_force=N, shear_modulus=G, poisson=NU)
        c11, c22, c23, c33 = kalker_coefficients(ratio, NU)
        xs, es, ps = (1e-3 * MU * N / (G * c * c * c11), 1e-3 * MU * N / (G * c * c * c22),
                      1e-3 * MU * N / (G * c**3 * c23))
        for law in laws:
            r = creep_forces([xs, 0.0, 0.0], [0.0, es, 0.0], [0.0, 0.0, ps], law=law, **kw)
            got = (-r.fx[0] / (G * c * c * xs), -r.fy[1] / (G * c * c * es),
                   -r.fy[2] / (G * c**3 * ps), r.mz[1] / (G * c**3 * es),
                   -r.mz[2] / (G * c**4 * ps))
            out[name, law] = tuple(g / k - 1 for g, k in zip(got, (c11, c22, c23, c23, c33),
                                                             strict=True))  # fmt: skip
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=40, help="the exact law's grid")
    parser.add_argument("--reference-grid", type=int, default=60,
                        help="finer grid for the reference's own uncertainty")
    args = parser.parse_args(argv)
    res = table(args.grid, args.reference_grid, log=lambda s: print(s, file=sys.stderr))
    laws = ["reference", *(x for x in LAWS if x != "exact")]
    print("| patch | sweep | " + " | ".join(laws) + " |")
    print("|---|---|" + "---|" * len(laws))
    for name in PATCHES:
        for sweep in SWEEPS:
            cells = []
            for law in laws:
                dfx, dfy, dmz = res[name, sweep, law]
                cells.append(f"{100 * max(dfx, dfy):.1f} / {100 * dmz:.1f}")
            print(f"| {name} | {sweep} | " + " | ".join(cells) + " |")
    print("\n(each cell: largest |F - F_exact| / (mu N) in %, over F_x and F_y / largest "
          "|M_z - M_z,exact| / (mu N c) in %)")
    coef = coefficient_table()
    print("\n| patch | law | C11 | C22 | C23 (F_y) | C23 (M_z) | C33 |")
    print("|---|---|---|---|---|---|---|")
    for name in PATCHES:
        for law in LAWS:
            cells = " | ".join(f"{100 * v:+.1f}" for v in coef[name, law])
            print(f"| {name} | {law} | {cells} |")
    print("\n(each law's linear coefficients at 1e-3 of the saturating creepages, relative "
          "to Kalker's table, in %)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
