"""What the commands print: consoles, progress displays, numbers, JSON, shared report lines.

Tables and lines go to stdout through :func:`stdout_console`; progress displays go to
stderr and only on a terminal (never in pipes, logs or tests); ``--json`` output goes
through :func:`json_safe` so that NaN and infinities become ``null``.
"""

from __future__ import annotations

import contextlib
import math
import sys
from collections.abc import Callable, Iterator
from typing import Any

__all__ = [
    "announce",
    "command_record",
    "fmt",
    "json_safe",
    "linear_critical_speed_line",
    "print_warnings",
    "verbose_option",
    "show_progress",
    "spinner",
    "stdout_console",
    "traced",
    "trial_progress",
]


def show_progress() -> bool:
    """Progress displays only when stderr is a terminal (never in pipes, logs or tests)."""
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


@contextlib.contextmanager
def spinner(text: str) -> Iterator[None]:
    """A rich spinner on stderr while a step runs (only on a terminal)."""
    if not show_progress():
        yield
        return
    from rich.console import Console

    with Console(stderr=True).status(text):
        yield


@contextlib.contextmanager
def trial_progress(search: str, count: bool = True) -> Iterator[Callable[[Any], None]]:
    """A callback showing each trial of a critical-speed search (a no-op off a terminal).

    Parameters
    ----------
    search : str
        Name of the search in the display, e.g. ``"critical speed"``.
    count : bool
        Also count the trials.

    Yields
    ------
    callable
        Called with each trial (``speed_kmh``, ``verdict``); with ``None`` it switches the
        display to the linear analysis that follows.
    """
    if not show_progress():
        yield lambda trial: None
        return
    from rich.console import Console
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    columns = (
        SpinnerColumn(),
        TextColumn("{task.description}"),
        *([TextColumn("[dim]{task.completed} trials")] if count else []),
        TimeElapsedColumn(),
    )
    first = "first trial" if count else "first run"
    with Progress(*columns, console=Console(stderr=True), transient=True) as progress:
        task = progress.add_task(f"{search}: {first} ...", total=None)

        def on_trial(trial: Any) -> None:
            if trial is None:
                progress.update(task, description="linear stability analysis ...")
                return
            progress.update(
                task,
                advance=1 if count else 0,
                description=f"{search}: {trial.speed_kmh:g} km/h was {trial.verdict}",
            )

        yield on_trial


def stdout_console() -> Any:
    """A rich console on stdout (no automatic highlighting of numbers)."""
    from rich.console import Console

    return Console(highlight=False)


def fmt(value: float | None, spec: str, unit: str = "") -> str:
    """``value`` formatted with ``spec`` (and ``unit``), or ``n/a`` when None or not finite."""
    if value is None or not math.isfinite(value):
        return "n/a"
    text = format(value, spec)
    return f"{text} {unit}" if unit else text


def json_safe(obj: Any) -> Any:
    """Recursively convert to JSON types, NaN and infinities to ``None``."""
    if isinstance(obj, dict):
        return {str(k): json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_safe(v) for v in obj]
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    if isinstance(obj, int):
        return obj
    try:
        value = float(obj)
    except (TypeError, ValueError):
        return str(obj)
    return value if math.isfinite(value) else None


def traced(data: dict[str, Any], vehicle: Any = None) -> dict[str, Any]:
    """``data`` (a command's JSON object) with the keys that trace it: ``railhunt_version``
    and, with a vehicle, ``vehicle`` and ``vehicle_fingerprint``
    (:func:`railhunt.provenance.provenance`); the keys already there come first."""
    from railhunt.provenance import provenance

    return {**data, **provenance(vehicle)}


def command_record() -> dict[str, Any]:
    """The running command and its options (as parsed), for a file's metadata sidecar."""
    import click

    ctx = click.get_current_context(silent=True)
    if ctx is None:
        return {}
    return {"command": f"railhunt {ctx.info_name}", "options": json_safe(ctx.params)}


