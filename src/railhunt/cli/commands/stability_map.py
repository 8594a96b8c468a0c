"""``railhunt stability-map``: linear and nonlinear critical speed against the curve radius."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.options import (
    build_vehicle,
    cant_option,
    file_option,
    number_range,
    vehicle_options,
)
from railhunt.cli.output import (
    command_record,
    fmt,
    json_safe,
    stdout_console,
    traced,
)
from railhunt.cli.rules import Excludes, command
from railhunt.cli.study import (
    STUDY_RULES,
    announce_study,
    check_study_outputs,
    check_workers_option,
    optional_out_rules,
    report_lost,
    running_study,
    scheduler_client,
    study_options,
    study_run,
)
from railhunt.verdicts import verdict_help

_HELP = """\
Linear and nonlinear critical speed of the vehicle against the curve radius.

\b
For each radius of --radius (m; 'inf' for straight track) the vehicle runs
in the constant part of a curve with the cant of --cant (mm), or with a cant
that keeps the cant deficiency of --cant-deficiency (mm) at every speed.
Linear critical speed: where the steady-curving equilibrium, followed along
the speed, loses stability (Hopf point). Nonlinear critical speed: the
paper's bisection, each trial run starting on the curving equilibrium over
an 8 mm x 20 m defect inside the curve, judged by the leading wheelset's
distance from that equilibrium.

\b
The radii run in parallel on all cores (a local Dask cluster) or on a Dask
cluster (--scheduler). With --out each radius is written to FILE as it
finishes; after Ctrl-C or a lost worker, the same command with --resume
computes only the missing radii.

\b
Examples:
  railhunt stability-map --radius 1000,2000,4000,8000,inf --cant 150 --png map.png
  railhunt stability-map --radius 2000,4000,inf --cant-deficiency 100 --json
  railhunt stability-map --radius 2000,4000,8000,inf --cant 150 --out map.csv --resume
