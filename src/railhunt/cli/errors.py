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

__all__ = ["DEBUG_ENV", "PROG", "CliError", "flag_names", "no_tracebacks", "one_line_usage_errors",
           "one_line_warnings", "user_input"]

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


#: Unit suffixes the library adds to an argument's name (``start_kmh``) that a flag of the
#: same quantity leaves out (``--start``).
_UNIT_SUFFIXES = ("", "_kmh", "_mm", "_m", "_s", "_hz")


def _flag_names(ctx: click.Context | None) -> dict[str, str]:
    """Library argument names -> the flag of the running command that sets them: a
    flag's destination or its own name, with or without a unit suffix."""
    if ctx is None:
        return {}
    names: dict[str, str] = {}
    for param in ctx.command.params:
        flags = [o for o in getattr(param, "opts", []) if o.startswith("--")]
        if not flags or param.name is None:
            continue
        flag = flags[0]
        for base in {param.name, flag[2:].replace("-", "_")}:
            for suffix in _UNIT_SUFFIXES:
                names.setdefault(base + suffix, flag)
    return names


def flag_names(message: str, ctx: click.Context | None = None) -> str:
    """``message`` with the library's argument names replaced by the flags that set them:
    ``start_kmh = 5.0 km/h is invalid`` becomes ``--start 5.0 km/h is invalid``; a code
    span in backticks is left as it is."""
    import re

    ctx = ctx or click.get_current_context(silent=True)
    names = _flag_names(ctx)
    if not names:
        return message

    def flag(match: re.Match[str]) -> str:
        name, assigned = match.group(1), match.group(2)
        if name not in names or not (assigned or "_" in name):  # prose words stay
            return match.group(0)
        return f"{names[name]} " if assigned else names[name]

    # A name in a code span (`allow = true`) is quoted literally, not an argument.
    return re.sub(r"(?<![\w`-])([a-z][a-z0-9_]*)(?![\w(`])( = )?", flag, message)


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
            raise CliError(flag_names(text)) from None
        click.echo(f"{PROG}: error: unexpected {type(exc).__name__}: {text[:300]} (run again "
                   f"with {DEBUG_ENV}=1 or 'railhunt --debug ...' to see where; please "
                   "report it)", err=True)  # fmt: skip
        raise SystemExit(1) from None


@contextlib.contextmanager
def one_line_warnings() -> Iterator[None]:
    """Python warnings raised while a command runs (a measuring spike in a profile, a free
    wheelset, a warning of a library railhunt uses) are printed as one ``warning: ...``
    line each on stderr: the message on one line, never the source file and line Python's
    own format shows, and a message repeated by a loop only once. The warning filters
    stay as they are (``PYTHONWARNINGS=error`` still turns a warning into an error)."""
    import warnings

    seen: set[str] = set()

    def show(message: Warning | str, category: type[Warning], filename: str, lineno: int,
             file: Any = None, line: str | None = None) -> None:  # fmt: skip
        text = " ".join(str(message).split()) or category.__name__
        if text not in seen:
            seen.add(text)
            click.echo(f"warning: {text}", err=True)

    with warnings.catch_warnings():
        warnings.showwarning = show
        yield


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
        text = flag_names(str(exc))
        if prefix.strip().endswith(":") and text.startswith(prefix.strip()[:-1] + " "):
            prefix = ""  # "--spectrum: --spectrum 'bad' is invalid" says it twice
        raise CliError(f"{prefix}{text}") from None
