"""The ``railhunt`` command line: the group in app.py, one module per command in commands/,
shared options in options.py, output helpers in output.py, declared option rules in rules.py.
"""

from __future__ import annotations

from railhunt.cli.app import main
from railhunt.cli.errors import CliError

__all__ = ["CliError", "main"]
