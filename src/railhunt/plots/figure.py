"""The figure helpers every plot uses: an Agg-rendered Figure and saving it.

Everything is drawn on :class:`matplotlib.figure.Figure` objects rendered by the Agg
canvas, so no GUI backend (and no global ``pyplot`` state) is ever involved.
"""

from __future__ import annotations

import os
from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

#: Start of the phase-plane window (s), as in the paper's Fig. 6 (after the transient).
PHASE_FROM = 3.0
#: Resolution of saved figures (dots per inch).
DPI = 120


def new_figure(width: float, height: float) -> Figure:
    """A figure of ``width`` x ``height`` inches with constrained layout on the Agg canvas."""
    fig = Figure(figsize=(width, height), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


#: The metadata key that names the program that made a figure, per file format.
_CREATOR_KEY = {"png": "Software", "pdf": "Creator", "svg": "Creator"}


def save_figure(fig: Figure, path: str | os.PathLike[str]) -> Path:
    """Save ``fig`` to ``path`` (format from the suffix) at :data:`DPI`; returns the path.

    A PNG, PDF or SVG file names railhunt and its version in its metadata (PNG
    ``Software``, PDF and SVG ``Creator``), as every JSON and CSV output carries
    ``railhunt_version``.
    """
    import matplotlib

    from railhunt._version import __version__

    path = Path(path)
    key = _CREATOR_KEY.get(path.suffix.lower().lstrip("."))
    creator = f"railhunt {__version__} (matplotlib {matplotlib.__version__})"
    fig.savefig(path, dpi=DPI, metadata={key: creator} if key else None)
    return path
