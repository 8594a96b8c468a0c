"""``railhunt frequency``: hunting frequency versus speed and its jump (Figs. 7b, 8)."""

from __future__ import annotations

import json
from pathlib import Path

import click

from railhunt.cli.errors import user_input
from railhunt.cli.options import (
    build_vehicle,
    check_outputs,
    file_option,
    initial_amplitude_option,
    kmh_option,
    overwrite_option,
    speed_count,
    vehicle_options,
)
from railhunt.cli.output import announce, fmt, json_safe, spinner, stdout_console, traced
from railhunt.cli.rules import command


@command("frequency", short_help="Hunting frequency vs speed (eigenvalue, then limit cycle).")
@kmh_option("--from", "from_kmh", 250.0, 1000.0, "Lowest speed (km/h).")
@kmh_option("--to", "to_kmh", 450.0, 1000.0, "Highest speed (km/h).")
@kmh_option("--step", "step_kmh", 10.0, 1000.0, "Speed step (km/h).")
@initial_amplitude_option("Initial lateral displacement of every wheelset (mm).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON on stdout.")
@file_option("--png", "png_file", "Draw frequency vs speed like the paper's Fig. 7b, the jump "
             "dashed.")
@file_option("--damper-png", "damper_png", "Draw, like the paper's Fig. 8, the leading "
             "wheelset's displacement and a yaw damper's velocity against the blow-off velocity "
             "at the first speed with a limit cycle.")
@overwrite_option
@vehicle_options
def frequency_command(from_kmh: float, to_kmh: float, step_kmh: float, initial_mm: float,
                      as_json: bool, png_file: Path | None, damper_png: Path | None,
                      overwrite: bool, vehicle_file: Path | None,
                      sets: dict[str, float]) -> None:  # fmt: skip
    """Hunting frequency of the leading wheelset versus speed (Hz).

    \b
    At each speed the vehicle is released from an initial lateral displacement
    of its wheelsets on ideal track. Where the motion decays, the frequency is
    that of the hunting eigenvalue; where it grows to a limit cycle, that of the
    cycle (FFT of the displacement after the transient, refined by shooting the
    periodic orbit). The switch between the two is the paper's frequency jump.
    """
    check_outputs(overwrite=overwrite, png=png_file, **{"damper-png": damper_png})
    n = speed_count(from_kmh, to_kmh, step_kmh, 500)
    vehicle = build_vehicle(vehicle_file, sets)
    import numpy as np

    from railhunt import Model, hunting_frequency
    from railhunt.analysis.frequency import frequency_jump, frequency_kind
    from railhunt.simulation import auto_step
    from railhunt.units import kmh_to_ms
    from railhunt.workload import SIMULATED_SECONDS, workload

    model = Model(vehicle)
    with user_input("--set/--vehicle: "):
        dt = auto_step(model, kmh_to_ms(to_kmh))
    announce(workload(n * SIMULATED_SECONDS["frequency speed"], dt, f"{n} speeds"), vehicle,
             kmh_to_ms(to_kmh))  # fmt: skip
    speeds = from_kmh + step_kmh * np.arange(n)
    results = []
    with spinner("simulating speeds"):
        for s in speeds:
            results.append(hunting_frequency(vehicle, float(s), initial_mm * 1e-3, model=model))
    freqs = np.array([r.frequency_hz for r in results])
    sources = [frequency_kind(r.source) for r in results]
    jump = frequency_jump(speeds, freqs, sources)
    if png_file is not None:
        from railhunt.plots import plot_hunting_frequency

        plot_hunting_frequency(speeds, freqs, sources, png_file, initial_mm * 1e-3)
    if damper_png is not None:
        from railhunt.plots import plot_damper_velocity

        pick = next((r for r in results if frequency_kind(r.source) == "limit-cycle"), None)
        title = None if pick is None else f"{pick.speed_kmh:g} km/h, {pick.verdict}"
        if pick is None:  # say so, in the figure and here, instead of a quiet stable run
            pick = results[-1]
            title = (f"no limit cycle in {speeds[0]:g}-{speeds[-1]:g} km/h: shown is the "
                     f"highest speed, {pick.speed_kmh:g} km/h, {pick.verdict}")  # fmt: skip
            click.echo(f"railhunt: note: --damper-png: {title}", err=True)
        plot_damper_velocity(pick.t, pick.y, pick.damper_velocity, pick.blowoff_velocity,
                             damper_png, title)  # fmt: skip
    if as_json:
        data = {
            "vehicle": vehicle.name,
            "initial_amplitude_mm": initial_mm,
            "jump": None if jump is None else {"speed_kmh": jump[0], "from_hz": jump[1],
                                               "to_hz": jump[2]},
            "points": [r.to_dict() for r in results],
        }  # fmt: skip
        click.echo(json.dumps(json_safe(traced(data, vehicle)), indent=2))
        return
    from rich.table import Table

    table = Table(title=f"hunting frequency of {vehicle.name}, {initial_mm:g} mm release")
    for head in ("speed (km/h)", "frequency (Hz)", "from", "amplitude (mm)", "eigen f (Hz)"):
        table.add_column(head, justify="right")
    for r in results:
        table.add_row(f"{r.speed_kmh:g}", fmt(r.frequency_hz, ".3f"), r.source,
                      fmt(r.amplitude * 1e3, ".2f"),
                      fmt(r.eigen_frequency_hz, ".3f"))  # fmt: skip
    out = stdout_console()
    out.print(table)
    if jump is None:
        out.print("no frequency jump in this speed range")
    else:
        out.print(f"frequency jump near {jump[0]:.1f} km/h: {jump[1]:.2f} Hz -> {jump[2]:.2f} Hz")
    for f in (png_file, damper_png):
        if f is not None:
            out.print(f"wrote {f}")
