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
from railhunt.cli.files import OutputPath
from railhunt.cli.options import check_outputs
from railhunt.cli.output import announce
from railhunt.cli.rules import Excludes, Requires

__all__ = ["CONNECT_RULE", "OUTPUT_SECONDS", "STUDY_RULES", "connect_timeout_option",
           "scheduler_client", "announce_study", "check_study_outputs",
           "check_workers_option", "optional_out_rules", "report_lost", "running_study",
           "study_options", "study_run"]  # fmt: skip

Decorator = Callable[[Callable[..., Any]], Callable[..., Any]]

#: The rule of ``--connect-timeout``: it is about ``--scheduler``.
CONNECT_RULE = Requires("--connect-timeout", "--scheduler",
                        "{a} is how long to try to reach {b}: give {b} ADDRESS")

#: The rules of every study command.
STUDY_RULES = (
    Excludes("--resume", "--overwrite", "{a} and {b} exclude each other"),
    Excludes("--scheduler", "--workers",
             "--workers sets the local cluster; a --scheduler cluster has its own"),
    CONNECT_RULE,
)  # fmt: skip


#: Where ``--wait-for-workers`` is kept between parsing and :func:`scheduler_client`.
_WAIT_KEY = "railhunt.wait_for_workers"


def _keep_wait(ctx: click.Context, param: click.Parameter, value: bool) -> bool:
    ctx.meta[_WAIT_KEY] = value
    return value


def connect_timeout_option(default: float = 30.0) -> Decorator:
    """``--connect-timeout S``: how long to try to reach ``--scheduler``, in (0, 3600] s;
    with it ``--wait-for-workers`` (read by :func:`scheduler_client`, not passed on)."""
    from railhunt.cli.options import number_range

    timeout = click.option("--connect-timeout", "connect_timeout", type=float,
                           default=default, show_default=True, metavar="S",
                           callback=number_range("s", 0.0, 3600.0),
                           help="How long to try to reach --scheduler and read its "
                           "handshake (s); a refused port fails at once.")  # fmt: skip
    wait = click.option("--wait-for-workers", is_flag=True, expose_value=False,
                        callback=_keep_wait,
                        help="Wait for the --scheduler's first worker as long as it takes "
                        "(without it, a scheduler with no workers is an error after "
                        "5 s).")  # fmt: skip

    def decorate(func: Callable[..., Any]) -> Callable[..., Any]:
        return timeout(wait(func))

    return decorate


