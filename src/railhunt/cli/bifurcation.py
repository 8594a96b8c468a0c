"""``railhunt bifurcation`` and ``railhunt frequency``: path following and hunting frequency."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click

from railhunt.cli import (
    CliError,
    _build_vehicle,
    _check_outputs,
    _fmt,
    _json_safe,
    _kmh_option,
    _number_range,
    _speed_count,
    _spinner,
    _stdout_console,
    _vehicle_options,
    main,
)

#: Blow-off force (N) standing for "no blow-off" ('inf' on the command line).
from railhunt.paper2019 import NO_BLOWOFF as _NO_BLOWOFF


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
            out.append(_NO_BLOWOFF)
        elif math.isfinite(kn) and 0 < kn <= 1e6:
            out.append(kn * 1e3)
        else:
            raise click.BadParameter(f"{item} kN is not valid: each force must be in (0, 1e6] kN "
                                     "or 'inf'")  # fmt: skip
    return out


def _png_option(help: str):
    return click.option("--png", "png_file", type=click.Path(dir_okay=False, path_type=Path),
                        metavar="FILE", help=help)  # fmt: skip


def _initial_amplitude_option(help: str):
    return click.option("--initial-amplitude", "initial_mm", type=float, default=3.0,
                        show_default=True, metavar="MM",
                        callback=_number_range("mm", 0.0, 20.0), help=help)  # fmt: skip


@main.command(short_help="Bifurcation diagram by path following (Hopf and fold speeds, type).")
@_kmh_option("--from", "from_kmh", 200.0, 2000.0, "Lowest speed of the diagram (km/h).")
@_kmh_option("--to", "to_kmh", 500.0, 2000.0, "Highest speed of the diagram (km/h).")
@_initial_amplitude_option("Disturbance whose crossing of the unstable branch is marked as "
                           "the paper's point P (mm).")  # fmt: skip
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON on stdout.")
@_png_option("Draw the diagram like the paper's Fig. 7a (stable solid, unstable dashed, "
             "Hopf point, folds and point P).")  # fmt: skip
@click.option("--fu-family", "fu_family", metavar="KN,KN,...", callback=_parse_forces,
              help="Also compute a diagram for each of these yaw damper blow-off forces (kN; "
              "'inf' for no blow-off) and report the bifurcation type of each, like the "
              "paper's Fig. 13.")  # fmt: skip
@click.option("--family-png", "family_png", type=click.Path(dir_okay=False, path_type=Path),
              metavar="FILE", help="Draw the --fu-family diagrams side by side (Fig. 13).")
@_vehicle_options
def bifurcation(from_kmh: float, to_kmh: float, initial_mm: float, as_json: bool,
                png_file: Path | None, fu_family: list[float] | None, family_png: Path | None,
                vehicle_file: Path | None, sets: dict[str, float]) -> None:  # fmt: skip
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
    """
    _check_outputs(png=png_file, **{"family-png": family_png})
    if to_kmh <= from_kmh:
        raise CliError(f"--to {to_kmh:g} km/h must be above --from {from_kmh:g} km/h")
    if family_png is not None and not fu_family:
        raise CliError("--family-png needs --fu-family")
    vehicle = _build_vehicle(vehicle_file, sets)
    from railhunt.analysis.continuation import bifurcation_diagram, bifurcation_family

    with _spinner("following limit cycles"):
        diagram = bifurcation_diagram(vehicle, (from_kmh, to_kmh))
    family = []
    if fu_family:
        with _spinner("following limit cycles of the F_u family"):
            family = bifurcation_family(vehicle, fu_family, "F_u", (from_kmh, to_kmh))
    if png_file is not None:
        from railhunt.plots import plot_bifurcation

        plot_bifurcation(diagram, png_file, initial_mm * 1e-3)
    if family_png is not None:
        from railhunt.plots import plot_bifurcation_family

        plot_bifurcation_family(family, family_png)
    summary = [{"F_u_kN": None if fu >= _NO_BLOWOFF else fu * 1e-3, "hopf_type": d.hopf_type,
                "hopf_speed_kmh": d.hopf_speed_kmh, "fold_speed_kmh": d.fold_speed_kmh}
               for fu, d in family]  # fmt: skip
    if as_json:
        data = diagram.to_dict(point_p_amplitude=initial_mm * 1e-3)
        data["vehicle"] = vehicle.name
        if family:
            data["fu_family"] = summary
        click.echo(json.dumps(_json_safe(data), indent=2))
        return
    out = _stdout_console()
    out.print(f"vehicle: {vehicle.name}")
    out.print(f"Hopf point (linear critical speed): {_fmt(diagram.hopf_speed_kmh, '.1f', 'km/h')}"
              f" at {_fmt(diagram.hopf_frequency_hz, '.2f', 'Hz')}"
              f" (from the orbits: {_fmt(diagram.hopf_speed_from_orbits_kmh, '.1f', 'km/h')})")
    out.print(f"bifurcation type: {diagram.hopf_type}")
    out.print(f"nonlinear critical speed (lowest limit cycle): "
              f"{_fmt(diagram.fold_speed_kmh, '.1f', 'km/h')}")
    for fold in diagram.folds:
        out.print(f"  fold at {fold.speed_kmh:.1f} km/h, amplitude {fold.amplitude * 1e3:.2f} mm")
    vp = diagram.point_p_kmh(initial_mm * 1e-3)
    out.print(f"point P ({initial_mm:g} mm meets an unstable branch): {_fmt(vp, '.1f', 'km/h')}")
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


