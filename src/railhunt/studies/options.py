"""How a study runs: one options object for :func:`railhunt.sweep`,
:func:`railhunt.stability_map`, :func:`railhunt.sensitivity` and :func:`railhunt.optimize`.

Each of those functions takes ``run=StudyOptions(...)``; the keywords they took before
(``out``, ``resume``, ``overwrite``, ``client``, ``scheduler``, ``workers``, ``progress``,
``connect_timeout``, ``wait_for_workers``) still work. Giving ``run=`` together with one of
those keywords set to anything but its default is an error that names the keyword: there is
one place where a study's running is said, never two that could disagree.

>>> from railhunt import StudyOptions
>>> run = StudyOptions(out="mu.csv", workers=2)
>>> run.replace(resume=True).resume
True
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from railhunt.studies.execute import CONNECT_TIMEOUT, check_connect_timeout, check_workers

__all__ = ["RUN_KEYWORDS", "TASK_SECONDS", "StudyOptions", "resolve_run"]

#: Work (s) one task of a study aims at: points are grouped so that each task holds about
#: this much evaluation time (at least one point).
TASK_SECONDS = 0.5


@dataclass(frozen=True)
class StudyOptions:
    """Where and how a study's points run, where they are written, what is shown.

    Parameters
    ----------
    out : path-like, optional
        Results file (``.csv``; ``.parquet`` with pyarrow), appended to as tasks finish.
    resume : bool
        Continue ``out``: compute only the points it lacks.
    overwrite : bool
        Replace an existing ``out``.
    client : dask.distributed.Client, optional
        Run on this Dask cluster (left open).
    scheduler : str, optional
        Address of a Dask scheduler to join (``tcp://host:8786``).
    workers : int, optional
        Worker processes of a local cluster, in [1, 1024] (capped at the cores; default:
        all cores). With 1, or when the whole study is estimated to cost less than
        starting the processes, the points run in this process without Dask.
    progress : bool or callable
        A progress bar on stderr, or ``progress(done, total)`` after each point.
    connect_timeout : float
        How long to try to reach ``scheduler`` (s), in (0, 3600].
    wait_for_workers : bool or float
        With ``scheduler``: True waits for a first worker as long as it takes, a number
        that many seconds; by default a scheduler without workers is an error after 5 s.
    task_seconds : float
        Evaluation time (s) a task aims at, in (0, 3600]: points are grouped into tasks of
        about this much work, measured on the first points (:mod:`railhunt.studies.tasks`).

    Raises
    ------
    ValueError
        A value outside its range, or both ``client`` and ``scheduler``.
    """

    out: str | Path | None = None
    resume: bool = False
    overwrite: bool = False
    client: Any = None
    scheduler: str | None = None
    workers: int | None = None
    progress: bool | Callable[[int, int], None] = False
    connect_timeout: float = CONNECT_TIMEOUT
    wait_for_workers: bool | float = False
    task_seconds: float = TASK_SECONDS

    def __post_init__(self) -> None:
        if self.client is not None and self.scheduler is not None:
            raise ValueError("give either client or scheduler, not both")
        if self.client is None and self.scheduler is None:
            check_workers(self.workers)
        check_connect_timeout(self.connect_timeout)
        wait = self.wait_for_workers
        if not isinstance(wait, bool):
            try:
                value = float(wait)
            except (TypeError, ValueError):
                value = math.nan
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"wait_for_workers = {wait!r} is invalid: must be True, "
                                 "False or a number of seconds > 0")  # fmt: skip
        try:
            task = float(self.task_seconds)
        except (TypeError, ValueError):
            task = math.nan
        if not (math.isfinite(task) and 0 < task <= 3600):
            raise ValueError(f"task_seconds = {self.task_seconds!r} s is invalid: must be in "
                             "(0, 3600] s")  # fmt: skip
        if not (isinstance(self.progress, bool) or callable(self.progress)):
            raise ValueError(f"progress = {self.progress!r} is invalid: must be True, False or "
                             "a function progress(done, total)")  # fmt: skip

    def replace(self, **changes: Any) -> StudyOptions:
        """A copy with ``changes`` (checked again)."""
        return dataclasses.replace(self, **changes)

    @property
    def local(self) -> bool:
        """Whether the points run on this machine (no ``client``, no ``scheduler``)."""
        return self.client is None and self.scheduler is None


#: The keywords every study function still takes besides ``run=`` (their defaults).
RUN_KEYWORDS: dict[str, Any] = {f.name: f.default for f in dataclasses.fields(StudyOptions)
                                if f.name != "task_seconds"}  # fmt: skip


def _is_default(name: str, value: Any) -> bool:
    default = RUN_KEYWORDS[name]
    if value is default:
        return True
    if isinstance(default, float) and isinstance(value, (int, float)) \
            and not isinstance(value, bool):  # fmt: skip
        return float(value) == default
    return False


def resolve_run(run: StudyOptions | None, **keywords: Any) -> StudyOptions:
    """The study's :class:`StudyOptions`: ``run``, or one made from the old keywords.

    Parameters
    ----------
    run : StudyOptions, optional
        The options given as ``run=``.
    **keywords
        The study function's own ``out``, ``resume``, ... (:data:`RUN_KEYWORDS`).

    Raises
    ------
    ValueError
        ``run`` given together with a keyword that is not at its default.
    TypeError
        ``run`` is not a :class:`StudyOptions`.
    """
    unknown = set(keywords) - set(RUN_KEYWORDS)
    if unknown:
        raise TypeError(f"unknown study keyword(s): {', '.join(sorted(unknown))}")
    if run is None:
        return StudyOptions(**keywords)
    if not isinstance(run, StudyOptions):
        raise TypeError(f"run = {run!r} is invalid: give a railhunt.StudyOptions")
    given = [k for k, v in keywords.items() if not _is_default(k, v)]
    if given:
        names = ", ".join(f"{k}=" for k in given)
        raise ValueError(f"run= and {names} both given: say it once, in run=StudyOptions("
                         f"{given[0]}=...) or run.replace({given[0]}=...), or drop run=")
    return run