#: Where ``--yes`` is kept (``click.Context.meta``).
YES_KEY = "railhunt.yes"


def announce(work: Any, vehicle: Any = None, speed: float | None = None) -> None:
    """Say on stderr, before it starts, that a computation will take more than a minute
    (``work`` is a :class:`railhunt.workload.Workload`; nothing when it is shorter).

    An estimate above :data:`railhunt.workload.CONFIRM_SECONDS` (an hour) is refused
    unless the command was given ``--yes``; with ``vehicle`` and ``speed`` (m/s) the
    refusal names what sets the step (:func:`railhunt.simulation.step_cause`).
    """
    import click

    from railhunt.workload import CONFIRM_SECONDS

    ctx = click.get_current_context(silent=True)
    confirmed = bool(ctx is not None and ctx.meta.get(YES_KEY))
    if work.seconds > CONFIRM_SECONDS and not confirmed:
        from railhunt.cli.errors import CliError

        cause = ""
        if vehicle is not None and speed is not None:
            from railhunt.model import Model
            from railhunt.simulation import step_cause

            cause = f"; {step_cause(Model(vehicle), speed)}"
        raise CliError(f"this would take {work.describe()}{cause}; give --yes to run it "
                       "anyway")  # fmt: skip
    if work.notable:
        click.echo(f"railhunt: note: this will take {work.describe()}", err=True)


def linear_critical_speed_line(linear: Any, curved: bool = False) -> str:
    """The line reporting a :func:`railhunt.linear_critical_speed` result (km/h, Hz);
    ``curved``: of the steady-curving equilibrium rather than centred running."""
    if math.isfinite(getattr(linear, "unstable_from_kmh", math.nan)) or (
            getattr(linear, "crossing", "") == "divergence"):  # fmt: skip
        return f"linear critical speed: {linear.text}"
    if not math.isfinite(linear.speed_kmh) and getattr(linear, "limit_reached", False):
        return (f"linear critical speed: none up to {linear.limit.last_valid_kmh:g} km/h (the "
                "steady-curving equilibrium stays stable up to where the search stopped: "
                f"limit reached, {linear.limit.text})")  # fmt: skip
    if not math.isfinite(linear.speed_kmh):
        state = "the steady-curving equilibrium" if curved else "centred running"
        return f"linear critical speed: none below 1000 km/h ({state} stays stable)"
    mode = "hunting mode" if linear.is_hunting_mode else "not the hunting mode"
    return (
        f"linear critical speed: {linear.speed_kmh:.1f} km/h "
        f"(Hopf point; {mode} at {linear.frequency_hz:.2f} Hz)"
    )


#: ``--verbose``: every trial's warning and every limit each run reached, one line each.
def verbose_option(func: Callable[..., Any]) -> Callable[..., Any]:
    """Add ``--verbose`` (the detail behind the one-line summaries of warnings)."""
    import click

    return click.option(
        "--verbose", "-v", is_flag=True,
        help="Print every trial's warning and every limit each run reached, one line each "
             "(by default one summary line per kind; --json has both).")(func)  # fmt: skip


def print_warnings(console: Any, result: Any, verbose: bool = False) -> None:
    """What a search's answer must be read with, one line per kind: its warnings that are
    not about limits (``warning: ...``), then one line per kind of limit its runs reached
    (:class:`railhunt.validity.LimitSummary.line`: the largest value, where, at which
    speeds, whether it decided anything); with ``verbose`` every detail below them."""
    summaries = list(getattr(result, "limit_summary", []))
    texts = {s.text for s in summaries}
    for warning in getattr(result, "warnings", []):
        if warning not in texts:
            console.print(f"[yellow]warning: {warning}[/yellow]")
    for summary in summaries:
        console.print(f"[yellow]{summary.line}[/yellow]")
    if verbose:
        for line in getattr(result, "details", []):
            console.print(f"  {line}")
