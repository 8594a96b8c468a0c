"""Whether a model is linear, and what that means for limit cycles.

A model is *linear* here when every force law in it is: Kalker's linear creep law on every
wheelset (no saturation), a contact geometry of first degree (conical treads or the
polynomials with only ``lambda1`` and a constant contact angle; no table from profiles), no
stops (no flange, no bump stop) and yaw dampers whose two stages are equal (or none). Its
equations are then linear in the state up to the yaw angle's trigonometry in the
creepages (``cos psi``, ``sin psi``: third order in ``psi``, below 1e-4 relative at 10 mrad).

A linear system has no limit cycles. Below its Hopf speed every motion decays, above it
every motion grows; at the Hopf speed itself it oscillates with any amplitude, neither
growing nor decaying: a vertical family of periodic orbits at one speed, with no fold. A
run of a linear model whose envelope stays still is at (or within the judge's resolution
of) that speed, not on a limit cycle.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from railhunt.kernel.creep import CreepLaw
from railhunt.kernel.layout import WR, DamperParam

__all__ = ["LINEAR_MODEL", "is_linear"]

#: What a linear model's periodic motion is, in words.
LINEAR_MODEL = ("a linear model (linear creep, contact of first degree, no stops, no "
                "blow-off) has no limit cycles: it oscillates with any amplitude only at its "
                "Hopf speed, where its motion neither grows nor decays")  # fmt: skip

_HIGHER = (WR.LAMBDA2, WR.LAMBDA3, WR.LAMBDA4, WR.LAMBDA5, WR.D1, WR.D4, WR.D5)


def is_linear(model: Any) -> bool:
    """Whether every force law of ``model`` (a :class:`railhunt.model.Model`) is linear
    (module docstring)."""
    s = model.system()
    wr = s.wheel_rail
    if np.any(wr[:, WR.CREEP_LAW] != int(CreepLaw.LINEAR)):
        return False
    if wr.shape[1] > WR.TABLE and np.any(wr[:, WR.TABLE] > 1):
        return False
    if np.any(wr[:, list(_HIGHER)] != 0.0):
        return False
    if s.stop.shape[0]:
        return False
    d = s.damper
    return bool(np.all(d[:, DamperParam.C_D1] == d[:, DamperParam.C_D2]))
