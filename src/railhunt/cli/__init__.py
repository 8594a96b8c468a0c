"""Command line interface: ``railhunt simulate | eigen | critical-speed | parameters | ...``.

The interface converts units at its edge (defect amplitudes in mm, speeds in km/h) and
calls the Python API in SI units. Every input error ends the program with one line on
stderr starting with ``railhunt: error:`` and exit status 2. Numba-compiled modules are
imported inside the commands, so ``railhunt --help`` stays fast.
"""

from __future__ import annotations

import contextlib
import functools
import json
import math
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

if TYPE_CHECKING:
    from railhunt.vehicle import Vehicle

__all__ = ["CliError", "main"]

PROG = "railhunt"
_NO_ARGS_IS_HELP = getattr(click.exceptions, "NoArgsIsHelpError", ())


# --------------------------------------------------------------------------- errors


class CliError(click.ClickException):
    """A user error: shown as one ``railhunt: error: ...`` line, exit status 2."""

    exit_code = 2

    def __init__(self, message: str) -> None:
        super().__init__(" ".join(str(message).split()))

    def show(self, file: Any = None) -> None:
        """Write the one-line message to stderr (``file`` is ignored)."""
        click.echo(f"{PROG}: error: {self.format_message()}", err=True)


@contextlib.contextmanager
def _one_line_usage_errors() -> Iterator[None]:
    """Turn click's multi-line usage errors into a :class:`CliError`."""
    try:
        yield
    except _NO_ARGS_IS_HELP:
        raise
    except click.UsageError as exc:
        message = exc.format_message()
        if exc.ctx is not None:
            message += f" (see '{exc.ctx.command_path} --help')"
        raise CliError(message) from None


@contextlib.contextmanager
def _user_input(prefix: str = "") -> Iterator[None]:
    """Report ``ValueError`` (invalid inputs) and ``OSError`` (files) as a :class:`CliError`."""
    try:
        yield
    except OSError as exc:
        where = f"{exc.filename}: " if exc.filename else ""
        raise CliError(f"{prefix}{where}{exc.strerror or exc}") from None
    except ValueError as exc:
        raise CliError(f"{prefix}{exc}") from None


class _Group(click.Group):
    """A group whose usage errors (from any subcommand) are one line and exit 2."""

    def make_context(
        self,
        info_name: str | None,
        args: list[str],
        parent: click.Context | None = None,
        **extra: Any,
    ) -> click.Context:
        with _one_line_usage_errors():
            return super().make_context(info_name, args, parent, **extra)

    def invoke(self, ctx: click.Context) -> Any:
        with _one_line_usage_errors():
            return super().invoke(ctx)


# --------------------------------------------------------------------------- option helpers


def _number_range(
    unit: str,
    low: float = 0.0,
    high: float = math.inf,
    low_open: bool = True,
    optional: bool = False,
) -> Callable[[click.Context, click.Parameter, float | None], float | None]:
    """Option callback: a finite number in ``(low, high]`` (or ``[low, high]``)."""

    def check(ctx: click.Context, param: click.Parameter, value: float | None) -> float | None:
        if value is None and optional:
            return None
        above = value > low if low_open else value >= low
        if value is None or not (math.isfinite(value) and above and value <= high):
            left = "(" if low_open else "["
            hi = "inf)" if math.isinf(high) else f"{high:g}]"
            raise click.BadParameter(
                f"{value:g} {unit} is not a valid value: must be finite and in "
                f"{left}{low:g}, {hi} {unit}"
            )
        return value

    return check


def _parse_set(
    ctx: click.Context, param: click.Parameter, items: tuple[str, ...]
) -> dict[str, float]:
    """Option callback of ``--set``: ``NAME=VALUE`` items to a dict of checked SI floats."""
    from railhunt.vehicle import UnknownParameterError, validate_value

    changes: dict[str, float] = {}
    for item in items:
        name, sep, text = item.partition("=")
        name, text = name.strip(), text.strip()
        if not sep or not name or not text:
            raise click.BadParameter(
                f"{item!r} is not of the form NAME=VALUE (SI units), e.g. --set C_d1=150e3"
            )
        try:
            value = float(text)
        except ValueError:
            raise click.BadParameter(
                f"{name}={text}: {text!r} is not a number (give the SI value, e.g. 1.5e5)"
            ) from None
        try:
            changes[name] = validate_value(name, value)
        except UnknownParameterError as exc:
            message = str(exc)
            if not exc.suggestions:
                message = f"unknown vehicle parameter {name!r}; 'railhunt parameters' lists them"
            raise click.BadParameter(f"{name}={text}: {message}") from None
        except ValueError as exc:
            raise click.BadParameter(f"{name}={text}: {exc}") from None
    return changes


