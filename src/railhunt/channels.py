"""Derived output channels: wheel/rail forces, wheel loads and body accelerations.

Computed after a run from the stored states through the model's own compiled functions
(:func:`railhunt.kernel.rhs.derived`, which calls the one right-hand side for the
accelerations and the wheelset forces for the guiding forces), so no equation is written
twice.

Channels (SI units)
-------------------
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

import numpy as np

from railhunt.kernel.layout import LAYOUT, SystemArrays
from railhunt.kernel.rhs import derived

_WHEELSETS = tuple(w.replace("wheelset", "w") for w in LAYOUT.wheelsets)  # "w1" ... "w4"
_ACC_NAMES = ("ddy_t1", "ddy_t2", "ddpsi_t1", "ddpsi_t2")
#: Names of the columns of the kernel's ``derived`` array, in order.
_KERNEL_COLUMNS: tuple[str, ...] = (
    tuple(f"SY_{w}" for w in _WHEELSETS)
    + tuple(f"Y_{w}L" for w in _WHEELSETS)
    + tuple(f"Y_{w}R" for w in _WHEELSETS)
    + tuple(f"Q_{w}L" for w in _WHEELSETS)
    + tuple(f"Q_{w}R" for w in _WHEELSETS)
    + _ACC_NAMES
)
#: Names of the derived channels, in the order of :func:`derived_channels`.
CHANNEL_NAMES: tuple[str, ...] = (
    tuple(f"SY_{w}" for w in _WHEELSETS)
    + _ACC_NAMES
    + tuple(f"{kind}_{w}{side}" for kind in ("Y", "Q", "YQ") for w in _WHEELSETS
            for side in "LR")  # fmt: skip
)
#: Unit of each derived channel (by the name's prefix).
CHANNEL_UNITS = {"SY": "N", "ddy": "m/s^2", "ddpsi": "rad/s^2", "Y": "N", "Q": "N", "YQ": "1"}
_ACC = np.array([LAYOUT.dof(n[2:]) for n in _ACC_NAMES])  # "ddy_t1" -> "y_t1"


def derived_channels(
    t: np.ndarray, x: np.ndarray, speed: float, system: SystemArrays
) -> dict[str, np.ndarray]:
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

    Returns
    -------
    dict
        Channel name -> values (see the module docstring for names and units).
    """
    t = np.ascontiguousarray(t, dtype=np.float64)
    x = np.ascontiguousarray(x, dtype=np.float64)
    res = derived(t, x, speed, system, _ACC)
    cols = {name: res[:, k].copy() for k, name in enumerate(_KERNEL_COLUMNS)}
    for w in _WHEELSETS:
        for side in "LR":
            cols[f"YQ_{w}{side}"] = cols[f"Y_{w}{side}"] / cols[f"Q_{w}{side}"]
    return {name: cols[name] for name in CHANNEL_NAMES}
