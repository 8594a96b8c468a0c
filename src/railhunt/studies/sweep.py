"""Parameter sweeps: critical speeds and hunting frequency over a design of vehicles.

Every point of a design (see :mod:`railhunt.studies.design`) is one vehicle; each is
evaluated by :func:`evaluate_point` with the same analyses the rest of railhunt uses
(:func:`railhunt.critical_speed`, :func:`railhunt.linear_critical_speed`,
:func:`railhunt.hunting_frequency`), in parallel (:mod:`railhunt.studies.execute`), and
written to a results file as it finishes (:mod:`railhunt.studies.store`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from railhunt.studies.design import Point, build_design, frequency_speed, parse_ties
from railhunt.studies.execute import (
    CONNECT_TIMEOUT,
    interrupted,  # noqa: F401 (its name here is kept)
)
from railhunt.studies.options import StudyOptions, resolve_run
from railhunt.studies.outputs import (
    NEW_OUTPUT_COLUMNS,
    OutputOptions,
    empty_columns,
    evaluate_output,
    options_from,
)
from railhunt.studies.runner import run_study
from railhunt.studies.store import (
    ALL_OUTPUTS,
    OUTPUTS,
    STATUS_FAILED,
    STATUS_NO_CRITICAL_SPEED,
    STATUS_OK,
    SweepResults,
    columns_for,
)
from railhunt.track import SampledTrack, SingleDefect, check_excitation
from railhunt.vehicle import Vehicle


def critical_speed_message(result: Any) -> str:
    """Why a critical-speed search found no change of verdict, in words."""
    verdicts = {t.verdict for t in result.trials}
    speeds = [t.speed_kmh for t in result.trials]
    if getattr(result, "limit_reached", False):
        if not speeds:
            return f"beyond the validity envelope at every speed: {result.limit.text}"
        return (f"stable at every speed tried, up to {max(speeds):g} km/h, where the search "
                f"stopped (limit reached: {result.limit.text})")  # fmt: skip
    if verdicts == {"stable"}:
        return f"stable at every speed tried, up to {max(speeds):g} km/h"
    if "stable" not in verdicts:
        return (f"not stable at any speed tried, down to {min(speeds):g} km/h "
                f"({', '.join(sorted(verdicts))})")  # fmt: skip
    return "the search did not bracket a change of verdict"


def evaluate_point(
    point: Point,
    vehicle: Vehicle,
    outputs: Sequence[str] = OUTPUTS,
    frequency_speed_kmh: float = 350.0,
    excitation: object = None,
    creep_law: str | None = None,
    frequency_amplitude: float | None = None,
    output_options: OutputOptions | None = None,
) -> dict[str, Any]:
    """Evaluate one point of a study: the results row of ``vehicle`` changed by the point.

    Parameters
    ----------
    point : Point
        The parameter values (SI) of this point.
    vehicle : Vehicle
        Nominal vehicle.
    outputs : sequence of str
        Any of ``"critical_speed"`` (nonlinear, by bisection with ``excitation``),
        ``"linear_critical_speed"`` (Hopf point) and ``"hunting_frequency"`` (at
        ``frequency_speed_kmh``, over ``excitation`` or after releasing every wheelset
        from ``frequency_amplitude``).
    frequency_speed_kmh : float
        Speed of the hunting-frequency run (km/h).
    excitation : SingleDefect, optional
        Excitation of the critical-speed search (default: its 8 mm defect).
    creep_law : str
        See :class:`railhunt.model.Model`.
    frequency_amplitude : float, optional
        Initial lateral displacement of every wheelset for the hunting frequency (m);
        default: run over ``excitation``, as the critical-speed search does.
    output_options : OutputOptions, optional
        Settings of the outputs of :mod:`railhunt.studies.outputs` (``fold_speed``,
        ``least_damping_ratio``, ``curving``).

    Returns
    -------
    dict
        One results row (see :func:`railhunt.studies.store.columns_for`). An analysis
        that raises makes the row ``status="failed"`` with the error as ``message``.
    """
    from railhunt.analysis.critical import critical_speed
    from railhunt.analysis.frequency import hunting_frequency
    from railhunt.analysis.hunting_branch import seed_crossing
    from railhunt.analysis.linear import linear_critical_speed
    from railhunt.model import Model

    row: dict[str, Any] = {"point": point.index, "line": point.line, **point.values}
    for name in outputs:
        if name == "hunting_frequency":
            row.update(frequency_speed_kmh=float(frequency_speed_kmh),
                       hunting_frequency_hz=math.nan, frequency_source="")  # fmt: skip
        elif name == "critical_speed":
            row["critical_speed_kmh"] = math.nan
        elif name in NEW_OUTPUT_COLUMNS:
            row.update(empty_columns(name))
        else:
            row.update(linear_critical_speed_kmh=math.nan, linear_frequency_hz=math.nan)
    status, message = STATUS_OK, ""
    try:
        v = vehicle.replace(**point.values)
        if "critical_speed" in outputs:
            res = critical_speed(v, excitation, creep_law=creep_law)
            row["critical_speed_kmh"] = float(res.speed_kmh)
            if not res.bracketed:
                status, message = STATUS_NO_CRITICAL_SPEED, critical_speed_message(res)
        lin = None
        if "linear_critical_speed" in outputs:
            lin = linear_critical_speed(v, creep_law=creep_law)
            row["linear_critical_speed_kmh"] = float(lin.speed_kmh)
            row["linear_frequency_hz"] = float(lin.frequency_hz)
        if "hunting_frequency" in outputs:
            model = Model(v, creep_law=creep_law)
            if lin is not None and (creep_law is not None
                                    or len(set(v.assembly.creep_laws)) == 1):  # fmt: skip
                # The hunting mode is followed from this Hopf point: not found twice.
                seed_crossing(model, lin)
            if frequency_amplitude is None:
                defect = SingleDefect() if excitation is None else excitation
                hf = hunting_frequency(v, frequency_speed_kmh, model=model,
                                       excitation=defect)  # fmt: skip
            else:
                hf = hunting_frequency(v, frequency_speed_kmh, frequency_amplitude,
                                       model=model)  # fmt: skip
            row["hunting_frequency_hz"] = float(hf.frequency_hz)
            row["frequency_source"] = hf.source
        for name in outputs:
            if name in NEW_OUTPUT_COLUMNS:
                row.update(evaluate_output(name, v, output_options, creep_law))
    except Exception as exc:  # noqa: BLE001 - one bad point must not end a study
        if interrupted(exc):
            raise KeyboardInterrupt from exc
        status, message = STATUS_FAILED, f"{type(exc).__name__}: {exc}"
    row["status"], row["message"] = status, message
    return row


def point_task(item: tuple[Point, float], vehicle: Vehicle, outputs: tuple[str, ...],
               excitation: object, creep_law: str, amplitude: float | None,
               output_options: OutputOptions | None = None) -> dict[str, Any]:  # fmt: skip
    """One task of a study: :func:`evaluate_point` of ``(point, frequency speed)``."""
    point, frequency_speed_kmh = item
    return evaluate_point(point, vehicle, outputs, frequency_speed_kmh, excitation, creep_law,
                          amplitude, output_options)  # fmt: skip


_warmed_up = False  # this process has run warm_up (its compiled code stays loaded)


def warm_up() -> None:
    """Load (or compile) every numba function a point uses, in this process (once: a
    second call returns at once)."""
    global _warmed_up
    if _warmed_up:
        return
    from railhunt.analysis.frequency import hunting_frequency

    hunting_frequency(Vehicle.paper2019(), 400.0)  # simulation, eigenvalues and shooting
    _warmed_up = True


def _json_values(values: object) -> object:
    arr = np.asarray(values, dtype=float)
    return [float(v) for v in arr.ravel()]


def sweep(
    vehicle: Vehicle,
    parameters: Mapping[str, object],
    outputs: Sequence[str] = OUTPUTS,
    *,
    design: str = "lines",
    samples: int | None = None,
    seed: int = 0,
    ties: Mapping[str, object] | None = None,
    frequency_speed_kmh: float | None = None,
    frequency_amplitude: float | None = None,
    excitation: object = None,
    creep_law: str | None = None,
    out: str | Path | None = None,
    resume: bool = False,
    overwrite: bool = False,
    client: Any = None,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: bool | Callable[[int, int], None] = False,
    connect_timeout: float = CONNECT_TIMEOUT,
    wait_for_workers: bool | float = False,
    output_options: OutputOptions | Mapping[str, Any] | None = None,
    run: StudyOptions | None = None,
) -> SweepResults:
    """Run a parameter study: critical speeds and hunting frequency at every point.

    Parameters
    ----------
    vehicle : Vehicle
        Nominal vehicle.
    parameters : Mapping
        Parameter name -> SI values (``lines``, ``grid``), or ``(low, high)``
        (``random``, ``lhs``). E.g. ``{"C_d1": np.linspace(20e3, 1000e3, 21)}``.
    outputs : sequence of str
        Any of ``"critical_speed"``, ``"linear_critical_speed"``, ``"hunting_frequency"``,
        ``"fold_speed"``, ``"least_damping_ratio"``, ``"curving"``
        (:mod:`railhunt.studies.outputs`; default the first three).
    design : {"lines", "grid", "random", "lhs"}
        One parameter at a time, full factorial, uniform random or Latin hypercube
        (:func:`railhunt.studies.design.build_design`).
    samples : int, optional
        Points of a ``random`` or ``lhs`` design.
    seed : int
        Seed of the random designs (the same seed gives the same points).
    ties : Mapping, optional
        Parameters that follow another, e.g. ``{"f22": "f11"}`` (the paper's f22 = f11)
        or ``{"f22": ("f11", 0.9)}``.
    frequency_speed_kmh : float, optional
        Speed of the hunting-frequency run (km/h); default the paper's: 300 km/h for lines
        of yaw-damper parameters (C_d1, C_d2, K_d, F_u), 350 km/h otherwise.
    frequency_amplitude : float, optional
        Initial lateral displacement of every wheelset in the hunting-frequency run (m),
        in (0, 0.02]. By default the frequency run goes over the critical-speed search's
        ``excitation`` instead, so the frequency is the limit cycle's exactly when that
        search would judge the frequency speed hunting: the paper's Sec. 3.3 (eigenvalue
        below V_cr, limit cycle above) and its Figs. 10-11, whose jumps sit where V_cr
        crosses the frequency speed. A release from 3 mm (the paper's Fig. 7b) puts the
        jump at the speed of the unstable 3 mm cycle instead.
    excitation : SingleDefect, optional
        Excitation of the critical-speed search (default 8 mm, 20 m defect).
    creep_law : str
        See :class:`railhunt.model.Model`.
    out : path-like, optional
        Results file (``.csv``; ``.parquet`` with pyarrow), written as points finish.
    resume : bool
        Continue ``out``: compute only the points it lacks.
    overwrite : bool
        Replace an existing ``out``.
    client : dask.distributed.Client, optional
        Run on this Dask cluster.
    scheduler : str, optional
        Address of a Dask scheduler to join.
    connect_timeout : float
        How long to try to reach ``scheduler`` (s), in (0, 3600]; a refused port, a
        server that is not a Dask scheduler or no answer in time raise
        :class:`railhunt.studies.execute.SchedulerError` (an ``OSError``).
    wait_for_workers : bool or float
        With ``scheduler``: a scheduler without workers is an error after a few seconds;
        True waits for a first worker as long as it takes, a number that many seconds.
    workers : int, optional
        Worker processes of the local cluster (default: all cores; 1 runs in this process).
    progress : bool or callable
        Show a progress bar (points done, rate, time left) on stderr, or call
        ``progress(done, total)`` after each point.
    output_options : OutputOptions or Mapping, optional
        The curve of the ``curving`` outputs, the speed range of ``least_damping_ratio``
        (:class:`railhunt.studies.outputs.OutputOptions`).
    run : StudyOptions, optional
        How the study runs, in one object (:class:`railhunt.StudyOptions`): instead of
        ``out`` ... ``wait_for_workers`` (giving both is an error naming the keyword).

    Returns
    -------
    SweepResults
        Rows sorted by point, with the counts of points computed, resumed and lost.
    """
    outputs = tuple(outputs)
    bad = [o for o in outputs if o not in ALL_OUTPUTS]
    if bad or not outputs:
        raise ValueError(f"outputs = {list(outputs)!r} is invalid: choose one or more of "
                         f"{', '.join(ALL_OUTPUTS)}")  # fmt: skip
    options = options_from(output_options)
    options.check_for(outputs)
    if frequency_speed_kmh is not None and not (math.isfinite(frequency_speed_kmh)
                                                and 0 < frequency_speed_kmh <= 1000):  # fmt: skip
        raise ValueError(f"frequency_speed_kmh = {frequency_speed_kmh!r} km/h is invalid: must "
                         "be in (0, 1000] km/h")  # fmt: skip
    options_run = resolve_run(run, out=out, resume=resume, overwrite=overwrite, client=client,
                              scheduler=scheduler, workers=workers, progress=progress,
                              connect_timeout=connect_timeout,
                              wait_for_workers=wait_for_workers)  # fmt: skip
    if frequency_amplitude is not None and not (math.isfinite(frequency_amplitude)
                                                and 0 < frequency_amplitude <= 0.02):  # fmt: skip
        raise ValueError(f"frequency_amplitude = {frequency_amplitude!r} m is invalid: must be "
                         "in (0, 0.02] m")  # fmt: skip
    if excitation is None:
        excitation = SingleDefect()
    check_excitation(excitation, (SingleDefect, SampledTrack))
    tie_map = parse_ties(ties, vehicle.parameters)
    points = build_design(vehicle, parameters, design, samples, seed, ties)
    for p in points:  # every combination must make a valid vehicle, before any work starts
        vehicle.replace(**p.values)
    names = list(parameters)
    speeds = {p.index: frequency_speed(p, names, frequency_speed_kmh) for p in points}
    meta = _describe(vehicle, parameters, outputs, design, samples, seed, tie_map, points,
                     speeds, frequency_amplitude, excitation, creep_law)  # fmt: skip
    meta.update(options.describe(outputs))
    # Each task carries its own point and frequency speed (not the whole study's).
    task = functools.partial(point_task, vehicle=vehicle, outputs=outputs,
                             excitation=excitation, creep_law=creep_law,
                             amplitude=frequency_amplitude, output_options=options)  # fmt: skip
    return run_study([(p.index, (p, speeds[p.index])) for p in points], task, meta,
                     label="sweep", run=options_run, warm_up=warm_up)


def _describe(vehicle: Vehicle, parameters: Mapping[str, object], outputs: tuple[str, ...],
              design: str, samples: int | None, seed: int,
              tie_map: dict[str, tuple[str, float]], points: list[Point],
              speeds: dict[int, float], frequency_amplitude: float | None,
              excitation: object, creep_law: str) -> dict[str, Any]:  # fmt: skip
    """The study description of a results file's sidecar; its fingerprint decides resume.

    It holds what changes the numbers and nothing else: the railhunt version and a hash
    of its sources (a file is not resumed by changed code), the vehicle's parameters and
    contact description (not its name), the design and its points' resolved options, and
    only the options the chosen outputs use.
    """
    from railhunt._cache import source_hash
    from railhunt._version import __version__
    from railhunt.provenance import provenance, vehicle_block

    names = list(parameters)
    param_cols = list(points[0].values)
    meta: dict[str, Any] = {
        "railhunt": __version__,
        "source": source_hash(),
        "vehicle": vehicle_block(vehicle),
        "provenance": provenance(vehicle),
        "design": design,
        "parameters": {n: _json_values(parameters[n]) for n in names},
        "ties": {f: [lf[0], lf[1]] for f, lf in tie_map.items()},
        "outputs": list(outputs),
        "creep_law": creep_law if creep_law is not None else vehicle.assembly.creep_laws[0],
        "points": len(points),
        "parameter_columns": param_cols,
        "columns": columns_for(param_cols, outputs),
    }
    if design in ("random", "lhs"):
        meta.update(samples=samples, seed=seed)
    if "hunting_frequency" in outputs:
        by_line = {p.line: speeds[p.index] for p in points}
        meta["frequency_speed_kmh"] = by_line
        meta["frequency_amplitude"] = frequency_amplitude
    if "critical_speed" in outputs or ("hunting_frequency" in outputs
                                       and frequency_amplitude is None):  # fmt: skip
        meta["excitation"] = repr(excitation)
    return meta