@main.command(short_help="Hunting frequency vs speed (eigenvalue, then limit cycle).")
@_kmh_option("--from", "from_kmh", 250.0, 1000.0, "Lowest speed (km/h).")
@_kmh_option("--to", "to_kmh", 450.0, 1000.0, "Highest speed (km/h).")
@_kmh_option("--step", "step_kmh", 10.0, 1000.0, "Speed step (km/h).")
@_initial_amplitude_option("Initial lateral displacement of every wheelset (mm).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON on stdout.")
@_png_option("Draw frequency vs speed like the paper's Fig. 7b, the jump dashed.")
@click.option("--damper-png", "damper_png", type=click.Path(dir_okay=False, path_type=Path),
              metavar="FILE", help="Draw, like the paper's Fig. 8, the leading wheelset's "
              "displacement and a yaw damper's velocity against the blow-off velocity at the "
              "first speed with a limit cycle.")  # fmt: skip
@_vehicle_options
def frequency(from_kmh: float, to_kmh: float, step_kmh: float, initial_mm: float,
              as_json: bool, png_file: Path | None, damper_png: Path | None,
              vehicle_file: Path | None, sets: dict[str, float]) -> None:  # fmt: skip
    """Hunting frequency of the leading wheelset versus speed (Hz).

    \b
    At each speed the vehicle is released from an initial lateral displacement
    of its wheelsets on ideal track. Where the motion decays, the frequency is
    that of the hunting eigenvalue; where it grows to a limit cycle, that of the
    cycle (FFT of the displacement after the transient, refined by shooting the
    periodic orbit). The switch between the two is the paper's frequency jump.
    """
    _check_outputs(png=png_file, **{"damper-png": damper_png})
    n = _speed_count(from_kmh, to_kmh, step_kmh, 500)
    vehicle = _build_vehicle(vehicle_file, sets)
    import numpy as np

    from railhunt.analysis.frequency import frequency_jump, hunting_frequency
    from railhunt.model import Model

    model = Model(vehicle)
    speeds = from_kmh + step_kmh * np.arange(n)
    results = []
    with _spinner("simulating speeds"):
        for s in speeds:
            results.append(hunting_frequency(vehicle, float(s), initial_mm * 1e-3, model=model))
    freqs = np.array([r.frequency_hz for r in results])
    sources = [r.source for r in results]
    jump = frequency_jump(speeds, freqs, sources)
    if png_file is not None:
        from railhunt.plots import plot_hunting_frequency

        plot_hunting_frequency(speeds, freqs, sources, png_file, initial_mm * 1e-3)
    if damper_png is not None:
        from railhunt.plots import plot_damper_velocity

        pick = next((r for r in results if r.source == "limit-cycle"), results[-1])
        plot_damper_velocity(pick.t, pick.y, pick.damper_velocity, pick.blowoff_velocity,
                             damper_png, f"{pick.speed_kmh:g} km/h, {pick.verdict}")  # fmt: skip
    if as_json:
        data = {
            "vehicle": vehicle.name,
            "initial_amplitude_mm": initial_mm,
            "jump": None if jump is None else {"speed_kmh": jump[0], "from_hz": jump[1],
                                               "to_hz": jump[2]},
            "points": [r.to_dict() for r in results],
        }  # fmt: skip
        click.echo(json.dumps(_json_safe(data), indent=2))
        return
    from rich.table import Table

    table = Table(title=f"hunting frequency of {vehicle.name}, {initial_mm:g} mm release")
    for head in ("speed (km/h)", "frequency (Hz)", "from", "amplitude (mm)", "eigen f (Hz)"):
        table.add_column(head, justify="right")
    for r in results:
        table.add_row(f"{r.speed_kmh:g}", _fmt(r.frequency_hz, ".3f"), r.source,
                      _fmt(r.amplitude * 1e3, ".2f"),
                      _fmt(r.eigen_frequency_hz, ".3f"))  # fmt: skip
    out = _stdout_console()
    out.print(table)
    if jump is None:
        out.print("no frequency jump in this speed range")
    else:
        out.print(f"frequency jump near {jump[0]:.1f} km/h: {jump[1]:.2f} Hz -> {jump[2]:.2f} Hz")
    for f in (png_file, damper_png):
        if f is not None:
            out.print(f"wrote {f}")
