"""Creepages, creep forces and the wear number of a wheelset at a given state.

The wear number of a wheel is the frictional work per distance rolled in its contact,
``T gamma = |F_x xi_x| + |F_y xi_y|`` (N): the creep forces after saturation times their
creepages (the spin term is left out, as in the usual T-gamma wear index). It is computed
from the kernel's own contact functions (:func:`railhunt.kernel.wheelset.wheel_creep`,
:func:`railhunt.kernel.contact.wheel_geometry`, the wheel loads of
:func:`railhunt.kernel.rhs.wheel_loads`) at the state asked for: no second copy of the
contact equations. With per-point contact mechanics, those of
:func:`railhunt.kernel.point_contact.point_wheel_creep`.
"""

from __future__ import annotations

import math

import numpy as np

from railhunt.kernel.contact import wheel_geometry
from railhunt.kernel.point_contact import point_wheel_creep, uses_per_point
from railhunt.kernel.rhs import wheel_loads
from railhunt.kernel.track import alignment
from railhunt.kernel.wheelset import wheel_creep
from railhunt.model import Model

__all__ = ["wheel_wear_numbers", "wheelset_creep"]


def wheelset_creep(model: Model, speed: float, x: np.ndarray, j: int = 0,
                   route: np.ndarray | None = None, t: float = 0.0) -> np.ndarray:  # fmt: skip
    """Creep forces and creepages of both wheels of wheelset ``j`` at state ``x``.

    Parameters
    ----------
    model : Model
        The vehicle model.
    speed : float
        Forward speed (m/s), > 0.
    x : numpy.ndarray
        State (38 entries).
    j : int
        Wheelset, 0 the leading one.
    route : numpy.ndarray, optional
        The route (a curve's steady route); straight track by default.
    t : float
        Time (s), for a route or track that varies along the line.

    Returns
    -------
    numpy.ndarray, shape (2, 6)
        Per wheel (left, right): ``F_x, F_y`` (N), ``M_z`` (N*m), ``xi_x, xi_y`` (-),
        ``phi`` (1/m).
    """
    v, s = model.args(speed, route=route)
    nq = s.linear.shape[0]
    iy, ip = int(s.wheelsets[j, 0]), int(s.wheelsets[j, 1])
    pos = v * t - s.wheelset_delay[j]
    yr, _ = alignment(pos, s.track, s.track_samples)
    wr = s.wheel_rail[j]
    q_l, q_r, track_rate = wheel_loads(pos, v, wr, s.route)
    if uses_per_point(wr):
        (fxl, fyl, mzl, fxr, fyr, mzr, xl, yl, sl, xr, yr_, sr, *_) = point_wheel_creep(
            x[iy] - yr, x[nq + iy], math.cos(x[ip]), math.sin(x[ip]),
            x[nq + ip] + track_rate, v, wr, q_l, q_r, s.creep_table)
        return np.array([[fxl, fyl, mzl, xl, yl, sl], [fxr, fyr, mzr, xr, yr_, sr]])
    r_l, r_r, d_l, d_r = wheel_geometry(x[iy] - yr, wr)
    out = wheel_creep(r_l, r_r, math.cos(d_l), math.sin(d_l), math.cos(d_r), math.sin(d_r),
                      math.cos(x[ip]), math.sin(x[ip]), x[nq + iy], x[nq + ip] + track_rate, v,
                      wr, q_l, q_r)  # fmt: skip
    fxl, fyl, mzl, fxr, fyr, mzr, xl, yl, sl, xr, yr_, sr = out
    return np.array([[fxl, fyl, mzl, xl, yl, sl], [fxr, fyr, mzr, xr, yr_, sr]])


def wheel_wear_numbers(model: Model, speed: float, x: np.ndarray, j: int = 0,
                       route: np.ndarray | None = None) -> np.ndarray:  # fmt: skip
    """Wear number ``T gamma = |F_x xi_x| + |F_y xi_y|`` (N) of the two wheels (left, right)
    of wheelset ``j`` at state ``x`` (see :func:`wheelset_creep`)."""
    c = wheelset_creep(model, speed, x, j, route)
    return np.abs(c[:, 0] * c[:, 3]) + np.abs(c[:, 1] * c[:, 4])
