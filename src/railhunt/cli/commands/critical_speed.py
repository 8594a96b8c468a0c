"""``railhunt critical-speed``: nonlinear (the paper's method) and linear critical speeds.

``--method stochastic`` runs over an irregular track instead; its run and report are in
:mod:`railhunt.cli.commands.stochastic`.
"""

from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import user_input
from railhunt.cli.options import (
    CURVE_RULES,
    build_curve,
    build_vehicle,
    curve_json,
    curve_options,
    defect_options,
    describe_curve,
    kmh_option,
    method_options,
    number_range,
    random_track_options,
    single_defect,
    vehicle_options,
)
from railhunt.cli.output import (
    announce,
    fmt,
    json_safe,
    linear_critical_speed_line,
    print_warnings,
    stdout_console,
    traced,
    trial_progress,
    verbose_option,
)
from railhunt.cli.rules import Excludes, Ordered, Requires, command
from railhunt.verdicts import verdict_help

RULES = (
    Excludes("--method=stochastic", ("--amplitude", "--wavelength"),
             "{b} describes the single defect and cannot be combined with --method stochastic "
             "(which runs over an irregular track)"),
    Requires(("--spectrum", "--seed", "--track-length", "--irregularity"), "--method=stochastic",
             "{a} only applies with --method stochastic"),
    Excludes(("--spectrum", "--seed", "--track-length"), "--irregularity",
             "{a} cannot be combined with {b}: the measured track replaces the random one"),
    Ordered("--tol", "--step",
            "--tol {tol_kmh:g} km/h is invalid: must be <= --step {step_kmh:g} km/h"),
    Excludes("--curve-radius", "--method=stochastic",
             "{a} cannot be combined with --method stochastic (which runs on straight "
             "irregular track)"),
    *CURVE_RULES,
)  # fmt: skip


@command("critical-speed", rules=RULES, epilog=verdict_help(),
         short_help="Nonlinear and linear critical speeds (km/h).")
@defect_options(
    "Peak lateral displacement of the track defect run over at each trial speed (mm), "
    "within ±50 mm."
)
@kmh_option("--start", "start_kmh", 300.0, 800.0, "First trial speed (km/h).")
@kmh_option("--step", "step_kmh", 10.0, 800.0,
            "Step while bracketing the critical speed (km/h).")  # fmt: skip
@kmh_option("--tol", "tol_kmh", 1.0, 800.0,
            "Resolution of the bisection (km/h); at most --step.")  # fmt: skip
@functools.partial(method_options, stochastic=True)
@random_track_options(
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
    callback=number_range("m", 200.0, 1e5, low_open=False),
    help="With --method stochastic: length of the irregular track run over at each speed (m).",
)
@curve_options("Length of the transition curves of --curve-radius (m), recorded in the "
               "JSON; the critical speeds are found in the constant curve and do not depend "
               "on it [default: R/10, within 20-300 m].")
