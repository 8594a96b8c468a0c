"""``railhunt reproduce``: recompute the paper's figures and write a self-contained report."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import CliError
from railhunt.cli.files import OutputPath
from railhunt.cli.options import check_output_folder, overwrite_option
from railhunt.cli.output import show_progress, spinner, stdout_console
from railhunt.cli.rules import Excludes, command
from railhunt.cli.study import (
    CONNECT_RULE,
    check_workers_option,
    connect_timeout_option,
    scheduler_client,
)

RULES = (Excludes("--scheduler", "--workers", "give either {a} or {b}, not both"),
         CONNECT_RULE)


@contextlib.contextmanager
def _dask_client(scheduler: str | None, workers: int | None,
                 connect_timeout: float) -> Iterator[Any]:  # fmt: skip
    """A Dask client: joined to ``scheduler``, or a new local cluster of ``workers`` processes.

    Yields None (everything runs in this process) for ``--workers 1``.
    """
    if scheduler is not None:
        with scheduler_client(scheduler, connect_timeout) as client:
            yield client
        return
    if workers == 1:
        yield None
        return
    from railhunt.studies.execute import check_workers, local_client

    with local_client(check_workers(workers)) as client:
        yield client


@contextlib.contextmanager
def _step_progress() -> Iterator[Callable[[str, str], None] | None]:
    """A rich display with one line per step on stderr (only on a terminal)."""
    if not show_progress():
        yield None
        return
    from rich.console import Console
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    columns = (SpinnerColumn(), TextColumn("{task.description}"), TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True)) as progress:
        tasks: dict[str, Any] = {}

        def update(title: str, state: str) -> None:
            if state == "start":
                tasks[title] = progress.add_task(f"{title}: computing", total=1)
                return
            style = {"ok": "green", "failed": "red"}.get(state, "yellow")
            progress.update(tasks[title], completed=1,
                            description=f"{title}: [{style}]{state}[/{style}]")  # fmt: skip

        yield update


def _announce(quick: bool, client: Any) -> None:
    """Announce a reproduction of more than a minute (measured times, shared by the
    client's workers)."""
    from railhunt.cli.output import announce
    from railhunt.workload import SIMULATED_SECONDS, workload

    n = 1
    if client is not None:
        try:
            n = max(1, len(client.scheduler_info().get("workers", {})))
        except Exception:  # noqa: BLE001 - only for the estimate
            n = 1
    key = "reproduce quick" if quick else "reproduce"
    announce(workload(SIMULATED_SECONDS[key], 1e-3, "the paper's figures, measured",
                      workers=n))  # fmt: skip


def _with_unit(value: object, text: str, unit: str) -> str:
    """A table cell: ``text`` showing ``value``, a number (or a bound such as '< 50') with
    its unit, other text as it is."""
    if value is None:
        return "not available"
    numeric = isinstance(value, int | float) or str(value)[:1] in "<>"
    return f"{text} {unit}" if unit and numeric else text


def _difference_style(agrees: bool | None) -> str:
    return "dim" if agrees is None else ("green" if agrees else "red")


@command("reproduce", rules=RULES,
         short_help="Recompute the paper's Figs. 6-8, 10-13 into an HTML report.")
@click.option("--out", "out_dir", required=True, metavar="DIR",
              type=OutputPath(folder=True),
              help="Folder for report.html, headline.json and the figures (created if "
              "missing; files of an earlier run are replaced only with --overwrite).")
@click.option("--quick", is_flag=True,
              help="Coarser and faster (under a minute): fewer speeds, a smaller F_u family, "
              "fewer sweep points, the stability map without the nonlinear search.")  # fmt: skip
@click.option("--scheduler", metavar="ADDRESS",
              help="Run the parallel parts on this Dask scheduler (e.g. tcp://host:8786) "
              "instead of a local cluster.")  # fmt: skip
@click.option("--workers", type=click.IntRange(min=1, max=256), metavar="N",
              help="Worker processes of the local Dask cluster (default: one per core; 1: "
              "no cluster, everything in this process).")  # fmt: skip
@connect_timeout_option(default=10.0)
@overwrite_option
def reproduce_command(out_dir: Path, quick: bool, scheduler: str | None,
                      workers: int | None, connect_timeout: float,
                      overwrite: bool) -> None:  # fmt: skip
    """Recompute the paper's Figs. 6, 7, 8, 10-13 for its vehicle and compare its numbers.

    \b
    Writes DIR/report.html: one self-contained file (figures embedded, no
    network needed) with a table of the paper's headline numbers beside
    railhunt's and the difference, each figure with the paper's caption, what
    railhunt shows and how it was computed, and the run times. Also writes
    DIR/headline.json (machine readable) and DIR/fig6.png ... fig13.png.
    The full run takes a few minutes on two cores, --quick under one.

    \b
    Beyond the paper (which computes on straight track only), a last section
    maps the linear and nonlinear critical speed of the vehicle in curves of
    2000, 4000 and 8000 m with 150 mm cant and on straight track
    (DIR/stability_map.png and .csv); --quick leaves out the nonlinear one.
    """
    from railhunt.studies.reproduce import OUTPUT_FILES

    check_output_folder("--out", out_dir, OUTPUT_FILES, overwrite)
    check_workers_option(workers)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CliError(f"--out {out_dir}: {exc.strerror or exc}") from None

    from railhunt import Vehicle, reproduce

    vehicle = Vehicle.paper2019()
    with spinner("loading the compiled model"):
        # Compile (or load) numba's cache here, before any worker starts: workers that
        # compile the same cache at once can crash (numba issue #4807).
        from railhunt.studies.sweep import warm_up

        warm_up()
    stack = contextlib.ExitStack()
    with spinner("starting Dask workers"):
        client = stack.enter_context(_dask_client(scheduler, workers, connect_timeout))
    _announce(quick, client)
    with stack, _step_progress() as progress:
        report = reproduce(out_dir, quick=quick, client=client, progress=progress,
                           vehicle=vehicle)  # fmt: skip

    from rich.table import Table

    table = Table(title=f"the paper's headline numbers and railhunt's ({report.vehicle})")
    for head in ("quantity (where)", "paper", "railhunt", "difference"):
        table.add_column(head, justify="left" if head == "quantity (where)" else "right")
    for row in report.headline:
        style = _difference_style(row.agrees)
        table.add_row(f"{row.quantity} ({row.where})",
                      _with_unit(row.paper, row.paper_text, row.unit),
                      _with_unit(row.railhunt, row.railhunt_text, row.unit),
                      f"[{style}]{row.difference}[/{style}]")  # fmt: skip
    out = stdout_console()
    out.print(table)
    for step in report.steps:
        line = f"{step.title}: {step.status} ({step.seconds:.1f} s)"
        if step.status != "ok":
            line += f": {step.message.splitlines()[0] if step.message else ''}"
        out.print(line)
    minutes, seconds = divmod(report.seconds, 60.0)
    out.print(f"total {int(minutes)} min {seconds:.0f} s"
              + (f" on {report.workers} Dask workers" if report.workers else ""))
    out.print(f"wrote {report.html}")
    if report.failed:
        names = ", ".join(s.title for s in report.failed)
        click.echo(f"railhunt: error: {names} failed (see the report)", err=True)
        raise SystemExit(1)

