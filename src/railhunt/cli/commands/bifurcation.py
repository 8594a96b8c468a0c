"""``railhunt bifurcation``: limit cycles versus speed by path following (Figs. 7a, 13)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import user_input
from railhunt.cli.options import (
    CURVE_RULES,
    build_curve,
    build_vehicle,
    check_outputs,
    curve_json,
    curve_options,
    describe_curve,
    file_option,
    initial_amplitude_option,
    kmh_option,
    overwrite_option,
    vehicle_options,
)
from railhunt.cli.output import announce, fmt, json_safe, spinner, stdout_console, traced
from railhunt.cli.rules import Ordered, Requires, command
from railhunt.paper2019 import NO_BLOWOFF  # the blow-off force standing for 'inf' (N)
from railhunt.verdicts import verdict_help

RULES = (
    Ordered("--from", "--to", "--to {to_kmh:g} km/h must be above --from {from_kmh:g} km/h",
            strict=True),
    Requires("--family-png", "--fu-family", "{a} needs {b}"),
    *CURVE_RULES,
)  # fmt: skip


def _parse_forces(ctx: click.Context, param: click.Parameter,
                  value: str | None) -> list[float] | None:  # fmt: skip
    """``--fu-family 1,3,8,inf`` (kN) to forces in N."""
    if value is None:
        return None
    out = []
    for item in value.split(","):
        item = item.strip()
        try:
            kn = float(item)
        except ValueError:
            raise click.BadParameter(f"{item!r} is not a number of kN (or 'inf')") from None
        if math.isinf(kn) and kn > 0:
            out.append(NO_BLOWOFF)
        elif math.isfinite(kn) and 0 < kn <= 1e6:
            out.append(kn * 1e3)
        else:
            raise click.BadParameter(f"{item} kN is not valid: each force must be in (0, 1e6] kN "
                                     "or 'inf'")  # fmt: skip
    return out


@command("bifurcation", rules=RULES, epilog=verdict_help(),
         short_help="Bifurcation diagram by path following (Hopf and fold speeds, type).")
@kmh_option("--from", "from_kmh", 200.0, 2000.0, "Lowest speed of the diagram (km/h).")
@kmh_option("--to", "to_kmh", 500.0, 2000.0, "Highest speed of the diagram (km/h).")
@initial_amplitude_option("Disturbance whose crossing of the unstable branch is marked as "
                          "the paper's point P (mm).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON on stdout.")
@file_option("--png", "png_file", "Draw the diagram like the paper's Fig. 7a (stable solid, "
             "unstable dashed, Hopf point, folds and point P).")
@click.option("--fu-family", "fu_family", metavar="KN,KN,...", callback=_parse_forces,
              help="Also compute a diagram for each of these yaw damper blow-off forces (kN; "
              "'inf' for no blow-off) and report the bifurcation type of each, like the "
              "paper's Fig. 13.")
@file_option("--family-png", "family_png", "Draw the --fu-family diagrams side by side "
             "(Fig. 13).")
@click.option("--wheelset", "wheelset", type=click.Choice(["leading", "largest"]),
              default="leading", show_default=True,
              help="Amplitude drawn in --png and --family-png: the leading wheelset's (the "
              "paper's) or the largest of all the wheelsets' (shows a cycle on which another "
              "wheelset hunts most, such as the paper's car's rear bogie, at its real size).")
@curve_options("Length of the transition curves of --curve-radius (m), recorded in the JSON; "
               "the limit cycles are those of the constant curve and do not depend on it "
               "[default: R/10, within 20-300 m].")
@overwrite_option
@vehicle_options
def bifurcation_command(from_kmh: float, to_kmh: float, initial_mm: float, as_json: bool,
                        png_file: Path | None, fu_family: list[float] | None,
                        family_png: Path | None, wheelset: str, curve_radius: float | None,
                        cant_mm: float | None, transition: float | None, direction: str,
                        overwrite: bool, vehicle_file: Path | None,
                        sets: dict[str, float]) -> None:  # fmt: skip
    """Limit cycles of the vehicle on ideal track versus speed.

    \b
    Follows the branch of limit cycles born at the Hopf point (the linear
    critical speed) by pseudo-arclength continuation of periodic orbits found
    by shooting, through its folds, plus any branch of large cycles that a
    simulation at the top speed settles on. Stability comes from the Floquet
    multipliers. Prints the Hopf speed (linear critical speed), the lowest
    speed with a limit cycle (nonlinear critical speed), the folds and the
    bifurcation type (subcritical, supercritical-a, supercritical-b as in
    the paper's Fig. 5).

    \b
    In a curve (--curve-radius, --cant, --direction) the limit cycles are
    those about the steady-curving equilibrium in the constant curve, shot
    over the whole period (a curve has no mirror symmetry); amplitudes are
    half the peak-to-peak swing of the leading wheelset.
    """
    check_outputs(overwrite=overwrite, png=png_file, **{"family-png": family_png})
    vehicle = build_vehicle(vehicle_file, sets)
    curve = build_curve(curve_radius, cant_mm, transition, direction)
    in_curve = {} if curve is None else {"curve": curve}
    from railhunt import bifurcation_diagram
    from railhunt.analysis.continuation import bifurcation_family

    _announce_diagrams(vehicle, from_kmh, to_kmh, 1 + len(fu_family or ()))

    with spinner("following limit cycles"):
        diagram = bifurcation_diagram(vehicle, (from_kmh, to_kmh), **in_curve)
    family = []
    if fu_family:
        with spinner("following limit cycles of the F_u family"):
            family = bifurcation_family(vehicle, fu_family, "F_u", (from_kmh, to_kmh),
                                        **in_curve)  # fmt: skip
    if png_file is not None:
        from railhunt.plots import plot_bifurcation

        plot_bifurcation(diagram, png_file, initial_mm * 1e-3, wheelset=wheelset)
    if family_png is not None:
        from railhunt.plots import plot_bifurcation_family

        plot_bifurcation_family(family, family_png, wheelset=wheelset)
    summary = [{"F_u_kN": None if fu >= NO_BLOWOFF else fu * 1e-3, "hopf_type": d.hopf_type,
                "hopf_speed_kmh": d.hopf_speed_kmh, "fold_speed_kmh": d.fold_speed_kmh}
               for fu, d in family]  # fmt: skip
    if as_json:
        data = diagram.to_dict(point_p_amplitude=initial_mm * 1e-3)
        data["vehicle"] = vehicle.name
        if curve is not None:
            data["curve"] = curve_json(curve)
        if family:
            data["fu_family"] = summary
        click.echo(json.dumps(json_safe(traced(data, vehicle)), indent=2))
        return
    out = stdout_console()
    out.print(f"vehicle: {vehicle.name}")
    if curve is not None:
        out.print(f"curve: {describe_curve(curve, transition=False)} (limit cycles about the "
                  "steady-curving equilibrium)")  # fmt: skip
    out.print(f"Hopf point (linear critical speed): {fmt(diagram.hopf_speed_kmh, '.1f', 'km/h')}"
              f" at {fmt(diagram.hopf_frequency_hz, '.2f', 'Hz')}"
              f" (from the orbits: {fmt(diagram.hopf_speed_from_orbits_kmh, '.1f', 'km/h')})")
    out.print(f"bifurcation type: {diagram.hopf_type}")
    if diagram.hopf_type == "linear":
        out.print(f"{diagram.message}; no fold")
    else:
        out.print(f"nonlinear critical speed (lowest limit cycle): {_fold_text(diagram)}")
    for fold in diagram.folds:
        out.print(f"  fold at {fold.speed_kmh:.1f} km/h, amplitude {fold.amplitude * 1e3:.2f} mm")
    vp = diagram.point_p_kmh(initial_mm * 1e-3)
    out.print(f"point P ({initial_mm:g} mm meets an unstable branch): {fmt(vp, '.1f', 'km/h')}")
    for n, b in enumerate(diagram.branches):
        out.print(f"branch {n + 1} ({b.origin}): {b.speed_kmh.size} orbits, "
                  f"{b.speed_kmh.min():.1f}-{b.speed_kmh.max():.1f} km/h, "
                  f"amplitude up to {b.amplitude.max() * 1e3:.2f} mm")
    if not diagram.complete:
        out.print(f"[yellow]incomplete: {diagram.message}[/yellow]")
    for row in summary:
        fu = "inf" if row["F_u_kN"] is None else f"{row['F_u_kN']:g} kN"
        out.print(f"F_u = {fu}: {row['hopf_type']}, Hopf {row['hopf_speed_kmh']:.1f} km/h, "
                  f"lowest limit cycle {row['fold_speed_kmh']:.1f} km/h")
    for f in (png_file, family_png):
        if f is not None:
            out.print(f"wrote {f}")


def _fold_text(diagram: Any) -> str:
    """The lowest limit cycle, or why there is none in the range."""
    if math.isfinite(diagram.fold_speed_kmh):
        return f"{diagram.fold_speed_kmh:.1f} km/h"
    low = diagram.speed_range_kmh[0]
    if diagram.fold_below_range:
        return (f"below the range: a branch of limit cycles still goes on at --from {low:g} "
                "km/h, so the lowest limit cycle lies below it; lower --from")
    return "n/a (no limit cycle found in the range)"


def _announce_diagrams(vehicle: Any, from_kmh: float, to_kmh: float, count: int) -> None:
    """Refuse a stiff damper's step, and announce diagrams of more than a minute."""
    from railhunt import Model
    from railhunt.simulation import auto_step
    from railhunt.units import kmh_to_ms
    from railhunt.workload import SIMULATED_SECONDS, workload

    with user_input("--set/--vehicle: "):
        step = auto_step(Model(vehicle), kmh_to_ms(to_kmh))
    per = SIMULATED_SECONDS["bifurcation diagram"]
    what = f"{count} diagram{'s' if count > 1 else ''} over {to_kmh - from_kmh:g} km/h"
    announce(workload(count * per, step, what), vehicle, kmh_to_ms(to_kmh))
