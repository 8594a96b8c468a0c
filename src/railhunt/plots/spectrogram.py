"""The STFT amplitude map of a signal with its dominant frequency bands (the paper's Fig. 9a).

The map is drawn with a perceptually uniform colormap (viridis), so that equal steps of
amplitude look equally different, and by default only up to the frequency range the
dominant bands call for (:func:`default_fmax`): a hunting band of a few hertz sampled at
1 kHz would otherwise sit in one pixel row below a 500 Hz axis.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from railhunt.plots.figure import new_figure, save_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from railhunt.analysis.spectrogram import Band, Spectrogram

__all__ = ["DEFAULT_FMAX", "default_fmax", "plot_spectrogram", "spectrogram_figure"]

#: The smallest upper frequency (Hz) of the default view: 0-20 Hz holds the hunting band
#: (a few Hz), the car body's rigid modes (about 1 Hz) and its elastic mode (about 10 Hz).
DEFAULT_FMAX = 20.0
#: Bands weaker than this fraction of the strongest one do not widen the default view.
_BAND_SHARE = 0.1
#: Colour of the dominant-band lines: red reads on viridis' dark blue and on its yellow.
_BAND_COLOUR = "tab:red"


def default_fmax(spec: Spectrogram, bands: list[Band] | None = None) -> float:
    """Upper frequency (Hz) of the default view of ``spec``.

    :data:`DEFAULT_FMAX` (20 Hz), or, when a dominant band at least a tenth as strong as
    the strongest reaches higher, twice that band's upper edge rounded up to 10 Hz; never
    above the Nyquist frequency (the last bin).
    """
    nyquist = float(spec.frequencies[-1])
    top = DEFAULT_FMAX
    bands = [b for b in bands or [] if not b.no_signal]
    if bands:
        strongest = max(b.amplitude for b in bands)
        edges = [b.high for b in bands if b.amplitude >= _BAND_SHARE * strongest]
        if edges and 2.0 * max(edges) > top:
            top = 10.0 * math.ceil(2.0 * max(edges) / 10.0)
    return min(top, nyquist)


def spectrogram_figure(
    spec: Spectrogram,
    title: str = "",
    unit: str = "",
    bands: list[Band] | None = None,
    fmax: float | None = None,
    *,
    full_range: bool = False,
) -> Figure:
    """The figure of :func:`plot_spectrogram`, not saved."""
    if fmax is not None and not (math.isfinite(fmax) and fmax > 0):
        raise ValueError(f"fmax = {fmax!r} Hz is invalid: must be finite and > 0")
    nyquist = float(spec.frequencies[-1])
    if full_range:
        top = nyquist
    elif fmax is not None:
        top = min(float(fmax), nyquist)
    else:
        top = default_fmax(spec, bands)
    fig = new_figure(9.0, 4.8)
    ax = fig.add_subplot(1, 1, 1)
    shown = spec.frequencies <= top + 0.5 * spec.resolution
    amp = spec.amplitude[shown]
    mesh = ax.pcolormesh(spec.times, spec.frequencies[shown], amp, shading="nearest",
                         cmap="viridis", vmin=0.0,
                         vmax=float(np.max(amp)) if amp.size and np.max(amp) > 0 else 1.0)
    fig.colorbar(mesh, ax=ax, label=f"amplitude{f' ({unit})' if unit else ''}")
    heard = [b for b in bands or [] if not b.no_signal]
    for k, b in enumerate(heard):
        ax.plot([b.start, b.end], [b.frequency, b.frequency], color=_BAND_COLOUR, lw=1.6,
                ls="--", label="dominant frequency of each stretch" if k == 0 else None)
    if heard:
        strongest = max(heard, key=lambda b: b.amplitude)
        ax.plot([], [], ls="none", label=f"strongest: {strongest.frequency:.3g} Hz, "
                f"{strongest.start:.3g}-{strongest.end:.3g} s")  # fmt: skip
    elif bands:
        ax.plot([], [], ls="none", label="no signal: the record is constant")
    if bands:
        ax.legend(loc="upper right", fontsize="small", framealpha=0.85)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("frequency (Hz)")
    ax.set_ylim(0.0, top)
    view = "full range" if top >= nyquist else f"0-{top:g} Hz of 0-{nyquist:g} Hz"
    ax.set_title(f"{title or 'short-time Fourier transform'} ({view}; window "
                 f"{spec.window:g} s, bins {spec.resolution:.3g} Hz)", fontsize="medium")
    return fig


def plot_spectrogram(
    spec: Spectrogram, path: str | os.PathLike[str], title: str = "", unit: str = "",
    bands: list[Band] | None = None, fmax: float | None = None, *, full_range: bool = False,
) -> Path:  # fmt: skip
    """Draw the STFT amplitude map (like the paper's Fig. 9(a)) to a file.

    Time (s) against frequency (Hz), the single-sided amplitude (in ``unit``) in viridis,
    each dominant band of ``bands`` as a red dashed line, with a legend naming the
    strongest.

    Parameters
    ----------
    spec : Spectrogram
        Output of :func:`railhunt.analysis.spectrogram.stft`.
    path : str or os.PathLike
        Output file; the format follows the suffix.
    title : str
        Title (default: "short-time Fourier transform"); the view and the resolution are
        added to it.
    unit : str
        Unit of the signal, for the colour bar.
    bands : list of Band, optional
        Output of :func:`railhunt.analysis.spectrogram.dominant_bands`.
    fmax : float, optional
        Upper frequency of the view (Hz). Default: :func:`default_fmax`, 0-20 Hz unless a
        strong band lies higher.
    full_range : bool
        Show every frequency up to the Nyquist frequency (overrides ``fmax``).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(spectrogram_figure(spec, title, unit, bands, fmax,
                                          full_range=full_range), path)  # fmt: skip
