"""``railhunt conicity``: a fleet of wheel profiles, each wheelset's equivalent conicity,
two-point bands and (``--critical-speed``) critical speeds."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click

from railhunt.cli.commands.contact import parse_inclination
from railhunt.cli.errors import CliError, user_input
from railhunt.cli.files import OutputPath
from railhunt.cli.options import VehicleOption, check_outputs, number_range, overwrite_option
from railhunt.cli.output import json_safe, stdout_console, traced
from railhunt.cli.rules import command

#: The vehicle of --critical-speed unless --vehicle names another.
DEFAULT_VEHICLE = "s1002_uic60_table"


def _smooth(ctx: click.Context, param: click.Parameter, value: str) -> float | str | None:
    text = value.strip().lower()
    if text in ("", "default"):
        return None
    if text == "auto":
        return "auto"
    try:
        mm = float(text)
    except ValueError:
        raise click.BadParameter(f"{value!r} is not a smoothing: use auto, default, 0 (none) "
                                 "or a tolerance in mm (at most 0.2)") from None  # fmt: skip
    if not (math.isfinite(mm) and 0.0 <= mm <= 0.2):
        raise click.BadParameter(f"{value!r} mm is invalid: the tolerance must be in "
                                 "[0, 0.2] mm")  # fmt: skip
    return mm * 1e-3


def _write_csv(path: Path, rows: list, critical: bool, vehicle: object) -> None:
    """The fleet's table as CSV (mm, km/h, Hz), its metadata beside it; the two-point
    bands as ``low:high`` pairs of lateral displacement (mm) separated by ``;``."""
    import csv

    from railhunt.cli.files import write_sidecar
    from railhunt.cli.output import command_record

    head = ["wheel", "file", "equivalent_conicity", "two_point_bands_mm",
            "centred_rolling_radius_mm", "smoothing_mm"]  # fmt: skip
    if critical:
        head += ["linear_critical_speed_kmh", "nonlinear_critical_speed_kmh", "frequency_hz"]
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(head)
        for r in rows:
            bands = ";".join(f"{lo * 1e3:.4g}:{hi * 1e3:.4g}" for lo, hi in r.bands)
            cells = [r.name, r.source, f"{r.conicity:.6g}", bands,
                     f"{r.centred_radius * 1e3:.6f}", f"{r.smoothing * 1e3:.6g}"]  # fmt: skip
            if critical:
                cells += [f"{r.linear_kmh:.6g}", f"{r.nonlinear_kmh:.6g}",
                          f"{r.frequency_hz:.6g}"]  # fmt: skip
            out.writerow(cells)
    write_sidecar(path, traced({"rows": len(rows)}, vehicle if critical else None),
                  **command_record())  # fmt: skip


class FleetVehicleOption(VehicleOption):
    """``--vehicle`` of the fleet: the vehicle whose wheel profile each file replaces."""

    help_lead = ("Vehicle for --critical-speed, whose wheel profile each file replaces: a "
                 "TOML file with a [contact] section")
    help_default = DEFAULT_VEHICLE


def _vehicle(value: str) -> object:
    from railhunt import Vehicle, load_vehicle
    from railhunt.vehicle import shipped_vehicles

    if Path(value).is_file():
        return load_vehicle(value)
    if value in shipped_vehicles():
        return Vehicle.shipped(value)
    raise CliError(f"--vehicle {value!r} is neither a file nor a shipped vehicle "
                   f"({', '.join(shipped_vehicles())})")  # fmt: skip


def _bands_mm(bands: list) -> str:
    """The bands in mm; a band and its mirror (a symmetric wheelset's) as one ``±``."""
    if not bands:
        return "-"
    keys = {(round(a, 6), round(b, 6)) for a, b in bands}
    out = []
    for a, b in bands:
        mirrored = (round(-b, 6), round(-a, 6)) in keys
        if mirrored and b < 0:
            continue
        if mirrored and a > 0:
            out.append(f"±{a * 1e3:.1f}…{b * 1e3:.1f}" if b > a else f"±{a * 1e3:.1f}")
        else:
            out.append(f"{a * 1e3:+.1f}…{b * 1e3:+.1f}" if b > a else f"{a * 1e3:+.1f}")
    return ", ".join(out)


@command("conicity",
         short_help="A fleet's wheel profiles: equivalent conicity, two-point bands, speeds.")
@click.argument("wheels", nargs=-1, required=True, metavar="WHEEL_FILES...")
@click.option("--rail", "rail", default="UIC60", show_default=True, metavar="FILE|UIC60",
              help="Upright rail profile: MiniProf .ban, SIMPACK .prr or 'y z' file in mm, "
                   "or UIC60 for the analytic 60E1 head.")
@click.option("--inclination", default="1:40", show_default=True, callback=parse_inclination,
              help="Rail inclination: 1:40, 1:20, none, or a tangent in [0, 0.1].")
@click.option("--gauge", default=1435.0, show_default=True, metavar="MM",
              callback=number_range("mm", 500.0, 2000.0), help="Track gauge (mm).")
@click.option("--back-to-back", "back_to_back", default=1360.0, show_default=True,
              metavar="MM", callback=number_range("mm", 400.0, 2000.0),
              help="Distance between the wheels' inner faces (mm).")
@click.option("--r0", "r0", default=430.0, show_default=True, metavar="MM",
              callback=number_range("mm", 100.0, 1000.0),
              help="Wheel radius at the tape circle (mm).")
@click.option("--amplitude", default=3.0, show_default=True, metavar="MM",
              callback=number_range("mm", 0.0, 30.0),
              help="Amplitude of the equivalent conicity (mm; EN 15302 reports 3 mm).")
@click.option("--penetration", default=0.1, show_default=True, metavar="MM",
              callback=number_range("mm", 0.001, 1.0),
              help="A second valley of a wheel's gap function less than this above its "
                   "lowest point is a second contact patch (mm).")
@click.option("--smooth", "smooth", default="default", show_default=True, callback=_smooth,
              metavar="auto|MM|default",
              help="Smoothing of the wheel files: a tolerance in mm (RMS distance of the "
                   "points from the smoothing spline; 0 for none), auto (the noise "
                   "estimated from the points) or default (auto for MiniProf files, none "
                   "for SIMPACK and text files).")
@click.option("--repair", is_flag=True,
              help="Drop the points of a MiniProf file that fold back instead of refusing it.")
@click.option("--critical-speed", "critical", is_flag=True,
              help="Also the linear and nonlinear critical speeds of --vehicle on each "
                   "wheelset (about 10 s per wheel).")
@click.option("--vehicle", "vehicle", default=DEFAULT_VEHICLE, metavar="FILE|NAME",
              cls=FleetVehicleOption)
@click.option("--png", "png_file", type=OutputPath(),
              help="Histogram of the fleet's equivalent conicities.")
@click.option("--csv", "csv_file", type=OutputPath(),
              help="Write the fleet's table (one row per wheel; mm, km/h, Hz).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units).")
@overwrite_option
def conicity_command(
    wheels: tuple[str, ...], rail: str, inclination: float, gauge: float,
    back_to_back: float, r0: float, amplitude: float, penetration: float,
    smooth: float | str | None, repair: bool, critical: bool, vehicle: str,
    png_file: Path | None, csv_file: Path | None, as_json: bool, overwrite: bool,
) -> None:
    """Equivalent conicity of each wheel profile of a fleet, before reprofiling.

    Each WHEEL_FILE (MiniProf .whl, SIMPACK .prw or 'y z' text in mm; S1002 for the
    new analytic profile) is one wheelset, both wheels as measured, on --rail. For each:
    the equivalent conicity at --amplitude (EN 15302 Annex B), the two-point bands (the
    lateral displacements, mm, where a wheel touches its rail on two patches) and, with
    --critical-speed, the linear and nonlinear critical speeds of --vehicle running on it
    (the profile substituted into the vehicle's [contact] section, r0 and the centred
    creepage coefficients following it).

    \b
    Examples:
      railhunt conicity S1002 examples/data/worn_hollow_1mm.whl examples/data/worn_hollow_2mm.whl
      railhunt conicity WHEEL_FILES... --rail FILE --inclination none --png FILE
      railhunt conicity examples/data/worn_hollow_2mm.whl --critical-speed --json
      railhunt conicity S1002 examples/data/worn_hollow_2mm.whl --csv fleet.csv
    """
    from railhunt.studies.fleet import wheel_fleet

    check_outputs(overwrite=overwrite, png=png_file, csv=csv_file)
    veh = _vehicle(vehicle) if critical else None
    echo = stdout_console().print if not as_json else None

    def progress(row: object) -> None:
        if critical and not as_json:
            click.echo(f"{row.name}: done", err=True)

    with user_input():
        rows = wheel_fleet(
            list(wheels), rail, rail_inclination=inclination, gauge=gauge * 1e-3,
            back_to_back=back_to_back * 1e-3, r0=r0 * 1e-3, amplitude=amplitude * 1e-3,
            penetration=penetration * 1e-3, smooth=smooth, repair=repair,
            critical_speeds=critical, vehicle=veh, progress=progress,
        )
    if png_file is not None:
        from railhunt.plots import plot_conicity_histogram

        with user_input("cannot write --png: "):
            plot_conicity_histogram([r.name for r in rows], [r.conicity for r in rows],
                                    png_file, amplitude * 1e-3)  # fmt: skip
    if csv_file is not None:
        with user_input("cannot write --csv: "):
            _write_csv(csv_file, rows, critical, veh)
    if as_json:
        data = {
            "rail": rail, "rail_inclination": inclination, "amplitude_m": amplitude * 1e-3,
            "penetration_m": penetration * 1e-3,
            "wheels": [{
                "name": r.name, "file": r.source, "equivalent_conicity": r.conicity,
                "two_point_bands_m": [list(b) for b in r.bands],
                "centred_rolling_radius_m": r.centred_radius, "smoothing_m": r.smoothing,
                **({"linear_critical_speed_kmh": r.linear_kmh,
                    "nonlinear_critical_speed_kmh": r.nonlinear_kmh,
                    "frequency_hz": r.frequency_hz} if critical else {}),
            } for r in rows],
        }
        click.echo(json.dumps(json_safe(traced(data, veh if critical else None))))
        return
    from rich.table import Table

    table = Table(title=f"{len(rows)} wheelset{'s' if len(rows) != 1 else ''} on {rail}, "
                        f"inclination {inclination:.4g}, gauge {gauge:g} mm")  # fmt: skip
    table.add_column("wheel", no_wrap=True)
    table.add_column(f"conicity {amplitude:g} mm", justify="right")
    table.add_column("two-point bands y mm")
    if critical:
        for head in ("linear km/h", "nonlinear km/h", "f Hz"):
            table.add_column(head, justify="right")
    for r in rows:
        cells = [r.name, "-" if math.isnan(r.conicity) else f"{r.conicity:.3f}",
                 _bands_mm(r.bands)]  # fmt: skip
        if critical:
            cells += [f"{r.linear_kmh:.1f}", f"{r.nonlinear_kmh:.0f}", f"{r.frequency_hz:.2f}"]
        table.add_row(*cells)
    echo(table)
    if critical:
        click.echo(f"critical speeds of {veh.name} with each wheel profile "
                   "(nonlinear: bisection over an 8 mm, 20 m alignment defect)")
