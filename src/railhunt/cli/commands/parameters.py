"""``railhunt parameters``: the vehicle parameters, their SI values, units and meaning."""

from __future__ import annotations

from pathlib import Path

from railhunt.cli.options import build_vehicle, vehicle_options
from railhunt.cli.output import stdout_console
from railhunt.cli.rules import command


@command("parameters", short_help="List the vehicle parameters, values and SI units.")
@vehicle_options
def parameters_command(vehicle_file: Path | None, sets: dict[str, float]) -> None:
    """List the vehicle parameters (name, SI value, unit, meaning, source).

    These are the names accepted by --set NAME=VALUE and in vehicle TOML files;
    values are in the SI unit shown. The source says where each value comes
    from, as the vehicle's file says ('--set' for a value changed on the
    command line). The derived v_u and N are listed last and cannot be set.
    """
    vehicle = build_vehicle(vehicle_file, sets)
    from rich.table import Table

    table = Table(title=f"parameters of {vehicle.name} (SI units)")
    for head in ("name", "value", "unit", "meaning", "source"):
        table.add_column(head, justify="right" if head == "value" else "left")
    for name, value, unit, meaning in vehicle.parameter_table(include_derived=True):
        style = "bold" if name in sets else None
        source = "--set" if name in sets else vehicle.source(name)
        if name not in vehicle.values:
            source = "derived"
        table.add_row(name, f"{value:.6g}", unit, meaning, source, style=style)
    stdout_console().print(table)
