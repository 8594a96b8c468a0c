"""Modes of the linearised vehicle: eigenpairs and which of them is the hunting mode.

The *hunting mode* is the least-damped oscillatory mode whose largest lateral
displacement (yaw angles scaled by the half gauge) is a wheelset's; modes are followed
from speed to speed by the modal assurance criterion of their shapes.
"""

from __future__ import annotations

import math

import numpy as np

from railhunt.kernel.layout import LAYOUT, StateLayout
from railhunt.model import Model


def sorted_eig(jac: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues and eigenvectors of ``jac``, sorted by decreasing real part."""
    w, vecs = np.linalg.eig(jac)
    order = np.argsort(-w.real)
    return w[order], vecs[:, order]


def eigenvalues(model: Model, speed: float) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues and eigenvectors of the Jacobian at the centred state (speed in m/s)."""
    return sorted_eig(model.jacobian(speed))


def hunting_mode_index(w: np.ndarray, vecs: np.ndarray, a: float,
                       layout: StateLayout = LAYOUT) -> int:  # fmt: skip
    """Index of the hunting mode among eigenpairs ``(w, vecs)``.

    Among the oscillatory modes (Im > 0) whose largest lateral displacement amplitude
    (yaw angles scaled by the half gauge ``a``) belongs to a wheelset, the least damped
    (largest real part). Falls back to the least-damped oscillatory mode. ``layout`` is
    the model's state layout (default: the paper's vehicle).
    """
    best, best_any = -1, -1
    for k in range(w.size):
        if w[k].imag <= 1e-6:
            continue
        if best_any < 0 or w[k].real > w[best_any].real:
            best_any = k
        better = best < 0 or w[k].real > w[best].real
        if better and is_wheelset_mode(vecs[:layout.n_dof, k], a, layout):
            best = k
    return best if best >= 0 else best_any


def is_wheelset_mode(q: np.ndarray, a: float, layout: StateLayout = LAYOUT) -> bool:
    """True when the largest lateral amplitude of mode shape ``q`` (coordinates) is a wheelset's."""
    lateral = np.abs(q[layout.body_y])
    wheel = np.concatenate([np.abs(q[layout.wheelset_y]), a * np.abs(q[layout.wheelset_psi])])
    return bool(wheel.max() >= lateral.max(initial=0.0))


def moves_the_wheelsets(q: np.ndarray, a: float, layout: StateLayout = LAYOUT,
                        share: float = 0.5) -> bool:  # fmt: skip
    """True when mode shape ``q`` moves a wheelset (lateral, or yaw times ``a``) at least
    ``share`` times as much as the body that moves most laterally: the test of whether the
    pair crossing at a Hopf point is a hunting instability. Looser than the per-speed
    pick (:func:`hunting_mode_index`, a wheelset must move most): a bogie frame held
    stiffly on its wheelsets (the Cooperrider bogie: frame 1.0, wheelsets 0.9) hunts with
    them."""
    lateral = np.abs(q[layout.body_y])
    wheel = np.concatenate([np.abs(q[layout.wheelset_y]), a * np.abs(q[layout.wheelset_psi])])
    return bool(wheel.max() >= share * lateral.max(initial=0.0))


def mac(p: np.ndarray, q: np.ndarray) -> float:
    """Modal assurance criterion of two complex mode shapes (0..1)."""
    den = np.vdot(p, p).real * np.vdot(q, q).real
    return float(abs(np.vdot(p, q)) ** 2 / den) if den > 0 else 0.0


def least_damped_rate(model: Model, speed: float, state: np.ndarray | None = None,
                      route: np.ndarray | None = None) -> tuple[float, float]:  # fmt: skip
    """Real parts (1/s) of the least damped oscillatory eigenvalue (NaN if none oscillates)
    and of the least damped eigenvalue of all, of the model linearised at ``state``
    (default the centred state) at ``speed`` (m/s)."""
    if state is None:
        w = model.centred_eigenvalues(speed)
    else:
        w = np.linalg.eigvals(model.jacobian(speed, state, route=route))
    osc = w[w.imag > 1e-6]
    return (float(np.max(osc.real)) if osc.size else math.nan), float(np.max(w.real))
