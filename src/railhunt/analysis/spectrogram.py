"""Time-frequency analysis of a measured (or simulated) signal, like the paper's Fig. 9(a).

The paper shows the short-time Fourier transform (STFT) of a measured car-body floor
acceleration: a band around 10 Hz present almost all the time (car-body elastic mode),
one around 1 Hz (rigid modes), and a section where the 10 Hz band grows strongly (car
body shaking driven by hunting after the yaw damper blew off). :func:`stft` computes such
a map and :func:`dominant_bands` reads the dominant frequency band off it over time.

Conventions: Hann window of ``window`` seconds, 75 % overlap, mean removed per window,
only windows that lie wholly inside the record (no zero padding at the ends); amplitudes
are single-sided (a sine of amplitude A shows as about A at its frequency). The frequency
resolution is ``1/window`` Hz.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy import signal

#: Names accepted for the time column (before any ``[unit]``), case-insensitive.
TIME_NAMES = ("t", "time")
#: Units accepted for the time column and their factor to seconds; no unit means seconds.
TIME_UNITS = {"": 1.0, "s": 1.0, "sec": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "min": 60.0}
#: A window whose peak amplitude is below this fraction of the record's largest excursion
#: from its mean (or a record without any) holds no signal, only rounding.
SILENCE = 1e-9


def _unit(header: str) -> str:
    text = header.strip()
    if text.endswith("]") and "[" in text:
        return text[text.rindex("[") + 1 : -1].strip()
    return ""


def _base(header: str) -> str:
    text = header.strip()
    if text.endswith("]") and "[" in text:
        text = text[: text.rindex("[")]
    return text.strip()


def read_channel(
    path: str | os.PathLike[str], channel: str
) -> tuple[np.ndarray, np.ndarray, str]:
    """Read the time column and one channel of a CSV file with a header row.

    The time column is called ``t`` or ``time``, in seconds unless a unit suffix says
    otherwise: ``t [s]``, ``t [ms]``, ``t [us]`` or ``t [min]`` are converted to seconds,
    any other unit is refused. A UTF-8 byte-order mark (Excel's "CSV UTF-8") is skipped.
    ``channel`` matches a header exactly or without its ``[unit]`` suffix, so
    ``y_w1`` finds ``y_w1 [m]`` in the CSV files of ``railhunt simulate --csv``.

    Returns
    -------
    t : numpy.ndarray
        Times (s), converted from the column's unit.
    y : numpy.ndarray
        Channel values (the file's unit).
    name : str
        The matched header.
    """
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as fh:
            rows = [r for r in csv.reader(fh) if any(c.strip() for c in r)]
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a text CSV file (byte {exc.start} is not UTF-8 text); "
                         "expected a header row with a time column and the channels, as "
                         "'railhunt simulate --csv' writes") from None
    except csv.Error as exc:
        raise ValueError(f"{path}: not a CSV file ({exc})") from None
    if not rows:
        raise ValueError(f"{path}: the file is empty; expected a header row with a time column")
    header = [h.strip() for h in rows[0]]
    bases = [_base(h) for h in header]
    listing = ", ".join(header)
    time_idx = next((i for i, b in enumerate(bases) if b.lower() in TIME_NAMES), None)
    if time_idx is None:
        raise ValueError(
            f"{path}: no time column (named 't' or 'time', in s); columns are: {listing}"
        )
    time_unit = _unit(header[time_idx])
    if time_unit.lower() not in TIME_UNITS and time_unit not in TIME_UNITS:
        raise ValueError(
            f"{path}: time column {header[time_idx]!r} is in {time_unit!r}; expected seconds "
            f"(or one of: {', '.join(repr(u) for u in TIME_UNITS if u)})"
        )
    to_seconds = TIME_UNITS.get(time_unit, TIME_UNITS.get(time_unit.lower(), 1.0))
    if channel in header:
        idx = header.index(channel)
    elif channel in bases:
        idx = bases.index(channel)
    else:
        raise ValueError(f"{path}: no column {channel!r}; available columns: {listing}")
    if idx == time_idx:
        raise ValueError(f"{path}: --channel {channel!r} is the time column; choose a signal")
    data = np.empty((len(rows) - 1, 2))
    for r, row in enumerate(rows[1:], start=2):
        for c, i in enumerate((time_idx, idx)):
            cell = row[i].strip() if i < len(row) else ""
            try:
                data[r - 2, c] = float(cell)
            except ValueError:
                raise ValueError(
                    f"{path}: line {r}: column {header[i]!r} value {cell!r} is not a number"
                ) from None
    if not np.all(np.isfinite(data)):
        raise ValueError(f"{path}: the time and {header[idx]!r} columns must be finite numbers")
    return data[:, 0] * to_seconds, data[:, 1], header[idx]


def check_uniform(t: np.ndarray, rtol: float = 1e-3) -> float:
    """The sampling step (s) of ``t``; ValueError unless it is uniform within ``rtol``."""
    if t.size < 2:
        raise ValueError(f"the record has {t.size} sample(s): too short for a spectrogram")
    dt = np.diff(t)
    if np.any(dt <= 0):
        k = int(np.argmax(dt <= 0))
        raise ValueError(
            f"time must increase strictly: t = {t[k + 1]:g} s (sample {k + 2}) follows "
            f"t = {t[k]:g} s"
        )
    step = float(np.median(dt))
    dev = np.abs(dt - step)
    if np.max(dev) > rtol * step:
        k = int(np.argmax(dev))
        raise ValueError(
            f"non-uniform sampling: the time step is {step:g} s but {dt[k]:g} s between "
            f"t = {t[k]:g} s and {t[k + 1]:g} s (more than {rtol:.1%} off); resample the "
            "record to a fixed step first"
        )
    return step


@dataclass
class Spectrogram:
    """STFT amplitude map.

    Attributes
    ----------
    times : numpy.ndarray
        Centre time of each window (s), on the record's time axis.
    frequencies : numpy.ndarray
        Frequencies (Hz).
    amplitude : numpy.ndarray
        Single-sided amplitude, shape (frequencies, times), in the signal's unit.
    window : float
        Window length (s); the resolution is ``1/window`` Hz.
    level : float
        Largest excursion of the record from its mean (signal unit); 0 for a constant (or
        all-zero) record, which holds no signal.
    """

    times: np.ndarray
    frequencies: np.ndarray
    amplitude: np.ndarray
    window: float
    level: float = math.inf

    def silent(self) -> np.ndarray:
        """Per window: True where the peak amplitude is only rounding (no signal)."""
        peak = np.max(self.amplitude[1:], axis=0) if self.amplitude.shape[0] > 1 else \
            np.zeros(self.times.size)
        return peak <= SILENCE * self.level

    @property
    def resolution(self) -> float:
        """Frequency bin width (Hz)."""
        return float(self.frequencies[1] - self.frequencies[0])


def stft(t: np.ndarray, y: np.ndarray, window: float = 2.0, overlap: float = 0.75) -> Spectrogram:
    """Short-time Fourier transform of a uniformly sampled record.

    Parameters
    ----------
    t, y : numpy.ndarray
        Times (s) and values.
    window : float
        Window length (s); at least 8 samples, and the record must hold two windows.
    overlap : float
        Fraction of overlap of consecutive windows, in [0, 0.95].
    """
    step = check_uniform(t)
    if not (math.isfinite(window) and window > 0):
        raise ValueError(f"window = {window!r} s is invalid: must be finite and > 0")
    if not (0.0 <= overlap <= 0.95):
        raise ValueError(f"overlap = {overlap!r} is invalid: must be in [0, 0.95]")
    fs = 1.0 / step
    nperseg = int(round(window * fs))
    if nperseg < 8:
        raise ValueError(
            f"window = {window:g} s holds only {nperseg} samples at {fs:g} Hz: "
            "needs at least 8 (make --window longer)"
        )
    duration = t[-1] - t[0] + step
    if y.size < 2 * nperseg:
        raise ValueError(
            f"the record is too short: {y.size} samples ({duration:g} s) but the "
            f"spectrogram needs at least two windows of {window:g} s ({2 * nperseg} "
            "samples); record longer or use a shorter --window"
        )
    noverlap = min(int(round(overlap * nperseg)), nperseg - 1)
    f, tau, z = signal.stft(
        y, fs=fs, window="hann", nperseg=nperseg, noverlap=noverlap, detrend="constant",
        boundary=None, padded=False,
    )  # fmt: skip
    amp = 2.0 * np.abs(z)
    amp[0] *= 0.5
    level = float(np.max(np.abs(y - np.mean(y)))) if y.size else 0.0
    return Spectrogram(times=t[0] + tau, frequencies=f, amplitude=amp, window=nperseg / fs,
                       level=level)


@dataclass
class Band:
    """A stretch of time over which the dominant frequency stays put.

    Attributes
    ----------
    start, end : float
        Centre times (s) of the first and last window of the stretch.
    frequency : float
        Median dominant frequency (Hz); NaN over a stretch without signal (the record is
        constant there, see :attr:`no_signal`).
    low, high : float
        Band around it (Hz): where the amplitude stays above ``1/sqrt(2)`` of the peak
        (half power), widest over the stretch.
    amplitude : float
        Largest peak amplitude over the stretch (signal unit).
    """

    start: float
    end: float
    frequency: float
    low: float
    high: float
    amplitude: float

    @property
    def no_signal(self) -> bool:
        """True over a stretch where the record holds no signal (constant or zero)."""
        return not math.isfinite(self.frequency)


def dominant_frequency_track(
    spec: Spectrogram, fmin: float | None = None, fmax: float | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per window: dominant frequency, half-power band (low, high) and peak amplitude.

    ``fmin`` defaults to the first bin above 0 Hz (the mean is not a vibration), ``fmax``
    to the Nyquist frequency. A window without signal (:meth:`Spectrogram.silent`) has
    NaN frequencies and a zero amplitude: no band dominates where nothing vibrates.
    """
    f = spec.frequencies
    lo_f = f[1] if fmin is None else float(fmin)
    hi_f = f[-1] if fmax is None else float(fmax)
    if not (0 <= lo_f < hi_f):
        raise ValueError(f"frequency range [{lo_f:g}, {hi_f:g}] Hz is invalid: need fmin < fmax")
    sel = np.nonzero((f >= lo_f) & (f <= hi_f))[0]
    if sel.size == 0:
        raise ValueError(
            f"no frequency bin in [{lo_f:g}, {hi_f:g}] Hz (bins every {spec.resolution:g} Hz "
            f"up to {f[-1]:g} Hz)"
        )
    n = spec.times.size
    peak_f, low, high, amp = (np.empty(n) for _ in range(4))
    for k in range(n):
        a = spec.amplitude[sel, k]
        i = int(np.argmax(a))
        half = a[i] / math.sqrt(2.0)
        i0 = i
        while i0 > 0 and a[i0 - 1] >= half:
            i0 -= 1
        i1 = i
        while i1 < a.size - 1 and a[i1 + 1] >= half:
            i1 += 1
        peak_f[k], low[k], high[k], amp[k] = f[sel[i]], f[sel[i0]], f[sel[i1]], a[i]
    quiet = spec.silent()
    peak_f[quiet] = low[quiet] = high[quiet] = np.nan
    amp[quiet] = 0.0
    return peak_f, low, high, amp


def dominant_bands(
    spec: Spectrogram, fmin: float | None = None, fmax: float | None = None
) -> list[Band]:
    """Stretches of time with the same dominant frequency (within one bin).

    A stretch without signal is one band whose :attr:`Band.no_signal` is True."""
    peak_f, low, high, amp = dominant_frequency_track(spec, fmin, fmax)
    res = spec.resolution
    quiet = np.isnan(peak_f)
    bands: list[Band] = []
    start = 0
    for k in range(1, peak_f.size + 1):
        if k < peak_f.size and quiet[k] and quiet[start]:
            continue
        if (k == peak_f.size or quiet[k] != quiet[start]
                or abs(peak_f[k] - np.median(peak_f[start:k])) > res * 1.01):  # fmt: skip
            seg = slice(start, k)
            bands.append(Band(
                start=float(spec.times[start]), end=float(spec.times[k - 1]),
                frequency=float(np.median(peak_f[seg])), low=float(np.min(low[seg])),
                high=float(np.max(high[seg])), amplitude=float(np.max(amp[seg])),
            ))  # fmt: skip
            start = k
    return bands

