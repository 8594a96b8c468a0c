"""Stochastic lateral track irregularities: published spectra, synthesis, measured files.

The paper's excitation type (c) is "a stochastic (measured) track irregularity". This
module makes one from a published power spectral density (PSD) of the lateral alignment,
or reads a measured one, and returns it as a :class:`railhunt.track.SampledTrack` that
:func:`railhunt.simulate` runs over (each wheelset meets it at its own delay).

Conventions (read these before comparing with other codes)
----------------------------------------------------------
* Spatial angular frequency ``Omega = 2*pi/wavelength`` in **rad/m**.
* **One-sided** PSD ``S(Omega)`` in **m^2/(rad/m)**: the variance of the profile is
  ``sigma^2 = integral_0^inf S(Omega) dOmega``. The spectra below are published in this
  form (German spectra directly in m^2/(rad/m); the FRA spectra in cm^2/(rad/m), converted
  here by 1e-4). To compare with a Welch estimate ``S_f(f)`` in m^2/(cycles/m) (one-sided,
  ``f = 1/wavelength``), use ``S(Omega) = S_f(f) / (2*pi)`` at ``Omega = 2*pi*f``.
* Alignment only. The 17-DOF model has two degrees of freedom per wheelset (lateral and
  yaw) and no wheelset roll, so it has no input for cross level (or vertical profile or
  gauge); those spectra are not generated.

Spectra
-------
German high-speed track spectra (low and high disturbance), the alignment PSD::

    S_a(Omega) = A_a * Omega_c^2 / ((Omega^2 + Omega_r^2) * (Omega^2 + Omega_c^2))

with ``Omega_c = 0.8246 rad/m``, ``Omega_r = 0.0206 rad/m`` and ``A_a = 2.119e-7 m*rad``
(low disturbance) or ``6.125e-7 m*rad`` (high disturbance). They were fitted to
measurements on Deutsche Bahn lines (ORE B176 background) and are reproduced, with these
constants, e.g. in W. Zhai, *Vehicle-Track Coupled Dynamics: Theory and Applications*,
Springer 2020, Sec. 3.2 (German high-speed spectra), and in G. Chen, W. Zhai, "A new
wheel/rail spatially dynamic coupling model and its verification", Vehicle System
Dynamics 41 (2004). (``Omega_s = 0.4380 rad/m`` and ``A_v``, ``A_g`` of the same family
belong to the cross-level, vertical and gauge spectra, not used here.)

US FRA track classes 1 to 6 (Federal Railroad Administration; Fries & Coffey 1977,
Hamid & Yang 1981; in SI as given by V. K. Garg, R. V. Dukkipati, *Dynamics of Railway
Vehicle Systems*, Academic Press 1984, and Zhai 2020, Sec. 3.2), the alignment PSD::

    S_a(Omega) = k * A_a * Omega_c^2 / (Omega^2 * (Omega^2 + Omega_c^2))   [cm^2/(rad/m)]

with ``k = 0.25``, ``Omega_c = 0.8245 rad/m`` and ``A_a`` (cm^2*rad/m) = 3.3634, 1.2107,
0.4128, 0.3027, 0.0762, 0.0339 for classes 1 to 6 (class 6 is the best track). The FRA
spectra are stated for wavelengths of about 1.5 m to 300 m.

Synthesis
---------
Random-phase harmonic superposition on the FFT grid of the record (Shinozuka's method):
``y(x) = sum_k sqrt(2 S(Omega_k) dOmega) cos(Omega_k x + phi_k)`` with
``Omega_k = k * dOmega``, ``dOmega = 2*pi/L``, only for ``Omega_k`` inside the wavelength
band, and independent phases ``phi_k`` uniform in ``[0, 2*pi)`` from a seeded
:class:`numpy.random.Generator`. The profile's variance equals the integral of the target
PSD over the band (to the grid's quadrature), and it is evaluated by one inverse real FFT.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from railhunt.results import Columns, ResultDisplay, Row
from railhunt.track import SampledTrack

#: Default wavelength band (m): EN 13848-1's ranges D1 to D3 (3-25, 25-70, 70-150 m), in
#: which track geometry is measured and assessed.
DEFAULT_BAND = (3.0, 150.0)


@dataclass(frozen=True)
class TrackSpectrum:
    """A published one-sided PSD of lateral alignment.

    Parameters
    ----------
    name : str
        Key in :data:`SPECTRA`.
    family : {"german", "fra"}
        Formula (see the module docstring).
    A_a : float
        Roughness constant in SI: m*rad (German) or m^2*rad/m (FRA, ``k*A_a`` already
        converted from cm^2).
    omega_c, omega_r : float
        Corner frequencies (rad/m); ``omega_r`` is unused by the FRA formula.
    description : str
        Human-readable name and source.
    """

    name: str
    family: str
    A_a: float
    omega_c: float
    omega_r: float = 0.0
    description: str = ""

    def psd(self, omega: np.ndarray | float) -> np.ndarray:
        """One-sided alignment PSD (m^2/(rad/m)) at spatial angular frequency ``omega`` (rad/m)."""
        w2 = np.asarray(omega, dtype=np.float64) ** 2
        wc2 = self.omega_c**2
        with np.errstate(divide="ignore"):
            if self.family == "german":
                return self.A_a * wc2 / ((w2 + self.omega_r**2) * (w2 + wc2))
            return self.A_a * wc2 / (w2 * (w2 + wc2))

    def variance(self, band: tuple[float, float] = DEFAULT_BAND) -> float:
        """Variance (m^2) of the alignment within a wavelength band (m), by quadrature."""
        lo, hi = _check_band(band)
        omega = np.geomspace(2 * math.pi / hi, 2 * math.pi / lo, 20001)
        s = self.psd(omega)
        return float(np.sum(0.5 * (s[1:] + s[:-1]) * np.diff(omega)))


def _german(name: str, a_a: float, level: str) -> TrackSpectrum:
    return TrackSpectrum(
        name, "german", a_a, 0.8246, 0.0206,
        f"German high-speed track spectrum, {level} disturbance, alignment (Zhai 2020, Sec. 3.2)",
    )  # fmt: skip


_FRA_A = {1: 3.3634, 2: 1.2107, 3: 0.4128, 4: 0.3027, 5: 0.0762, 6: 0.0339}  # cm^2*rad/m

#: The available spectra by name.
SPECTRA: dict[str, TrackSpectrum] = {
    "german-low": _german("german-low", 2.119e-7, "low"),
    "german-high": _german("german-high", 6.125e-7, "high"),
    **{
        f"fra-{c}": TrackSpectrum(
            f"fra-{c}", "fra", 0.25 * a * 1e-4, 0.8245, 0.0,
            f"US FRA track class {c}, alignment (Garg & Dukkipati 1984; Zhai 2020, Sec. 3.2)",
        )  # fmt: skip
        for c, a in _FRA_A.items()
    },
}


def track_spectrum(name: str) -> TrackSpectrum:
    """The published spectrum called ``name`` (see :data:`SPECTRA`)."""
    try:
        return SPECTRA[name]
    except (KeyError, TypeError):
        raise ValueError(
            f"spectrum = {name!r} is invalid: must be one of {', '.join(SPECTRA)}"
        ) from None


def _check_band(band: tuple[float, float]) -> tuple[float, float]:
    try:
        lo, hi = (float(b) for b in band)
    except (TypeError, ValueError):
        raise ValueError(
            f"band = {band!r} is invalid: must be two wavelengths (m), shortest first"
        ) from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise ValueError(
            f"band = ({lo!r}, {hi!r}) m is invalid: must be finite wavelengths with "
            "0 < shortest < longest"
        )
    return lo, hi


@dataclass(frozen=True, repr=False)
class TrackIrregularity(ResultDisplay, SampledTrack):
    """A lateral alignment on a uniform grid, usable as excitation (a ``SampledTrack``).

    Attributes
    ----------
    s0, ds : float
        Track position of the first sample and spacing (m).
    alignment : numpy.ndarray
        Lateral rail displacement (m), + left.
    spectrum : str
        Name of the spectrum it was drawn from, or ``"measured"``.
    band : tuple of float
        Wavelength band (m) of the synthesis (NaN for measured tracks).
    seed : int or None
        Seed of the random phases (``None`` for measured tracks or unseeded draws).
    source : str
        Where it came from (spectrum description or file name).
    """

    spectrum: str = "measured"
    band: tuple[float, float] = (math.nan, math.nan)
    seed: int | None = None
    source: str = field(default="", compare=False)

    @property
    def distance(self) -> np.ndarray:
        """Track position of each sample (m)."""
        return self.s0 + self.ds * np.arange(len(self.alignment))

    @property
    def length(self) -> float:
        """Length of the irregular section (m)."""
        return self.ds * (len(self.alignment) - 1)

    @property
    def rms(self) -> float:
        """Root mean square of the alignment (m)."""
        return float(np.sqrt(np.mean(np.square(self.alignment))))

    def _summary(self) -> list[Row]:
        return [("spectrum", self.spectrum, ""), ("source", self.source or "-", ""),
                ("seed", self.seed, ""), ("starts at", self.s0, "m"),
                ("length", self.length, "m"), ("spacing", self.ds, "m"),
                ("rms alignment", self.rms, "m"),
                ("largest |alignment|", float(np.max(np.abs(self.alignment))), "m")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row per sample: track position and lateral alignment."""
        return {"distance": (self.distance, "m"), "alignment": (self.alignment, "m")}


