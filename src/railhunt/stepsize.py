"""The largest step at which classical RK4 stays stable for the model (numerical blow-up).

A fixed-step RK4 run is stable only while ``h * lambda`` lies inside RK4's region of
absolute stability for every eigenvalue ``lambda`` of the linearised model:
``|R(h lambda)| <= 1`` with ``R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24`` (the region
reaches 2.785 along the negative real axis and 2.828 along the imaginary one). Beyond that
step the state grows by orders of magnitude within a few steps whatever the physics: a
*blow-up*, not hunting and not a derailment. :func:`stable_step` computes the step from
the model's eigenvalues at a speed (the yaw dampers' blow-off stage ``K_d / C_d2``
included, the rate a damper relaxes at once it has blown off) and :func:`check_step`
refuses a larger one with that number.
"""

from __future__ import annotations

import numpy as np

from railhunt.kernel.layout import DamperParam
from railhunt.model import Model
from railhunt.units import ms_to_kmh


def rk4_growth(z: np.ndarray) -> np.ndarray:
    """``|R(z)|`` of classical RK4 (the amplification of one step for ``z = h lambda``)."""
    return np.abs(1.0 + z + z**2 / 2.0 + z**3 / 6.0 + z**4 / 24.0)


def stable_step_for(eigenvalues: np.ndarray) -> float:
    """Largest ``h`` (s) with ``|R(h lambda)| <= 1`` for every damped eigenvalue (1/s).

    Eigenvalues with a real part ``>= 0`` (the physics' own growth, or a rigid-body mode)
    are left out: no step makes them decay. Found on a grid of ``h |lambda|`` in steps of
    0.001 up to 3, to within 0.05 %.
    """
    lam = np.asarray(eigenvalues, dtype=complex).ravel()
    lam = lam[(lam.real < 0.0) & (np.abs(lam) > 0.0)]
    if lam.size == 0:
        return np.inf
    r = np.linspace(0.0, 3.0, 3001)[1:]
    unit = lam / np.abs(lam)
    grow = rk4_growth(r[None, :] * unit[:, None]) > 1.0 + 1e-12
    first = np.where(grow.any(axis=1), grow.argmax(axis=1), r.size - 1)
    limit = r[np.maximum(first - 1, 0)] / np.abs(lam)
    return float(np.min(limit))


def stable_step(model: Model, speed: float) -> float:
    """Largest stable RK4 step (s) for ``model`` at ``speed`` (m/s).

    From the eigenvalues of the Jacobian at the centred state and the yaw dampers'
    second-stage relaxation rate ``K_d / C_d2`` (a real eigenvalue once a damper has
    blown off, which the centred state does not show).
    """
    lam = np.linalg.eigvals(model.jacobian(speed))
    d = model.dpar
    blown = -d[:, DamperParam.K_D] / d[:, DamperParam.C_D2]
    return stable_step_for(np.concatenate([lam, blown.astype(complex)]))


def check_step(model: Model, speed: float, dt: float, name: str = "dt") -> float:
    """Refuse an RK4 step above :func:`stable_step` (``ValueError`` with the number).

    Returns the stable step (s).
    """
    h_max = stable_step(model, speed)
    if dt > h_max:
        lam = np.linalg.eigvals(model.jacobian(speed))
        fastest = float(np.max(np.abs(lam)))
        raise ValueError(
            f"{name} = {dt:g} s is invalid: RK4 blows up above {h_max:.4g} s for this "
            f"vehicle at {ms_to_kmh(speed):g} km/h (fastest eigenvalue |lambda| = "
            f"{fastest:.4g} 1/s, yaw damper blow-off K_d/C_d2 included); give {name} <= "
            f"{h_max:.4g} s or leave it out (automatic step)"
        )
    return h_max
