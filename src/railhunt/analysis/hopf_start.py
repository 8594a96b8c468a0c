"""The start of a Hopf branch: the crossing mode at the Hopf point, the coordinate that
measures the branch, and its first three small limit cycles.

:func:`railhunt.analysis.continuation.bifurcation_diagram` and
:func:`railhunt.analysis.fold.fold_speed` start the branch of limit cycles born at the
Hopf point from these.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from railhunt.analysis.curving import EquilibriumPath
from railhunt.analysis.linear import eigenvalues, hunting_mode_index
from railhunt.analysis.modes import sorted_eig
from railhunt.analysis.newton import newton
from railhunt.analysis.periodic import PeriodicOrbit, Shooting
from railhunt.model import Model
from railhunt.units import kmh_to_ms

if TYPE_CHECKING:
    from railhunt.analysis.branch_tracer import BranchTracer


def hopf_mode_shape(model: Model, hopf_kmh: float,
                path: EquilibriumPath | None = None) -> tuple[np.ndarray, float]:  # fmt: skip
    """Hunting eigenvector normalised to 1 at :func:`measure_coordinate` (real state
    shape) and the period (s).

    About the centred state, or about the curving equilibrium of ``path``.
    """
    if path is None:
        w, vecs = eigenvalues(model, kmh_to_ms(hopf_kmh))
    else:
        w, vecs = sorted_eig(path.jacobian_kmh(hopf_kmh))
    k = hunting_mode_index(w, vecs, model.half_gauge, model.layout)
    if w[k].real < -1e-3:
        # The pick is clearly damped here, so it is not the pair that crosses at this Hopf
        # point (two nearly equal bogie modes of a long vehicle): start from the crossing
        # pair itself, the oscillatory eigenvalue with the largest real part.
        osc = np.flatnonzero(w.imag > 1e-6)
        k = int(osc[np.argmax(w.real[osc])])
    lam = w[k]
    if lam.imag < 0:
        lam, vec = np.conj(lam), np.conj(vecs[:, k])
    else:
        vec = vecs[:, k]
    vec = vec / vec[measure_coordinate(model, vec)]
    return np.real(vec), 2 * math.pi / abs(lam.imag)


def measure_coordinate(model: Model, shape: np.ndarray) -> int:
    """Index of the displacement that measures the Hopf branch: its phase condition, step
    control, small orbits and end at a second Hopf point use it.

    y_w1, unless the leading wheelset moves less than :data:`LEADING_SHARE` of the wheelset
    that moves most laterally in the crossing mode ``shape`` (complex or real state
    vector): then that wheelset's lateral displacement. The paper's vehicle: y_w1 (it
    moves 0.12 of the rear wheelset at the Hopf point); the articulated pair of
    ``examples/data/articulated_pair.toml``, whose crossing mode lives on its rear bogie
    (y_w1 0.066 of y_w6): y_w6.
    """
    layout = model.layout
    amp = np.abs(shape[layout.wheelset_y])
    k = int(np.argmax(amp))
    if abs(shape[layout.y_w1]) >= LEADING_SHARE * amp[k]:
        return layout.y_w1
    return int(layout.wheelset_y[k])


#: The leading wheelset measures the Hopf branch while it moves at least this share of the
#: wheelset that moves most in the crossing mode (:func:`measure_coordinate`).
LEADING_SHARE = 0.1


#: The measure coordinate's ``x(0)`` (:func:`measure_coordinate`, y_w1 for the paper's
#: vehicle) of the three small orbits that start the Hopf branch (m).
SMALL_ORBIT_SEEDS = (5e-5, 1e-4, 2e-4)


def small_orbit_seeds(shoot: Shooting, shape: np.ndarray) -> tuple[float, ...]:
    """The measure coordinate's ``x(0)`` of the three small orbits of the Hopf branch (m).

    Small orbits are small on every wheelset: where the crossing mode ``shape`` (normalised
    to 1 at :func:`measure_coordinate`) moves another wheelset more than that, the seeds
    shrink by that ratio (the paper's vehicle: y_w1, the measure, moves most, the seeds
    are :data:`SMALL_ORBIT_SEEDS`).
    """
    largest = float(np.max(np.abs(shape[shoot.model.layout.wheelset_y])))
    if largest > 1.0:
        return tuple(s / largest for s in SMALL_ORBIT_SEEDS)
    return SMALL_ORBIT_SEEDS


def hopf_branch_start(shoot: Shooting, tracer: BranchTracer, x_hopf: np.ndarray, shape: np.ndarray,
                      period0: float, hopf: float,
                      ) -> list[tuple[np.ndarray, PeriodicOrbit, tuple]]:  # fmt: skip
    """Three small orbits of the Hopf branch, the measure coordinate's ``x(0)``
    (:func:`measure_coordinate`) fixed at 0.05, 0.1 and 0.2 mm.

    Started from the hunting eigenvector ``shape`` about ``x_hopf`` and the Hopf period
    (natural parameter: the speed is an unknown). Returns ``(u, orbit, linearisation)``
    of each, in order of amplitude.
    """
    iy = tracer.iy
    seeds = small_orbit_seeds(shoot, shape)
    small: list[tuple[np.ndarray, PeriodicOrbit, tuple]] = []
    u = shoot.pack(x_hopf + seeds[0] * shape, period0, kmh_to_ms(hopf))
    for n, eps in enumerate(seeds):
        target = (x_hopf[tracer.measure] + eps) / shoot.scale[tracer.measure]
        if n >= 2:
            u = small[-1][0] + (small[-1][0] - small[-2][0]) * (eps - seeds[n - 1]) / (
                seeds[n - 1] - seeds[n - 2])  # fmt: skip
        u = u.copy()
        u[iy] = target

        def fun(w: np.ndarray, target: float = target) -> np.ndarray:
            return np.append(shoot.residual(w), w[iy] - target)

        def jac_fun(w: np.ndarray, r: np.ndarray) -> np.ndarray:
            row = np.zeros(w.size)
            row[iy] = 1.0
            return np.vstack([shoot.jacobian(w, r[:-1]), row])

        guess = u
        u, norm, it, ok, _ = newton(fun, jac_fun, guess, tol=1e-9, max_iter=20)
        if not ok and small:
            # Where two hunting modes (front and rear bogie) nearly coincide, the previous
            # orbit with only the measure coordinate moved can be too poor a start: start
            # again from the previous orbit scaled about the equilibrium to the new size.
            x_prev, period, speed = shoot.unpack(small[-1][0])
            scaled = x_hopf + (x_prev - x_hopf) * (eps / seeds[n - 1])
            u, norm, it, ok, _ = newton(fun, jac_fun, shoot.pack(scaled, period, speed),
                                        tol=1e-9, max_iter=20)  # fmt: skip
        if not ok:
            raise RuntimeError(f"no small limit cycle found near the Hopf point ({hopf:.1f} km/h)")
        orbit, lin = tracer.solve(u, norm, it)
        small.append((u, orbit, lin))
    return small
