"""Errors of the command line: every user error is one ``railhunt: error: ...`` line.

:class:`CliError` is the one error a command raises for bad input (exit status 2);
:func:`user_input` turns the library's ``ValueError`` and ``OSError`` into one, and
:func:`one_line_usage_errors` does the same for click's own usage errors.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

import click

__all__ = ["DEBUG_ENV", "PROG", "CliError", "no_tracebacks", "one_line_usage_errors",
           "user_input"]

#: Name of the program in messages and usage lines.
PROG = "railhunt"

_NO_ARGS_IS_HELP = getattr(click.exceptions, "NoArgsIsHelpError", ())


class CliError(click.ClickException):
    """A user error: shown as one ``railhunt: error: ...`` line, exit status 2."""

    exit_code = 2

    def __init__(self, message: str) -> None:
        super().__init__(" ".join(str(message).split()))

    def show(self, file: Any = None) -> None:
        """Write the one-line message to stderr (``file`` is ignored)."""
        click.echo(f"{PROG}: error: {self.format_message()}", err=True)


@contextlib.contextmanager
def one_line_usage_errors() -> Iterator[None]:
    """Turn click's multi-line usage errors into a :class:`CliError`."""
    try:
        yield
    except _NO_ARGS_IS_HELP:
        raise
    except click.UsageError as exc:
        message = exc.format_message()
        if exc.ctx is not None:
            message += f" (see '{exc.ctx.command_path} --help')"
        raise CliError(message) from None


#: Set to 1 (or give ``railhunt --debug``) to see the traceback of an unexpected error.
DEBUG_ENV = "RAILHUNT_DEBUG"
#: Where ``--debug`` is kept (``click.Context.meta``).
DEBUG_KEY = "railhunt.debug"


def _debugging(ctx: click.Context | None) -> bool:
    import os

    flag = os.environ.get(DEBUG_ENV, "").strip().lower() not in ("", "0", "no", "false")
    return flag or bool(ctx is not None and ctx.meta.get(DEBUG_KEY))


@contextlib.contextmanager
def no_tracebacks(ctx: click.Context | None = None) -> Iterator[None]:
    """The command line's safety net: no traceback reaches a user.

    An invalid input the command did not catch itself (a library ``ValueError``, a
    ``TypeError`` naming an argument, a curve without a steady state) becomes one
    ``railhunt: error:`` line (exit status 2); any other exception one line naming it, with
    the hint to rerun with ``RAILHUNT_DEBUG=1`` or ``--debug`` for the traceback (exit
    status 1). With either of those the exception propagates unchanged.
    """
    try:
        yield
    except (click.ClickException, click.exceptions.Exit, click.Abort):
        raise
    except Exception as exc:
        if _debugging(ctx):
            raise
        from railhunt.analysis.curving import CurvingError

        text = " ".join(str(exc).split()) or type(exc).__name__
        if isinstance(exc, ValueError | TypeError | CurvingError):
            raise CliError(text) from None
        click.echo(f"{PROG}: error: unexpected {type(exc).__name__}: {text[:300]} (run again "
                   f"with {DEBUG_ENV}=1 or 'railhunt --debug ...' to see where; please "
                   "report it)", err=True)  # fmt: skip
        raise SystemExit(1) from None


@contextlib.contextmanager
def user_input(prefix: str = "") -> Iterator[None]:
    """Report ``ValueError`` (invalid inputs) and ``OSError`` (files) as a :class:`CliError`.

    Parameters
    ----------
    prefix : str
        Put before the message, e.g. ``"--irregularity: "`` or ``"cannot write --csv: "``.
    """
    try:
        yield
    except OSError as exc:
        where = f"{exc.filename}: " if exc.filename else ""
        raise CliError(f"{prefix}{where}{exc.strerror or exc}") from None
    except ValueError as exc:
        raise CliError(f"{prefix}{exc}") from None
