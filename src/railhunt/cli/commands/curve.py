"""``railhunt curve``: steady curving in a constant curve, its stability, the curve entry."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.options import (
    CURVE_LEAD_IN,
    build_curve,
    build_vehicle,
    cant_option,
    check_outputs,
    curve_json,
    describe_curve,
    direction_option,
    file_option,
    number_range,
    overwrite_option,
    radius_option,
    transition_option,
    vehicle_options,
)
from railhunt.cli.output import announce, fmt, json_safe, spinner, stdout_console, traced
from railhunt.cli.rules import command

#: Track (m) the curve-entry run of ``--png`` covers past the end of the entry transition,
#: beyond the length of the vehicle: the wheelsets settle into the constant curve.
ENTRY_SETTLE = 100.0


@command("curve", short_help="Steady curving in a curve: wheel forces, Y/Q, stability.")
@radius_option("--radius", "radius", True, "Radius of the curve (m), at least 50 m.")
@cant_option("Cant of the curve (mm): height of the outer rail over the inner one over the "
             "1500 mm rail-centre distance, in [0, 500] mm [default: 0].")  # fmt: skip
@click.option("--speed", type=float, required=True, metavar="KMH",
              callback=number_range("km/h", 0.0, 1000.0), help="Forward speed (km/h).")
@transition_option("Length of the entry transition of the --png run (m) [default: R/10, "
                   "within 20-300 m]; the steady state does not depend on it.")
@direction_option("Which way the curve turns (left: toward +y; the results are mirror "
                  "images).")  # fmt: skip
@click.option("--json", "as_json", is_flag=True,
              help="Print the steady-curving state as JSON (SI units; speed in km/h).")
@file_option("--png", "png_file", "Draw the curve entry: a run through the entry transition "
             "into the constant curve (wheelset displacements, yaw damper forces against the "
             "blow-off force F_u, Y/Q of the leading wheelset).")  # fmt: skip
@overwrite_option
@vehicle_options
def curve_command(radius: float, cant_mm: float | None, speed: float, transition: float | None,
                  direction: str, as_json: bool, png_file: Path | None, overwrite: bool,
                  vehicle_file: Path | str | None, sets: dict[str, float]) -> None:  # fmt: skip
    """Steady curving of the vehicle in the constant part of a curve, and its stability.

    \b
    Solves the quasi-static equilibrium in the curve (every rate zero) on the
    model's own equations of motion and prints, per wheelset, the lateral
    displacement relative to the track and the angle of attack; per wheel the
    guiding force Y, the wheel load Q and the derailment quotient Y/Q; the sum
    of the guiding forces; the unbalanced lateral acceleration and cant
    deficiency; the car body and bogie offsets, the secondary lateral bump stop
    forces, and the stability of that state (the least damped eigenvalue and
    the hunting mode's frequency and damping ratio).

    \b
    Signs: lateral displacements + to the left (+y); in a curve to the left
    the outside is to the right. Y is + outward from the track centre on each
    wheel (a wheel pressing its flange against its rail has Y > 0); an angle
    of attack is + when the wheelset's front points toward the outer rail.
    """
    check_outputs(overwrite=overwrite, png=png_file)
    vehicle = build_vehicle(vehicle_file, sets)
    curve = build_curve(radius, cant_mm, transition, direction, start=CURVE_LEAD_IN)

    from railhunt import curving
    from railhunt.analysis.curving import CurvingError

    with spinner("solving the steady-curving equilibrium ..."), user_input():
        try:
            state = curving(vehicle, speed, curve)
        except CurvingError as exc:
            raise CliError(f"{exc} in the curve of --radius {radius:g} m") from None
    entry = None
    if png_file is not None:
        entry = _curve_entry(vehicle, speed, curve, png_file)
    if as_json:
        data = state.to_dict()
        data.update(vehicle=vehicle.name, curve=curve_json(curve),
                    balance_speed_kmh=_balance_kmh(curve, vehicle))  # fmt: skip
        if entry is not None:
            data["curve_entry"] = entry
        click.echo(json.dumps(json_safe(traced(data, vehicle)), indent=1))
        return
    _print_state(state, vehicle, curve)
    if entry is not None:
        peak = entry["peak_derailment_quotient_w1"]
        from railhunt.validity import YQ_LIMIT

        star = "*" if peak > YQ_LIMIT else ""
        click.echo(f"png: {png_file} (curve entry from {entry['start_m']:g} m, "
                   f"{entry['duration_s']:.2f} s: solver {entry['status']}; peak yaw damper "
                   f"force {entry['peak_damper_force_N'] * 1e-3:.2f} kN, blow-off force F_u "
                   f"{vehicle.blowoff_force * 1e-3:g} kN; peak Y/Q of the leading wheelset "
                   f"{peak:.3f}{star})")  # fmt: skip
        for warning in entry["warnings"]:
            click.echo(f"warning: curve entry: {warning}")


def _balance_kmh(curve: Any, vehicle: Any) -> float:
    from railhunt.units import ms_to_kmh

    return ms_to_kmh(curve.balance_speed(g=vehicle.gravity))


def _curve_entry(vehicle: Any, speed: float, curve: Any, png_file: Path) -> dict[str, Any]:
    """Simulate the run through the entry transition and draw it; its key numbers."""
    import numpy as np

    from railhunt import simulate
    from railhunt.plots import plot_curve_entry
    from railhunt.units import kmh_to_ms

    length = curve.start + curve.transition + vehicle.length + ENTRY_SETTLE
    duration = length / kmh_to_ms(speed)
    from railhunt import Model
    from railhunt.simulation import auto_step
    from railhunt.workload import workload

    with user_input("--set/--vehicle: "):
        step = auto_step(Model(vehicle), kmh_to_ms(speed))
    announce(workload(duration, step, f"the curve entry, {duration:.1f} s simulated"), vehicle,
             kmh_to_ms(speed))  # fmt: skip
    with spinner(f"simulating the curve entry ({duration:.1f} s) ..."), user_input():
        run = simulate(vehicle, speed, duration=duration, curve=curve)
    with spinner("plotting ..."), user_input("cannot write --png: "):
        plot_curve_entry(run, vehicle, png_file, curve=curve)
    forces = np.abs(np.column_stack([run[f"F_{d}"] for d in run.layout.dampers]
                                    or [np.zeros(run.t.size)]))  # fmt: skip
    yq = np.abs(np.column_stack([run["YQ_w1L"], run["YQ_w1R"]]))
    peak = float(yq.max())
    warnings = entry_warnings(curve, peak) + list(run.warnings)
    return {"start_m": curve.start, "transition_m": curve.transition, "duration_s": duration,
            "status": run.status, "peak_damper_force_N": float(forces.max()),
            "peak_derailment_quotient_w1": peak, "warnings": warnings,
            "png": str(png_file)}  # fmt: skip


def entry_warnings(curve: Any, peak_yq: float) -> list[str]:
    """What a run through a curve entry must be read with beyond its limits: a curve
    without a transition (its curvature and cant jump: the entry is a kink in the track),
    and a peak Y/Q beyond Nadal's 0.8 in a single sample (EN 14363 judges the 2 m sliding
    mean, which the run's limits report)."""
    from railhunt.validity import YQ_LIMIT

    out = []
    if curve.transition == 0.0:
        out.append("--transition 0: the curvature and the cant jump at the curve's start, "
                   "an entry without a transition (a kink in the track); its forces are an "
                   "impact no track gives, give a transition of 20 m or more")  # fmt: skip
    if peak_yq > YQ_LIMIT:
        out.append(f"peak Y/Q {peak_yq:.3g} beyond {YQ_LIMIT:g} (EN 14363's Nadal limit) in a "
                   "single sample; EN 14363 judges its 2 m sliding mean")  # fmt: skip
    return out


def _print_state(state: Any, vehicle: Any, curve: Any) -> None:
    """The steady-curving table and its summary lines."""
    from rich.table import Table

    table = Table(title=f"steady curving of {vehicle.name} at {state.speed_kmh:g} km/h: "
                  f"{describe_curve(curve, transition=False)}")  # fmt: skip
    heads = ("wheelset", "y (mm)", "attack (mrad)", "ΣY (kN)", "wheel", "Y (kN)", "Q (kN)",
             "Y/Q")  # fmt: skip
    for head in heads:
        table.add_column(head, justify="left" if head == "wheel" else "right")
    for j in range(state.wheelset_y.size):
        for k, side in enumerate(("left", "right")):
            first = (str(j + 1), f"{state.wheelset_y[j] * 1e3:.3f}",
                     f"{state.attack_angle[j] * 1e3:.3f}", f"{state.sum_Y[j] * 1e-3:.2f}")
            table.add_row(*(first if k == 0 else ("",) * 4), side,
                          f"{state.Y[j, k] * 1e-3:.2f}", f"{state.Q[j, k] * 1e-3:.2f}",
                          _marked(state.derailment_quotient[j, k]),
                          end_section=k == 1)  # fmt: skip
    out = stdout_console()
    out.print(table)
    deficit = state.cant_deficiency
    what = "cant deficiency" if deficit >= 0 else "cant excess"
    out.print(f"unbalanced acceleration: {state.unbalanced_acceleration:.3f} m/s^2, {what} "
              f"{abs(deficit) * 1e3:.1f} mm (balance speed "
              f"{_balance_kmh(curve, vehicle):.1f} km/h)")  # fmt: skip
    bogies = ", ".join(f"{y * 1e3:.2f}" for y in state.bogie_y) or "(none)"
    out.print(f"offsets relative to the track: car body {state.car_body_y * 1e3:.2f} mm, "
              f"bogies {bogies} mm")  # fmt: skip
    stops = ", ".join(f"{f * 1e-3:.2f}" for f in state.bump_stop_force)
    gaps = ", ".join(sorted({f"{g * 1e3:g}" for g in vehicle.assembly.stop[:, 0]}))
    if stops:
        what = ("secondary lateral bump stops" if (vehicle.assembly.stop_track < 0).all()
                else "stops and flange contacts")  # fmt: skip
        out.print(f"{what}: {stops} kN (free play {gaps} mm)")
    verdict = "[green]stable[/green]" if state.stable else "[red]unstable[/red]"
    out.print(f"stability of this state: {verdict}, least damping ratio "
              f"{state.least_damping_ratio:.4f}; hunting mode "
              f"{fmt(state.hunting_frequency_hz, '.2f', 'Hz')}, damping ratio "
              f"{fmt(state.hunting_damping_ratio, '.4f')}")  # fmt: skip
    for warning in state.warnings:
        out.print(f"[yellow]warning: {warning}[/yellow]")


def _marked(yq: float) -> str:
    """A Y/Q cell, red and starred beyond Nadal's 0.8 (EN 14363)."""
    from railhunt.validity import YQ_LIMIT

    return f"[red]{yq:.3f}*[/red]" if yq > YQ_LIMIT else f"{yq:.3f}"


def print_run_in_curve(run: Any, vehicle: Any, curve: Any) -> None:
    """The lines ``railhunt simulate`` adds for a run through a curve: where the curve is,
    where the run ends relative to the track, the peak yaw damper force and Y/Q."""
    import numpy as np

    from railhunt.units import kmh_to_ms

    full = curve.curve_start()
    reach = full / kmh_to_ms(run.speed_kmh)
    where = (f"the leading wheelset there at {reach:.2f} s" if run.t[-1] >= reach else
             "not reached: the run ended before, give a longer --duration")  # fmt: skip
    click.echo(f"curve:      {describe_curve(curve)}; entry from {curve.start:g} m, constant "
               f"curve from {full:g} m ({where})")  # fmt: skip
    forces = np.abs(np.column_stack([run[f"F_{d}"] for d in run.layout.dampers]
                                    or [np.zeros(run.t.size)]))  # fmt: skip
    names = [f"{b.tag}{side}" for b in run.layout.bodies if b.is_wheelset for side in "LR"]
    yq = np.abs(np.column_stack([run[f"YQ_{n}"] for n in names]))
    k = int(np.argmax(yq.max(axis=0)))
    click.echo(f"in curve:   y_w1 at the end {run['y_w1'][-1] * 1e3:.3f} mm relative to the "
               f"track; peak yaw damper force {forces.max() * 1e-3:.2f} kN (F_u "
               f"{vehicle.blowoff_force * 1e-3:g} kN); peak |Y/Q| {yq[:, k].max():.3f} "
               f"({names[k]})")  # fmt: skip
    for warning in entry_warnings(curve, float(yq[:, k].max())):
        click.echo(f"warning:    {warning}")