def _vehicle_options(func: Callable[..., Any]) -> Callable[..., Any]:
    """Add ``--vehicle FILE`` and repeatable ``--set NAME=VALUE`` to a command."""
    func = click.option(
        "--set",
        "sets",
        metavar="NAME=VALUE",
        multiple=True,
        callback=_parse_set,
        help="Change one vehicle parameter, in SI units (repeatable), e.g. --set C_d1=150e3 "
        "(yaw damper first-stage damping, N*s/m). 'railhunt parameters' lists the names.",
    )(func)
    func = click.option(
        "--vehicle",
        "vehicle_file",
        metavar="FILE|NAME",
        callback=_vehicle_source,
        help="Vehicle TOML file (SI units), or the name of a vehicle shipped with railhunt: "
        "paper2019; s1002_uic60 (the paper's vehicle with S1002 wheels on UIC60 rails 1:40, "
        "fitted polynomials); s1002_uic60_table (the same with the contact geometry "
        "tabulated from the profiles). Default: paper2019.",
    )(func)
    return func


def _vehicle_source(
    ctx: click.Context, param: click.Parameter, value: str | None
) -> Path | str | None:
    """``--vehicle``: an existing file, else the name of a shipped vehicle."""
    if value is None:
        return None
    path = Path(value)
    if path.is_file():
        return path
    from railhunt.vehicle import shipped_vehicles

    names = shipped_vehicles()
    if value in names:
        return value
    raise click.BadParameter(
        f"{value!r} is neither a file nor a shipped vehicle ({', '.join(names)})"
    )


def _build_vehicle(vehicle_file: Path | str | None, sets: dict[str, float]) -> Vehicle:
    """The vehicle of ``--vehicle`` (or paper2019) with the ``--set`` changes applied."""
    from railhunt.vehicle import Vehicle, load_vehicle

    with _user_input():
        if vehicle_file is None:
            vehicle = Vehicle.paper2019()
        elif isinstance(vehicle_file, str):
            vehicle = Vehicle.shipped(vehicle_file)
        else:
            vehicle = load_vehicle(vehicle_file)
    if sets:
        given = ", ".join(f"{k}={v:g}" for k, v in sets.items())
        with _user_input(f"--set {given}: "):
            vehicle = vehicle.replace(name=f"{vehicle.name} with {given}", **sets)
    return vehicle


def _check_outputs(**files: Path | None) -> None:
    """Fail early (before a long run) when an output file's folder does not exist."""
    for option, path in files.items():
        if path is not None and not path.resolve().parent.is_dir():
            raise CliError(f"--{option} {path}: folder {str(path.parent)!r} does not exist")


def _speed_count(from_kmh: float, to_kmh: float, step_kmh: float, most: int) -> int:
    """Number of speeds ``from, from + step, ... <= to`` of a ``--from/--to/--step`` scan."""
    if to_kmh < from_kmh:
        raise CliError(f"--to {to_kmh:g} km/h is below --from {from_kmh:g} km/h")
    n = int(math.floor((to_kmh - from_kmh) / step_kmh + 1e-9)) + 1
    if n > most:
        raise CliError(f"--step {step_kmh:g} km/h gives {n} speeds: at most {most} are allowed")
    return n


def _random_track_options(
    default: str | None, spectrum_help: str, seed_context: str, irregularity_help: str
) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Add ``--spectrum NAME``, ``--seed N`` (a random track) and ``--irregularity FILE``
    (a measured one) to a command."""

    def decorate(func: Callable[..., Any]) -> Callable[..., Any]:
        func = click.option(
            "--irregularity",
            "irregularity_file",
            type=click.Path(exists=True, dir_okay=False, path_type=Path),
            metavar="FILE",
            help=f"{irregularity_help} (CSV with columns 'distance' and 'alignment', units "
            "[m] or [mm] in the header; shifted to start at 0 m and faded in and out over "
            "20 m).",
        )(func)
        func = click.option(
            "--seed",
            type=click.IntRange(min=0),
            default=1,
            show_default=True,
            help=f"{seed_context} seed of the random track (same seed, same track).",
        )(func)
        return click.option(
            "--spectrum",
            default=default,
            show_default=default is not None,
            metavar="NAME",
            help=spectrum_help,
        )(func)

    return decorate


def _kmh_option(
    flag: str, dest: str, default: float, high: float, help: str
) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """A speed option in km/h, finite and in ``(0, high]``."""
    return click.option(
        flag,
        dest,
        type=float,
        default=default,
        show_default=True,
        metavar="KMH",
        callback=_number_range("km/h", 0.0, high),
        help=help,
    )


def _defect_options(amplitude_help: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Add ``--amplitude`` (mm) and ``--wavelength`` (m) of the single track defect."""

    def decorate(func: Callable[..., Any]) -> Callable[..., Any]:
        func = click.option(
            "--wavelength",
            type=float,
            default=20.0,
            show_default=True,
            metavar="M",
            callback=_number_range("m", 0.5, 1000.0, low_open=False),
            help="Length of the single track defect along the track (m).",
        )(func)
        return click.option(
            "--amplitude",
            type=float,
            default=8.0,
            show_default=True,
            metavar="MM",
            callback=_number_range("mm", -50.0, 50.0, low_open=False),
            help=amplitude_help,
        )(func)

    return decorate


