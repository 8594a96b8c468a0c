"""Imports the modules of :mod:`railhunt.cli` that add commands to ``railhunt``.

One line per topic module, each of which decorates :func:`railhunt.cli.main`.
"""

from __future__ import annotations

from railhunt.cli import (
    bifurcation,  # noqa: F401
    contact,  # noqa: F401
    reproduce,  # noqa: F401
    spectrogram,  # noqa: F401
    studies,  # noqa: F401
    sweep,  # noqa: F401
)
