"""Imports the modules of :mod:`railhunt.cli` that add commands to ``railhunt``.

One line per topic module, each of which decorates :func:`railhunt.cli.main`.
"""

from __future__ import annotations

from railhunt.cli import contact  # noqa: F401