def _single_defect(amplitude_mm: float, wavelength: float) -> Any:
    """The :class:`railhunt.track.SingleDefect` the defect options describe (mm to m)."""
    from railhunt.track import SingleDefect

    with _user_input():
        return SingleDefect(amplitude=amplitude_mm * 1e-3, wavelength=wavelength)


def _method_options(func: Callable[..., Any], stochastic: bool = False) -> Callable[..., Any]:
    """Add ``--method`` and ``--dt`` to a command (``stochastic``: also the search method)."""
    func = click.option(
        "--dt",
        type=float,
        default=None,
        metavar="S",
        callback=_number_range("s", 0.0, 0.01, optional=True),
        help="Time step of the fixed-step rk4 integrator (s). Default: chosen from the "
        "model's fastest dynamics (1 ms for the paper's vehicle).",
    )(func)
    choices = ["rk4", "dopri5"] + (["stochastic"] if stochastic else [])
    text = (
        "Integrator: classical fixed-step Runge-Kutta (the paper's) or adaptive "
        "Dormand-Prince 5(4)."
    )
    if stochastic:
        text = (
            "rk4, dopri5: the single-defect method with that integrator (classical "
            "fixed-step Runge-Kutta, the paper's, or adaptive Dormand-Prince 5(4)). "
            "stochastic: run (with rk4) over a random irregular track instead and find the "
            "lowest speed that breaks the acceptance-test instability criterion (EN 14363 "
            "style)."
        )
    func = click.option(
        "--method",
        type=click.Choice(choices),
        default="rk4",
        show_default=True,
        help=text,
    )(func)
    return func


# --------------------------------------------------------------------------- progress


def _show_progress() -> bool:
    """Progress displays only when stderr is a terminal (never in pipes, logs or tests)."""
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


@contextlib.contextmanager
def _spinner(text: str) -> Iterator[None]:
    """A rich spinner on stderr while a step runs (only on a terminal)."""
    if not _show_progress():
        yield
        return
    from rich.console import Console

    with Console(stderr=True).status(text):
        yield


def _stdout_console() -> Any:
    from rich.console import Console

    return Console(highlight=False)


def _fmt(value: float, spec: str, unit: str = "") -> str:
    if value is None or not math.isfinite(value):
        return "n/a"
    text = format(value, spec)
    return f"{text} {unit}" if unit else text


def _json_safe(obj: Any) -> Any:
    """Recursively convert to JSON types, NaN and infinities to ``None``."""
    if isinstance(obj, dict):
        return {str(k): _json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_json_safe(v) for v in obj]
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    if isinstance(obj, int):
        return obj
    try:
        value = float(obj)
    except (TypeError, ValueError):
        return str(obj)
    return value if math.isfinite(value) else None


# --------------------------------------------------------------------------- group

