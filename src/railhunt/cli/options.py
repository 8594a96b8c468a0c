"""Options shared by the commands, with their checks, and what they build.

The vehicle (``--vehicle``/``--set``), number ranges, speeds in km/h, the single track
defect (``--amplitude``/``--wavelength``), a curve (``--curve-radius``/``--cant`` in mm/
``--transition``/``--direction``), the integrator (``--method``/``--dt``), a random or
measured track (``--spectrum``/``--seed``/``--irregularity``), output files and a sweep's
results file. Units are converted here, at the edge: the library is called in SI units.
The library is imported inside the functions, so ``railhunt --help`` stays fast.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.files import (  # noqa: F401 - the output files' options, shared from here
    OVERWRITE_POLICY,
    check_output_folder,
    check_outputs,
    file_option,
    overwrite_option,
    write_sidecar,
)
from railhunt.cli.rules import Requires

if TYPE_CHECKING:
    from railhunt.curve import Curve
    from railhunt.irregularity import TrackIrregularity
    from railhunt.track import SingleDefect
    from railhunt.vehicle import Vehicle

__all__ = [
    "CURVE_LEAD_IN",
    "CURVE_RULES",
    "MEASURED_TAPER",
    "OVERWRITE_POLICY",
    "build_curve",
    "build_vehicle",
    "cant_option",
    "check_output_folder",
    "check_outputs",
    "curve_json",
    "curve_options",
    "default_transition",
    "defect_options",
    "describe_curve",
    "direction_option",
    "file_option",
    "initial_amplitude_option",
    "kmh_option",
    "load_results",
    "measured_track",
    "method_options",
    "number_range",
    "overwrite_option",
    "radius_option",
    "random_track_options",
    "results_argument",
    "single_defect",
    "speed_count",
    "transition_option",
    "VehicleOption",
    "vehicle_help",
    "vehicle_options",
    "write_sidecar",
]

Decorator = Callable[[Callable[..., Any]], Callable[..., Any]]

#: Fade-in and fade-out (m) applied to measured alignments on the command line.
MEASURED_TAPER = 20.0


# --------------------------------------------------------------------------- numbers


def number_range(
    unit: str,
    low: float = 0.0,
    high: float = math.inf,
    low_open: bool = True,
    optional: bool = False,
) -> Callable[[click.Context, click.Parameter, float | None], float | None]:
    """Option callback: a finite number in ``(low, high]`` (or ``[low, high]``).

    Parameters
    ----------
    unit : str
        Unit of the option, shown in the error (e.g. ``"km/h"``).
    low, high : float
        Bounds, in ``unit``.
    low_open : bool
        False: ``low`` itself is allowed.
    optional : bool
        True: the option may be left out (None).
    """

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


def kmh_option(flag: str, dest: str, default: float, high: float, help: str) -> Decorator:
    """A speed option in km/h, finite and in ``(0, high]``."""
    return click.option(
        flag,
        dest,
        type=float,
        default=default,
        show_default=True,
        metavar="KMH",
        callback=number_range("km/h", 0.0, high),
        help=help,
    )


def speed_count(from_kmh: float, to_kmh: float, step_kmh: float, most: int) -> int:
    """Number of speeds ``from, from + step, ... <= to`` of a ``--from/--to/--step`` scan.

    Raises
    ------
    CliError
        When ``--to`` is below ``--from`` or the scan holds more than ``most`` speeds.
    """
    if to_kmh < from_kmh:
        raise CliError(f"--to {to_kmh:g} km/h is below --from {from_kmh:g} km/h")
    n = int(math.floor((to_kmh - from_kmh) / step_kmh + 1e-9)) + 1
    if n > most:
        raise CliError(f"--step {step_kmh:g} km/h gives {n} speeds: at most {most} are allowed")
    return n


def initial_amplitude_option(help: str) -> Decorator:
    """``--initial-amplitude MM``: a release from a lateral displacement, in ``(0, 20]`` mm."""
    return click.option("--initial-amplitude", "initial_mm", type=float, default=3.0,
                        show_default=True, metavar="MM",
                        callback=number_range("mm", 0.0, 20.0), help=help)  # fmt: skip


# --------------------------------------------------------------------------- vehicle


def _parse_set(
    ctx: click.Context, param: click.Parameter, items: tuple[str, ...]
) -> dict[str, float]:
    """Option callback of ``--set``: ``NAME=VALUE`` items to a dict of checked SI floats."""
    from railhunt.vehicle import UnknownParameterError, validate_value

    # --vehicle is eager (processed first): another layout's parameters are checked by
    # Vehicle.replace when the vehicle is built (build_vehicle), against its own table.
    other_vehicle = ctx.params.get("vehicle_file") is not None
    changes: dict[str, float] = {}
    for item in items:
        name, sep, text = item.partition("=")
        name, text = name.strip(), text.strip()
        if not sep or not name or not text:
            raise click.BadParameter(
                f"{item!r} is not of the form NAME=VALUE (SI units), e.g. C_d1=150e3"
            )
        try:
            value = float(text)
        except ValueError:
            raise click.BadParameter(
                f"{name}={text}: {text!r} is not a number (give the SI value, e.g. 1.5e5)"
            ) from None
        if other_vehicle:  # its own table (and its uses) check it, in build_vehicle
            changes[name] = value
            continue
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


def _store_allowed(ctx: click.Context, param: click.Parameter, names: tuple[str, ...]) -> None:
    """``--allow NAME``: kept for :func:`build_vehicle` (not an argument of the commands)."""
    ctx.meta["railhunt.allow"] = tuple(n.strip() for n in names if n.strip())


def vehicle_options(func: Callable[..., Any]) -> Callable[..., Any]:
    """Add ``--vehicle FILE|NAME`` and repeatable ``--set NAME=VALUE`` to a command.

    The command receives ``vehicle_file`` (a path, a shipped vehicle's name or None) and
    ``sets`` (parameter name to checked SI value); :func:`build_vehicle` makes the vehicle.
    """
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
        "--allow",
        metavar="NAME",
        multiple=True,
        expose_value=False,
        callback=_store_allowed,
        help="Take parameter NAME's value (of the file or of --set) even outside the range "
        "its use makes plausible, on purpose: a scale model, a study beyond the usual "
        "(repeatable; as allow = true in a vehicle file). Its rules of sign still hold.",
    )(func)
    func = click.option(
        "--vehicle",
        "vehicle_file",
        cls=VehicleOption,
        metavar="FILE|NAME",
        is_eager=True,
        callback=_vehicle_source,
    )(func)
    return func


def vehicle_help(lead: str = "Vehicle TOML file (SI units)", default: str = "paper2019") -> str:
    """The help of ``--vehicle``: every vehicle shipped in railhunt's data directory, by
    name (read when the help is shown, so that a vehicle added to the directory is listed
    by every command).

    Parameters
    ----------
    lead : str
        What the option is, before the list of names.
    default : str
        The vehicle used when the option is not given.
    """
    from railhunt.vehicle import shipped_vehicles

    return (f"{lead}, or the name of a vehicle shipped with railhunt: "
            f"{', '.join(shipped_vehicles())} ('railhunt vehicles' describes each, 'railhunt "
            f"parameters --vehicle NAME' lists its parameters). Default: {default}.")


class VehicleOption(click.Option):
    """``--vehicle``, whose help lists the shipped vehicles (:func:`vehicle_help`), read
    from the data directory when the help is shown, not when the command line starts."""

    #: The help's opening words and default (:func:`vehicle_help`).
    help_lead: str = "Vehicle TOML file (SI units)"
    help_default: str = "paper2019"

    def get_help_record(self, ctx: click.Context) -> tuple[str, str] | None:
        self.help = vehicle_help(self.help_lead, self.help_default)
        return super().get_help_record(ctx)


def build_vehicle(vehicle_file: Path | str | None, sets: dict[str, float]) -> Vehicle:
    """The vehicle of ``--vehicle`` (or paper2019) with the ``--set`` changes applied."""
    from railhunt import Vehicle, load_vehicle

    with user_input():
        if vehicle_file is None:
            vehicle = Vehicle.paper2019()
        elif isinstance(vehicle_file, str):
            vehicle = Vehicle.shipped(vehicle_file)
        else:
            vehicle = load_vehicle(vehicle_file)
    ctx = click.get_current_context(silent=True)
    allowed = ctx.meta.get("railhunt.allow", ()) if ctx is not None else ()
    if allowed:
        with user_input("--allow: "):
            vehicle = vehicle.allowing(*allowed)
    if sets:
        import warnings

        from railhunt.vehicle.errors import DerivedOverrideWarning

        given = ", ".join(f"{k}={v:g}" for k, v in sets.items())
        with user_input(f"--set {given}: "), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", DerivedOverrideWarning)
            vehicle = vehicle.replace(name=f"{vehicle.name} with {given}", **sets)
        for w in caught:  # a derived parameter set directly: said once, as a note
            if issubclass(w.category, DerivedOverrideWarning):
                click.echo(f"railhunt: note: {w.message}", err=True)
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    if vehicle.contact is not None:
        # The profiles of [contact] must give a geometry that fits the vehicle (the wheels
        # fit the track, r0 is the centred rolling radius): checked once, here, before
        # any command (or every point of a study) fails on it.
        from railhunt.model import Model

        where = "--vehicle " + (str(vehicle_file) if vehicle_file else vehicle.name)
        with user_input(f"{where}: [contact]: "):
            Model(vehicle)
    return vehicle


# --------------------------------------------------------------------------- excitation


def defect_options(amplitude_help: str) -> Decorator:
    """Add ``--amplitude`` (mm) and ``--wavelength`` (m) of the single track defect."""

    def decorate(func: Callable[..., Any]) -> Callable[..., Any]:
        func = click.option(
            "--wavelength",
            type=float,
            default=20.0,
            show_default=True,
            metavar="M",
            callback=number_range("m", 0.5, 1000.0, low_open=False),
            help="Length of the single track defect along the track (m).",
        )(func)
        return click.option(
            "--amplitude",
            type=float,
            default=8.0,
            show_default=True,
            metavar="MM",
            callback=number_range("mm", -50.0, 50.0, low_open=False),
            help=amplitude_help,
        )(func)

    return decorate


def single_defect(amplitude_mm: float, wavelength: float) -> SingleDefect:
    """The single track defect the defect options describe (``amplitude_mm`` in mm to m)."""
    from railhunt import SingleDefect

    with user_input():
        return SingleDefect(amplitude=amplitude_mm * 1e-3, wavelength=wavelength)


def random_track_options(
    default: str | None, spectrum_help: str, seed_context: str, irregularity_help: str
) -> Decorator:
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


def measured_track(path: Path) -> TrackIrregularity:
    """The measured alignment of ``path``, starting at 0 m, faded in and out over 20 m
    (or over half the record when it is shorter than 40 m)."""
    from railhunt import load_irregularity

    raw = load_irregularity(path)
    return load_irregularity(path, taper=min(MEASURED_TAPER, raw.length / 2))


# --------------------------------------------------------------------------- curves

#: Straight track (m) between the end of the single defect (or the start of the run) and
#: the entry transition of ``--curve-radius`` in ``simulate``: the curve comes after the
#: defect, so that the run shows the defect's response and then the curve entry.
CURVE_LEAD_IN = 20.0


def default_transition(radius: float) -> float:
    """Transition length (m) used when ``--transition`` is not given: R / 10 within
    [20, 300] m (e.g. 300 m for R >= 3000 m, 100 m for 1000 m, 30 m for 300 m)."""
    return min(300.0, max(20.0, radius / 10.0))


def radius_option(flag: str, dest: str, required: bool, help: str) -> Decorator:
    """A curve radius option (m), finite and at least 50 m."""
    return click.option(flag, dest, type=float, required=required, metavar="M",
                        callback=number_range("m", 50.0, math.inf, low_open=False,
                                              optional=not required),
                        help=help)  # fmt: skip


def cant_option(help: str, flag: str = "--cant", dest: str = "cant_mm") -> Decorator:
    """The cant (mm) of a curve: height of the outer rail over the inner one, in [0, 500]
    mm over the 1500 mm rail-centre distance (:class:`railhunt.Curve`'s range)."""
    return click.option(flag, dest, type=float, default=None, metavar="MM",
                        callback=number_range("mm", 0.0, 500.0, low_open=False, optional=True),
                        help=help)  # fmt: skip


def transition_option(help: str) -> Decorator:
    """``--transition M``: length of each transition curve, in [0, 2000] m."""
    return click.option("--transition", "transition", type=float, default=None, metavar="M",
                        callback=number_range("m", 0.0, 2000.0, low_open=False, optional=True),
                        help=help)  # fmt: skip


def direction_option(help: str) -> Decorator:
    """``--direction left|right``: which way the curve turns (left: toward +y)."""
    return click.option("--direction", type=click.Choice(["left", "right"]), default="left",
                        show_default=True, help=help)  # fmt: skip


#: The rules every command with :func:`curve_options` declares.
CURVE_RULES = (
    Requires(("--cant", "--transition", "--direction"), "--curve-radius",
             "{a} describes the curve and needs {b} (its radius in m)"),
)  # fmt: skip


def curve_options(transition_help: str) -> Decorator:
    """Add ``--curve-radius M``, ``--cant MM``, ``--transition M`` and ``--direction`` (run
    in a curve instead of on straight track); declare :data:`CURVE_RULES` with them.

    The command receives ``curve_radius``, ``cant_mm``, ``transition`` and ``direction``;
    :func:`build_curve` makes the :class:`railhunt.Curve`.
    """

    def decorate(func: Callable[..., Any]) -> Callable[..., Any]:
        func = direction_option("Which way the curve of --curve-radius turns (left: "
                                "toward +y).")(func)  # fmt: skip
        func = transition_option(transition_help)(func)
        func = cant_option("Cant of the curve of --curve-radius (mm): height of the outer "
                           "rail over the inner one over the 1500 mm rail-centre distance, "
                           "in [0, 500] mm [default: 0].")(func)  # fmt: skip
        return radius_option("--curve-radius", "curve_radius", False,
                             "Run in a curve of this radius (m, at least 50 m) instead of "
                             "on straight track.")(func)  # fmt: skip

    return decorate


def build_curve(radius: float | None, cant_mm: float | None, transition: float | None,
                direction: str = "left", start: float = 0.0) -> Curve | None:  # fmt: skip
    """The curve the curve options describe, in SI units (None without a radius).

    ``cant_mm`` in mm (None: 0); ``transition`` in m (None: :func:`default_transition`);
    ``start`` (m) where the entry transition begins.
    """
    if radius is None:
        return None
    from railhunt import Curve

    if transition is None:
        transition = default_transition(radius)
    with user_input():
        return Curve(radius, cant=(cant_mm or 0.0) * 1e-3, transition=transition,
                     direction=direction, start=start)  # fmt: skip


def curve_json(curve: Curve | None) -> dict[str, Any] | None:
    """The curve as the commands' JSON reports it (radius and lengths in m, cant in mm)."""
    if curve is None:
        return None
    return {"radius_m": curve.radius, "cant_mm": curve.cant * 1e3,
            "transition_m": curve.transition, "direction": curve.direction}  # fmt: skip


def describe_curve(curve: Curve, transition: bool = True) -> str:
    """A curve in words: radius, direction, cant (and the length of its transitions)."""
    text = f"R = {curve.radius:g} m to the {curve.direction}, cant {curve.cant * 1e3:g} mm"
    return text + (f", transitions {curve.transition:g} m" if transition else "")



def method_options(func: Callable[..., Any], stochastic: bool = False) -> Callable[..., Any]:
    """Add ``--method`` and ``--dt`` to a command (``stochastic``: also the search method)."""
    func = click.option(
        "--dt",
        type=float,
        default=None,
        metavar="S",
        callback=number_range("s", 0.0, 0.01, optional=True),
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


# --------------------------------------------------------------------------- files


#: The RESULTS argument of the commands that read a sweep's results file.
results_argument = click.argument(
    "results",
    metavar="RESULTS",
    type=click.Path(exists=True, dir_okay=False, path_type=Path),
)


def load_results(results: Path, read: Callable[[Path], Any]) -> Any:
    """Run ``read(results)``; an invalid file becomes one ``railhunt: error:`` line."""
    try:
        return read(results)
    except OSError as exc:
        raise CliError(f"{results}: {exc.strerror or exc}") from None
    except (ValueError, KeyError, ImportError) as exc:  # ImportError: Parquet without pyarrow
        text = str(exc.args[0]) if isinstance(exc, KeyError) and exc.args else str(exc)
        if str(results) not in text:
            text = f"{results}: {text}"
        raise CliError(text) from None