@click.option(
    "--json",
    "as_json",
    is_flag=True,
    help="Print one JSON object (speeds in km/h; unknown values as null) instead of tables.",
)
@verbose_option
@vehicle_options
def critical_speed_command(
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
    curve_radius: float | None,
    cant_mm: float | None,
    transition: float | None,
    direction: str,
    as_json: bool,
    verbose: bool,
    vehicle_file: Path | None,
    sets: dict[str, float],
) -> None:
    """Nonlinear and linear critical speeds: above which speed does it hunt?

    \b
    Nonlinear critical speed (the paper's method): at each trial speed the
    vehicle runs over one lateral track defect and the motion of every
    wheelset and bogie frame is judged 'stable' (it died out) or not:
    'hunting', 'undecided', 'derailed' or 'blow-up' (the verdicts are defined
    below); the worst decides, and the table names it. Starting at
    --start the speed is stepped by --step until the verdict changes, then
    bisected to --tol. The result is the highest stable speed (km/h); in a
    curve the search stops at the first limit of the validity envelope.

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

    \b
    In a curve (--curve-radius, --cant, --direction; not with --method
    stochastic) both are found in the constant part of the curve: each trial
    starts on the steady-curving equilibrium, the defect lies inside the
    curve, and the motion is judged by its distance from that equilibrium;
    the linear critical speed is where that equilibrium, followed along the
    speed, loses stability.
    """
    vehicle = build_vehicle(vehicle_file, sets)
    if method != "stochastic" and amplitude == 0.0:
        from railhunt.cli.errors import CliError

        raise CliError("--amplitude 0 mm is invalid: a defect of zero size excites nothing, "
                       "so every speed would look stable; give a nonzero amplitude, within "
                       "±50 mm")  # fmt: skip
    if method == "stochastic":
        from railhunt.cli.commands.stochastic import report_stochastic_critical_speed

        report_stochastic_critical_speed(
            vehicle, spectrum=spectrum, seed=seed, track_length=track_length,
            irregularity_file=irregularity_file, start_kmh=start_kmh, step_kmh=step_kmh,
            tol_kmh=tol_kmh, dt=dt, as_json=as_json, verbose=verbose,
        )  # fmt: skip
        return

    from railhunt import critical_speed, linear_critical_speed

    excitation = single_defect(amplitude, wavelength)
    curve = build_curve(curve_radius, cant_mm, transition, direction)
    _announce_search(vehicle, excitation, start_kmh, step_kmh, tol_kmh, dt)

    with trial_progress("critical speed") as on_trial, user_input():
        result = critical_speed(
            vehicle,
            excitation=excitation,
            start_kmh=start_kmh,
            step_kmh=step_kmh,
            tol_kmh=tol_kmh,
            method=method,
            dt=dt,
            progress=on_trial,
            curve=curve,
        )
        on_trial(None)
        linear = linear_critical_speed(vehicle, curve=curve)  # stops at the curving limit

    if as_json:
        data = _critical_json(vehicle, excitation, tol_kmh, result, linear)
        if curve is not None:
            data["curve"] = curve_json(curve)
        click.echo(json.dumps(data, allow_nan=False))
        return

    from rich.table import Table

    where = "" if curve is None else f" in a curve, {describe_curve(curve, transition=False)}"
    table = Table(
        title=f"critical speed trials of {vehicle.name} "
        f"({amplitude:g} mm x {wavelength:g} m defect, {method}){where}"
    )
    for head in (  # short heads: the table fits in 80 columns
        "#",
        "km/h",
        "verdict",
        "amp. mm",
        "growth 1/s",
        "run s",
        "note",
    ):
        table.add_column(head, justify="left" if head in ("verdict", "note") else "right")
    leading = vehicle.assembly.layout.wheelsets[0]
    for i, trial in enumerate(result.trials, 1):
        note = _trial_note(trial, leading)
        table.add_row(
            str(i),
            f"{trial.speed_kmh:g}",
            trial.verdict,
            fmt(1e3 * trial.amplitude, ".3f"),
            fmt(trial.growth_rate, ".3g"),
            f"{trial.duration:.1f}",
            note,
            style="green" if trial.verdict == "stable" else "red",
        )
    console = stdout_console()
    console.print(table)
    for note in _notes_used(result.trials):
        console.print(f"{note}: {_note_meaning(note)}")
    console.print(_nonlinear_line(result, tol_kmh, leading))
    console.print(linear_critical_speed_line(linear, curved=curve is not None))
    if _above_linear(result, linear):
        console.print(f"[yellow]note: the nonlinear critical speed lies above the linear one "
                      f"({linear.speed_kmh:.1f} km/h), where centred running is unstable: a "
                      "trial above it can only be stable on a branch of limit cycles, so "
                      "check it with a larger --amplitude or 'railhunt bifurcation'[/yellow]")
    print_warnings(console, result, verbose)


#: The note of a trial judged hunting on a stationary envelope.
STEADY = "steady cycle"
#: The note of a trial whose verdict was taken on the envelope's trend at the end.
TREND = "trend at the end"
#: The note of an undecided trial (its reason, in words, is in --verbose and the JSON).
NO_DECAY_NO_CYCLE = "no decay, no cycle"


def _note_meaning(note: str) -> str:
    """What a note of the trial table means (the verdict words' definitions)."""
    from railhunt.verdicts import STEADY_CYCLE, UNDECIDED, VERDICTS

    return {STEADY: VERDICTS[STEADY_CYCLE],
            TREND: "the verdict was taken on the envelope's trend when the longest duration "
                   "(60 s) ran out",
            NO_DECAY_NO_CYCLE: f"undecided: {VERDICTS[UNDECIDED]}"}[note]  # fmt: skip


def _notes_used(trials: list[Any]) -> list[str]:
    """The notes of the table that need a word of explanation, in the order first used."""
    out: list[str] = []
    for trial in trials:
        note = _trial_kind(trial)
        if note in (STEADY, TREND, NO_DECAY_NO_CYCLE) and note not in out:
            out.append(note)
    return out


def _trial_note(trial: Any, leading: str = "") -> str:
    """The note column: first the deciding body when it is not the leading wheelset
    (``leading``), then :func:`_trial_kind`."""
    body = getattr(trial, "body", "")
    by = f"{body}: " if body and body != leading and trial.verdict != "stable" else ""
    kind = _trial_kind(trial)
    return by + kind if kind else by.rstrip(": ")


def _trial_kind(trial: Any) -> str:
    """How the verdict was taken: the solver's status if not ok, else the note's word (an
    undecided trial's reason is in --verbose and the JSON; its size and trend are in the
    table)."""
    if trial.verdict == "undecided":
        return NO_DECAY_NO_CYCLE
    if trial.verdict in ("derailed", "blow-up"):
        return "left the track" if trial.verdict == "derailed" else "numerics: smaller dt"
    if trial.status != "ok":
        return trial.status
    if not trial.decided:
        return TREND
    return STEADY if trial.verdict == "hunting" else ""