_MAIN_HELP = """\
Hunting stability of a high-speed railway vehicle (17-DOF lateral model).

\b
Hunting is the self-excited lateral oscillation of a railway vehicle. The
coned wheel treads steer each wheelset back towards the track centre, so at
low speed a lateral disturbance dies out. Above a critical speed the creep
forces between wheel and rail feed energy into this motion instead: the
wheelsets and bogies swing from side to side on a limit cycle of a few Hz,
wearing wheels and rails and risking flange contact and derailment.

\b
Which command answers which question:
  simulate        What does the vehicle do at one speed after a track
                  defect (or an initial offset)?  Time history, phase plane.
  eigen           How well damped is the hunting mode of the linearised
                  model at each speed, and at what frequency does it hunt?
  critical-speed  Above which speed does the vehicle hunt?  Nonlinear
                  (simulation, the paper's method) and linear (eigenvalues);
                  --method stochastic: irregular track, EN 14363 criterion.
  parameters      Which vehicle parameters exist, with values and units.
  spectrogram     Which frequencies dominate a measured signal, and when?
                  (short-time Fourier transform of a CSV channel)
  sweep           Which parameters move the critical speed and the hunting
                  frequency?  Lines, grids and samples of vehicles, on all
                  cores or a Dask cluster; resumable results files.
  sections        How much of that change happens in each section of the
                  paper's Table 1 ranges?  (Fig. 12, frequency jump removed)
  plot            V_cr and hunting frequency against each swept parameter
                  from a results file (Figs. 10 and 11).

\b
Units: speeds in km/h; defect amplitudes and displacements in mm;
wavelengths in m; times in s; frequencies in Hz. Vehicle parameters
(--vehicle FILE, --set NAME=VALUE) are always SI (kg, N/m, N*s/m, m, ...),
exactly as in the vehicle TOML files.

\b
Examples:
  railhunt simulate --speed 320 --png run.png
  railhunt eigen --from 100 --to 500 --png locus.png
  railhunt critical-speed --set C_d1=150e3 --json

Input errors are reported as one 'railhunt: error:' line with exit status 2.
"""


@click.group(
    PROG,
    cls=_Group,
    help=_MAIN_HELP,
    context_settings={"help_option_names": ["-h", "--help"]},
)
@click.version_option(package_name="railhunt", prog_name=PROG)
def main() -> None:
    """Entry point of the railhunt command (help text: _MAIN_HELP)."""


# --------------------------------------------------------------------------- simulate


