"""Derived output channels: wheel/rail forces, wheel loads and body accelerations.

Computed after a run from the stored states through the model's own compiled functions
(:func:`railhunt.kernel.rhs.derived`, which calls the one right-hand side for the
accelerations and the wheelset forces for the guiding forces), so no equation is written
twice.

Channels (SI units)
-------------------
Every layout has these for each of its wheelsets (``w1`` ... ``wN``, tags of its
bodies) and its bogie frames (``t1`` ...); the paper's vehicle has four and two.

``SY_w1`` ... ``SY_w4``
    Sum of the guiding forces of wheelset *j*, ΣY (N): the total lateral force the
    wheelset exerts on the track (the "track-shifting force" of EN 14363), + toward +y
    (left). It is minus the lateral force of the rails on the wheelset: creep forces
    after saturation plus the lateral components of the normal loads.
``Y_w1L``, ``Y_w1R`` ... ``Y_w4R``
    Guiding force of each wheel (N): the lateral force of the wheel on its rail, positive
    outward from the track centre (toward the wheel's own flange side), so that a wheel
    pressing its flange against its rail has ``Y > 0``. ``SY_wj = Y_wjL - Y_wjR``.
``Q_w1L`` ... ``Q_w4R``
    Wheel load (N): the static ``N`` on straight track, the quasi-static load with the
    load transfer of the unbalanced lateral acceleration in a curve.
``YQ_w1L`` ... ``YQ_w4R``
    Derailment quotient Y/Q of each wheel (dimensionless).
``ddy_t1``, ``ddy_t2``
    Lateral acceleration of the front and rear bogie frame at its centre (m/s^2).
``ddpsi_t1``, ``ddpsi_t2``
    Yaw acceleration of the bogie frames (rad/s^2); the lateral acceleration of a frame
    above its wheelsets is ``ddy_t +/- l1 * ddpsi_t``.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from railhunt.kernel.layout import LAYOUT, StateLayout, SystemArrays
from railhunt.kernel.rhs import derived

#: Unit of each derived channel (by the name's prefix).
CHANNEL_UNITS = {"SY": "N", "ddy": "m/s^2", "ddpsi": "rad/s^2", "Y": "N", "Q": "N", "YQ": "1"}


def _is_frame(body: object) -> bool:
    kind = getattr(body, "kind", "")
    return kind == "frame" or (not kind and body.name.startswith("bogie"))  # type: ignore[attr-defined]


@lru_cache(maxsize=64)
def _plan(layout: StateLayout) -> tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...],
                                        np.ndarray]:  # fmt: skip
    """Wheelset tags, the kernel's column names, the channel names and the acceleration
    indices of a layout: every wheelset's forces, every bogie frame's accelerations."""
    tags = tuple(b.tag for b in layout.bodies if b.is_wheelset)
    frames = [b for b in layout.bodies if _is_frame(b)]
    acc = tuple(f"dd{c}_{b.tag}" for c in ("y", "psi") for b in frames if c in b.coordinates)
    kernel = (tuple(f"SY_{w}" for w in tags) + tuple(f"Y_{w}L" for w in tags)
              + tuple(f"Y_{w}R" for w in tags) + tuple(f"Q_{w}L" for w in tags)
              + tuple(f"Q_{w}R" for w in tags) + acc)  # fmt: skip
    names = (tuple(f"SY_{w}" for w in tags) + acc
             + tuple(f"{kind}_{w}{side}" for kind in ("Y", "Q", "YQ") for w in tags
                     for side in "LR"))  # fmt: skip
    index = np.array([layout.dof(n.split("_", 1)[0][2:] + "_" + n.split("_", 1)[1])
                      for n in acc], dtype=np.int64)  # "ddy_t1" -> "y_t1"  # fmt: skip
    return tags, kernel, names, index


_WHEELSETS, _KERNEL_COLUMNS, CHANNEL_NAMES, _ACC = _plan(LAYOUT)
_ACC_NAMES = tuple(n for n in CHANNEL_NAMES if n.startswith("dd"))
#: Names of the derived channels of the paper's vehicle, in the order of
#: :func:`derived_channels` (:func:`channel_names` gives them for any layout).



def channel_names(layout: StateLayout = LAYOUT) -> tuple[str, ...]:
    """Names of the derived channels of a layout: ``SY_`` of each wheelset, the bogie
    frames' accelerations ``ddy_``, ``ddpsi_``, then ``Y_``, ``Q_``, ``YQ_`` of each wheel."""
    return _plan(layout)[2]


def derived_channels(
    t: np.ndarray, x: np.ndarray, speed: float, system: SystemArrays,
    layout: StateLayout = LAYOUT, accelerations: bool = True,
) -> dict[str, np.ndarray]:  # fmt: skip
    """Guiding forces, wheel loads and bogie accelerations along a run.

    Parameters
    ----------
    t : numpy.ndarray
        Times (s).
    x : numpy.ndarray
        States, one row per time.
    speed : float
        Forward speed of the run (m/s).
    system : SystemArrays
        The model's arrays with the run's track input (:meth:`railhunt.model.Model.system`).
    layout : StateLayout
        The model's state layout (``model.layout``; default: the paper's vehicle).
    accelerations : bool
        Include the bogie frames' accelerations (``ddy_``, ``ddpsi_``); without them the
        right-hand side is not evaluated, only the wheel/rail forces (about half the cost:
        what the validity limits of a trial run read).

    Returns
    -------
    dict
        Channel name -> values (see the module docstring for names and units).
    """
    tags, kernel, names, acc = _plan(layout)
    t = np.ascontiguousarray(t, dtype=np.float64)
    x = np.ascontiguousarray(x, dtype=np.float64)
    if not accelerations:
        kernel, acc = kernel[:5 * len(tags)], acc[:0]  # the wheel/rail columns only
        names = tuple(n for n in names if not n.startswith("dd"))
    res = derived(t, x, speed, system, acc)
    cols = {name: res[:, k].copy() for k, name in enumerate(kernel)}
    for w in tags:
        for side in "LR":
            cols[f"YQ_{w}{side}"] = cols[f"Y_{w}{side}"] / cols[f"Q_{w}{side}"]
    return {name: cols[name] for name in names}
