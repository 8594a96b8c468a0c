"""Derived output channels: wheel/rail guiding forces and body accelerations.

Computed after a run from the stored states through the model's own compiled functions
(:func:`railhunt.kernel.rhs.derived`, which calls the one right-hand side for the
accelerations and the wheelset forces for ΣY), so no equation is written twice.

Channels (SI units)
-------------------
``SY_w1`` ... ``SY_w4``
    Sum of the guiding forces of wheelset *j*, ΣY = Y_left + Y_right (N): the total
    lateral force the wheelset exerts on the track (the "track-shifting force" of
    EN 14363), + toward +y (left). It is minus the lateral force of the rails on the
    wheelset returned by ``wheelset_forces``: creep forces after saturation plus the
    lateral components of the normal loads (gravitational stiffness).
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

#: Names of the derived channels, in the column order of :func:`derived_channels`.
CHANNEL_NAMES: tuple[str, ...] = (
    "SY_w1", "SY_w2", "SY_w3", "SY_w4", "ddy_t1", "ddy_t2", "ddpsi_t1", "ddpsi_t2",
)  # fmt: skip
#: Unit of each derived channel.
CHANNEL_UNITS = {"SY": "N", "ddy": "m/s^2", "ddpsi": "rad/s^2"}
_ACC = np.array([LAYOUT.dof(n) for n in ("y_t1", "y_t2", "psi_t1", "psi_t2")])


def derived_channels(
    t: np.ndarray, x: np.ndarray, speed: float, system: SystemArrays
) -> dict[str, np.ndarray]:
    """Guiding forces and bogie accelerations along a run.

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
    return {name: res[:, k].copy() for k, name in enumerate(CHANNEL_NAMES)}
