"""``railhunt creep``: creep-force curves of the creep laws on one contact patch."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.options import (
    check_outputs,
    file_option,
    number_range,
    overwrite_option,
    write_sidecar,
)
from railhunt.cli.output import command_record, json_safe, traced
from railhunt.cli.rules import Requires, command

_LAWS = ("exact", "fastsim-modified", "fastsim", "polach", "heuristic", "vermeulen-johnson",
         "linear")


def _laws(ctx: click.Context, param: click.Parameter, value: str) -> tuple[str, ...]:
    names = tuple(dict.fromkeys(s.strip().lower() for s in value.split(",") if s.strip()))
    bad = [n for n in names if n not in _LAWS]
    if bad or not names:
        raise click.BadParameter(f"{value!r} is not a list of laws: use some of "
                                 + ", ".join(_LAWS) + " (comma-separated) or all")
    return names


def _laws_or_all(ctx: click.Context, param: click.Parameter, value: str) -> tuple[str, ...]:
    return _LAWS if value.strip().lower() == "all" else _laws(ctx, param, value)


RULES = (
    Requires("--a", "--b", "--a and --b give the patch together: give both, or neither "
             "(the Hertz ellipse of --load and the radii)"),
    Requires("--b", "--a", "--a and --b give the patch together: give both, or neither "
             "(the Hertz ellipse of --load and the radii)"),
)


@command("creep", rules=RULES,
         short_help="Creep-force curves of the creep laws on one contact patch.")
@click.option("--sweep", type=click.Choice(["xi", "eta", "phi"]), default="eta",
              show_default=True, help="The creepage swept: longitudinal xi, lateral eta, "
              "or spin phi.")
@click.option("--max", "max_value", type=float, default=None, metavar="VALUE",
              help="Largest value of the swept creepage (xi, eta in per mille, phi in 1/m; "
                   "negative for a negative sweep) [default: three times the creepage that "
                   "saturates Kalker's linear law: 3 mu N / f].")
@click.option("--points", default=31, show_default=True,
              type=click.IntRange(2, 2001), help="Points of the sweep, from 0 to --max.")
@click.option("--xi", default=0.0, show_default=True, metavar="PERMILLE",
              callback=number_range("per mille", -1000.0, 1000.0, low_open=False),
              help="Fixed longitudinal creepage (per mille).")
@click.option("--eta", default=0.0, show_default=True, metavar="PERMILLE",
              callback=number_range("per mille", -1000.0, 1000.0, low_open=False),
              help="Fixed lateral creepage (per mille).")
@click.option("--phi", default=0.0, show_default=True, metavar="1/M",
              callback=number_range("1/m", -1000.0, 1000.0, low_open=False),
              help="Fixed spin creepage (1/m).")
@click.option("--a", "a_mm", type=float, default=None, metavar="MM",
              callback=number_range("mm", 0.0, 1000.0, optional=True),
              help="Semi-axis along the rolling direction (mm), with --b.")
@click.option("--b", "b_mm", type=float, default=None, metavar="MM",
              callback=number_range("mm", 0.0, 1000.0, optional=True),
              help="Semi-axis across the rolling direction (mm), with --a.")
@click.option("--load", "load_kn", default=53.41, show_default=True, metavar="KN",
              callback=number_range("kN", 0.0, 10000.0),
              help="Normal force (kN); the paper's wheel load by default.")
@click.option("--wheel-radius", "wheel_radius", default=430.0, show_default=True,
              metavar="MM", callback=number_range("mm", 1.0, 5000.0),
              help="Rolling radius (mm), for the Hertz ellipse.")
@click.option("--wheel-profile-radius", "wheel_profile", default=math.inf, show_default=True,
              metavar="MM", type=float,
              help="Radius of the wheel profile at the contact (mm; negative concave, inf "
                   "straight), for the Hertz ellipse.")
@click.option("--rail-profile-radius", "rail_profile", default=300.0, show_default=True,
              metavar="MM", type=float,
              help="Radius of the rail head at the contact (mm), for the Hertz ellipse.")
@click.option("--mu", default=0.3, show_default=True, callback=number_range("", 0.0, 10.0),
              help="Friction coefficient.")
@click.option("--shear-modulus", "shear_gpa", default=82.0, show_default=True, metavar="GPA",
              callback=number_range("GPa", 0.0, 10000.0), help="Shear modulus G (GPa).")
@click.option("--poisson", default=0.28, show_default=True,
              callback=number_range("", 0.0, 0.4999, low_open=False), help="Poisson's ratio.")
@click.option("--laws", default="all", show_default=True, callback=_laws_or_all,
              help="Comma-separated laws: " + ", ".join(_LAWS) + ", or all.")
@click.option("--grid", type=click.IntRange(4, 400), default=None, metavar="N",
              help="Elements along and across the patch for exact, fastsim and "
                   "fastsim-modified [default: 40 (exact, extrapolated from 20 and 40), "
                   "50 (FASTSIM)].")
@file_option("--png", "png_file", "Plot the force and the spin moment against the creepage, "
             "one line per law.")
@file_option("--csv", "csv_file", "Write the curves (one row per point; N, N*m).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units).")
@overwrite_option
def creep_command(
    sweep: str, max_value: float | None, points: int, xi: float, eta: float, phi: float,
    a_mm: float | None, b_mm: float | None, load_kn: float, wheel_radius: float,
    wheel_profile: float, rail_profile: float, mu: float, shear_gpa: float, poisson: float,
    laws: tuple[str, ...], grid: int | None, png_file: Path | None, csv_file: Path | None,
    as_json: bool, overwrite: bool,
) -> None:
    """Creep forces and spin moment of the creep laws on one contact patch.

    The patch is the ellipse --a x --b (mm) or, without them, the Hertz ellipse of --load
    between a wheel (--wheel-radius, --wheel-profile-radius) and a rail
    (--rail-profile-radius) of steel (G = --shear-modulus, nu = --poisson). One creepage
    (--sweep) runs from 0 to --max with the other two fixed; the laws are Kalker's exact
    theory of steady rolling, modified FASTSIM (three blended flexibilities), Kalker's
    FASTSIM, Polach with his spin term, the paper's heuristic law, Vermeulen-Johnson and
    Kalker's linear law. Prints the force of the swept direction
    over mu N and the spin moment over mu N c (c = sqrt(ab)) per law; --json and --csv
    in SI units (creepages as numbers, phi in 1/m).

    \b
    Examples:
      railhunt creep --png creep.png
      railhunt creep --sweep phi --eta 1 --laws exact,fastsim-modified,polach
      railhunt creep --a 8 --b 4 --load 82 --eta -0.625 --sweep phi --max 1.25
    """
    from railhunt import creep_coefficients
    from railhunt.mechanics.curves import creep_curves

    check_outputs(overwrite=overwrite, png=png_file, csv=csv_file)
    g = shear_gpa * 1e9
    n = load_kn * 1e3
    if a_mm is not None and b_mm is not None:
        a, b = a_mm * 1e-3, b_mm * 1e-3
    else:
        with user_input():
            cc = creep_coefficients(n, wheel_radius * 1e-3, wheel_profile * 1e-3,
                                    rail_profile * 1e-3, young=2.0 * g * (1.0 + poisson),
                                    nu=poisson)
        a, b = cc.a, cc.b
    if not 0.05 <= a / b <= 20.0:
        raise CliError(f"the patch's a/b = {a / b:.4g} ({a * 1e3:.4g} x {b * 1e3:.4g} mm) is "
                       "invalid: must be in [0.05, 20]")
    from railhunt.mechanics.coefficients import kalker_coefficients

    c11, c22, c23, c33 = kalker_coefficients(a / b, poisson)
    c = math.sqrt(a * b)
    if max_value is None:
        stiffness = {"xi": g * c * c * c11, "eta": g * c * c * c22, "phi": g * c**3 * c23}
        top = 3.0 * mu * n / stiffness[sweep]
    else:
        if not (math.isfinite(max_value) and max_value != 0.0):
            raise CliError(f"--max {max_value!r} is invalid: must be finite and not 0")
        top = max_value * (1e-3 if sweep != "phi" else 1.0)
    import numpy as np

    values = np.linspace(0.0, top, points)
    with user_input():
        curves = creep_curves(sweep, values, a=a, b=b, mu=mu, normal_force=n, laws=laws,
                              xi=xi * 1e-3, eta=eta * 1e-3, phi=phi, shear_modulus=g,
                              poisson=poisson, grid=grid)
    if csv_file is not None:
        with user_input("cannot write --csv: "):
            cols = curves._columns()
            names = list(cols)
            table = np.column_stack([np.asarray(cols[k][0], dtype=float) for k in names])
            np.savetxt(csv_file, table, delimiter=",", fmt="%.9g", comments="",
                       header=",".join(names))
            write_sidecar(csv_file, traced({}), units={k: u for k, (_, u) in cols.items()},
                          **command_record())  # fmt: skip
    if png_file is not None:
        from railhunt.plots import plot_creep_curves

        with user_input("cannot write --png: "):
            plot_creep_curves(curves, png_file)
    if as_json:
        data = {
            "sweep": sweep, "values": values.tolist(), "fixed": curves.fixed,
            "a_m": a, "b_m": b, "normal_force_n": n, "mu": mu, "shear_modulus_pa": g,
            "poisson": poisson, "kalker_coefficients": [c11, c22, c23, c33],
            "laws": {law: {"fx_n": curves.fx[law].tolist(), "fy_n": curves.fy[law].tolist(),
                           "mz_nm": curves.mz[law].tolist()} for law in laws},
        }
        click.echo(json.dumps(json_safe(traced(data))))
        return
    force = "F_x" if sweep == "xi" else "F_y"
    unit = "1/m" if sweep == "phi" else "per mille"
    click.echo(f"patch {a * 1e3:.4g} x {b * 1e3:.4g} mm (a/b = {a / b:.4g}), N = "
               f"{n / 1e3:.4g} kN, mu = {mu:g}, G = {shear_gpa:g} GPa, nu = {poisson:g}; "
               f"Kalker C11 {c11:.4g}, C22 {c22:.4g}, C23 {c23:.4g}, C33 {c33:.4g}")
    fixed = ", ".join(f"{k} = {v * (1 if k == 'phi' else 1e3):g}"
                      f"{' 1/m' if k == 'phi' else ' per mille'}"
                      for k, v in curves.fixed.items())
    click.echo(f"{sweep} from 0 to {top * (1 if sweep == 'phi' else 1e3):.4g} {unit}; "
               f"{fixed}")
    shown = np.unique(np.linspace(0, points - 1, min(points, 11)).round().astype(int))
    scale = 1.0 if sweep == "phi" else 1e3
    width = max(8, *(len(law) for law in laws))
    for title, get, norm in ((f"{force} / (mu N)", lambda law: curves.fx[law]
                              if sweep == "xi" else curves.fy[law], mu * n),
                             ("M_z / (mu N c)", lambda law: curves.mz[law], mu * n * c)):
        click.echo("")
        click.echo(f"{title}:")
        click.echo(f"{sweep:>10}  " + "  ".join(f"{law:>{width}}" for law in laws))
        for k in shown:
            click.echo(f"{values[k] * scale:10.4g}  "
                       + "  ".join(f"{get(law)[k] / norm:>{width}.4f}" for law in laws))