@contextlib.contextmanager
def scheduler_client(scheduler: str | None, connect_timeout: float) -> Iterator[Any]:
    """A Dask client joined to ``--scheduler`` (None without one), closed on exit; a
    scheduler that cannot be joined is one ``railhunt: error:`` line naming it."""
    ctx = click.get_current_context(silent=True)
    wait = bool(ctx.meta.get(_WAIT_KEY)) if ctx is not None else False
    if scheduler is None:
        if wait:
            raise CliError("--wait-for-workers is about --scheduler: give --scheduler ADDRESS")
        yield None
        return
    from railhunt.studies.execute import SchedulerError, join_scheduler

    if wait:
        click.echo(f"railhunt: waiting for the first worker of {scheduler} (Ctrl-C to stop)",
                   err=True)  # fmt: skip
    try:
        client = join_scheduler(scheduler, connect_timeout, wait_for_workers=wait)
    except SchedulerError as exc:
        raise CliError(f"--scheduler {scheduler}: {exc}") from None
    try:
        yield client
    finally:
        try:
            client.close()
        except Exception:  # noqa: BLE001 - shutting down; nothing left to save
            pass


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
    The study's description ``FILE.sweep.json`` (and a Parquet file's journal) go with
    ``out``: one left from an earlier run counts as ``out`` existing.
    """
    from railhunt.studies.store import journal_path
    from railhunt.studies.store import sidecar_path as study_sidecar

    check_outputs(overwrite=overwrite, **files)
    if out is None:
        return
    for option, path in files.items():
        if path is not None and path.resolve() == out.resolve():
            raise CliError(f"--out and --{option} both name {out}: give each its own file")
    companions = [p for p in (journal_path(out), study_sidecar(out)) if p != out]
    for option, path in files.items():
        if path is not None and path.resolve() in [p.resolve() for p in companions]:
            raise CliError(f"--{option} {path} is the study file of --out {out}: choose "
                           "another file")  # fmt: skip
    if not (resume or overwrite):
        if out.exists():
            raise CliError(f"--out {out} exists: continue it with --resume, replace it with "
                           "--overwrite, or choose another file")  # fmt: skip
        left = [p for p in companions if p.exists()]
        if left:
            raise CliError(f"--out {out}: {left[0]} of an earlier study exists: continue it "
                           "with --resume, replace it with --overwrite, or choose another "
                           "file")  # fmt: skip
    check_outputs(overwrite=True, out=out, **{f"out {out}: its study file": companions[-1]})


#: Where ``--task-seconds`` is kept between parsing and :func:`study_run`.
_TASK_KEY = "railhunt.task_seconds"


def _keep_task_seconds(ctx: click.Context, param: click.Parameter,
                       value: float | None) -> float | None:  # fmt: skip
    if value is not None:
        from railhunt.cli.options import number_range

        value = number_range("s", 0.0, 3600.0)(ctx, param, value)
    ctx.meta[_TASK_KEY] = value
    return value


def study_run(out: Path | None, resume: bool, overwrite: bool, workers: int | None,
              client: Any, progress: bool | None = None) -> Any:  # fmt: skip
    """The :class:`railhunt.StudyOptions` of a study command's shared flags
    (:func:`study_options`): the results file, ``--resume``/``--overwrite``, the local
    workers or the joined ``--scheduler``'s client, ``--task-seconds``, and a progress bar
    on a terminal (``progress`` None: :func:`railhunt.cli.output.show_progress`)."""
    from railhunt.cli.output import show_progress
    from railhunt.studies.options import TASK_SECONDS, StudyOptions

    ctx = click.get_current_context(silent=True)
    task = ctx.meta.get(_TASK_KEY) if ctx is not None else None
    with user_input():
        return StudyOptions(out=out, resume=resume, overwrite=overwrite, client=client,
                            workers=None if client is not None else workers,
                            progress=show_progress() if progress is None else progress,
                            task_seconds=TASK_SECONDS if task is None else task)  # fmt: skip


def study_options(out_required: bool = True,
                  out_help: str = "Results file (.csv, or .parquet with pyarrow).",
                  ) -> Decorator:  # fmt: skip
    """Add ``--out FILE``, ``--resume``, ``--overwrite``, ``--workers N``, ``--scheduler
    ADDRESS``, ``--connect-timeout S``, ``--wait-for-workers`` and ``--task-seconds S`` (in
    this order in the help) to a study command: the one set of flags of every study.

    The command receives ``out`` (a Path or None), ``resume``, ``overwrite``, ``workers``,
    ``scheduler`` and ``connect_timeout``; check ``workers`` with
    :func:`check_workers_option`, join the scheduler with :func:`scheduler_client`, and
    make the study's :class:`railhunt.StudyOptions` with :func:`study_run`.
    """

    def decorate(func: Callable[..., Any]) -> Callable[..., Any]:
        func = click.option("--task-seconds", type=float, metavar="S", expose_value=False,
                            callback=_keep_task_seconds,
                            help="Work per task (s): points are grouped into tasks of about "
                            "this much evaluation time, measured on the first points; each "
                            "task's rows are written to FILE at once [default: 0.5].")(func)
        func = connect_timeout_option()(func)
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
        return click.option("--out", "out", type=OutputPath(),
                            required=out_required, metavar="FILE", help=out_help)(func)

    return decorate


#: The parameters that set the automatic step (the yaw dampers' relaxation rates).
STEP_PARAMETERS = frozenset({"C_d1", "C_d2", "K_d"})

#: Simulated time (s) of one point per study output: the nonlinear critical-speed search
#: (~8 trials), the hunting-frequency run and shooting, the fold speed's continuation; the
#: linear and curving outputs cost no steps (fitted with ``benchmarks/workload.py``, see
#: :mod:`railhunt.workload`).
OUTPUT_SECONDS = {"critical_speed": 120.0, "hunting_frequency": 16.0,
                  # the fold: ~80 orbits of ~1.2 shooting Jacobians (40 half-period flows)
                  "fold_speed": 450.0}


#: Points of a study whose own step is computed for its estimate (evenly spread over the
#: study; the others are counted at the mean rate of these).
STEP_SAMPLE = 64


def announce_study(vehicle: Any, points: list[Any], outputs: tuple[str, ...],
                   workers: int | None, scheduler: str | None,
                   what: str = "points") -> None:  # fmt: skip
    """Announce a study of more than a minute before it starts (:mod:`railhunt.workload`).

    Each point runs at its own automatic step, so the steps are counted point by point
    (at most :data:`STEP_SAMPLE` of them, evenly spread, stand for the others) when the
    study varies a parameter that sets the step; a point whose step is refused (a stiff
    damper) is left out: it fails alone, with the reason in its row.
    """
    from railhunt import Model
    from railhunt.simulation import StiffDamperError, auto_step
    from railhunt.studies.execute import check_workers
    from railhunt.units import kmh_to_ms
    from railhunt.workload import workload

    per_point = sum(OUTPUT_SECONDS.get(o, 0.0) for o in outputs)
    if not points or per_point == 0.0:
        return
    varied = any(n in STEP_PARAMETERS for p in points for n in p.values)
    chosen = points[:: max(1, len(points) // STEP_SAMPLE)][:STEP_SAMPLE] if varied else []
    rates, stiffest = [], (0.0, vehicle)
    for values in [{}] + [p.values for p in chosen]:
        try:
            v = vehicle.replace(**values)
            rates.append(1.0 / auto_step(Model(v), kmh_to_ms(300.0)))
        except (StiffDamperError, ValueError):
            continue
        stiffest = max(stiffest, (rates[-1], v), key=lambda r: r[0])
    if not rates:
        return
    rate = sum(rates[1:]) / len(rates[1:]) if len(rates) > 1 else rates[0]
    n = 1 if scheduler is not None else check_workers(workers)
    announce(workload(len(points) * per_point, 1.0 / rate,
                      f"{len(points)} {what} of ~{per_point:.0f} s simulated", workers=n),
             stiffest[1], kmh_to_ms(300.0))  # fmt: skip


def check_workers_option(workers: int | None) -> None:
    """``--workers N`` must be in [1, 1024] (or left out: all cores); more than the cores
    are capped at them, with a note on stderr saying so and why."""
    if workers is not None and not 1 <= workers <= 1024:
        raise CliError(f"--workers {workers} is invalid: must be in [1, 1024]")
    from railhunt.studies.execute import capped_workers

    why = capped_workers(workers)
    if why is not None:
        click.echo(f"railhunt: note: --workers {why}", err=True)


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
    """Exit with status 1 when points of the study were lost (they can be resumed), or
    when every point failed (the study computed nothing: its first error is shown)."""
    from railhunt.studies.store import STATUS_FAILED

    failed = [row for row in result.rows if row.get("status") == STATUS_FAILED]
    if result.rows and len(failed) == len(result.rows) and not result.lost:
        click.echo(f"railhunt: error: every one of the {len(failed)} {points} failed; the "
                   f"first: {failed[0].get('message', '')}", err=True)  # fmt: skip
        raise SystemExit(1)
    if result.lost:
        how = ("run the same command with --resume to compute them" if result.path is not None
               else "run the command again")  # fmt: skip
        click.echo(f"railhunt: {result.lost} {points} were lost ({result.lost_reasons[0]}); "
                   f"{how}", err=True)  # fmt: skip
        raise SystemExit(1)
