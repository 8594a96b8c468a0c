"""Track input seen by the compiled right-hand side: the lateral alignment of the rails.

The track is described by a 4-entry parameter array ``[code, p1, p2, p3]`` and a sample
array (see :class:`TrackInput`); :func:`railhunt.track.encode` builds them from the
excitation objects of the object layer. Positions ``s`` (m) run along the track.
"""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
from numba import njit


class TrackInput(IntEnum):
    """Codes of the track input (slot 0 of the parameter array) and their parameters."""

    IDEAL = 0  # straight, perfectly aligned track
    BUMP = 1  # [1, amplitude (m), wavelength (m), start (m)]: A (1 - cos(2 pi x / L)) / 2
    SINE = 2  # [2, amplitude (m), wavelength (m), start (m)]: A sin(2 pi x / L)
    SAMPLED = 3  # [3, s0 (m), ds (m), n]: samples on a uniform grid, linear in between


@njit(cache=True)
def alignment(s: float, params: np.ndarray, samples: np.ndarray) -> tuple[float, float]:
    """Lateral rail displacement (m) and its slope d/ds (rad) at track position ``s`` (m).

    Zero (ideal track) outside the defect or the sampled stretch.
    """
    code = int(params[0])
    if code == TrackInput.BUMP or code == TrackInput.SINE:
        amp, wl, s0 = params[1], params[2], params[3]
        x = s - s0
        if x <= 0.0 or x >= wl:
            return 0.0, 0.0
        k = 2.0 * math.pi / wl
        if code == TrackInput.BUMP:
            return 0.5 * amp * (1.0 - math.cos(k * x)), 0.5 * amp * k * math.sin(k * x)
        return amp * math.sin(k * x), amp * k * math.cos(k * x)
    if code == TrackInput.SAMPLED:
        s0, ds, n = params[1], params[2], int(params[3])
        pos = (s - s0) / ds
        if pos <= 0.0 or pos >= n - 1:
            return 0.0, 0.0
        i = int(pos)
        w = pos - i
        slope = (samples[i + 1] - samples[i]) / ds
        return samples[i] + w * (samples[i + 1] - samples[i]), slope
    return 0.0, 0.0


@njit(cache=True)
def rail_offsets(t: np.ndarray, v: float, delay: np.ndarray, track: np.ndarray,
                 samples: np.ndarray) -> np.ndarray:  # fmt: skip
    """Lateral alignment of the rails under each wheelset at the times ``t`` (m), wheelset
    ``j`` at the track position ``v t - delay[j]`` (:func:`alignment`)."""
    out = np.empty((t.shape[0], delay.shape[0]))
    for i in range(t.shape[0]):
        for j in range(delay.shape[0]):
            out[i, j] = alignment(v * t[i] - delay[j], track, samples)[0]
    return out
