"""Track input: ideal track, a single lateral alignment defect, sampled irregularities.

Track positions ``s`` (m) are measured along the track from where the leading wheelset
stands at ``t = 0``; wheelset ``j`` is at ``s_j(t) = v*t - offset_j`` with ``offset_j``
its distance behind the leading wheelset, so each wheelset meets a defect in turn.

The compiled right-hand side reads the track from a small array (``code``, then
parameters) and a sample array (:mod:`railhunt.kernel.track`); :func:`encode` builds them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from railhunt.kernel.track import TrackInput


def _check(name: str, value: float, low: float, high: float, unit: str) -> float:
    value = float(value)
    if not (math.isfinite(value) and low <= value <= high):
        raise ValueError(
            f"{name} = {value!r} {unit} is invalid: must be finite and in [{low}, {high}] {unit}"
        )
    return value


@dataclass(frozen=True)
class SingleDefect:
    """A single lateral alignment defect followed by ideal track (the paper's type (b)).

    Parameters
    ----------
    amplitude : float
        Peak lateral displacement of the rails (m), e.g. ``0.005``.
    wavelength : float
        Length of the defect along the track (m).
    start : float
        Track position where the defect begins (m), measured from the leading wheelset's
        position at ``t = 0``.
    shape : {"bump", "sine"}
        ``"bump"``: ``A*(1 - cos(2*pi*x/L))/2``, a smooth one-sided kink (zero slope at
        both ends); ``"sine"``: ``A*sin(2*pi*x/L)``, one full period.
    """

    amplitude: float = 0.008
    wavelength: float = 20.0
    start: float = 1.0
    shape: str = "bump"

    def __post_init__(self) -> None:
        _check("amplitude", self.amplitude, -0.05, 0.05, "m")
        _check("wavelength", self.wavelength, 0.5, 1000.0, "m")
        _check("start", self.start, 0.0, 1e5, "m")
        if self.shape not in ("bump", "sine"):
            raise ValueError(f"shape = {self.shape!r} is invalid: must be 'bump' or 'sine'")

    def end(self) -> float:
        """Track position where the defect ends (m)."""
        return self.start + self.wavelength


#: The wheelsets :class:`InitialDisplacement` displaces by default (1 = leading).
DEFAULT_DISPLACED = (1, 2, 3, 4)


@dataclass(frozen=True)
class InitialDisplacement:
    """Start from a laterally displaced wheelset on ideal track.

    Parameters
    ----------
    amplitude : float
        Initial lateral displacement (m), within ±0.02 m.
    wheelsets : tuple of int
        Which wheelsets (1 = leading) are displaced; by default the first four
        (:data:`DEFAULT_DISPLACED`), which on a vehicle with fewer is all of them. Any other
        number the vehicle does not have is an error when the run starts.
    """

    amplitude: float = 0.003
    wheelsets: tuple[int, ...] = DEFAULT_DISPLACED

    def __post_init__(self) -> None:
        # A start beyond 20 mm is past the flange, next to the 25 mm derailment limit.
        _check("amplitude", self.amplitude, -0.02, 0.02, "m")
        for w in self.wheelsets:
            if isinstance(w, bool) or not isinstance(w, int) or w < 1:
                raise ValueError(f"wheelsets contains {w!r}: wheelsets are numbered from 1")

    def end(self) -> float:
        """Track position where the excitation ends (m): at the start."""
        return 0.0


@dataclass(frozen=True)
class SampledTrack:
    """A lateral alignment sampled on a uniform grid, ideal track outside it.

    Parameters
    ----------
    s0 : float
        Track position of the first sample (m).
    ds : float
        Sample spacing (m).
    alignment : numpy.ndarray
        Lateral rail displacement at each sample (m).
    """

    s0: float
    ds: float
    alignment: np.ndarray

    def end(self) -> float:
        """Track position of the last sample (m)."""
        return self.s0 + self.ds * (len(self.alignment) - 1)


def check_excitation(excitation: object, accepted: tuple[type, ...],
                     name: str = "excitation") -> object:  # fmt: skip
    """Return ``excitation`` if it is None or one of the ``accepted`` types.

    Raises
    ------
    TypeError
        Naming the value and the accepted types, e.g. ``excitation = 'bump' is invalid:
        must be a SingleDefect or SampledTrack (e.g. railhunt.SingleDefect(amplitude=0.008,
        wavelength=20.0)), or None``.
    """
    if excitation is None or isinstance(excitation, accepted):
        return excitation
    names = " or ".join(t.__name__ for t in accepted)
    raise TypeError(f"{name} = {excitation!r} is invalid: must be a {names} (e.g. "
                    "railhunt.SingleDefect(amplitude=0.008, wavelength=20.0)), or None")


def encode(excitation: object) -> tuple[np.ndarray, np.ndarray]:
    """Arrays that describe the track to the compiled right-hand side.

    Returns
    -------
    params : numpy.ndarray
        ``[code, p1, p2, p3]``.
    samples : numpy.ndarray
        Alignment samples (m) for sampled track, else a one-element dummy.
    """
    dummy = np.zeros(1)
    if isinstance(excitation, SingleDefect):
        code = TrackInput.BUMP if excitation.shape == "bump" else TrackInput.SINE
        params = [code, excitation.amplitude, excitation.wavelength, excitation.start]
        return np.array(params, dtype=np.float64), dummy
    if isinstance(excitation, SampledTrack):
        samples = np.ascontiguousarray(excitation.alignment, dtype=np.float64)
        params = [TrackInput.SAMPLED, excitation.s0, excitation.ds, len(samples)]
        return np.array(params, dtype=np.float64), samples
    return np.array([TrackInput.IDEAL, 0.0, 0.0, 0.0], dtype=np.float64), dummy
