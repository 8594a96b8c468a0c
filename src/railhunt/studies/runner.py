"""Running a study: every point a task, each result written as it finishes, resumable.

:func:`run_study` is the loop that :func:`railhunt.sweep` and
:func:`railhunt.stability_map` share: open the results file (resuming it if asked), run the
points the file does not hold yet (in this process or on Dask, :func:`run_tasks`), write and
report each row as it arrives, close the file (sorted when complete), and return the rows.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from contextlib import ExitStack
from pathlib import Path
from typing import Any

from railhunt.studies.execute import CONNECT_TIMEOUT, open_client, progress_bar, run_tasks
from railhunt.studies.store import ResultFileError, ResultStore, SweepResults


def run_study(
    points: Sequence[tuple[int, Any]],
    task: Callable[[Any], dict[str, Any]],
    meta: dict[str, Any],
    *,
    label: str,
    out: str | Path | None = None,
    resume: bool = False,
    overwrite: bool = False,
    client: Any = None,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: bool | Callable[[int, int], None] = False,
    warm_up: Callable[[], None] | None = None,
    connect_timeout: float = CONNECT_TIMEOUT,
    wait_for_workers: bool | float = False,
) -> SweepResults:
    """Run ``task`` on every point a results file does not hold yet.

    Parameters
    ----------
    points : sequence of (int, object)
        Each point's index (the ``point`` column of its row) and the item ``task`` takes.
    task : callable
        Picklable; ``task(item)`` returns the point's results row (a dict with ``point``).
    meta : dict
        The study description (``<file>.sweep.json``; its fingerprint decides resume).
    label : str
        Name of the progress bar.
    out, resume, overwrite : optional
        Results file, continue it, or replace it (:class:`ResultStore`).
    client, scheduler, workers : optional
        Where the tasks run (:func:`railhunt.studies.execute.run_tasks`).
    progress : bool or callable
        A progress bar on stderr, or ``progress(done, total)`` after each point.
    warm_up : callable, optional
        Compiles the tasks' code in this process before workers start (only if there is
        work to do).
    connect_timeout : float
        How long to try to reach ``scheduler`` (s).
    wait_for_workers : bool or float
        With ``scheduler``: wait for a first worker (True: as long as it takes; a number:
        that many seconds); by default a scheduler without workers is an error after a
        few seconds (:func:`railhunt.studies.execute.join_scheduler`).

    The scheduler is joined and the results file's folder checked before anything is
    created: a wrong address or folder leaves no file behind.

    Returns
    -------
    SweepResults
        Rows sorted by point, with the counts computed/resumed/lost and the wall time.
    """
    if out and not Path(out).parent.is_dir():
        raise ResultFileError(f"{out}: folder {str(Path(out).parent)!r} does not exist; "
                              "create it first or choose another file")  # fmt: skip
    with ExitStack() as stack:
        if client is None and scheduler is not None:
            client = stack.enter_context(open_client(scheduler, 1, connect_timeout,
                                                     wait_for_workers))  # fmt: skip
            scheduler = None
        return _run(points, task, meta, label=label, out=out, resume=resume,
                    overwrite=overwrite, client=client, workers=workers, progress=progress,
                    warm_up=warm_up)  # fmt: skip


def _run(points: Sequence[tuple[int, Any]], task: Callable[[Any], dict[str, Any]],
         meta: dict[str, Any], *, label: str, out: str | Path | None, resume: bool,
         overwrite: bool, client: Any, workers: int | None,
         progress: bool | Callable[[int, int], None],
         warm_up: Callable[[], None] | None) -> SweepResults:  # fmt: skip
    start = time.perf_counter()
    store = ResultStore(out, meta, resume=resume, overwrite=overwrite) if out else None
    rows: dict[int, dict[str, Any]] = dict(store.rows) if store else {}
    resumed = len(rows)
    total = len(points)
    todo = [item for index, item in points if index not in rows]
    bar = progress_bar() if progress is True else None
    bar_task = None
    if bar is not None:
        bar.start()
        bar_task = bar.add_task(label, total=total, completed=resumed)

    def on_result(row: dict[str, Any]) -> None:
        rows[row["point"]] = row
        if store is not None:
            store.write(row)
        if bar is not None:
            bar.advance(bar_task)
        elif callable(progress):
            progress(len(rows), total)

    lost: list[tuple[Any, str]] = []
    complete = False
    try:
        lost = run_tasks(task, todo, on_result, client=client, workers=workers,
                         warm_up=warm_up if todo else None)  # fmt: skip
        # every point of this design is in (the file may hold others: an optimisation's
        # earlier generations), so the file is rewritten sorted by point
        complete = all(index in rows for index, _ in points)
    finally:
        if bar is not None:
            bar.stop()
        if store is not None:
            store.close(complete)
    result = SweepResults([rows[k] for k in sorted(rows)], meta, Path(out) if out else None)
    result.computed = len(rows) - resumed
    result.resumed = resumed
    result.lost_reasons = [reason for _, reason in lost]
    result.elapsed_s = time.perf_counter() - start
    return result
