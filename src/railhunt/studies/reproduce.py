"""Recompute the paper's results figures (Figs. 6, 7, 8, 10–13) and compare its numbers;
go beyond the paper with the stability map of its vehicle in curves.

:func:`reproduce` runs one independent step per figure for the default vehicle
(``paper2019``), writes each figure as ``DIR/figN.png`` (and ``DIR/stability_map.png``
beyond the paper), a machine-readable
``DIR/headline.json`` and a self-contained ``DIR/report.html``
(:mod:`railhunt.studies.report`), and returns a :class:`Report`. Every step returns its
figure files, its rows of the headline table (the paper's number beside railhunt's, with
the difference) and its run time; a step that raises is recorded as failed and the others
still run.

The steps live by theme in ``reproduce_fig6_8``, ``reproduce_fig10_12``,
``reproduce_fig13`` and (beyond the paper, railhunt's own results) ``reproduce_curves``;
the records they return (:class:`Headline`, :class:`Step`, :class:`Report`) in
:mod:`railhunt.studies.records`; the paper's captions, sentences and
numbers in :mod:`railhunt.paper2019`. Where railhunt differs from the paper the table says
so; the reasons are documented in ``docs/bifurcation.md`` and ``docs/model.md`` and
summarised in ``docs/reproduce.md``.
"""

from __future__ import annotations

import datetime as _dt
import json
import time
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any

import railhunt.paper2019 as paper2019
from railhunt.paper2019 import NO_BLOWOFF as NO_BLOWOFF
from railhunt.studies.records import Context, Headline, Report, Settings, Step, show
from railhunt.studies.reproduce_curves import curves
from railhunt.studies.reproduce_fig6_8 import fig6, fig7, fig8, peak_period
from railhunt.studies.reproduce_fig10_12 import FIG10_LINES as FIG10_LINES
from railhunt.studies.reproduce_fig10_12 import FIG11_LINES as FIG11_LINES
from railhunt.studies.reproduce_fig10_12 import fig10_12, sweep_headline
from railhunt.studies.reproduce_fig13 import fig13
from railhunt.vehicle import Vehicle

__all__ = ["OUTPUT_FILES", "Headline", "Report", "Settings", "Step", "reproduce", "show",
           "sweep_headline"]  # fmt: skip

# Earlier names, kept importable from here: ``railhunt reproduce`` imports ``_show``, the
# tests ``_Context``, ``_period`` and ``_fig13``.
_show = show
_Context = Context
_period = peak_period
_fig13 = fig13

# --------------------------------------------------------------------------- driver

#: The files a run writes into its folder (the sweeps' ``.sweep.json`` sidecars aside).
OUTPUT_FILES = ("report.html", "headline.json", "fig6.png", "fig7a.png", "fig7b.png",
                "fig8.png", "fig10.png", "fig11.png", "fig12.png", "fig13.png", "sweep.csv",
                "stability_map.png", "stability_map.csv")  # fmt: skip

#: The steps, in report order.
STEPS: tuple[Callable[[Context], Step], ...] = (fig6, fig7, fig8, fig10_12, fig13, curves)
_TITLES = {"fig6": "Fig. 6", "fig7": "Fig. 7", "fig8": "Fig. 8", "fig10_12": "Figs. 10–12",
           "fig13": "Fig. 13", "curves": "Beyond the paper: curves"}  # fmt: skip


def reproduce(
    out_dir: str | Path,
    quick: bool = False,
    client: Any = None,
    progress: Callable[[str, str], None] | None = None,
    vehicle: Vehicle | None = None,
    settings: Settings | None = None,
) -> Report:
    """Recompute the paper's Figs. 6, 7, 8, 10–13 and write a self-contained HTML report;
    beyond the paper, the stability map of the vehicle in curves.

    Parameters
    ----------
    out_dir : str or pathlib.Path
        Output folder (created if missing): ``report.html``, ``headline.json``, ``figN.png``
        (``fig7a.png``, ``fig7b.png`` for Fig. 7), with the sweep ``sweep.csv``, and
        ``stability_map.png`` and ``stability_map.csv``.
    quick : bool
        Coarser settings (:meth:`Settings.quick`): a run of under a minute.
    client : dask.distributed.Client, optional
        Runs the Fig. 13 family members (and the sweep and the stability map) as Dask tasks;
        otherwise everything runs in this process.
    progress : callable, optional
        Called as ``progress(title, state)`` with ``state`` ``"start"`` when a step starts
        and its status (``"ok"``, ``"not available"``, ``"failed"``) when it ends.
    vehicle : Vehicle, optional
        Default: the paper's vehicle (``Vehicle.paper2019()``). The paper's numbers are of
        that vehicle; for another one the table compares against them all the same.
    settings : Settings, optional
        Overrides ``quick``.

    Returns
    -------
    Report
    """
    from railhunt._version import __version__
    from railhunt.provenance import vehicle_fingerprint
    from railhunt.studies.report import write_html

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    settings = settings or (Settings.quick() if quick else Settings())
    vehicle = vehicle or paper2019.vehicle()
    ctx = Context(vehicle, out, settings, client)
    started = _dt.datetime.now(_dt.UTC).replace(microsecond=0).isoformat()
    t_start = time.perf_counter()
    steps = []
    for func in STEPS:
        title = _TITLES[func.__name__]
        if progress is not None:
            progress(title, "start")
        t0 = time.perf_counter()
        try:
            step = func(ctx)
        except Exception as exc:  # noqa: BLE001 - one failed figure must not lose the others
            step = Step(func.__name__.replace("_", "-"), title, "", status="failed",
                        message=f"{type(exc).__name__}: {exc}\n{traceback.format_exc(limit=4)}")
        step.seconds = time.perf_counter() - t0
        steps.append(step)
        if progress is not None:
            progress(title, step.status)
    workers = 0
    if client is not None:
        try:
            workers = len(client.scheduler_info().get("workers", {}))
        except Exception:  # noqa: BLE001 - only for the report's header
            workers = 0
    report = Report(out, out / "report.html", out / "headline.json", steps, vehicle.name,
                    __version__, started, settings != Settings(),
                    time.perf_counter() - t_start, workers,
                    vehicle_fingerprint(vehicle))  # fmt: skip
    report.json.write_text(json.dumps(report.to_dict(), indent=2, ensure_ascii=False) + "\n",
                           encoding="utf-8")  # fmt: skip
    write_html(report, report.html)
    return report
