"""What the study commands share (``sweep``, ``stability-map``): the results file and its
``--resume``/``--overwrite``, where the points run (``--workers``/``--scheduler``), their
declared rules, and an interrupted or partly lost study.

Each point of a study is written to the results file as it finishes; after Ctrl-C or a
lost worker the same command with ``--resume`` computes only the missing points.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.options import check_outputs
from railhunt.cli.rules import Excludes, Requires

__all__ = ["STUDY_RULES", "check_study_outputs", "check_workers_option", "optional_out_rules",
           "report_lost", "running_study", "study_options"]  # fmt: skip

Decorator = Callable[[Callable[..., Any]], Callable[..., Any]]

#: The rules of every study command.
STUDY_RULES = (
    Excludes("--resume", "--overwrite", "{a} and {b} exclude each other"),
    Excludes("--scheduler", "--workers",
             "--workers sets the local cluster; a --scheduler cluster has its own"),
)  # fmt: skip


def optional_out_rules() -> tuple[Requires, ...]:
    """The rules of a study whose ``--out`` may be left out: ``--resume`` is about that
    file (``--overwrite`` is also about the study's other output files)."""
    return (Requires("--resume", "--out",
                     "{a} is about the results file: give {b} FILE"),)  # fmt: skip


def check_study_outputs(out: Path | None, resume: bool, overwrite: bool,
                        **files: Path | None) -> None:  # fmt: skip
    """Check a study's results file ``out`` and its other output ``files`` before it starts.

    ``out`` may exist with ``--resume`` (it is continued) or ``--overwrite`` (replaced);
    the other files follow the overwrite policy of :func:`railhunt.cli.options.check_outputs`.
    """
    from railhunt.studies.store import journal_path

    check_outputs(overwrite=overwrite, **files)
    if out is None:
        return
    for option, path in files.items():
        if path is not None and path.resolve() == out.resolve():
            raise CliError(f"--out and --{option} both name {out}: give each its own file")
    exists = out.exists() or journal_path(out).exists()
    if exists and not (resume or overwrite):
        raise CliError(f"--out {out} exists: continue it with --resume, replace it with "
                       "--overwrite, or choose another file")  # fmt: skip
    check_outputs(overwrite=True, out=out)


def study_options(out_required: bool = True,
                  out_help: str = "Results file (.csv, or .parquet with pyarrow).",
                  ) -> Decorator:  # fmt: skip
    """Add ``--out FILE``, ``--resume``, ``--overwrite``, ``--workers N`` and
    ``--scheduler ADDRESS`` (in this order in the help) to a study command.

    The command receives ``out`` (a Path or None), ``resume``, ``overwrite``, ``workers``
    and ``scheduler``; check ``workers`` with :func:`check_workers_option`.
    """

    def decorate(func: Callable[..., Any]) -> Callable[..., Any]:
        func = click.option("--scheduler", metavar="ADDRESS",
                            help="Run on the Dask cluster of this scheduler (e.g. "
                            "tcp://10.0.0.5:8786).")(func)  # fmt: skip
        func = click.option("--workers", type=int, metavar="N",
                            help="Worker processes on this machine [default: all cores; 1: "
                            "no Dask].")(func)  # fmt: skip
        func = click.option("--overwrite", is_flag=True,
                            help="Replace FILE (and any other output file) if it exists.")(func)
        func = click.option("--resume", is_flag=True,
                            help="Continue FILE: compute only its missing points.")(func)
        return click.option("--out", "out", type=click.Path(dir_okay=False, path_type=Path),
                            required=out_required, metavar="FILE", help=out_help)(func)

    return decorate


def check_workers_option(workers: int | None) -> None:
    """``--workers N`` must be in [1, 1024] (or left out: all cores)."""
    if workers is not None and not 1 <= workers <= 1024:
        raise CliError(f"--workers {workers} is invalid: must be in [1, 1024]")


@contextlib.contextmanager
def running_study(out: Path | None, points: str = "points") -> Iterator[None]:
    """Run a study: its input and file errors become one ``railhunt: error:`` line; Ctrl-C
    says how many ``points`` are in ``out`` and how to finish (exit status 130)."""
    from railhunt.studies.store import ResultFileError

    try:
        with user_input():
            yield
    except ResultFileError as exc:
        raise CliError(str(exc)) from None
    except KeyboardInterrupt:
        if out is None:
            click.echo(f"railhunt: interrupted: the finished {points} were not kept (give "
                       "--out FILE to keep them and --resume to finish)", err=True)  # fmt: skip
            raise SystemExit(130) from None
        from railhunt import read_results

        done = len(read_results(out)) if out.exists() else 0
        click.echo(f"railhunt: interrupted: {done} {points} are in {out}; run the same "
                   "command with --resume to finish", err=True)  # fmt: skip
        raise SystemExit(130) from None


def report_lost(result: Any, points: str = "points") -> None:
    """Exit with status 1 when points of the study were lost (they can be resumed)."""
    if result.lost:
        how = ("run the same command with --resume to compute them" if result.path is not None
               else "run the command again")  # fmt: skip
        click.echo(f"railhunt: {result.lost} {points} were lost ({result.lost_reasons[0]}); "
                   f"{how}", err=True)  # fmt: skip
        raise SystemExit(1)
