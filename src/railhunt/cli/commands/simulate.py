"""``railhunt simulate``: one run at one speed, over a defect, an offset or an irregular track."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.options import (
    CURVE_LEAD_IN,
    CURVE_RULES,
    build_curve,
    build_vehicle,
    check_outputs,
    curve_options,
    defect_options,
    file_option,
    measured_track,
    method_options,
    number_range,
    overwrite_option,
    random_track_options,
    single_defect,
    vehicle_options,
    write_sidecar,
)
from railhunt.cli.output import announce, command_record, spinner
from railhunt.cli.rules import Excludes, Ordered, Requires, command
from railhunt.verdicts import verdict_help

RULES = (
    Ordered("--output-dt", "--duration",
            "--output-dt {output_dt:g} s is invalid: must be <= --duration {duration:g} s"),
    Excludes("--initial-displacement", ("--amplitude", "--wavelength"),
             "{a} cannot be combined with {b}: choose either a track defect or an initial "
             "displacement"),
    Excludes("--spectrum", "--irregularity", "{a} cannot be combined with {b}: choose one track"),
    Excludes(("--spectrum", "--irregularity"),
             ("--amplitude", "--wavelength", "--initial-displacement"),
             "{a} cannot be combined with {b}: choose one excitation"),
    Requires("--seed", "--spectrum", "{a} only applies with {b}"),
    *CURVE_RULES,
)  # fmt: skip


@command("simulate", rules=RULES, epilog=verdict_help(),
         short_help="Simulate one speed: time history and phase plane.")
@click.option(
    "--speed",
    type=float,
    required=True,
    metavar="KMH",
    callback=number_range("km/h", 0.0, 1000.0),
    help="Forward speed (km/h).",
)
@click.option(
    "--duration",
    type=float,
    default=10.0,
    show_default=True,
    metavar="S",
    callback=number_range("s", 0.0, 1e5),
    help="Simulated time (s).",
)
@defect_options("Peak lateral displacement of the single track defect (mm), within ±50 mm.")
@click.option(
    "--initial-displacement",
    type=float,
    default=None,
    metavar="MM",
    callback=number_range("mm", -20.0, 20.0, low_open=False, optional=True),
    help="Instead of a track defect, start with every wheelset displaced "
    "laterally by this much (mm) on ideal track, within ±20 mm (a start beyond it is "
    "past the flange, toward the 25 mm derailment limit).",
)
@random_track_options(
    None,
    "Instead of a track defect, run over a random lateral alignment following this "
    "track spectrum (german-low, german-high, fra-1 ... fra-6), long enough for the whole "
    "run, and report the acceptance-test instability criterion.",
    "With --spectrum:",
    "Instead of a track defect, run over this measured alignment",
)
@curve_options("Length of each transition curve of --curve-radius (m) [default: R/10, "
               "within 20-300 m].")
@method_options
@click.option(
    "--output-dt",
    "--output-step",
    "output_dt",
    type=float,
    default=None,
    metavar="S",
    callback=number_range("s", optional=True),
    help="Keep one output sample per this interval (s); --output-step is the same option. "
    "Default: every step.",
)
@file_option("--csv", "csv_file", "Write all channels (SI units, header with units).")
@file_option("--png", "png_file", "Plot the leading wheelset: lateral displacement (mm) vs "
             "time and its phase plane after 3 s (with --curve-radius: the curve entry, "
             "wheelsets, yaw damper forces and Y/Q against distance).")  # fmt: skip
@overwrite_option
@vehicle_options
def simulate_command(
    speed: float,
    duration: float,
    amplitude: float,
    wavelength: float,
    initial_displacement: float | None,
    spectrum: str | None,
    seed: int,
    irregularity_file: Path | None,
    curve_radius: float | None,
    cant_mm: float | None,
    transition: float | None,
    direction: str,
    method: str,
    dt: float | None,
    output_dt: float | None,
    csv_file: Path | None,
    png_file: Path | None,
    overwrite: bool,
    vehicle_file: Path | None,
    sets: dict[str, float],
) -> None:
    """Simulate the vehicle at one constant speed on straight track.

    \b
    By default the vehicle runs over a single lateral alignment defect (a
    smooth one-sided bump of --amplitude mm over --wavelength m, 1 m ahead)
    followed by ideal track; with --initial-displacement it instead starts
    with its wheelsets offset on ideal track. Below the critical speed the
    motion decays back to the centre line; above it the leading wheelset
    settles on a hunting limit cycle, or it derails (beyond 25 mm); the
    verdict line says which, and tells a numerical blow-up from a
    derailment. A 'limit:' line names each limit of the validity envelope the
    run reached (the largest value, where and when); none changes the verdict.

    \b
    With --spectrum NAME (or --irregularity FILE) it runs over an irregular
    track instead (the paper's excitation type (c)), each wheelset meeting it
    in turn, and prints the acceptance-test instability criterion (100 m
    sliding rms of the sum of guiding forces and of the bogie frame lateral
    acceleration, band-passed f0 +/- 2 Hz, against their limits).

    \b
    With --curve-radius M the track turns into a curve (--cant, --transition,
    --direction) after the excitation: its entry transition begins 20 m after
    the single defect (or 20 m ahead with the other excitations), and
    displacements are measured from the track at each body's position.

    Prints the solver's status (how the integration ended), the verdict on
    the run (stable, hunting, undecided, derailed or blow-up, the words
    below; with the leading wheelset's amplitude in mm, judged after the
    excitation as the critical-speed search judges a trial) and the peak and
    final lateral amplitude (mm); --csv and --png save the details (the CSV's
    metadata in FILE.meta.json).
    """
    check_outputs(overwrite=overwrite, csv=csv_file, png=png_file)
    tracks = (("--spectrum", spectrum), ("--irregularity", irregularity_file))
    irregular = [flag for flag, value in tracks if value]
    vehicle = build_vehicle(vehicle_file, sets)

    import numpy as np

    from railhunt import InitialDisplacement, simulate

    if initial_displacement is not None:
        with user_input():
            excitation: Any = InitialDisplacement(
                amplitude=initial_displacement * 1e-3,
                wheelsets=tuple(range(1, len(vehicle.layout.wheelsets) + 1)))
        described = f"all wheelsets displaced by {initial_displacement:g} mm"
    elif irregular:
        from railhunt import track_irregularity
        from railhunt.units import kmh_to_ms

        with user_input(f"{irregular[0]}: "):
            if spectrum:
                length = min(max(kmh_to_ms(speed) * duration, 200.0), 1e5)
                excitation = track_irregularity(spectrum, length=length, seed=seed)
                described = f"{spectrum} irregularity, seed {seed}"
            else:
                excitation = measured_track(irregularity_file)
                described = f"measured alignment {irregularity_file}"
        described += f", {excitation.length:g} m, rms {excitation.rms * 1e3:.2f} mm"
    else:
        excitation = single_defect(amplitude, wavelength)
        described = f"{amplitude:g} mm x {wavelength:g} m lateral bump at {excitation.start:g} m"
    lead_in = CURVE_LEAD_IN + (excitation.start + excitation.wavelength
                               if initial_displacement is None and not irregular else 0.0)
    curve = build_curve(curve_radius, cant_mm, transition, direction, start=lead_in)
    _check_work(vehicle, speed, duration, method, dt, output_dt)
    with spinner(f"simulating {duration:g} s at {speed:g} km/h ..."), user_input():
        result = simulate(
            vehicle,
            speed,
            duration=duration,
            excitation=excitation,
            method=method,
            dt=dt,
            output_dt=output_dt,
            curve=curve,
        )

    t = result.t
    y = np.abs(result["y_w1"]) * 1e3
    final = float(y[t >= t[-1] - 1.0].max())
    note = "max |y_w1| over the last 1 s"
    if result.excitation_end > t[-1] and not irregular:
        note += "; the run ended before the last wheelset left the defect"
    click.echo(f"vehicle:    {vehicle.name}")
    click.echo(f"speed:      {speed:g} km/h, {method}, {t[-1]:g} s simulated")
    click.echo(f"excitation: {described}")
    from railhunt import Model
    from railhunt.analysis.critical import judge_run
    from railhunt.analysis.linearity import is_linear

    verdict = judge_run(result, two_sided=curve is not None,
                        linear_model=is_linear(Model(vehicle)))  # fmt: skip
    click.echo(f"status:     solver {result.status} ({result.message})")
    if not irregular:
        click.echo(f"verdict:    {verdict.text}")
    click.echo(f"y_w1:       peak {y.max():.3f} mm, final amplitude {final:.3f} mm ({note})")
    if curve is not None:
        from railhunt.cli.commands.curve import print_run_in_curve

        print_run_in_curve(result, vehicle, curve)
    if irregular:
        _print_criterion(result, vehicle)
    limits = {lim.text for lim in result.limits}
    for warning in result.warnings:  # a blow-up; the limits below
        if warning not in limits:
            click.echo(f"warning:    {warning}")
    for lim in result.limits:
        click.echo(f"limit:      {lim.text}: changes no verdict")
    if csv_file is not None:
        with user_input("cannot write --csv: "):
            result.to_csv(csv_file)
            write_sidecar(csv_file, _provenance(vehicle), **command_record(),
                          columns=result.table()[0], status=result.status,
                          verdict=None if irregular else verdict.verdict)  # fmt: skip
        click.echo(f"csv:        {csv_file} ({t.size} rows, {len(result.channel_names)} channels)")
    if png_file is not None:
        from railhunt.plots import plot_curve_entry, plot_time_history

        with spinner("plotting ..."), user_input("cannot write --png: "):
            if curve is None:
                plot_time_history(result, png_file,
                                  verdict=None if irregular else verdict.short)
            else:
                plot_curve_entry(result, vehicle, png_file, curve=curve)
        click.echo(f"png:        {png_file}")


def _provenance(vehicle: Any) -> dict[str, Any]:
    from railhunt.provenance import provenance

    return provenance(vehicle)


def _check_work(vehicle: Any, speed: float, duration: float, method: str, dt: float | None,
                output_dt: float | None) -> None:  # fmt: skip
    """Before the run: refuse a stiff damper's step or histories that do not fit in memory
    (naming the flags that help), and announce a run of more than a minute."""
    from railhunt import Model
    from railhunt.simulation import OutputTooLargeError, auto_step, check_output_size
    from railhunt.units import kmh_to_ms
    from railhunt.workload import workload

    with user_input("--set/--vehicle: "):
        step = dt if dt is not None else auto_step(Model(vehicle), kmh_to_ms(speed))
    try:
        check_output_size(duration, step, output_dt, method, vehicle.assembly.layout)
    except OutputTooLargeError as exc:
        every = f"every {output_dt:g} s" if output_dt is not None else f"every {step:g} s step"
        hint = (f"--output-dt {exc.output_dt:g}" if exc.output_dt else "--output-dt S")
        raise CliError(f"--duration {duration:g} s with one sample {every} gives "
                       f"{exc.rows:.3g} rows, about {exc.nbytes / 1e9:.3g} GB: more than half "
                       f"the {exc.available / 1e9:.3g} GB of memory available; give {hint} "
                       "(--output-step) or a shorter --duration") from None
    if method == "rk4":
        announce(workload(duration, step, f"{duration:g} s simulated"), vehicle,
                 kmh_to_ms(speed))  # fmt: skip


def _print_criterion(result: Any, vehicle: Any) -> None:
    """The acceptance-test instability criterion of a run over an irregular track."""
    from railhunt import assess_stability

    with user_input():
        a = assess_stability(result, vehicle)
    if a.distance.size:
        click.echo(
            f"criterion:  {a.verdict} (f0 {a.f0_hz:.2f} Hz; ΣY rms max "
            f"{a.sum_y_rms.max() / 1e3:.2f} kN = {a.sum_y_ratio:.2f} x limit "
            f"{a.sum_y_limit / 1e3:.2f} kN; bogie frame rms max "
            f"{a.acceleration_rms.max():.2f} m/s^2 = {a.acceleration_ratio:.2f} x limit "
            f"{a.acceleration_limit:.2f} m/s^2)"
        )
    else:
        click.echo("criterion:  not evaluated (the run covers less than 100 m of track)")
