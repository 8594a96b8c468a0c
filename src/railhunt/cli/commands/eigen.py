"""``railhunt eigen``: the hunting mode of the linearised model versus speed."""

from __future__ import annotations

import math
from pathlib import Path

import click

from railhunt.cli.errors import user_input
from railhunt.cli.options import (
    build_vehicle,
    check_outputs,
    file_option,
    kmh_option,
    overwrite_option,
    speed_count,
    vehicle_options,
    write_sidecar,
)
from railhunt.cli.output import command_record, linear_critical_speed_line, spinner, stdout_console
from railhunt.cli.rules import command


@command("eigen",
         short_help="Damping and frequency of the hunting mode vs speed (linearised model).")
@kmh_option("--from", "from_kmh", 50.0, 1000.0, "Lowest speed (km/h).")
@kmh_option("--to", "to_kmh", 500.0, 1000.0, "Highest speed (km/h).")
@kmh_option("--step", "step_kmh", 10.0, 1000.0, "Speed step (km/h).")
@file_option("--png", "png_file", "Plot the root locus (eigenvalues coloured by speed, hunting "
             "mode highlighted) and the hunting damping ratio vs speed.")  # fmt: skip
@file_option("--csv", "csv_file", "Write the hunting-mode table (one row per speed).")
@file_option("--mode-png", "mode_png_file", "Draw the hunting mode's shape at the Hopf point "
             "(plan view: each body's lateral and yaw motion over a period), for any layout.")
@overwrite_option
@vehicle_options
def eigen_command(
    from_kmh: float,
    to_kmh: float,
    step_kmh: float,
    png_file: Path | None,
    csv_file: Path | None,
    mode_png_file: Path | None,
    overwrite: bool,
    vehicle_file: Path | None,
    sets: dict[str, float],
) -> None:
    """Hunting mode of the linearised model versus speed.

    \b
    Linearises the model about the centred equilibrium on ideal track and
    computes its eigenvalues at each speed (two per coordinate and one per
    yaw damper force; 'railhunt vehicle NAME' counts them). The hunting mode
    is the least damped oscillation dominated by wheelset lateral/yaw motion;
    its frequency (Hz) rises with speed and its damping ratio falls. Where the
    damping ratio crosses zero is the linear critical speed (Hopf point):
    above it even a tiny disturbance grows. Prints a table of hunting frequency (Hz) and
    damping ratio (%) vs speed (km/h) and the linear critical speed.
    """
    check_outputs(overwrite=overwrite, csv=csv_file, png=png_file, mode_png=mode_png_file)
    n = speed_count(from_kmh, to_kmh, step_kmh, 5000)
    vehicle = build_vehicle(vehicle_file, sets)

    import numpy as np

    from railhunt import eigen_analysis, linear_critical_speed

    speeds = from_kmh + step_kmh * np.arange(n)
    with spinner(f"eigenvalues at {n} speeds ..."), user_input():
        res = eigen_analysis(vehicle, speeds)
        linear = linear_critical_speed(vehicle)

    from rich.table import Table

    table = Table(title=f"hunting mode of {vehicle.name} (linearised)")
    for head in ("speed (km/h)", "frequency (Hz)", "damping ratio (%)", "Re λ (1/s)"):
        table.add_column(head, justify="right")
    zeta = res.hunting_damping_ratio
    for s, f, z, lam in zip(speeds, res.hunting_frequency_hz, zeta, res.hunting, strict=True):
        style = "red" if z < 0 else None
        table.add_row(f"{s:g}", f"{f:.3f}", f"{100 * z:.2f}", f"{lam.real:.3f}", style=style)
    console = stdout_console()
    console.print(table)
    console.print(linear_critical_speed_line(linear))

    if csv_file is not None:
        header = (
            "speed_kmh,hunting_frequency_hz,hunting_damping_ratio,"
            "hunting_real_per_s,hunting_imag_per_s,max_real_part_per_s"
        )
        data = np.column_stack(
            [
                speeds,
                res.hunting_frequency_hz,
                zeta,
                res.hunting.real,
                res.hunting.imag,
                res.eigenvalues.real.max(axis=1),
            ]
        )
        with user_input("cannot write --csv: "):
            np.savetxt(csv_file, data, delimiter=",", header=header, comments="", fmt="%.9g")
            from railhunt.provenance import provenance

            write_sidecar(csv_file, provenance(vehicle), **command_record(),
                          columns=header.split(","))  # fmt: skip
        click.echo(f"csv: {csv_file}")
    if png_file is not None:
        from railhunt.plots import plot_root_locus

        with spinner("plotting ..."), user_input("cannot write --png: "):
            plot_root_locus(res, png_file, linear=linear)
        click.echo(f"png: {png_file}")
    if mode_png_file is not None:
        from railhunt.plots.layout import plot_hunting_mode

        if not math.isfinite(linear.speed_kmh):
            raise click.UsageError("--mode-png: no Hopf point between 20 and 1000 km/h")
        with spinner("plotting the mode ..."), user_input("cannot write --mode-png: "):
            plot_hunting_mode(vehicle, mode_png_file, linear.speed_kmh)
        click.echo(f"mode png: {mode_png_file}")
