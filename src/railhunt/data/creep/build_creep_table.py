"""Build the shipped creep table ``exact_table.npz`` from Kalker's exact theory.

Run from anywhere (about 46 000 solutions of 15-25 ms: about 10-20 minutes on 2 cores)::

    python -m railhunt.data.creep.build_creep_table            # 2 processes
    python -m railhunt.data.creep.build_creep_table --processes 1 --out table.npz

Each slice of ``a/b`` (0.05 ... 20, uniform in ``ln(a/b)``) solves the steady rolling
contact problem with ``railhunt.creep_forces(..., law="exact")`` at every node of the
normalised creepages (:mod:`railhunt.contact.creep_table`; all nodes of a slice in one
call, each case starting from its neighbour's solution), and the correction ``D`` the
compiled law interpolates is written with the grid, the solver's own linear coefficients
and these build notes. The accuracy against the solver at points between the nodes is
printed at the end (and checked by the tests).
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

#: Slices: ln(a/b) from ln(0.05) to ln(20) in steps of 0.5 (a/b x 1.65).
A_OVER_B = np.exp(np.linspace(math.log(0.05), math.log(20.0), 13))
#: Nodes of s_x on [0, 1], of s_y and s_s on [-1, 1].
N_X, N_Y, N_S = 11, 25, 25
#: Elements of the exact solver's patch grid: 40 x 40, Richardson-extrapolated from 20 x 20
#: (``creep_forces(law="exact")``'s default, grid-converged to a few parts in a thousand of
#: mu N); each slice is normalised by the solver's own linear theory on that grid.
GRID = 40


def exact(xi: float, eta: float, phi: float, a: float, b: float, mu: float, normal_force: float,
          shear_modulus: float, poisson: float) -> tuple[float, float, float]:  # fmt: skip
    """Kalker's exact theory (``railhunt.creep_forces(..., law="exact")``)."""
    from railhunt.mechanics.laws import creep_forces

    f = creep_forces(xi, eta, phi, a=a, b=b, mu=mu, normal_force=normal_force, law="exact",
                     shear_modulus=shear_modulus, poisson=poisson, grid=GRID)  # fmt: skip
    return float(f.fx), float(f.fy), float(f.mz)


def exact_batch(xi: np.ndarray, eta: np.ndarray, phi: np.ndarray, a: float, b: float,
                mu: float, normal_force: float, shear_modulus: float, poisson: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """:func:`exact` for arrays of creepages on one patch (solved in one compiled loop)."""
    from railhunt.mechanics.laws import creep_forces

    f = creep_forces(xi, eta, phi, a=a, b=b, mu=mu, normal_force=normal_force, law="exact",
                     shear_modulus=shear_modulus, poisson=poisson, grid=GRID)  # fmt: skip
    return np.asarray(f.fx), np.asarray(f.fy), np.asarray(f.mz)


def accuracy(table: object, points: int = 200, seed: int = 1) -> dict[str, float]:
    """Largest and RMS difference between the compiled law (creepages normalised with
    Kalker's coefficients, as in the right-hand side) and the exact solver at random points
    between the nodes and slices, in units of mu N (forces) and mu N c (moment)."""
    from railhunt.mechanics.coefficients import kalker_coefficients

    rng = np.random.default_rng(seed)
    err = []
    g, n_load, mu, nu = 8.0e10, 5.0e4, 0.3, table.poisson
    for _ in range(points):
        ab = math.exp(rng.uniform(math.log(0.06), math.log(18.0)))
        a, b = 6e-3 * math.sqrt(ab), 6e-3 / math.sqrt(ab)
        c = math.sqrt(a * b)
        c11, c22, c23, c33 = (float(v) for v in kalker_coefficients(ab, nu))
        f11, f22, f23, f33 = g * c * c * c11, g * c * c * c22, g * c**3 * c23, g * c**4 * c33
        u = rng.normal(size=3) * 10.0 ** rng.uniform(-1.0, 1.0, size=3)
        xi, eta, phi = (u[0] * mu * n_load / f11, u[1] * mu * n_load / f22,
                        u[2] * mu * n_load / f23)  # fmt: skip
        ref = np.array(exact(xi, eta, phi, a, b, mu, n_load, g, nu)) / np.array(
            [mu * n_load, mu * n_load, mu * n_load * c])
        got = np.array(table.normalised(u[0], u[1], u[2], ab,
                                        moment=(f23 / (f22 * c), f33 / (f23 * c))))
        err.append(np.abs(got - ref))
    e = np.array(err)
    return {"max_fx": float(e[:, 0].max()), "max_fy": float(e[:, 1].max()),
            "max_mz": float(e[:, 2].max()), "rms_fx": float(np.sqrt(np.mean(e[:, 0] ** 2))),
            "rms_fy": float(np.sqrt(np.mean(e[:, 1] ** 2))),
            "rms_mz": float(np.sqrt(np.mean(e[:, 2] ** 2)))}


def main(argv: list[str] | None = None) -> int:
    from railhunt.contact.creep_table import build_creep_table, save_creep_table

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--processes", type=int, default=2)
    parser.add_argument("--out", type=Path, default=Path(__file__).with_name("exact_table.npz"))
    args = parser.parse_args(argv)
    t0 = time.time()
    if args.processes > 1:
        from multiprocessing import Pool

        with Pool(args.processes) as pool:
            table = build_creep_table(
                exact_batch, a_over_b=A_OVER_B, n_x=N_X, n_y=N_Y, n_s=N_S, poisson=0.3,
                map_slices=lambda f, it: pool.map(f, it, chunksize=1), vectorised=True)
    else:
        table = build_creep_table(exact_batch, a_over_b=A_OVER_B, n_x=N_X, n_y=N_Y, n_s=N_S,
                                  poisson=0.3, vectorised=True)  # fmt: skip
    seconds = time.time() - t0
    table.meta.update(solver=f"railhunt.creep_forces(law='exact', grid={GRID})",
                      nodes="x".join(str(n) for n in table.values.shape[:4]),
                      seconds=round(seconds, 1),
                      command="python -m railhunt.data.creep.build_creep_table")
    table.meta["accuracy"] = accuracy(table)
    save_creep_table(table, args.out)
    print(f"wrote {args.out}: {table.values.shape} nodes in {seconds:.0f} s")
    print("against the exact solver at 200 random points (|F| / mu N, |M| / mu N c):",
          ", ".join(f"{k} {v:.4f}" for k, v in table.meta["accuracy"].items()))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
