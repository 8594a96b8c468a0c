"""``railhunt contact --patches``: every contact patch of a yawed wheelset along y."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click
import numpy as np

from railhunt.cli.errors import user_input
from railhunt.cli.options import write_sidecar
from railhunt.cli.output import announce, command_record, json_safe, traced

_FIELDS = ("x", "y", "z", "rolling_radius", "contact_angle", "wheel_y", "rail_y", "gap", "a",
           "b", "normal_force", "vertical_load")  # fmt: skip


def run_patches(wheel: object, rail: object, *, inclination: float, gauge: float,
                back_to_back: float, r0: float, y_max: float, y_step: float, yaw: float,
                load: float, shear_modulus: float, poisson: float, png_file: Path | None,
                csv_file: Path | None, as_json: bool) -> None:  # fmt: skip
    """The patches' table (mm, deg, kN), CSV, chart or JSON (SI); inputs in the CLI's
    units (mm, mrad, kN, GPa)."""
    from railhunt.contact.patches import contact_patches_along
    from railhunt.workload import contact_workload

    n = int(round(y_max / y_step))
    ys = y_step * 1e-3 * np.arange(-n, n + 1)
    announce(contact_workload(4 * ys.size, f"patches at ±{y_max:g} mm in steps of "
                                           f"{y_step:g} mm"))  # fmt: skip
    with user_input():
        contacts = contact_patches_along(
            wheel, rail, ys, yaw * 1e-3, rail_inclination=inclination, gauge=gauge * 1e-3,
            back_to_back=back_to_back * 1e-3, r0=r0 * 1e-3,
            normal_load=load * 1e3 if load > 0 else None,
            shear_modulus=shear_modulus * 1e9, poisson=poisson)  # fmt: skip
    rows = [(c, side, k, p) for c in contacts for side in ("left", "right")
            for k, p in enumerate(getattr(c, side))]  # fmt: skip
    if csv_file is not None:
        with user_input("cannot write --csv: "):
            table = np.array([[c.y * 1e3, 0 if side == "left" else 1, k + 1, p.x * 1e3,
                               p.wheel_y * 1e3, p.rail_y * 1e3, p.rolling_radius * 1e3,
                               p.contact_angle, p.gap * 1e3, p.a * 1e3, p.b * 1e3,
                               p.normal_force * 1e-3, p.vertical_load * 1e-3]
                              for c, side, k, p in rows])  # fmt: skip
            header = ("y_mm,wheel_right,patch,x_mm,wheel_y_mm,rail_y_mm,rolling_radius_mm,"
                      "contact_angle_rad,gap_mm,a_mm,b_mm,normal_force_kN,vertical_load_kN")
            np.savetxt(csv_file, table, delimiter=",", fmt="%.9g", comments="", header=header)
            write_sidecar(csv_file, traced({"wheel": wheel.name, "rail": rail.name,
                                            "yaw_rad": yaw * 1e-3}),
                          **command_record())  # fmt: skip
    if png_file is not None:
        from railhunt.plots import plot_contact_patches

        with user_input("cannot write --png: "):
            plot_contact_patches(contacts, png_file)
    if as_json:
        data = {"wheel": wheel.name, "rail": rail.name, "rail_inclination": inclination,
                "yaw_rad": yaw * 1e-3, "normal_load_n": load * 1e3,
                "contacts": [{"y_m": c.y, "roll_rad": c.roll,
                              **{side: [{name: getattr(p, name) for name in _FIELDS}
                                        for p in getattr(c, side)]
                                 for side in ("left", "right")}}
                             for c in contacts]}  # fmt: skip
        click.echo(json.dumps(json_safe(traced(data))))
        return
    two = [c.y for c in contacts if len(c.left) > 1 or len(c.right) > 1]
    click.echo(f"{wheel.name} on {rail.name}, inclination {inclination:.4g}, yaw {yaw:g} mrad, "
               f"wheel load {load:g} kN")  # fmt: skip
    if two:
        click.echo(f"two-point contact at {len(two)} of {len(contacts)} displacements, "
                   f"|y| {min(abs(v) for v in two) * 1e3:.2f} to "
                   f"{max(abs(v) for v in two) * 1e3:.2f} mm")  # fmt: skip
    else:
        click.echo("one patch per wheel at every displacement")
    from rich.table import Table

    from railhunt.cli.output import stdout_console

    every = max(1, int(round(1.0 / y_step)))
    table = Table(title="left wheel's patches (every 1 mm, and wherever it has two)")
    for head in ("y mm", "patch", "x mm", "wheel y mm", "r mm", "δ deg", "gap µm", "N kN",
                 "share %"):  # fmt: skip
        table.add_column(head, justify="right")
    for i, c in enumerate(contacts):
        if (i - n) % every and len(c.left) < 2:
            continue
        total = sum(p.vertical_load for p in c.left)
        for k, p in enumerate(c.left):
            share = f"{100 * p.vertical_load / total:.1f}" if total > 0 else "-"
            table.add_row(f"{c.y * 1e3:+.2f}", str(k + 1), f"{p.x * 1e3:+.3f}",
                          f"{p.wheel_y * 1e3:+.2f}", f"{p.rolling_radius * 1e3:.3f}",
                          f"{math.degrees(p.contact_angle):.2f}", f"{p.gap * 1e6:.1f}",
                          f"{p.normal_force * 1e-3:.4g}", share)  # fmt: skip
    stdout_console().print(table)