"""

RULES = (
    *STUDY_RULES,
    *optional_out_rules(),
    Excludes("--cant", "--cant-deficiency",
             "{a} and {b} exclude each other: give a fixed cant, or the cant deficiency to "
             "keep at every speed"),
)  # fmt: skip

def _parse_radii(ctx: click.Context, param: click.Parameter, value: str) -> list[float]:
    """``--radius 1000,2000,inf``: radii in m, each at least 50 m or 'inf', none twice."""
    radii: list[float] = []
    for item in value.split(","):
        item = item.strip()
        try:
            radius = float(item)
        except ValueError:
            radius = math.nan
        if not (radius == math.inf or (math.isfinite(radius) and radius >= 50.0)):
            raise click.BadParameter(f"{item!r} is not a valid radius: each must be a number "
                                     "of m in [50, inf), or 'inf' for straight track")
        if radius in radii:
            raise click.BadParameter(f"{item} m is given twice")
        radii.append(radius)
    return radii


@command("stability-map", rules=RULES, epilog=verdict_help(), help=_HELP,
         short_help="Critical speeds against the curve radius (stability map).")
@click.option("--radius", "radii", required=True, metavar="M,M,...", callback=_parse_radii,
              help="Curve radii (m), comma-separated, each at least 50 m; 'inf' for straight "
              "track.")  # fmt: skip
@cant_option("Cant of every curve (mm), in [0, 500] mm over the 1500 mm rail-centre distance "
             "[default: 0].")  # fmt: skip
@click.option("--cant-deficiency", "deficiency_mm", type=float, metavar="MM",
              callback=number_range("mm", -500.0, 500.0, low_open=False, optional=True),
              help="Instead of a fixed cant: the cant deficiency (mm, in [-500, 500] mm) kept "
              "at every speed; the cant follows the speed (held within [0, 500] mm).")
@click.option("--outputs", default="linear_critical_speed,critical_speed", show_default=True,
              metavar="LIST",
              help="Comma-separated outputs per radius.")
@file_option("--png", "png_file", "Draw the stability map (critical speeds against the radius, "
             "straight track at the right edge; with a fixed cant, the speed at which the "
             "cant deficiency reaches 150 mm dashed).")  # fmt: skip
@file_option("--csv", "csv_file", "Write the table (one row per radius; SI, speeds in km/h).")
@click.option("--json", "as_json", is_flag=True, help="Print a JSON summary instead of a table.")
@study_options(out_required=False,
               out_help="Results file written radius by radius (.csv, or .parquet with "
               "pyarrow), which --resume continues.")  # fmt: skip
@vehicle_options
def stability_map_command(radii: list[float], cant_mm: float | None,
                          deficiency_mm: float | None, outputs: str, png_file: Path | None,
                          csv_file: Path | None, as_json: bool, out: Path | None,
                          resume: bool, overwrite: bool, workers: int | None,
                          scheduler: str | None, connect_timeout: float,
                          vehicle_file: Path | str | None,
                          sets: dict[str, float]) -> None:  # fmt: skip
    """``railhunt stability-map`` (help text: ``_HELP``)."""
    from railhunt.studies.stability_map import MAP_OUTPUTS

    check_workers_option(workers)
    chosen = tuple(dict.fromkeys(o.strip() for o in outputs.split(",") if o.strip()))
    if not chosen or any(o not in MAP_OUTPUTS for o in chosen):
        raise CliError(f"--outputs {outputs}: choose from {', '.join(MAP_OUTPUTS)}")
    check_study_outputs(out, resume, overwrite, png=png_file, csv=csv_file)
    vehicle = build_vehicle(vehicle_file, sets)

    from railhunt import stability_map

    cant = (cant_mm or 0.0) * 1e-3
    deficiency = None if deficiency_mm is None else deficiency_mm * 1e-3
    from railhunt.studies.design import Point

    announce_study(vehicle, [Point(i, "radius", {}) for i in range(len(radii))], chosen,
                   workers, scheduler, what="radii")  # fmt: skip
    with running_study(out, points="radii"), \
            scheduler_client(scheduler, connect_timeout) as client:  # fmt: skip
        result = stability_map(vehicle, radii, cant, cant_deficiency=deficiency,
                               outputs=chosen,
                               run=study_run(out, resume, overwrite, workers,
                                             client))  # fmt: skip
    if csv_file is not None:
        with user_input("cannot write --csv: "):
            csv_file.write_text(result.to_csv_text(), encoding="utf-8")
            from railhunt.cli.options import write_sidecar
            from railhunt.provenance import provenance

            write_sidecar(csv_file, provenance(vehicle), **command_record(),
                          columns=result.columns)  # fmt: skip
    if png_file is not None and result.rows:
        from railhunt.plots import plot_stability_map

        with user_input("cannot write --png: "):
            plot_stability_map(result, png_file)
    if as_json:
        held = ({"cant_mm": cant * 1e3} if deficiency is None
                else {"cant_deficiency_mm": deficiency * 1e3})  # fmt: skip
        rows = [{**row, "straight_track": row["radius_m"] == math.inf} for row in result.rows]
        click.echo(json.dumps(json_safe(traced({
            "vehicle": vehicle.name, **held, "outputs": list(chosen),
            "file": None if out is None else str(out), "points": len(radii),
            "computed": result.computed, "resumed": result.resumed, "lost": result.lost,
            "elapsed_s": result.elapsed_s, "rows": rows}, vehicle)), indent=1))  # fmt: skip
    else:
        _print_map(result, vehicle, cant, deficiency, out)
        for flag, path in (("csv", csv_file), ("png", png_file)):
            if path is not None:
                click.echo(f"{flag}: {path}")
    report_lost(result, points="radii")


def _print_map(result: Any, vehicle: Any, cant: float, deficiency: float | None,
               out: Path | None) -> None:  # fmt: skip
    """The table of the stability map and a line on the run."""
    from rich.table import Table

    held = (f"cant {cant * 1e3:g} mm" if deficiency is None
            else f"cant deficiency {deficiency * 1e3:g} mm")  # fmt: skip
    table = Table(title=f"stability map of {vehicle.name} ({held})")
    cols = result.columns
    shown = [(c, head, spec) for c, head, spec in (
        ("linear_critical_speed_kmh", "V_lin (km/h)", ".1f"),
        ("linear_frequency_hz", "f_lin (Hz)", ".2f"),
        ("critical_speed_kmh", "V_cr (km/h)", ".0f")) if c in cols]  # fmt: skip
    for head in ("radius (m)", *(h for _, h, _ in shown), "status", "note"):
        table.add_column(head, justify="left" if head in ("status", "note") else "right")
    for row in result.rows:
        radius = "straight" if row["radius_m"] == math.inf else f"{row['radius_m']:g}"
        table.add_row(radius, *(fmt(row[c], spec) for c, _, spec in shown), row["status"],
                      row["message"])  # fmt: skip
    stdout_console().print(table)
    where = f" in {out}" if out is not None else ""
    click.echo(f"{len(result.rows)} radii{where}: {result.computed} computed, "
               f"{result.resumed} already there, {result.lost} lost; "
               f"{result.elapsed_s:.1f} s")  # fmt: skip
