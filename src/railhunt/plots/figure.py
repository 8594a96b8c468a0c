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


def save_figure(fig: Figure, path: str | os.PathLike[str]) -> Path:
    """Save ``fig`` to ``path`` (format from the suffix) at :data:`DPI`; returns the path."""
    path = Path(path)
    fig.savefig(path, dpi=DPI)
    return path