def _taper(n: int, ds: float, taper: float) -> np.ndarray:
    """Raised-cosine fade-in and fade-out over ``taper`` metres (1 inside)."""
    w = np.ones(n)
    m = min(int(round(taper / ds)), n // 2)
    if m > 0:
        ramp = 0.5 * (1.0 - np.cos(np.pi * np.arange(m) / m))
        w[:m] = ramp
        w[n - m:] = ramp[::-1]
    return w


def track_irregularity(
    spectrum: str = "german-low",
    length: float = 2000.0,
    dx: float = 0.25,
    seed: int | np.random.Generator | None = None,
    band: tuple[float, float] = DEFAULT_BAND,
    taper: float = 20.0,
    start: float = 0.0,
    scale: float = 1.0,
) -> TrackIrregularity:
    """A random lateral alignment whose PSD follows a published track spectrum.

    Parameters
    ----------
    spectrum : str
        Name of the spectrum: ``"german-low"``, ``"german-high"`` or ``"fra-1"`` ...
        ``"fra-6"`` (formulas, constants and sources in the module docstring).
    length : float
        Length of the irregular track (m), in [10, 1e5]; at least the longest wavelength.
    dx : float
        Sample spacing (m), in (0, 1]; at most a quarter of the shortest wavelength.
    seed : int or numpy.random.Generator, optional
        Seed of the random phases: the same seed gives the same track.
    band : tuple of float
        Shortest and longest wavelength (m) kept; default 3-150 m (EN 13848-1 D1-D3).
    taper : float
        Length (m) of the raised-cosine fade-in and fade-out at both ends, so that the
        vehicle enters and leaves the irregularity smoothly; 0 for none.
    start : float
        Track position of the first sample (m), measured like every track position from
        the leading wheelset's position at ``t = 0``.
    scale : float
        Factor on the amplitudes (1 = the published spectrum; 2 = four times its PSD).

    Returns
    -------
    TrackIrregularity
        Alignment samples in m; pass it as ``excitation`` to :func:`railhunt.simulate`.
    """
    spec = track_spectrum(spectrum)
    lo, hi = _check_band(band)
    length = float(length)
    dx = float(dx)
    if not (math.isfinite(length) and 10.0 <= length <= 1e5):
        raise ValueError(f"length = {length!r} m is invalid: must be finite and in [10, 1e5] m")
    if not (math.isfinite(dx) and 0.0 < dx <= 1.0):
        raise ValueError(f"dx = {dx!r} m is invalid: must be finite and in (0, 1] m")
    if dx > lo / 4:
        raise ValueError(
            f"dx = {dx!r} m is invalid: must be at most a quarter of the shortest "
            f"wavelength ({lo:g} m / 4 = {lo / 4:g} m)"
        )
    if length < hi:
        raise ValueError(
            f"length = {length:g} m is invalid: must be at least the longest wavelength "
            f"of the band ({hi:g} m)"
        )
    for name, value, low, high in (("taper", taper, 0.0, length / 2), ("start", start, 0.0, 1e5),
                                   ("scale", scale, 0.0, 100.0)):  # fmt: skip
        if not (math.isfinite(value) and low <= value <= high):
            raise ValueError(
                f"{name} = {value!r} is invalid: must be finite and in [{low:g}, {high:g}]"
            )
    if not (seed is None or isinstance(seed, np.random.Generator)
            or (isinstance(seed, int | np.integer) and not isinstance(seed, bool)
                and seed >= 0)):  # fmt: skip
        raise ValueError(f"seed = {seed!r} is invalid: must be an integer >= 0, a "
                         "numpy.random.Generator or None")  # fmt: skip
    n = int(round(length / dx)) + 1
    n_fft = n - 1  # the record is one period of the FFT grid, plus its closing sample
    d_omega = 2.0 * math.pi / (n_fft * dx)
    k = np.arange(n_fft // 2 + 1)
    omega = k * d_omega
    inside = (omega >= 2 * math.pi / hi) & (omega <= 2 * math.pi / lo) & (k < n_fft / 2)
    amp = np.zeros(k.size)
    amp[inside] = np.sqrt(2.0 * spec.psd(omega[inside]) * d_omega) * float(scale)
    rng = np.random.default_rng(seed)
    phase = rng.uniform(0.0, 2.0 * math.pi, k.size)
    coeff = 0.5 * n_fft * amp * np.exp(1j * phase)
    y = np.fft.irfft(coeff, n=n_fft)
    y = np.append(y, y[0]) * _taper(n, dx, float(taper))
    seed_value = seed if isinstance(seed, int | np.integer) else None
    return TrackIrregularity(
        s0=float(start), ds=dx, alignment=y, spectrum=spec.name, band=(lo, hi),
        seed=None if seed_value is None else int(seed_value), source=spec.description,
    )  # fmt: skip


_LENGTH_UNITS = {"m": 1.0, "mm": 1e-3}


def _split_unit(header: str) -> tuple[str, str | None]:
    """``"alignment [mm]"`` -> ``("alignment", "mm")``; ``"alignment"`` -> (…, None)."""
    text = header.strip()
    if text.endswith("]") and "[" in text:
        name, _, unit = text[:-1].rpartition("[")
        return name.strip(), unit.strip()
    return text, None


def load_irregularity(
    path: str | os.PathLike[str],
    dx: float | None = None,
    start: float | None = 0.0,
    taper: float = 0.0,
) -> TrackIrregularity:
    """Read a measured lateral alignment from a CSV file.

    The file has a header row with a ``distance`` column and an ``alignment`` column
    (other columns are ignored). A unit in brackets is honoured: ``[m]`` (default) or
    ``[mm]``, e.g. ``distance [m],alignment [mm]``. Distances must increase strictly.
    The record is resampled linearly onto a uniform grid (spacing ``dx``, default the
    median spacing of the file).

    Parameters
    ----------
    path : path-like
        CSV file.
    dx : float, optional
        Grid spacing (m) of the returned track.
    start : float or None
        Track position (m) of the first sample (the file's distances are shifted); 0 by
        default, so the leading wheelset starts at the beginning of the record. ``None``
        keeps the file's distances (ideal track before the first one).
    taper : float
        Length (m) of a raised-cosine fade-in and fade-out at both ends (0: the record
        as measured; the vehicle then meets the first value as a step).

    Returns
    -------
    TrackIrregularity
        With ``spectrum = "measured"``.
    """
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as fh:
            rows = list(csv.reader(fh))
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a text CSV file (byte {exc.start} is not UTF-8 text); "
                         "expected a header 'distance,alignment' and one row per track "
                         "position") from None  # fmt: skip
    except csv.Error as exc:
        raise ValueError(f"{path}: not a CSV file ({exc})") from None
    rows = [r for r in rows if any(cell.strip() for cell in r)]
    if not rows:
        raise ValueError(f"{path}: the file is empty; expected a header 'distance,alignment'")
    header = [_split_unit(h) for h in rows[0]]
    names = [h[0].lower() for h in header]
    cols: dict[str, int] = {}
    for want in ("distance", "alignment"):
        if want not in names:
            raise ValueError(
                f"{path}: no {want!r} column; columns are: {', '.join(rows[0])} "
                "(expected 'distance' and 'alignment', units [m] or [mm])"
            )
        cols[want] = names.index(want)
    factors = {}
    for want, i in cols.items():
        unit = header[i][1] or "m"
        if unit not in _LENGTH_UNITS:
            raise ValueError(f"{path}: column {rows[0][i]!r} has unit {unit!r}; use [m] or [mm]")
        factors[want] = _LENGTH_UNITS[unit]
    data = np.empty((len(rows) - 1, 2))
    for r, row in enumerate(rows[1:], start=2):
        for c, want in enumerate(("distance", "alignment")):
            try:
                data[r - 2, c] = float(row[cols[want]]) * factors[want]
            except (IndexError, ValueError):
                cell = row[cols[want]] if cols[want] < len(row) else ""
                raise ValueError(
                    f"{path}: line {r}: {want} {cell!r} is not a number"
                ) from None
    if data.shape[0] < 2:
        raise ValueError(f"{path}: at least 2 data rows are needed, found {data.shape[0]}")
    if not np.all(np.isfinite(data)):
        raise ValueError(f"{path}: distances and alignments must be finite numbers")
    s, y = data[:, 0], data[:, 1]
    steps = np.diff(s)
    if np.any(steps <= 0):
        bad = int(np.argmax(steps <= 0)) + 3
        raise ValueError(f"{path}: line {bad}: distances must increase strictly")
    if np.max(np.abs(y)) > 0.05:
        raise ValueError(
            f"{path}: alignment reaches {np.max(np.abs(y)):.4g} m; lateral irregularities "
            "must be within ±0.05 m (give the unit in the header, e.g. 'alignment [mm]')"
        )
    step = float(np.median(steps)) if dx is None else float(dx)
    if not (math.isfinite(step) and 0.0 < step <= 10.0):
        raise ValueError(f"dx = {step!r} m is invalid: must be finite and in (0, 10] m")
    n = int(math.floor((s[-1] - s[0]) / step + 1e-9)) + 1
    grid = s[0] + step * np.arange(n)
    s0 = float(s[0]) if start is None else float(start)
    if not (math.isfinite(s0) and 0.0 <= s0 <= 1e5):
        raise ValueError(f"start = {s0!r} m is invalid: must be finite and in [0, 1e5] m")
    length = step * (n - 1)
    if not (math.isfinite(taper) and 0.0 <= taper <= length / 2):
        raise ValueError(
            f"taper = {taper!r} m is invalid: must be finite and in [0, {length / 2:g}] m "
            "(half the record)"
        )
    return TrackIrregularity(
        s0=s0, ds=step, alignment=np.interp(grid, s, y) * _taper(n, step, float(taper)),
        spectrum="measured", source=str(path),
    )  # fmt: skip