@main.command(short_help="Simulate one speed: time history and phase plane.")
@click.option(
    "--speed",
    type=float,
    required=True,
    metavar="KMH",
    callback=_number_range("km/h", 0.0, 1000.0),
    help="Forward speed (km/h).",
)
@click.option(
    "--duration",
    type=float,
    default=10.0,
    show_default=True,
    metavar="S",
    callback=_number_range("s", 0.0, 1e5),
    help="Simulated time (s).",
)
@_defect_options("Peak lateral displacement of the single track defect (mm), within ±50 mm.")
@click.option(
    "--initial-displacement",
    type=float,
    default=None,
    metavar="MM",
    callback=_number_range("mm", -50.0, 50.0, low_open=False, optional=True),
    help="Instead of a track defect, start with all four wheelsets displaced "
    "laterally by this much (mm) on ideal track.",
)
@_random_track_options(
    None,
    "Instead of a track defect, run over a random lateral alignment following this "
    "track spectrum (german-low, german-high, fra-1 ... fra-6), long enough for the whole "
    "run, and report the acceptance-test instability criterion.",
    "With --spectrum:",
    "Instead of a track defect, run over this measured alignment",
)
@_method_options
@click.option(
    "--output-dt",
    type=float,
    default=None,
    metavar="S",
    callback=_number_range("s", optional=True),
    help="Keep one output sample per this interval (s). Default: every step.",
)
@click.option(
    "--csv",
    "csv_file",
    type=click.Path(dir_okay=False, path_type=Path),
    metavar="FILE",
    help="Write all channels (SI units, header with units).",
)
@click.option(
    "--png",
    "png_file",
    type=click.Path(dir_okay=False, path_type=Path),
    metavar="FILE",
    help="Plot the leading wheelset: lateral displacement (mm) vs "
    "time and its phase plane after 3 s.",
)
@_vehicle_options
def simulate(
    speed: float,
    duration: float,
    amplitude: float,
    wavelength: float,
    initial_displacement: float | None,
    spectrum: str | None,
    seed: int,
    irregularity_file: Path | None,
    method: str,
    dt: float | None,
    output_dt: float | None,
    csv_file: Path | None,
    png_file: Path | None,
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
    settles on a hunting limit cycle (or derails beyond 25 mm).

    \b
    With --spectrum NAME (or --irregularity FILE) it runs over an irregular
    track instead (the paper's excitation type (c)), each wheelset meeting it
    in turn, and prints the acceptance-test instability criterion (100 m
    sliding rms of the sum of guiding forces and of the bogie frame lateral
    acceleration, band-passed f0 +/- 2 Hz, against their limits).

    Prints the run's status and the leading wheelset's peak and final
    lateral amplitude (mm); --csv and --png save the details.
    """
    _check_outputs(csv=csv_file, png=png_file)
    if output_dt is not None and output_dt > duration:
        raise CliError(
            f"--output-dt {output_dt:g} s is invalid: must be <= --duration {duration:g} s"
        )
    ctx = click.get_current_context()
    explicit = [
        name
        for name in ("amplitude", "wavelength")
        if ctx.get_parameter_source(name) is click.core.ParameterSource.COMMANDLINE
    ]
    if initial_displacement is not None and explicit:
        raise CliError(
            f"--initial-displacement cannot be combined with --{explicit[0]}: "
            "choose either a track defect or an initial displacement"
        )
    track_given = (("--spectrum", spectrum), ("--irregularity", irregularity_file))
    irregular = [flag for flag, value in track_given if value]
    if len(irregular) == 2:
        raise CliError("--spectrum cannot be combined with --irregularity: choose one track")
    if irregular and (explicit or initial_displacement is not None):
        other = f"--{explicit[0]}" if explicit else "--initial-displacement"
        raise CliError(
            f"{irregular[0]} cannot be combined with {other}: choose one excitation"
        )
    if ctx.get_parameter_source("seed") is click.core.ParameterSource.COMMANDLINE and not spectrum:
        raise CliError("--seed only applies with --spectrum")
    vehicle = _build_vehicle(vehicle_file, sets)

    import numpy as np

    from railhunt.simulation import simulate as run_simulation
    from railhunt.track import InitialDisplacement

    if initial_displacement is not None:
        with _user_input():
            excitation: Any = InitialDisplacement(amplitude=initial_displacement * 1e-3)
        described = f"all wheelsets displaced by {initial_displacement:g} mm"
    elif irregular:
        from railhunt.cli.stochastic import measured_track
        from railhunt.irregularity import track_irregularity

        with _user_input(f"{irregular[0]}: "):
            if spectrum:
                length = min(max(speed / 3.6 * duration, 200.0), 1e5)
                excitation = track_irregularity(spectrum, length=length, seed=seed)
                described = f"{spectrum} irregularity, seed {seed}"
            else:
                excitation = measured_track(irregularity_file)
                described = f"measured alignment {irregularity_file}"
        described += f", {excitation.length:g} m, rms {excitation.rms * 1e3:.2f} mm"
    else:
        excitation = _single_defect(amplitude, wavelength)
        described = f"{amplitude:g} mm x {wavelength:g} m lateral bump at {excitation.start:g} m"
    with _spinner(f"simulating {duration:g} s at {speed:g} km/h ..."), _user_input():
        result = run_simulation(
            vehicle,
            speed,
            duration=duration,
            excitation=excitation,
            method=method,
            dt=dt,
            output_dt=output_dt,
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
    click.echo(f"status:     {result.status} ({result.message})")
    click.echo(f"y_w1:       peak {y.max():.3f} mm, final amplitude {final:.3f} mm ({note})")
    if irregular:
        from railhunt.analysis.stochastic import assess

        with _user_input():
            a = assess(result, vehicle)
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

    if csv_file is not None:
        with _user_input("cannot write --csv: "):
            result.to_csv(csv_file)
        click.echo(f"csv:        {csv_file} ({t.size} rows, {len(result.channel_names)} channels)")
    if png_file is not None:
        from railhunt.plots import plot_time_history

        with _spinner("plotting ..."), _user_input("cannot write --png: "):
            plot_time_history(result, png_file)
        click.echo(f"png:        {png_file}")


# --------------------------------------------------------------------------- eigen


@main.command(short_help="Hunting frequency and damping vs speed (linearised model).")
@_kmh_option("--from", "from_kmh", 50.0, 1000.0, "Lowest speed (km/h).")
@_kmh_option("--to", "to_kmh", 500.0, 1000.0, "Highest speed (km/h).")
@_kmh_option("--step", "step_kmh", 10.0, 1000.0, "Speed step (km/h).")
@click.option(
    "--png",
    "png_file",
    type=click.Path(dir_okay=False, path_type=Path),
    metavar="FILE",
    help="Plot the root locus (eigenvalues coloured by speed, hunting "
    "mode highlighted) and the hunting damping ratio vs speed.",
)
@click.option(
    "--csv",
    "csv_file",
    type=click.Path(dir_okay=False, path_type=Path),
    metavar="FILE",
    help="Write the hunting-mode table (one row per speed).",
)
@_vehicle_options
def eigen(
    from_kmh: float,
    to_kmh: float,
    step_kmh: float,
    png_file: Path | None,
    csv_file: Path | None,
    vehicle_file: Path | None,
    sets: dict[str, float],
) -> None:
    """Hunting mode of the linearised model versus speed.

    \b
    Linearises the model about the centred equilibrium on ideal track and
    computes its 38 eigenvalues at each speed. The hunting mode is the least
    damped oscillation dominated by wheelset lateral/yaw motion; its frequency
    (Hz) rises with speed and its damping ratio falls. Where the damping ratio
    crosses zero is the linear critical speed (Hopf point): above it even a
    tiny disturbance grows. Prints a table of hunting frequency (Hz) and
    damping ratio (%) vs speed (km/h) and the linear critical speed.
    """
    _check_outputs(csv=csv_file, png=png_file)
    n = _speed_count(from_kmh, to_kmh, step_kmh, 5000)
    vehicle = _build_vehicle(vehicle_file, sets)

    import numpy as np

    from railhunt.analysis.linear import eigen_analysis, linear_critical_speed

    speeds = from_kmh + step_kmh * np.arange(n)
    with _spinner(f"eigenvalues at {n} speeds ..."), _user_input():
        res = eigen_analysis(vehicle, speeds)
        linear = linear_critical_speed(vehicle)

    from rich.table import Table

    table = Table(title=f"hunting mode of {vehicle.name} (linearised)")
    for head in ("speed (km/h)", "frequency (Hz)", "damping ratio (%)", "Re λ (1/s)"):
        table.add_column(head, justify="right")
    zeta = res.hunting_damping_ratio
    for s, f, z, lam in zip(speeds, res.hunting_frequency_hz, zeta, res.hunting, strict=True):
        style = "red" if z < 0 else None
        table.add_row(f"{s:g}", f"{f:.3f}", f"{100 * z:.2f}", f"{lam.real:.3f}", style=style)
    console = _stdout_console()
    console.print(table)
    console.print(_linear_line(linear))

    if csv_file is not None:
        header = (
            "speed_kmh,hunting_frequency_hz,hunting_damping_ratio,"
            "hunting_real_per_s,hunting_imag_per_s,max_real_part_per_s"
        )
        data = np.column_stack(
            [
                speeds,
                res.hunting_frequency_hz,
                zeta,
                res.hunting.real,
                res.hunting.imag,
                res.eigenvalues.real.max(axis=1),
            ]
        )
        with _user_input("cannot write --csv: "):
            np.savetxt(csv_file, data, delimiter=",", header=header, comments="", fmt="%.9g")
        click.echo(f"csv: {csv_file}")
    if png_file is not None:
        from railhunt.plots import plot_root_locus

        with _spinner("plotting ..."), _user_input("cannot write --png: "):
            plot_root_locus(res, png_file, linear=linear)
        click.echo(f"png: {png_file}")


def _linear_line(linear: Any) -> str:
    if not math.isfinite(linear.speed_kmh):
        return "linear critical speed: none below 1000 km/h (centred running stays stable)"
    mode = "hunting mode" if linear.is_hunting_mode else "not the hunting mode"
    return (
        f"linear critical speed: {linear.speed_kmh:.1f} km/h "
        f"(Hopf point; {mode} at {linear.frequency_hz:.2f} Hz)"
    )


# --------------------------------------------------------------------------- critical speed


@main.command("critical-speed", short_help="Nonlinear and linear critical speeds (km/h).")
@_defect_options(
    "Peak lateral displacement of the track defect run over at each trial speed (mm), "
    "within ±50 mm."
)
@_kmh_option("--start", "start_kmh", 300.0, 800.0, "First trial speed (km/h).")
@_kmh_option("--step", "step_kmh", 10.0, 800.0,
             "Step while bracketing the critical speed (km/h).")  # fmt: skip
@_kmh_option("--tol", "tol_kmh", 1.0, 800.0,
             "Resolution of the bisection (km/h); at most --step.")  # fmt: skip
@functools.partial(_method_options, stochastic=True)
@_random_track_options(
    "german-high",
    "With --method stochastic: track spectrum of the lateral alignment: german-low, "
    "german-high (German high-speed spectra, low/high disturbance) or fra-1 ... fra-6 "
    "(US FRA track classes, 6 the best).",
    "With --method stochastic:",
    "With --method stochastic: run over this measured alignment instead",
)
@click.option(
    "--track-length",
    type=float,
    default=2000.0,
    show_default=True,
    metavar="M",
    callback=_number_range("m", 200.0, 1e5, low_open=False),
    help="With --method stochastic: length of the irregular track run over at each speed (m).",
)
@click.option(
    "--json",
    "as_json",
    is_flag=True,
    help="Print one JSON object (speeds in km/h; unknown values as null) instead of tables.",
)
@_vehicle_options
def critical_speed(
    amplitude: float,
    wavelength: float,
    start_kmh: float,
    step_kmh: float,
    tol_kmh: float,
    method: str,
    dt: float | None,
    spectrum: str,
    seed: int,
    track_length: float,
    irregularity_file: Path | None,
    as_json: bool,
    vehicle_file: Path | None,
    sets: dict[str, float],
) -> None:
    """Nonlinear and linear critical speeds: above which speed does it hunt?

    \b
    Nonlinear critical speed (the paper's method): at each trial speed the
    vehicle runs over one lateral track defect and the leading wheelset's
    motion is judged 'stable' (decays back to the centre line) or 'hunting'
    (settles on a limit cycle, or derails). Starting at --start the speed is
    stepped by --step until the verdict changes, then bisected to --tol. The
    result is the highest stable speed (km/h).

    \b
    Linear critical speed: where the least damped eigenvalue of the
    linearised model crosses into instability (see 'railhunt eigen'). It is
    usually higher: below it small disturbances die out, but a large enough
    disturbance can already throw the vehicle onto a hunting limit cycle,
    which is why the nonlinear value is the one that matters in service.

    \b
    Stochastic critical speed (--method stochastic, the paper's excitation
    type (c)): at each trial speed the vehicle runs over a random irregular
    track (--spectrum, --seed, --track-length) or a measured one
    (--irregularity FILE); the acceptance-test instability criterion (EN 14363
    style) compares the 100 m sliding rms of the sum of guiding forces and of
    the bogie frame lateral acceleration, band-passed f0 +/- 2 Hz, with their
    limits. The result is the lowest speed that breaks the criterion (km/h).
    """
    ctx = click.get_current_context()
    explicit = {
        name
        for name in ctx.params
        if ctx.get_parameter_source(name) is click.core.ParameterSource.COMMANDLINE
    }
    track_opts = {"spectrum": "--spectrum", "seed": "--seed", "track_length": "--track-length",
                  "irregularity_file": "--irregularity"}  # fmt: skip
    if method == "stochastic":
        for name, flag in (("amplitude", "--amplitude"), ("wavelength", "--wavelength")):
            if name in explicit:
                raise CliError(
                    f"{flag} describes the single defect and cannot be combined with "
                    "--method stochastic (which runs over an irregular track)"
                )
        if irregularity_file is not None:
            for name in ("spectrum", "seed", "track_length"):
                if name in explicit:
                    raise CliError(
                        f"{track_opts[name]} cannot be combined with --irregularity: the "
                        "measured track replaces the random one"
                    )
    else:
        given = [flag for name, flag in track_opts.items() if name in explicit]
        if given:
            raise CliError(f"{given[0]} only applies with --method stochastic")
    vehicle = _build_vehicle(vehicle_file, sets)
    if tol_kmh > step_kmh:
        raise CliError(f"--tol {tol_kmh:g} km/h is invalid: must be <= --step {step_kmh:g} km/h")
    if method == "stochastic":
        from railhunt.cli.stochastic import stochastic_critical_speed_command

        stochastic_critical_speed_command(
            vehicle, spectrum=spectrum, seed=seed, track_length=track_length,
            irregularity_file=irregularity_file, start_kmh=start_kmh, step_kmh=step_kmh,
            tol_kmh=tol_kmh, dt=dt, as_json=as_json,
        )  # fmt: skip
        return

    from railhunt.analysis.critical import critical_speed as run_critical_speed
    from railhunt.analysis.linear import linear_critical_speed

    excitation = _single_defect(amplitude, wavelength)

    with _trial_progress() as on_trial, _user_input():
        result = run_critical_speed(
            vehicle,
            excitation=excitation,
            start_kmh=start_kmh,
            step_kmh=step_kmh,
            tol_kmh=tol_kmh,
            method=method,
            dt=dt,
            progress=on_trial,
        )
        on_trial(None)
        linear = linear_critical_speed(vehicle)

    if as_json:
        click.echo(
            json.dumps(
                _critical_json(vehicle, excitation, tol_kmh, result, linear), allow_nan=False
            )
        )
        return

    from rich.table import Table

    table = Table(
        title=f"critical speed trials of {vehicle.name} "
        f"({amplitude:g} mm x {wavelength:g} m defect, {method})"
    )
    for head in (
        "#",
        "speed (km/h)",
        "verdict",
        "amplitude (mm)",
        "growth (1/s)",
        "simulated (s)",
        "note",
    ):
        table.add_column(head, justify="left" if head in ("verdict", "note") else "right")
    for i, trial in enumerate(result.trials, 1):
        note = trial.status if trial.status != "ok" else ("" if trial.decided else "undecided")
        table.add_row(
            str(i),
            f"{trial.speed_kmh:g}",
            trial.verdict,
            _fmt(1e3 * trial.amplitude, ".3f"),
            _fmt(trial.growth_rate, ".3g"),
            f"{trial.duration:.1f}",
            note,
            style="red" if trial.verdict == "hunting" else "green",
        )
    console = _stdout_console()
    console.print(table)
    console.print(_nonlinear_line(result, tol_kmh))
    console.print(_linear_line(linear))


def _nonlinear_line(result: Any, tol_kmh: float) -> str:
    if result.bracketed:
        return (
            f"nonlinear critical speed: {result.speed_kmh:g} km/h (highest stable speed; "
            f"hunting at {result.first_hunting_kmh:g} km/h, resolution {tol_kmh:g} km/h)"
        )
    verdicts = {t.verdict for t in result.trials}
    if verdicts == {"stable"}:
        why = "every trial speed up to 800 km/h was stable"
    else:
        why = "every trial speed down to 20 km/h was hunting"
    return f"nonlinear critical speed: not found ({why})"


@contextlib.contextmanager
def _trial_progress() -> Iterator[Callable[[Any], None]]:
    """A callback ticking a rich progress display per trial (a no-op off a terminal).

    Calling it with ``None`` switches the display to the linear analysis.
    """
    if not _show_progress():
        yield lambda trial: None
        return
    from rich.console import Console
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    columns = (
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TextColumn("[dim]{task.completed} trials"),
        TimeElapsedColumn(),
    )
    with Progress(*columns, console=Console(stderr=True), transient=True) as progress:
        task = progress.add_task("critical speed: first trial ...", total=None)

        def on_trial(trial: Any) -> None:
            if trial is None:
                progress.update(task, description="linear stability analysis ...")
                return
            progress.update(
                task,
                advance=1,
                description=f"critical speed: {trial.speed_kmh:g} km/h was {trial.verdict}",
            )

        yield on_trial


def _critical_json(
    vehicle: Any, excitation: Any, tol_kmh: float, result: Any, linear: Any
) -> dict[str, Any]:
    data = {
        "method": "defect",
        "nonlinear_critical_speed_kmh": result.speed_kmh,
        "linear_critical_speed_kmh": linear.speed_kmh,
        "linear_hunting_frequency_hz": linear.frequency_hz,
        "linear_crossing_is_hunting_mode": bool(linear.is_hunting_mode),
        "bracketed": bool(result.bracketed),
        "first_hunting_speed_kmh": result.first_hunting_kmh,
        "tol_kmh": tol_kmh,
        "vehicle": vehicle.name,
        "excitation": {
            "amplitude_mm": excitation.amplitude * 1e3,
            "wavelength_m": excitation.wavelength,
        },
        "trials": [
            {
                "speed_kmh": t.speed_kmh,
                "verdict": t.verdict,
                "amplitude_mm": t.amplitude * 1e3,
                "growth_rate_per_s": t.growth_rate,
                "duration_s": t.duration,
                "decided": bool(t.decided),
                "status": t.status,
            }
            for t in result.trials
        ],
    }
    return _json_safe(data)


# --------------------------------------------------------------------------- parameters


@main.command(short_help="List the vehicle parameters, values and SI units.")
@_vehicle_options
def parameters(vehicle_file: Path | None, sets: dict[str, float]) -> None:
    """List the vehicle parameters (name, SI value, unit, meaning).

    These are the names accepted by --set NAME=VALUE and in vehicle TOML files;
    values are in the SI unit shown. The derived v_u and N are listed last and
    cannot be set.
    """
    vehicle = _build_vehicle(vehicle_file, sets)
    from rich.table import Table

    table = Table(title=f"parameters of {vehicle.name} (SI units)")
    for head in ("name", "value", "unit", "meaning"):
        table.add_column(head, justify="right" if head == "value" else "left")
    for name, value, unit, meaning in vehicle.parameter_table(include_derived=True):
        style = "bold" if name in sets else None
        table.add_row(name, f"{value:.6g}", unit, meaning, style=style)
    _stdout_console().print(table)


# --------------------------------------------------------------------------- more commands
# Each topic's commands live in a module of this package that decorates ``main``; importing
# them here registers the commands. Keep this block last: the modules import from above.

from railhunt.cli import _registry  # noqa: E402, F401

if __name__ == "__main__":  # pragma: no cover
    main()
