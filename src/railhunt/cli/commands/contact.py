"""``railhunt contact``: wheel/rail contact geometry and equivalent conicity from profiles."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.files import OutputPath
from railhunt.cli.options import check_outputs, number_range, overwrite_option, write_sidecar
from railhunt.cli.output import announce, command_record, json_safe, traced
from railhunt.cli.rules import Ordered, command

_INCLINATIONS = {"1:40": 1.0 / 40.0, "1:20": 1.0 / 20.0, "none": 0.0, "0": 0.0}


def _inclination(ctx: click.Context, param: click.Parameter, value: str) -> float:
    text = value.strip().lower()
    if text in _INCLINATIONS:
        return _INCLINATIONS[text]
    try:
        if ":" in text:
            num, den = (float(p) for p in text.split(":"))
            incl = num / den
        else:
            incl = float(text)
    except (ValueError, ZeroDivisionError):
        raise click.BadParameter(
            f"{value!r} is not a valid inclination: use 1:40, 1:20, none or a tangent "
            "in [0, 0.1]"
        ) from None
    if not (math.isfinite(incl) and 0.0 <= incl <= 0.1):
        raise click.BadParameter(f"{value!r} is not a valid inclination: the tangent must "
                                 "be in [0, 0.1]")
    return incl


#: ``--inclination``'s parser, for the commands that share the option.
parse_inclination = _inclination

RULES = (
    Ordered("--step", "--y-max",
            "--step {y_step:g} mm is invalid: must be at most --y-max {y_max:g} mm"),
)


@command("contact", rules=RULES,
         short_help="Contact geometry and equivalent conicity of wheel and rail profiles.")
@click.option("--wheel", "wheel", default="S1002", show_default=True, metavar="FILE|S1002",
              help="Wheel profile: SIMPACK .prw or 'y z' text/CSV file in mm (field side "
                   "at +y, radius increase at +z), or S1002 for the analytic EN 13715 profile.")
@click.option("--rail", "rail", default="UIC60", show_default=True, metavar="FILE|UIC60",
              help="Upright rail profile: SIMPACK .prr or 'y z' file in mm (depth at +z), "
                   "or UIC60 for the analytic 60E1 head. The shipped MBench UIC60 file is "
                   "already inclined 1:40: use it with --inclination none.")
@click.option("--inclination", default="1:40", show_default=True, callback=_inclination,
              help="Rail inclination: 1:40, 1:20, none, or a tangent in [0, 0.1].")
@click.option("--gauge", default=1435.0, show_default=True, metavar="MM",
              callback=number_range("mm", 500.0, 2000.0), help="Track gauge (mm).")
@click.option("--back-to-back", "back_to_back", default=1360.0, show_default=True,
              metavar="MM", callback=number_range("mm", 400.0, 2000.0),
              help="Distance between the wheels' inner faces (mm).")
@click.option("--r0", "r0", default=430.0, show_default=True, metavar="MM",
              callback=number_range("mm", 100.0, 1000.0),
              help="Wheel radius at the tape circle (mm).")
@click.option("--y-max", "y_max", default=12.0, show_default=True, metavar="MM",
              callback=number_range("mm", 0.1, 30.0),
              help="Largest lateral wheelset displacement (mm).")
@click.option("--step", "y_step", default=0.1, show_default=True, metavar="MM",
              callback=number_range("mm", 0.001, 1.0), help="Step of the displacement (mm).")
@click.option("--amplitude", default=3.0, show_default=True, metavar="MM",
              callback=number_range("mm", 0.0, 30.0),
              help="Amplitude of the equivalent conicity reported (mm).")
@click.option("--png", "png_file", type=OutputPath(),
              help="Plot r_L, r_R, delta r, contact angles, roll and contact points.")
@click.option("--csv", "csv_file", type=OutputPath(),
              help="Write the table (mm, rad, mrad).")
@click.option("--creep", "creep", is_flag=True,
              help="Also tabulate the contact mechanics at each contact point along y: "
                   "Hertz semi-axes a, b and a/b, Kalker's C11, C22, C23, C33 and the "
                   "normal force N = Q / cos(delta) under --load.")
@click.option("--load", "load", default=10900.0 * 9.8 / 2.0 / 1e3, show_default=True,
              metavar="KN", callback=number_range("kN", 0.0, 1000.0),
              help="Vertical wheel load Q for --creep (kN; default the paper's W g / 2).")
@click.option("--shear-modulus", "shear_modulus", default=2.1e11 / 2.6 / 1e9,
              show_default=True, metavar="GPA", callback=number_range("GPa", 10.0, 1000.0,
                                                                      low_open=False),
              help="Shear modulus of wheel and rail for --creep (GPa; default E = 210 GPa "
                   "with nu = 0.3).")
@click.option("--poisson", "poisson", default=0.3, show_default=True,
              callback=number_range("", 0.0, 0.499, low_open=False),
              help="Poisson's ratio for --creep.")
@click.option("--patches", "patches", is_flag=True,
              help="Every contact patch of each wheel instead (two-point contact, the "
                   "wheelset yawed by --yaw): position, lead ahead of the axle, rolling "
                   "radius, contact angle, gap and the share of --load.")
@click.option("--yaw", "yaw", default=0.0, show_default=True, metavar="MRAD",
              callback=number_range("mrad", -50.0, 50.0, low_open=False),
              help="Wheelset yaw for --patches (mrad, + counter-clockwise from above).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units).")
@overwrite_option
def contact_command(
    wheel: str, rail: str, inclination: float, gauge: float, back_to_back: float,
    r0: float, y_max: float, y_step: float, amplitude: float, png_file: Path | None,
    csv_file: Path | None, creep: bool, load: float, shear_modulus: float, poisson: float,
    patches: bool, yaw: float, as_json: bool, overwrite: bool,
) -> None:
    """Contact geometry of a wheelset on its rails, and its equivalent conicity.

    Rigid contact (minimum-distance search with the wheelset roll that keeps both wheels
    on their rails) for lateral displacements within --y-max: rolling radii, their
    difference, contact angles, roll and contact-point jumps (two-point contact). The
    equivalent conicity follows EN 15302 (Annex B integration; Annex C regression).
    Inputs and outputs in mm; --json in SI units.

    \b
    With --creep, the contact mechanics at each contact point as the per-point model
    computes them: the Hertz ellipse from the profiles' curvatures there (a along the
    rolling direction), Kalker's coefficients for its a/b and the normal force that
    carries the vertical load --load at that contact angle.

    \b
    With --patches, every patch where a wheel touches its rail, the wheelset yawed by
    --yaw: a second valley of the gap function is a patch when the wheel's elastic
    approach under --load reaches it (two-point contact); each patch's lead ahead of the
    axle, rolling radius, contact angle, gap and share of the load. --png draws the
    contact-point chart of both patches.

    \b
    Examples:
      railhunt contact --png s1002_uic60.png
      railhunt contact --patches --yaw 5 --png patches.png
      railhunt contact --wheel worn.prw --inclination 1:20 --amplitude 2
      railhunt contact --creep --load 60 --csv ellipses.csv
    """
    from railhunt import (
        contact_geometry,
        equivalent_conicity,
        equivalent_conicity_regression,
        read_profile,
        s1002,
        uic60,
    )
    from railhunt.contact.conicity import ConicityError

    check_outputs(overwrite=overwrite, png=png_file, csv=csv_file)
    with user_input("--wheel: "):
        w = s1002(step=1e-5) if wheel.upper() == "S1002" else read_profile(wheel, "wheel")
    with user_input("--rail: "):
        r = uic60(0.0, step=1e-5) if rail.upper() == "UIC60" else read_profile(rail, "rail")
    from railhunt.workload import contact_workload

    if patches:
        from railhunt.cli.commands.contact_patches import run_patches

        run_patches(w, r, inclination=inclination, gauge=gauge, back_to_back=back_to_back,
                    r0=r0, y_max=y_max, y_step=y_step, yaw=yaw, load=load,
                    shear_modulus=shear_modulus, poisson=poisson, png_file=png_file,
                    csv_file=csv_file, as_json=as_json)  # fmt: skip
        return
    positions = 2 * int(round(y_max / y_step)) + 1
    announce(contact_workload(positions, f"±{y_max:g} mm in steps of {y_step:g} mm"))
    with user_input():
        geo = contact_geometry(
            w, r, rail_inclination=inclination, gauge=gauge * 1e-3,
            back_to_back=back_to_back * 1e-3, r0=r0 * 1e-3, y_max=y_max * 1e-3,
            y_step=y_step * 1e-3,
        )
    try:
        tan_ge = equivalent_conicity(geo.y, geo.delta_r, amplitude * 1e-3)
        tan_reg = equivalent_conicity_regression(geo.y, geo.delta_r, amplitude * 1e-3)
    except ConicityError as exc:
        raise CliError(f"--amplitude {amplitude:g} mm: {exc}") from None
    flange = geo.flange_contact_y()
    jumps = [float(v) for v in geo.y[geo.jump]]
    points = None
    if creep:
        from railhunt.contact.point_contact import point_contact

        with user_input("--creep: "):
            points = point_contact(geo, shear_modulus * 1e9, poisson)
    if csv_file is not None:
        import numpy as np

        with user_input("cannot write --csv: "):
            table = np.column_stack([
                geo.y * 1e3, geo.r_left * 1e3, geo.r_right * 1e3, geo.delta_r * 1e3,
                geo.delta_left, geo.delta_right, geo.roll * 1e3,
                geo.wheel_left * 1e3, geo.wheel_right * 1e3, geo.jump.astype(int),
            ])
            header = ("y_mm,r_left_mm,r_right_mm,delta_r_mm,delta_left_rad,"
                      "delta_right_rad,roll_mrad,wheel_left_mm,wheel_right_mm,jump")
            if points is not None:
                cols, names = _creep_columns(points, load * 1e3)
                table = np.column_stack([table, *cols])
                header += "," + ",".join(names)
            np.savetxt(csv_file, table, delimiter=",", fmt="%.9g", comments="",
                       header=header)
            write_sidecar(csv_file, traced({"wheel": w.name, "rail": r.name}),
                          **command_record())  # fmt: skip
    if png_file is not None:
        from railhunt.plots import plot_contact_geometry

        with user_input("cannot write --png: "):
            plot_contact_geometry(geo, png_file)
    if as_json:
        data = {
            "wheel": w.name, "rail": r.name, "rail_inclination": inclination,
            "amplitude_m": amplitude * 1e-3,
            "equivalent_conicity": tan_ge, "equivalent_conicity_regression": tan_reg,
            "flange_contact_y_m": list(flange), "jump_y_m": jumps,
            "y_m": geo.y.tolist(), "r_left_m": geo.r_left.tolist(),
            "r_right_m": geo.r_right.tolist(), "delta_left_rad": geo.delta_left.tolist(),
            "delta_right_rad": geo.delta_right.tolist(), "roll_rad": geo.roll.tolist(),
        }
        if points is not None:
            data["creep"] = _creep_json(points, load * 1e3)
        click.echo(json.dumps(json_safe(traced(data))))
        return
    i0 = int(abs(geo.y).argmin())
    click.echo(f"{w.name} on {r.name}, inclination {inclination:.4g}, gauge {gauge:g} mm, "
               f"back-to-back {back_to_back:g} mm")
    click.echo(f"centred: r = {geo.r_left[i0] * 1e3:.3f} mm, contact angle "
               f"{math.degrees(geo.delta_left[i0]):.2f} deg, contact points "
               f"{geo.contact_distance[i0] * 1e3:.1f} mm apart")
    click.echo(f"equivalent conicity at {amplitude:g} mm: {tan_ge:.4f} (EN 15302 Annex B), "
               f"{tan_reg:.4f} (Annex C regression)")
    fl = ", ".join("-" if math.isnan(v) else f"{v * 1e3:+.1f} mm" for v in flange)
    click.echo(f"flange contact (contact angle > 45 deg) from y = {fl}")
    if jumps:
        click.echo("contact-point jumps at y = " + ", ".join(f"{v * 1e3:+.1f}" for v in jumps)
                   + " mm")
    if points is not None:
        _echo_creep(points, load * 1e3, y_step)


def _creep_columns(points: object, load: float) -> tuple[list, list[str]]:
    """The --creep columns of the CSV (mm, kN) and their names."""
    a, b = points.ellipse(load)
    n = points.normal_force(load)
    cols, names = [], []
    for k, side in enumerate(("left", "right")):
        cols += [a[k] * 1e3, b[k] * 1e3, points.a_over_b[k], points.c11[k], points.c22[k],
                 points.c23[k], points.c33[k], n[k] * 1e-3]
        names += [f"{q}_{side}" for q in ("a_mm", "b_mm", "a_over_b", "c11", "c22", "c23",
                                           "c33", "normal_force_kN")]
    return cols, names


def _creep_json(points: object, load: float) -> dict:
    """The --creep block of --json (SI)."""
    a, b = points.ellipse(load)
    n = points.normal_force(load)
    out: dict = {"load_n": load, "shear_modulus_pa": points.shear_modulus,
                 "poisson": points.poisson}
    for k, side in enumerate(("left", "right")):
        out[side] = {"a_m": a[k].tolist(), "b_m": b[k].tolist(),
                     "a_over_b": points.a_over_b[k].tolist(), "c11": points.c11[k].tolist(),
                     "c22": points.c22[k].tolist(), "c23": points.c23[k].tolist(),
                     "c33": points.c33[k].tolist(), "normal_force_n": n[k].tolist()}
    return out


def _echo_creep(points: object, load: float, y_step: float) -> None:
    """The --creep table of the left wheel (the right one is its mirror), every 1 mm."""
    from rich.table import Table

    from railhunt.cli.output import stdout_console

    a, b = points.ellipse(load)
    n = points.normal_force(load)
    every = max(1, int(round(1.0 / y_step)))
    table = Table(title=f"left wheel's contact at Q = {load * 1e-3:.4g} kN (the right "
                        "wheel's at -y)")  # fmt: skip
    for head in ("y mm", "δ deg", "a mm", "b mm", "a/b", "C11", "C22", "C23", "C33",
                 "N kN"):
        table.add_column(head, justify="right")
    centre = points.y.size // 2
    for i in sorted(set(range(centre % every, points.y.size, every))):
        table.add_row(f"{points.y[i] * 1e3:+.1f}", f"{math.degrees(points.delta[0, i]):.2f}",
                      f"{a[0, i] * 1e3:.2f}", f"{b[0, i] * 1e3:.2f}",
                      f"{points.a_over_b[0, i]:.3g}", f"{points.c11[0, i]:.3g}",
                      f"{points.c22[0, i]:.3g}", f"{points.c23[0, i]:.3g}",
                      f"{points.c33[0, i]:.3g}", f"{n[0, i] * 1e-3:.4g}")  # fmt: skip
    stdout_console().print(table)
