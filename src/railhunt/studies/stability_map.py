"""Stability map: linear and nonlinear critical speed against the curve radius.

Each radius is one point of a study, run on the machinery of :func:`railhunt.sweep`:
in parallel on a local Dask cluster (or any cluster), written to a results file as it
finishes, resumable after an interruption. The curve has either a fixed cant (every speed
in the same curve) or a fixed cant deficiency (the cant follows the speed,
:func:`railhunt.curve.fixed_deficiency`). An infinite radius is straight track.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from railhunt.curve import Curve, fixed_deficiency
from railhunt.studies.execute import CONNECT_TIMEOUT
from railhunt.studies.options import StudyOptions, resolve_run
from railhunt.studies.runner import run_study
from railhunt.studies.store import (
    STATUS_FAILED,
    STATUS_NO_CRITICAL_SPEED,
    STATUS_OK,
    SweepResults,
    columns_for,
)
from railhunt.track import SampledTrack, SingleDefect, check_excitation
from railhunt.vehicle import Vehicle

#: The analyses a stability map can run at each radius.
MAP_OUTPUTS = ("linear_critical_speed", "critical_speed")


def check_radii(radii: Sequence[float]) -> list[float]:
    """Radii (m) as floats, each finite >= 50 m or ``inf`` (straight track), no repeats."""
    out = []
    for r in radii:
        try:
            value = float(r)
        except (TypeError, ValueError):
            raise ValueError(f"radii contains {r!r}: each radius must be a number in m "
                             "(inf for straight track)") from None  # fmt: skip
        if not (value == math.inf or (math.isfinite(value) and value >= 50.0)):
            raise ValueError(f"radii contains {r!r} m: each radius must be at least 50 m, "
                             "or inf for straight track")  # fmt: skip
        out.append(value)
    if not out:
        raise ValueError("radii is empty: give at least one radius (m)")
    if len(set(out)) != len(out):
        raise ValueError(f"radii = {out!r} repeats a radius")
    return out


def curve_for(vehicle: Vehicle, radius: float, cant: float, cant_deficiency: float | None,
              direction: str) -> Curve | Callable[[float], Curve] | None:  # fmt: skip
    """The curve of one point: None for straight track, a Curve (fixed cant) or a
    function of speed (fixed cant deficiency)."""
    if radius == math.inf:
        return None
    if cant_deficiency is not None:
        return fixed_deficiency(radius, cant_deficiency, direction, g=vehicle.gravity)
    return Curve(radius, cant, direction=direction)


def evaluate_radius(item: tuple[int, float], vehicle: Vehicle, cant: float,
                    cant_deficiency: float | None, direction: str, outputs: tuple[str, ...],
                    excitation: object, creep_law: str) -> dict[str, Any]:  # fmt: skip
    """The results row of one radius (a task of the study)."""
    from railhunt.analysis.critical import critical_speed
    from railhunt.analysis.linear import linear_critical_speed
    from railhunt.studies.sweep import critical_speed_message, interrupted

    index, radius = item
    row: dict[str, Any] = {"point": index, "line": "radius", "radius_m": radius}
    if cant_deficiency is None:
        row["cant_m"] = cant if radius != math.inf else 0.0
    else:
        row["cant_deficiency_m"] = cant_deficiency if radius != math.inf else 0.0
    if "critical_speed" in outputs:
        row["critical_speed_kmh"] = math.nan
    if "linear_critical_speed" in outputs:
        row.update(linear_critical_speed_kmh=math.nan, linear_frequency_hz=math.nan)
    status, message = STATUS_OK, ""
    try:
        curve = curve_for(vehicle, radius, cant, cant_deficiency, direction)
        # In a curve the map stops at the first limit of the steady-curving state.
        limit = None if curve is None else curving_limit_of(vehicle, curve, creep_law)
        top = 1000.0
        if limit is not None and limit.reached:
            top = limit.last_valid_kmh if math.isfinite(limit.last_valid_kmh) else 0.0
            message = f"limit reached: {limit.text}"
        if "linear_critical_speed" in outputs and top > 20.0 + 1.0:
            lin = linear_critical_speed(vehicle, creep_law=creep_law, curve=curve,
                                        max_kmh=top)  # fmt: skip
            row["linear_critical_speed_kmh"] = float(lin.speed_kmh)
            row["linear_frequency_hz"] = float(lin.frequency_hz)
            if not math.isfinite(lin.speed_kmh):
                stays = (f"the equilibrium stays stable up to {top:g} km/h"
                         + (", the last speed inside the validity envelope" if top < 1000.0
                            else ""))  # fmt: skip
                message = "; ".join(m for m in (message, stays) if m)
        if "critical_speed" in outputs and top == 0.0:
            status = STATUS_NO_CRITICAL_SPEED  # beyond the envelope from the lowest speed
        elif "critical_speed" in outputs:
            res = critical_speed(vehicle, excitation, creep_law=creep_law, curve=curve)
            row["critical_speed_kmh"] = float(res.speed_kmh)
            extra = [w for w in res.warnings if w not in message]
            if not res.bracketed:
                status = STATUS_NO_CRITICAL_SPEED
                tried = [t.speed_kmh for t in res.trials]
                calm = res.limit_reached and tried and all(t.verdict == "stable"
                                                           for t in res.trials)  # fmt: skip
                extra = [f"stable at every speed tried, up to {max(tried):g} km/h, below the "
                         "limit" if calm else critical_speed_message(res)]  # fmt: skip
            message = "; ".join(m for m in (message, *extra) if m)
    except Exception as exc:  # noqa: BLE001 - one bad radius must not end the study
        if interrupted(exc):
            raise KeyboardInterrupt from exc
        status, message = STATUS_FAILED, f"{type(exc).__name__}: {exc}"
    row["status"], row["message"] = status, message
    return row


def curving_limit_of(vehicle: Vehicle, curve: Any, creep_law: str) -> Any:
    """The first limit of the validity envelope the steady-curving state reaches between
    20 and 800 km/h (:func:`railhunt.analysis.curving_limit.curving_limit`), as the
    critical-speed search in that curve finds it."""
    from railhunt.analysis.curving import EquilibriumPath
    from railhunt.analysis.curving_limit import curving_limit
    from railhunt.model import Model

    path = EquilibriumPath(Model(vehicle, creep_law=creep_law), curve)
    return curving_limit(path, 20.0, 800.0)


def _warm_up() -> None:
    """Load (or compile) the curve code in this process before workers start."""
    from railhunt.analysis.curving import curving

    curving(Vehicle.paper2019(), 200.0, Curve(2000.0, 0.1))


def stability_map(
    vehicle: Vehicle,
    radii: Sequence[float],
    cant: float = 0.0,
    *,
    cant_deficiency: float | None = None,
    direction: str = "left",
    outputs: Sequence[str] = MAP_OUTPUTS,
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
    run: StudyOptions | None = None,
) -> SweepResults:
    """Linear and nonlinear critical speed of a vehicle in curves of several radii.

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle.
    radii : sequence of float
        Curve radii (m), each at least 50 m; ``math.inf`` for straight track.
    cant : float
        Cant of every curve (m), 0 to 0.5 m (straight track has none).
    cant_deficiency : float, optional
        Instead of a fixed cant: the cant deficiency (m) to keep at every speed; the cant
        follows the speed (:func:`railhunt.curve.fixed_deficiency`).
    direction : {"left", "right"}
        Which way the curves turn (the results are mirror images).
    outputs : sequence of str
        ``"linear_critical_speed"`` (the Hopf point of the curving equilibrium) and/or
        ``"critical_speed"`` (the bisection over a defect inside the curve).
    excitation : SingleDefect, optional
        Defect of the nonlinear search (default 8 mm, 20 m).
    creep_law : str
        See :class:`railhunt.model.Model`.
    out, resume, overwrite, client, scheduler, workers, progress
        As for :func:`railhunt.sweep`: results file (CSV or Parquet) written as radii
        finish, resumable; Dask cluster or local workers; progress bar or callback.
    connect_timeout : float
        As for :func:`railhunt.sweep`: how long to try to reach ``scheduler`` (s).
    wait_for_workers : bool or float
        As for :func:`railhunt.sweep`: wait for the scheduler's first worker.
    run : StudyOptions, optional
        How the study runs, in one object (:class:`railhunt.StudyOptions`), instead of
        ``out`` ... ``wait_for_workers``.

    Returns
    -------
    SweepResults
        One row per radius, sorted as given: ``radius_m``, ``cant_m`` (or
        ``cant_deficiency_m``), ``linear_critical_speed_kmh``, ``linear_frequency_hz``,
        ``critical_speed_kmh``, ``status`` and ``message``.
    """
    radii = check_radii(radii)
    check_excitation(excitation, (SingleDefect, SampledTrack))
    outputs = tuple(outputs)
    bad = [o for o in outputs if o not in MAP_OUTPUTS]
    if bad or not outputs:
        raise ValueError(f"outputs = {list(outputs)!r} is invalid: choose one or more of "
                         f"{', '.join(MAP_OUTPUTS)}")  # fmt: skip
    if cant_deficiency is None:
        Curve(1000.0, cant, direction=direction)  # validate cant and direction
    else:
        fixed_deficiency(1000.0, cant_deficiency, direction)
    options_run = resolve_run(run, out=out, resume=resume, overwrite=overwrite, client=client,
                              scheduler=scheduler, workers=workers, progress=progress,
                              connect_timeout=connect_timeout,
                              wait_for_workers=wait_for_workers)  # fmt: skip
    if excitation is None:
        excitation = SingleDefect()
    param_cols = ["radius_m", "cant_m" if cant_deficiency is None else "cant_deficiency_m"]
    meta: dict[str, Any] = _describe(vehicle, radii, cant, cant_deficiency, direction,
                                     outputs, excitation, creep_law, param_cols)  # fmt: skip
    task = functools.partial(evaluate_radius, vehicle=vehicle, cant=cant,
                             cant_deficiency=cant_deficiency, direction=direction,
                             outputs=outputs, excitation=excitation,
                             creep_law=creep_law)  # fmt: skip
    return run_study([(i, (i, r)) for i, r in enumerate(radii)], task, meta,
                     label="stability map", run=options_run, warm_up=_warm_up)


def _describe(vehicle: Vehicle, radii: list[float], cant: float,
              cant_deficiency: float | None, direction: str, outputs: tuple[str, ...],
              excitation: object, creep_law: str,
              param_cols: list[str]) -> dict[str, Any]:  # fmt: skip
    """The study description (sidecar); its fingerprint decides whether a file resumes."""
    from railhunt._cache import source_hash
    from railhunt._version import __version__
    from railhunt.provenance import provenance, vehicle_block

    meta: dict[str, Any] = {
        "railhunt": __version__,
        "source": source_hash(),
        "study": "stability-map",
        "vehicle": vehicle_block(vehicle),
        "provenance": provenance(vehicle),
        "radii": [r if math.isfinite(r) else "inf" for r in radii],
        "direction": direction,
        "outputs": list(outputs),
        "creep_law": creep_law if creep_law is not None else vehicle.assembly.creep_laws[0],
        "points": len(radii),
        "parameter_columns": param_cols,
        "columns": columns_for(param_cols, outputs),
    }
    if cant_deficiency is None:
        meta["cant_m"] = float(cant)
    else:
        meta["cant_deficiency_m"] = float(cant_deficiency)
    if "critical_speed" in outputs:
        meta["excitation"] = repr(excitation)
    return meta
