"""``railhunt vehicles`` (the shipped vehicles, one line each with its source) and
``railhunt vehicle NAME|FILE`` (one vehicle's layout: bodies, elements, a picture)."""

from __future__ import annotations

from pathlib import Path

import click

from railhunt.cli.errors import user_input
from railhunt.cli.options import check_outputs, file_option, overwrite_option
from railhunt.cli.output import spinner, stdout_console
from railhunt.cli.rules import command


def _shipped_lines() -> list[tuple[str, str, str]]:
    """``(name, description, source)`` of every shipped vehicle, read from its file's
    ``[vehicle]`` table (no model is built)."""
    import tomllib

    from railhunt.vehicle import shipped_vehicles
    from railhunt.vehicle.files import shipped_path

    out = []
    for name in shipped_vehicles():
        meta = tomllib.loads(shipped_path(name).read_text(encoding="utf-8")).get("vehicle", {})
        out.append((name, str(meta.get("description", "")),
                    str(meta.get("source", "see its parameters' sources"))))  # fmt: skip
    return out


@command("vehicles", short_help="List the shipped vehicles, one line each with its source.")
def vehicles_command() -> None:
    """List the vehicles shipped with railhunt: name, description and source.

    \b
    Each name works as --vehicle NAME in every command, as [vehicle] base = NAME
    in a vehicle file, and as 'railhunt vehicle NAME --png FILE' for a picture
    of its layout. 'railhunt parameters --vehicle NAME' lists its parameters
    with their units, meanings and sources.
    """
    for name, description, source in _shipped_lines():
        click.echo(f"{name}: {description} (source: {source})")


def _resolve(value: str) -> object:
    """The vehicle of ``NAME|FILE``: a file that exists, else a shipped vehicle's name."""
    from railhunt import Vehicle, load_vehicle
    from railhunt.vehicle import shipped_vehicles

    path = Path(value)
    if path.is_file():
        with user_input():
            return load_vehicle(path)
    names = shipped_vehicles()
    if value not in names:
        raise click.BadParameter(
            f"{value!r} is neither a file nor a shipped vehicle ({', '.join(names)})",
            param_hint="'NAME|FILE'",
        )
    with user_input():
        return Vehicle.shipped(value)


@command("vehicle", short_help="One vehicle's layout: bodies, elements, plan and side view.")
@click.argument("source", metavar="NAME|FILE")
@file_option("--png", "png_file", "Draw the layout: plan and side view, bodies where they "
             "sit, elements as symbols at their attachment points, wheelsets on their rails.")
@overwrite_option
def vehicle_command(source: str, png_file: Path | None, overwrite: bool) -> None:
    """The layout of one vehicle (a shipped NAME or a layout FILE).

    \b
    Prints its bodies (kind, position x and height of the centre of gravity,
    coordinates), how many force elements of each kind join them, and its
    numbers of coordinates, wheelsets and yaw dampers. With --png it draws
    the layout in plan and side view.
    """
    check_outputs(overwrite=overwrite, png=png_file)
    vehicle = _resolve(source)
    from rich.table import Table

    from railhunt.model import Model

    with user_input():
        model = Model(vehicle)
    spec = vehicle.layout
    values = vehicle.as_dict()
    table = Table(title=f"{vehicle.name}: {vehicle.description}")
    for head in ("body", "kind", "x (m)", "height (m)", "coordinates"):
        table.add_column(head, justify="right" if "(m)" in head else "left")
    for b in spec.bodies:
        table.add_row(b.name, b.kind, f"{b.x(values):.3f}", f"{b.height(values):.3f}",
                      ", ".join(b.coordinates) or "(moves with the track)")  # fmt: skip
    console = stdout_console()
    console.print(table)
    kinds: dict[str, int] = {}
    for el in spec.elements:
        key = f"{el.kind} to the track" if el.body_b == "track" else el.kind
        kinds[key] = kinds.get(key, 0) + 1
    console.print("elements: " + ", ".join(f"{n} {k}" for k, n in kinds.items()))
    layout = model.layout
    console.print(f"{layout.n_dof} coordinates, {len(layout.wheelsets)} wheelsets, "
                  f"{layout.n_damper} yaw dampers (state of {layout.n_state})")  # fmt: skip
    if png_file is not None:
        from railhunt.plots.layout import plot_layout

        with spinner("plotting ..."), user_input("cannot write --png: "):
            plot_layout(vehicle, png_file)
        click.echo(f"png: {png_file}")
