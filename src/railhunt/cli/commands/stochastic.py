"""``railhunt critical-speed --method stochastic``: the run and its report.

The options and their rules live with the ``critical-speed`` command in
:mod:`railhunt.cli.commands.critical_speed`; this module builds the irregular track, runs
:func:`railhunt.stochastic_critical_speed` and prints the table or the JSON object.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import user_input
from railhunt.cli.options import measured_track
from railhunt.cli.output import (
    announce,
    json_safe,
    linear_critical_speed_line,
    print_warnings,
    stdout_console,
    traced,
    trial_progress,
)


def report_stochastic_critical_speed(
    vehicle: Any,
    spectrum: str,
    seed: int,
    track_length: float,
    irregularity_file: Path | None,
    start_kmh: float,
    step_kmh: float,
    tol_kmh: float,
    dt: float | None,
    as_json: bool,
    verbose: bool = False,
) -> None:
    """Run the stochastic critical-speed search and report it (table or JSON).

    Parameters
    ----------
    vehicle : Vehicle
        The vehicle of ``--vehicle``/``--set``.
    spectrum, seed, track_length : str, int, float
        The random track (``--spectrum``, ``--seed``, ``--track-length`` in m), unless
        ``irregularity_file`` gives a measured one.
    irregularity_file : Path or None
        ``--irregularity``: CSV of a measured alignment.
    start_kmh, step_kmh, tol_kmh : float
        First trial speed, bracketing step and bisection resolution (km/h).
    dt : float or None
        Time step of the rk4 integrator (s); None: chosen from the model.
    as_json : bool
        Print one JSON object instead of the table.
    verbose : bool
        ``--verbose``: every limit of every run, one line each, below the summaries.
    """
    from railhunt import linear_critical_speed, stochastic_critical_speed, track_irregularity
    from railhunt.analysis.stochastic import acceleration_limit, bogie_mass, sum_y_limit

    with user_input("--irregularity: " if irregularity_file else "--spectrum: "):
        if irregularity_file is not None:
            track = measured_track(irregularity_file)
        else:
            track = track_irregularity(spectrum, length=track_length, seed=seed)
    _announce_runs(vehicle, track.length, start_kmh, step_kmh, tol_kmh, dt)
    with trial_progress("stochastic critical speed", count=False) as on_trial, user_input():
        result = stochastic_critical_speed(
            vehicle, irregularity=track, start_kmh=start_kmh, step_kmh=step_kmh,
            tol_kmh=tol_kmh, dt=dt, progress=on_trial,
        )  # fmt: skip
        on_trial(None)
        linear = linear_critical_speed(vehicle)

    if irregularity_file is not None:
        described = f"measured alignment {irregularity_file}"
    else:
        described = f"{spectrum} spectrum, seed {seed}"
    described += f", {track.length:g} m, rms {track.rms * 1e3:.2f} mm"
    if as_json:
        data = {
            "method": "stochastic",
            "stochastic_critical_speed_kmh": result.speed_kmh,
            "highest_stable_speed_kmh": result.highest_stable_kmh,
            "linear_critical_speed_kmh": linear.speed_kmh,
            "linear_hunting_frequency_hz": linear.frequency_hz,
            "linear_crossing_is_hunting_mode": bool(linear.is_hunting_mode),
            "bracketed": bool(result.bracketed),
            "tol_kmh": tol_kmh,
            "warnings": result.warnings,
            "limit_summary": [s.to_dict() for s in result.limit_summary],
            "details": result.details,
            "limits": [lim.to_dict() for lim in result.limits],
            "vehicle": vehicle.name,
            "irregularity": {
                "spectrum": getattr(track, "spectrum", "measured"),
                "seed": getattr(track, "seed", None),
                "file": None if irregularity_file is None else str(irregularity_file),
                "length_m": track.length,
                "rms_mm": track.rms * 1e3,
                "band_m": list(getattr(track, "band", (math.nan, math.nan))),
            },
            "criterion": {
                "window_m": 100.0,
                "step_m": 10.0,
                "half_band_hz": 2.0,
                "sum_y_limit_kn": sum_y_limit(vehicle) / 1e3,
                "acceleration_limit_m_s2": acceleration_limit(vehicle),
                "static_wheel_load_kn": vehicle.N / 1e3,
                "bogie_mass_t": bogie_mass(vehicle) / 1e3,
            },
            "trials": [
                {
                    "speed_kmh": a.speed_kmh,
                    "verdict": a.verdict,
                    "f0_hz": a.f0_hz,
                    "sum_y_rms_max_kn": float(a.sum_y_rms.max()) / 1e3 if a.sum_y_rms.size
                    else None,
                    "sum_y_ratio": a.sum_y_ratio,
                    "acceleration_rms_max_m_s2": float(a.acceleration_rms.max())
                    if a.acceleration_rms.size else None,
                    "acceleration_ratio": a.acceleration_ratio,
                    "status": a.status,
                    "limits": [lim.to_dict() for lim in a.limits],
                }
                for a in result.trials
            ],
        }  # fmt: skip
        click.echo(json.dumps(json_safe(traced(data, vehicle)), allow_nan=False))
        return

    from rich.table import Table

    table = Table(title=f"stochastic critical speed trials of {vehicle.name} ({described})")
    heads = ("#", "speed (km/h)", "verdict", "f0 (Hz)", "ΣY rms (kN)", "ΣY / limit",
             "ÿ+ rms (m/s²)", "ÿ+ / limit", "note")  # fmt: skip
    for head in heads:
        table.add_column(head, justify="left" if head in ("verdict", "note") else "right")
    for i, a in enumerate(result.trials, 1):
        table.add_row(
            str(i), f"{a.speed_kmh:g}", a.verdict, f"{a.f0_hz:.2f}",
            f"{a.sum_y_rms.max() / 1e3:.2f}" if a.sum_y_rms.size else "n/a",
            f"{a.sum_y_ratio:.2f}",
            f"{a.acceleration_rms.max():.2f}" if a.acceleration_rms.size else "n/a",
            f"{a.acceleration_ratio:.2f}", "" if a.status == "ok" else a.status,
            style="red" if a.unstable else "green",
        )  # fmt: skip
    console = stdout_console()
    console.print(table)
    console.print(
        f"limits: ΣY rms {sum_y_limit(vehicle) / 1e3:.2f} kN (static wheel load "
        f"{vehicle.N / 1e3:.2f} kN), bogie frame ÿ+ rms {acceleration_limit(vehicle):.2f} m/s² "
        f"(bogie mass {bogie_mass(vehicle) / 1e3:.2f} t); 100 m sliding rms, f0 ± 2 Hz"
    )
    if result.bracketed:
        console.print(
            f"stochastic critical speed: {result.speed_kmh:g} km/h (lowest speed breaking "
            f"the criterion; criterion met at {result.highest_stable_kmh:g} km/h, resolution "
            f"{tol_kmh:g} km/h)"
        )
    else:
        verdicts = {a.verdict for a in result.trials}
        why = ("every trial speed up to 800 km/h met the criterion" if verdicts == {"stable"}
               else "every trial speed down to 20 km/h broke the criterion")  # fmt: skip
        console.print(f"stochastic critical speed: not found ({why})")
    console.print(linear_critical_speed_line(linear))
    print_warnings(console, result, verbose)


def _announce_runs(vehicle: Any, length: float, start_kmh: float, step_kmh: float,
                   tol_kmh: float, dt: float | None) -> None:  # fmt: skip
    """Refuse a stiff damper's step, and announce a search of more than a minute."""
    from railhunt import Model
    from railhunt.simulation import auto_step
    from railhunt.units import kmh_to_ms
    from railhunt.workload import workload

    with user_input("--set/--vehicle: "):
        step = dt if dt is not None else auto_step(Model(vehicle), kmh_to_ms(start_kmh))
    trials = 3 + math.ceil(math.log2(max(step_kmh / tol_kmh, 1.0)))
    per_trial = length / kmh_to_ms(start_kmh)
    announce(workload(trials * per_trial, step, f"~{trials} runs of {per_trial:.0f} s over "
                      f"{length:g} m of track"), vehicle, kmh_to_ms(start_kmh))  # fmt: skip
