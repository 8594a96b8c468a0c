"""Build the shipped creep table ``exact_table.npz`` from Kalker's exact theory.

Run from anywhere (a few minutes on 2 cores)::

    python -m railhunt.data.creep.build_creep_table            # 2 processes
    python -m railhunt.data.creep.build_creep_table --processes 1 --out table.npz

Each slice of ``a/b`` (0.05 ... 20, uniform in ``ln(a/b)``) solves the steady rolling
contact problem with ``railhunt.creep_forces(..., law="exact")`` at every node of the
normalised creepages (:mod:`railhunt.contact.creep_table`), and the correction ``D`` the
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

#: Slices: ln(a/b) from ln(0.05) to ln(20) in steps of 0.25 (a/b x 1.28).
A_OVER_B = np.exp(np.linspace(math.log(0.05), math.log(20.0), 25))
#: Nodes of s_x on [0, 1], of s_y and s_s on [-1, 1].
N_X, N_Y, N_S = 9, 17, 25
#: Grid of the exact solver (elements per semi-axis direction).
GRID = 40


def exact(xi: float, eta: float, phi: float, a: float, b: float, mu: float, normal_force: float,
          shear_modulus: float, poisson: float) -> tuple[float, float, float]:  # fmt: skip
    """Kalker's exact theory (``railhunt.mechanics.creep_forces(..., law="exact")``)."""
    from railhunt.mechanics import creep_forces

    f = creep_forces(xi, eta, phi, a=a, b=b, mu=mu, normal_force=normal_force, law="exact",
                     shear_modulus=shear_modulus, poisson=poisson)  # fmt: skip
    return float(f.fx), float(f.fy), float(f.mz)


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
            table = build_creep_table(exact, a_over_b=A_OVER_B, n_x=N_X, n_y=N_Y, n_s=N_S,
                                      poisson=0.3, map_slices=pool.map)  # fmt: skip
    else:
        table = build_creep_table(exact, a_over_b=A_OVER_B, n_x=N_X, n_y=N_Y, n_s=N_S,
                                  poisson=0.3)  # fmt: skip
    seconds = time.time() - t0
    table.meta.update(solver="railhunt.creep_forces(law='exact')", seconds=round(seconds, 1),
                      command="python -m railhunt.data.creep.build_creep_table")
    save_creep_table(table, args.out)
    print(f"wrote {args.out}: {table.values.shape} nodes in {seconds:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
