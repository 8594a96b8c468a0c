"""Running a study: its points in tasks, each task's rows written as it finishes, resumable.

:class:`StudyRun` is the loop that :func:`railhunt.sweep`, :func:`railhunt.stability_map`,
:func:`railhunt.sensitivity` and :func:`railhunt.optimize` share: open the results file
(resuming it if asked), run the points the file does not hold yet in tasks sized by their
measured cost (:mod:`railhunt.studies.tasks`: in this process, or on a local or given Dask
cluster), append each task's rows and report each point as it arrives, close the file
(sorted when complete). An optimisation runs one batch per generation on the same
:class:`StudyRun`: one file, one cluster, one progress bar for the whole study.
:func:`run_study` runs one batch.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from contextlib import ExitStack
from pathlib import Path
from typing import Any

from railhunt.studies.execute import CONNECT_TIMEOUT, open_client, progress_bar
from railhunt.studies.options import StudyOptions, resolve_run
from railhunt.studies.store import ResultFileError, ResultStore, SweepResults
from railhunt.studies.tasks import TaskEngine


class StudyRun:
    """One study's results file, cluster and progress, for one or more batches of points.

    The scheduler is joined and the results file's folder checked before anything is
    created: a wrong address or folder leaves no file behind. Use it as a context manager;
    leaving it closes the file (sorted by point when :attr:`complete` was set) and the
    cluster it started.

    Parameters
    ----------
    meta : dict
        The study description (``<file>.sweep.json``; its fingerprint decides resume).
    options : StudyOptions
        Where the points run, the file, the progress.
    label : str
        Name of the progress bar.
    total : int
        Points of the whole study (every batch).
    warm_up : callable, optional
        Compiles the tasks' code in this process before a local cluster starts.
    """

    def __init__(self, meta: dict[str, Any], options: StudyOptions, *, label: str, total: int,
                 warm_up: Callable[[], None] | None = None) -> None:  # fmt: skip
        self.meta = meta
        self.options = options
        self.total = total
        self.start = time.perf_counter()
        self.complete = False
        self.lost: list[tuple[Any, str]] = []
        out = options.out
        if out and not Path(out).parent.is_dir():
            raise ResultFileError(f"{out}: folder {str(Path(out).parent)!r} does not exist; "
                                  "create it first or choose another file")  # fmt: skip
        self._stack = ExitStack()
        try:
            client = options.client
            if client is None and options.scheduler is not None:
                client = self._stack.enter_context(open_client(
                    options.scheduler, 1, options.connect_timeout,
                    options.wait_for_workers))  # fmt: skip
            self.store = (ResultStore(out, meta, resume=options.resume,
                                      overwrite=options.overwrite) if out else None)  # fmt: skip
        except BaseException:
            self._stack.close()
            raise
        self.rows: dict[int, dict[str, Any]] = dict(self.store.rows) if self.store else {}
        self.resumed = len(self.rows)
        self.engine = TaskEngine(options, client, warm_up,
                                 lambda: self.total - len(self.rows))  # fmt: skip
        self._stack.callback(self.engine.close)
        self.bar = progress_bar() if options.progress is True else None
        self._bar_task = None
        if self.bar is not None:
            self.bar.start()
            self._bar_task = self.bar.add_task(label, total=total, completed=self.resumed)

    # ------------------------------------------------------------------ rows

    def _accept(self, rows: list[dict[str, Any]]) -> None:
        """A task's rows: each reported, then all appended to the file at once (also when
        a progress callback raises: the rows it was told about are kept)."""
        accepted: list[dict[str, Any]] = []
        progress = self.options.progress
        try:
            for row in rows:
                point = row["point"]
                if point in self.rows:
                    continue
                self.rows[point] = row
                accepted.append(row)
                if callable(progress) and not isinstance(progress, bool):
                    progress(len(self.rows), self.total)
        finally:
            if self.store is not None:
                self.store.write_many(accepted)
            if self.bar is not None and accepted:
                self.bar.advance(self._bar_task, len(accepted))

    def label(self, text: str) -> None:
        """Rename the progress bar (an optimisation's generation)."""
        if self.bar is not None:
            self.bar.update(self._bar_task, description=text)

    def run(self, points: Sequence[tuple[int, Any]],
            task: Callable[[Any], dict[str, Any]]) -> list[tuple[Any, str]]:  # fmt: skip
        """Evaluate the ``(index, item)`` points the file does not hold; returns the lost
        ``(item, reason)`` pairs (also added to :attr:`lost`)."""
        todo = [item for index, item in points if index not in self.rows]
        lost = self.engine.run(task, todo, self._accept)
        self.lost += lost
        return lost

    def results(self) -> SweepResults:
        """Every row so far, sorted by point, with the counts and the wall time."""
        out = self.options.out
        result = SweepResults([self.rows[k] for k in sorted(self.rows)], self.meta,
                              Path(out) if out else None)  # fmt: skip
        result.computed = len(self.rows) - self.resumed
        result.resumed = self.resumed
        result.lost_reasons = [reason for _, reason in self.lost]
        result.elapsed_s = time.perf_counter() - self.start
        result.evaluation_s = self.engine.evaluation_s + self.engine.worker_evaluation_s
        return result

    # ------------------------------------------------------------------ closing

    def close(self) -> None:
        """Stop the progress bar, close the cluster and the file."""
        try:
            if self.bar is not None:
                self.bar.stop()
                self.bar = None
            self._stack.close()
        finally:
            if self.store is not None:
                store, self.store = self.store, None
                store.close(self.complete)

    def __enter__(self) -> StudyRun:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def run_study(
    points: Sequence[tuple[int, Any]],
    task: Callable[[Any], dict[str, Any]],
    meta: dict[str, Any],
    *,
    label: str,
    run: StudyOptions | None = None,
    warm_up: Callable[[], None] | None = None,
    out: str | Path | None = None,
    resume: bool = False,
    overwrite: bool = False,
    client: Any = None,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: bool | Callable[[int, int], None] = False,
    connect_timeout: float = CONNECT_TIMEOUT,
    wait_for_workers: bool | float = False,
) -> SweepResults:
    """Run ``task`` on every point a results file does not hold yet (one batch).

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
    run : StudyOptions, optional
        Where the points run, the file and the progress; or the keywords ``out`` ...
        ``wait_for_workers`` (:func:`railhunt.studies.options.resolve_run`).
    warm_up : callable, optional
        Compiles the tasks' code in this process before a local cluster starts.

    Returns
    -------
    SweepResults
        Rows sorted by point, with the counts computed/resumed/lost and the wall time.
    """
    options = resolve_run(run, out=out, resume=resume, overwrite=overwrite, client=client,
                          scheduler=scheduler, workers=workers, progress=progress,
                          connect_timeout=connect_timeout,
                          wait_for_workers=wait_for_workers)  # fmt: skip
    with StudyRun(meta, options, label=label, total=len(points), warm_up=warm_up) as study:
        study.run(points, task)
        # every point of this design is in (the file may hold others), so the file is
        # rewritten sorted by point
        study.complete = all(index in study.rows for index, _ in points)
        return study.results()
