"""The hunting mode followed in speed from the pair that crosses at the Hopf point.

Below (and above) the linear critical speed, the mode that goes unstable there is found
at any speed by continuation of its eigenvalue: from the crossing pair at the linear
critical speed, step towards the requested speed and at each step take the oscillatory
eigenvalue nearest (relative to the previous one's magnitude) to the previous step's;
where the nearest two are not clearly apart, the step is halved.

:func:`hunting_mode_at` picks the least damped among the wheelset modes of
:func:`railhunt.analysis.modes.hunting_mode_index` and this continuation. Where the
continuation is itself a wheelset mode (the paper's vehicle at its speeds) the pick is
unchanged; a bogie frame that hunts with its wheelsets moving less than itself (the
Cooperrider bogie) is then no longer passed over for another mode.
"""

from __future__ import annotations

import bisect
import math
import weakref
from dataclasses import dataclass

import numpy as np

from railhunt.analysis.linear import LinearCriticalSpeed, linear_critical_speed
from railhunt.analysis.modes import is_wheelset_mode
from railhunt.model import Model
from railhunt.units import kmh_to_ms

#: Largest continuation step (km/h) and the step below which halving stops (km/h).
MAX_STEP_KMH, MIN_STEP_KMH = 5.0, 0.05
#: The nearest eigenvalue must be this many times nearer than the second nearest.
SEPARATION = 3.0

@dataclass
class _Branch:
    """The crossing pair at the linear critical speed and the points tracked from it."""

    critical_kmh: float
    points: list[tuple[float, complex]]  # (speed km/h, eigenvalue 1/s), sorted by speed


_BRANCHES: weakref.WeakKeyDictionary[Model, _Branch | None] = weakref.WeakKeyDictionary()


def _branch(model: Model) -> _Branch | None:
    """The model's branch, seeded with the linear critical speed's crossing pair."""
    if model not in _BRANCHES:
        seed_crossing(model, linear_critical_speed(model.vehicle, model=model))
    return _BRANCHES[model]


def seed_crossing(model: Model, lin: LinearCriticalSpeed) -> None:
    """Start ``model``'s continuation from ``lin``, its linear critical speed
    (:func:`~railhunt.analysis.linear.linear_critical_speed` of ``model.vehicle`` with
    ``model``'s creep law and contact geometry), when the caller has it already: it is
    not computed again."""
    lam = complex(lin.eigenvalue)
    if not math.isfinite(lin.speed_kmh) or abs(lam.imag) < 1e-6:
        _BRANCHES[model] = None
    else:
        lam = lam if lam.imag > 0 else lam.conjugate()
        _BRANCHES[model] = _Branch(float(lin.speed_kmh), [(float(lin.speed_kmh), lam)])


def _nearest(w: np.ndarray, lam: complex) -> tuple[int, bool]:
    """Index of the oscillatory eigenvalue of ``w`` nearest ``lam`` (relative), and whether
    it is clearly nearer than the next."""
    osc = np.flatnonzero(w.imag > 1e-6)
    d = np.abs(w[osc] - lam) / max(abs(lam), 1.0)
    order = np.argsort(d)
    clear = order.size < 2 or d[order[1]] >= SEPARATION * d[order[0]]
    return int(osc[order[0]]), bool(clear)


def crossing_mode_index(model: Model, speed_kmh: float, w: np.ndarray) -> int | None:
    """Index into ``w`` (the eigenvalues of ``model`` at ``speed_kmh``, km/h) of the
    continuation of the pair that crosses at the linear critical speed, or ``None`` when
    the model has no Hopf point in 20-1000 km/h or no oscillatory eigenvalue."""
    branch = _branch(model)
    if branch is None or not np.any(w.imag > 1e-6):
        return None
    # Start from the tracked point nearest the target among those between the crossing
    # and the target: each of them lies on the path from the crossing.
    lo, hi = sorted((branch.critical_kmh, speed_kmh))
    on_path = [p for p in branch.points if lo <= p[0] <= hi]
    s, lam = min(on_path, key=lambda p: abs(p[0] - speed_kmh))
    step = MAX_STEP_KMH
    while s != speed_kmh:
        nxt = s + math.copysign(min(step, abs(speed_kmh - s)), speed_kmh - s)
        w_next = np.linalg.eigvals(model.jacobian(kmh_to_ms(nxt)))  # no vectors needed
        k, clear = _nearest(w_next, lam)
        if not clear and step > MIN_STEP_KMH:
            step /= 2
            continue
        s, lam = nxt, complex(w_next[k])
        step = min(2 * step, MAX_STEP_KMH)
    if all(p[0] != speed_kmh for p in branch.points):
        bisect.insort(branch.points, (float(speed_kmh), lam), key=lambda p: p[0])
    return _nearest(w, lam)[0]


def hunting_mode_at(model: Model, speed_kmh: float, w: np.ndarray, vecs: np.ndarray) -> int:
    """Index of the hunting mode among the eigenpairs ``(w, vecs)`` of ``model`` at
    ``speed_kmh`` (km/h): the least damped among the wheelset modes
    (:func:`railhunt.analysis.modes.hunting_mode_index`) and the continuation of the
    crossing pair (:func:`crossing_mode_index`)."""
    layout, a = model.layout, model.half_gauge
    osc = np.flatnonzero(w.imag > 1e-6)
    wheelset = {int(k) for k in osc if is_wheelset_mode(vecs[:layout.n_dof, k], a, layout)}
    best = _least_damped(w, osc, wheelset)
    # The continuation can only change the pick when it ends on a mode that is not a
    # wheelset mode and is at least as lightly damped as the best wheelset mode: where
    # no such mode exists (the paper's vehicle), it is not run at all.
    if best < 0 or any(k not in wheelset and w[k].real >= w[best].real for k in osc):
        cont = crossing_mode_index(model, speed_kmh, w)
        best = _least_damped(w, osc, wheelset | ({cont} if cont is not None else set()))
    if best >= 0:
        return best
    return int(osc[np.argmax(w[osc].real)]) if osc.size else 0


def _least_damped(w: np.ndarray, osc: np.ndarray, candidates: set[int]) -> int:
    """Index of the eigenvalue of largest real part among ``candidates`` (first in index
    order on a tie; they must be in ``osc``, the oscillatory ones), or -1 for none."""
    best = -1
    for k in osc:
        if k in candidates and (best < 0 or w[k].real > w[best].real):
            best = int(k)
    return best