def _above_linear(result: Any, linear: Any) -> bool:
    """Whether a found nonlinear critical speed lies above the linear one."""
    import math

    return bool(result.bracketed and math.isfinite(linear.speed_kmh)
                and result.speed_kmh > linear.speed_kmh)  # fmt: skip


def _announce_search(vehicle: Any, excitation: Any, start_kmh: float, step_kmh: float,
                     tol_kmh: float, dt: float | None) -> None:  # fmt: skip
    """Refuse invalid search settings and a stiff damper's step (before any estimate),
    and announce a search of more than a minute."""
    import inspect
    import math

    from railhunt.analysis.critical import critical_speed
    from railhunt.analysis.search import check_search

    bounds = inspect.signature(critical_speed).parameters
    with user_input():
        check_search(start_kmh, step_kmh, tol_kmh, bounds["min_kmh"].default,
                     bounds["max_kmh"].default)  # fmt: skip

    from railhunt import Model
    from railhunt.analysis.critical import Judgement
    from railhunt.simulation import auto_step, excitation_end_time
    from railhunt.units import kmh_to_ms
    from railhunt.workload import SIMULATED_SECONDS, workload

    model = Model(vehicle)
    with user_input("--set/--vehicle: "):
        step = dt if dt is not None else auto_step(model, kmh_to_ms(start_kmh))
    bisect = math.ceil(math.log2(max(step_kmh / tol_kmh, 1.0)))
    trials = 3 + bisect
    t_exc = excitation_end_time(model, excitation, kmh_to_ms(start_kmh))
    per_trial = t_exc + SIMULATED_SECONDS["critical-speed trial"]
    # At most: bracketing all the way to 20 or 800 km/h, every trial to its longest run.
    most = (max(start_kmh - 20.0, 800.0 - start_kmh) / step_kmh + 1 + bisect) * (
        t_exc + Judgement().max_duration)
    announce(workload(trials * per_trial, step, f"~{trials} trials of ~{per_trial:.0f} s "
                      "simulated", most_simulated=most), vehicle, kmh_to_ms(start_kmh))  # fmt: skip


def _nonlinear_line(result: Any, tol_kmh: float, leading: str = "") -> str:
    if result.bracketed:
        body = getattr(result, "deciding_body", "")
        by = f" ({body})" if body and body != leading else ""  # the leading one: as always
        return (
            f"nonlinear critical speed: {result.speed_kmh:g} km/h (highest stable speed; "
            f"hunting at {result.first_hunting_kmh:g} km/h{by}, resolution {tol_kmh:g} km/h)"
        )
    verdicts = {t.verdict for t in result.trials}
    top = max((t.speed_kmh for t in result.trials), default=800.0)
    if getattr(result, "limit_reached", False):
        why = (f"stable up to {top:g} km/h, where the search stopped: limit reached, "
               f"{result.limit.text}")  # fmt: skip
    elif verdicts == {"stable"}:
        why = f"every trial speed up to {top:g} km/h was stable"
    elif "stable" not in verdicts:
        low = min((t.speed_kmh for t in result.trials), default=20.0)
        words = ", ".join(sorted(verdicts))
        why = f"no trial speed down to {low:g} km/h was stable ({words})"
    else:
        why = "the search did not bracket a change of verdict"
    return f"nonlinear critical speed: not found ({why})"


def _critical_json(
    vehicle: Any, excitation: Any, tol_kmh: float, result: Any, linear: Any
) -> dict[str, Any]:
    data = {
        "method": "defect",
        "nonlinear_critical_speed_kmh": result.speed_kmh,
        "linear_critical_speed_kmh": linear.speed_kmh,
        "linear_hunting_frequency_hz": linear.frequency_hz,
        "linear_crossing_is_hunting_mode": bool(linear.is_hunting_mode),
        "linear_crossing": getattr(linear, "crossing", ""),
        "linear_unstable_from_kmh": getattr(linear, "unstable_from_kmh", None),
        "linear_warnings": list(getattr(linear, "warnings", [])),
        "linear_curving_limit": (None if getattr(linear, "limit", None) is None
                                 else linear.limit.to_dict()),
        "warnings": list(getattr(result, "warnings", [])),
        "limit_summary": [s.to_dict() for s in getattr(result, "limit_summary", [])],
        "details": list(getattr(result, "details", [])),
        "limits": [lim.to_dict() for lim in getattr(result, "limits", [])],
        "curving_limit": (None if getattr(result, "limit", None) is None
                          else result.limit.to_dict()),
        "bracketed": bool(result.bracketed),
        "first_hunting_speed_kmh": result.first_hunting_kmh,
        "deciding_body": getattr(result, "deciding_body", ""),
        "tol_kmh": tol_kmh,
        "above_linear_critical_speed": _above_linear(result, linear),
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
                "reason": getattr(t, "reason", ""),
                "limits": [lim.to_dict() for lim in getattr(t, "limits", [])],
                "body": getattr(t, "body", ""),
            }
            for t in result.trials
        ],
    }
    return json_safe(traced(data, vehicle))
