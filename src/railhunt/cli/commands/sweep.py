"""``railhunt sweep``: parameter studies written point by point, on all cores or a cluster."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.factors import curve_flags, output_options_from
from railhunt.cli.options import build_vehicle, number_range, vehicle_options
from railhunt.cli.output import fmt, json_safe, show_progress, stdout_console, traced
from railhunt.cli.rules import Excludes, Requires, command
from railhunt.cli.study import (
    STUDY_RULES,
    announce_study,
    check_study_outputs,
    check_workers_option,
    report_lost,
    running_study,
    scheduler_client,
    study_options,
    study_run,
)

_SWEEP_HELP = """\
Critical speeds and hunting frequency over a range of vehicle parameters.

\b
Each NAME is a vehicle parameter ('railhunt parameters' lists them) and
takes its own --from/--to/--num, in the order given (one --num applies to
all). Values are SI, as in --set (N*s/m, N/m, N, -). Every point runs the
nonlinear critical-speed search (8 mm defect, bisection to 1 km/h), the
linear critical speed (Hopf point) and the hunting frequency over the same
defect: the eigenvalue's if the motion decays, the limit cycle's if it
hunts (at 300 km/h for the yaw-damper parameters C_d1, C_d2, K_d, F_u and
350 km/h for the others, as in the paper; --frequency-speed overrides).

\b
Designs: 'lines' (default) sweeps each NAME alone, the others at their
nominal values (the paper's Figs. 10-11); 'grid' runs every combination;
'random' and 'lhs' (Latin hypercube) draw --samples points in the ranges
--from..--to with --seed.

\b
The points run in parallel on all cores (a local Dask cluster), or on a
Dask cluster with --scheduler ADDRESS. Each point is written to --out as it
finishes (.csv; .parquet with pyarrow). After Ctrl-C, a killed process or
a lost worker, run the same command with --resume: only the missing points
are computed. Identical inputs give identical files.

\b
Examples:
  railhunt sweep C_d1 --from 20e3 --to 1000e3 --num 21 --out cd1.csv
  railhunt sweep f11 --from 2e6 --to 11e6 --num 10 --tie f22=f11 --out f11.csv
  railhunt sweep C_d1 --from 100e3 --to 600e3 K_d --from 1e6 --to 20e6 \\
      --num 5 --design grid --out grid.csv
  railhunt sweep mu --from 0.05 --to 0.5 --num 10 --out mu.csv --resume
  railhunt sweep --table1 --out table1.csv      # the paper's Figs. 10-12
"""


#: Largest study the command line starts (a grid grows as the product of its --num).
MAX_POINTS = 1_000_000

RULES = (
    *STUDY_RULES,
    Requires("--samples", "--design=random|lhs",
             "--samples is for the random and lhs designs, not {design!r}"),
    Requires("--design=random|lhs", "--samples",
             "--design {design} draws its points at random: give their number with --samples N"),
    Excludes("--table1", ("--from", "--to", "--num", "--design!=lines", "--spacing!=linear"),
             "--table1 sets the values itself: drop --from/--to/--num/--design/--spacing"),
)  # fmt: skip


def _parse_ties(ctx: click.Context, param: click.Parameter,
                items: tuple[str, ...]) -> dict[str, tuple[str, float]]:  # fmt: skip
    """``--tie f22=f11`` or ``--tie f22=0.9*f11``."""
    out: dict[str, tuple[str, float]] = {}
    for item in items:
        follower, sep, rhs = item.partition("=")
        factor_text, star, leader = rhs.rpartition("*")
        try:
            factor = float(factor_text) if star else 1.0
        except ValueError:
            factor = math.nan
        follower, leader = follower.strip(), leader.strip()
        if not sep or not follower or not leader or not math.isfinite(factor):
            raise click.BadParameter(f"{item!r} is not of the form FOLLOWER=LEADER or "
                                     "FOLLOWER=FACTOR*LEADER, e.g. f22=f11")  # fmt: skip
        for name in (follower, leader):
            _known_parameter(item, name)
        out[follower] = (leader, factor)
    return out


def parse_tie_option(ctx: click.Context, param: click.Parameter,
                     items: tuple[str, ...]) -> dict[str, tuple[str, float]]:  # fmt: skip
    """``--tie f22=f11`` or ``--tie f22=0.9*f11`` (see :func:`_parse_ties`)."""
    return _parse_ties(ctx, param, items)


def _known_parameter(item: str, name: str) -> None:
    """``--tie ITEM``: ``name`` must be a vehicle parameter (suggest close names if not)."""
    from railhunt.vehicle import PARAMETERS
    from railhunt.vehicle.parameters import suggest

    ctx = click.get_current_context(silent=True)
    if name in PARAMETERS or (ctx is not None and ctx.params.get("vehicle_file") is not None):
        return  # another vehicle's names: checked against its table by the study
    close = suggest(name)
    hint = (f"did you mean {' or '.join(close)}?" if close else
            f"tie two of the {len(PARAMETERS)} names 'railhunt parameters' lists, e.g. f22=f11")
    raise click.BadParameter(f"{item!r}: {name!r} is not a vehicle parameter; {hint}")


def _pair(names: tuple[str, ...], option: str, values: tuple, default: object = None) -> list:
    """The per-NAME values of a repeatable option, in the order of the NAMEs.

    With a ``default`` (``--num``) the option may be left out or given once for all NAMEs;
    otherwise (``--from``, ``--to``: each parameter has its own scale) once per NAME.
    """
    if not values and default is not None:
        return [default] * len(names)
    if len(values) == 1 and default is not None:
        return list(values) * len(names)
    if len(values) != len(names):
        once = "once, or " if default is not None else ""
        raise CliError(f"{option} is given {len(values)} times for {len(names)} NAMEs "
                       f"({', '.join(names)}): give it {once}once per NAME")  # fmt: skip
    return list(values)


def _ranges(names, froms, tos, nums, spacing, design):
    """NAME -> SI values (lines, grid) or (low, high) (random, lhs)."""
    import numpy as np

    if len(set(names)) != len(names):
        raise CliError(f"a NAME is given twice: {', '.join(names)}")
    lows = _pair(names, "--from", froms)
    highs = _pair(names, "--to", tos)
    counts = _pair(names, "--num", nums, default=11)
    out: dict[str, object] = {}
    for name, lo, hi, n in zip(names, lows, highs, counts, strict=True):
        if not (math.isfinite(lo) and math.isfinite(hi)) or hi < lo:
            raise CliError(f"{name}: --from {lo:g} --to {hi:g} is not a range (need from <= to)")
        if design in ("random", "lhs"):
            out[name] = (lo, hi)
            continue
        if not 1 <= n <= 100_000:
            raise CliError(f"{name}: --num {n} is invalid: must be in [1, 100000]")
        if n > 1 and lo == hi:
            raise CliError(f"{name}: --from and --to are both {lo:g}: {n} points would be the "
                           "same point (use --num 1)")  # fmt: skip
        if spacing == "log":
            if lo <= 0:
                raise CliError(f"{name}: --spacing log needs --from > 0, got {lo:g}")
            out[name] = np.geomspace(lo, hi, n) if n > 1 else np.array([lo])
        else:
            out[name] = np.linspace(lo, hi, n) if n > 1 else np.array([lo])
    return out


@command("sweep", rules=RULES, help=_SWEEP_HELP,
         short_help="Parameter study: critical speeds and frequency.")
@click.argument("names", nargs=-1, metavar="NAME [NAME2 ...]")
@click.option("--table1", is_flag=True,
              help="The paper's study: each Table 1 parameter (or each NAME of Table 1) over "
                   "its three sections, f22 tied to f11; no --from/--to.")
@click.option("--points-per-section", "per_section", type=int, default=5, show_default=True,
              metavar="N", help="With --table1: points per section, both ends included.")
@click.option("--from", "froms", type=float, multiple=True, metavar="VALUE",
              help="Start of NAME's range (SI), once per NAME.")
@click.option("--to", "tos", type=float, multiple=True, metavar="VALUE",
              help="End of NAME's range (SI), once per NAME.")
@click.option("--num", "nums", type=int, multiple=True, metavar="N",
              help="Values per NAME including both ends (once, or once per NAME) [default: 11].")
@click.option("--spacing", type=click.Choice(["linear", "log"]), default="linear",
              show_default=True, help="Spacing of the values of 'lines' and 'grid'.")
@click.option("--design", type=click.Choice(["lines", "grid", "random", "lhs"]), default="lines",
              show_default=True, help="How the NAMEs are combined (see above).")
@click.option("--samples", type=int, metavar="N", help="Points of a random or lhs design.")
@click.option("--seed", type=int, default=0, show_default=True,
              help="Seed of a random or lhs design.")
@click.option("--tie", "ties", multiple=True, callback=_parse_ties, metavar="F=L",
              help="F follows L at every point: f22=f11, or f22=0.9*f11 (repeatable).")
@click.option("--outputs", default="critical_speed,linear_critical_speed,hunting_frequency",
              show_default=True, metavar="LIST",
              help="Comma-separated outputs per point; also fold_speed, least_damping_ratio "
                   "and curving (max_YQ, sum_Y_leading, wear_number in --curve-radius).")
@click.option("--frequency-speed", "frequency_kmh", type=float, metavar="KMH",
              help="Speed of the hunting-frequency run (km/h) [default: 300 for yaw-damper "
                   "parameters, 350 otherwise].")
@click.option("--frequency-amplitude", "amplitude_mm", type=float, metavar="MM",
              callback=number_range("mm", 0.0, 20.0, optional=True),
              help="Release every wheelset from MM for the frequency run [default: run over "
                   "the critical-speed defect, as the paper's Sec. 3.3 defines it].")
@curve_flags
@study_options()
@click.option("--json", "as_json", is_flag=True, help="Print a JSON summary instead of a table.")
@vehicle_options
def sweep_command(names, table1, per_section, froms, tos, nums, spacing, design, samples, seed,
                  ties, outputs, frequency_kmh, amplitude_mm, curve_radius, cant, curve_speed,
                  damping_range, out, resume, overwrite, workers, scheduler, connect_timeout,
                  as_json, vehicle_file, sets) -> None:  # fmt: skip
    """``railhunt sweep`` (help text: ``_SWEEP_HELP``)."""
    from railhunt import sweep
    from railhunt.studies.store import ALL_OUTPUTS

    check_workers_option(workers)
    chosen = tuple(dict.fromkeys(o.strip() for o in outputs.split(",") if o.strip()))
    bad = [o for o in chosen if o not in ALL_OUTPUTS]
    if bad or not chosen:
        raise CliError(f"--outputs {outputs}: choose from {', '.join(ALL_OUTPUTS)}")
    options = output_options_from(curve_radius, cant, curve_speed, damping_range)
    check_study_outputs(out, resume, overwrite)
    vehicle = build_vehicle(vehicle_file, sets)
    if table1:
        from railhunt import table1_study

        with user_input("--table1: "):
            parameters, table_ties = table1_study(per_section, names or None)
        ties = {**{f: (lead, 1.0) for f, lead in table_ties.items()}, **ties}
    elif not names:
        raise CliError("give at least one parameter NAME with --from/--to, or --table1")
    else:
        parameters = _ranges(names, froms, tos, nums, spacing, design)
        if design == "grid":
            size = math.prod(len(v) for v in parameters.values())
            if size > MAX_POINTS:
                raise CliError(f"--design grid gives {size} points: at most {MAX_POINTS} "
                               "(use --design lhs --samples N for large spaces)")  # fmt: skip
    _announce(vehicle, parameters, design, samples, seed, ties, chosen, workers, scheduler)
    progress = show_progress()
    with running_study(out), scheduler_client(scheduler, connect_timeout) as client:
        result = sweep(vehicle, parameters, chosen, design=design, samples=samples,
                       seed=seed, ties=ties, frequency_speed_kmh=frequency_kmh,
                       frequency_amplitude=None if amplitude_mm is None
                       else amplitude_mm * 1e-3, output_options=options,
                       run=study_run(out, resume, overwrite, workers, client,
                                     progress))  # fmt: skip
    if as_json:
        click.echo(json.dumps(json_safe(traced({
            "file": str(out), "points": result.meta["points"], "computed": result.computed,
            "resumed": result.resumed, "lost": result.lost, "elapsed_s": result.elapsed_s,
            "rows": result.rows}, vehicle)), indent=1))  # fmt: skip
    else:
        _print_summary(result, out)
    report_lost(result)


def _announce(vehicle, parameters, design, samples, seed, ties, outputs, workers,
              scheduler) -> None:  # fmt: skip
    """Announce a study of more than a minute (its points as the sweep will build them)."""
    from railhunt.studies.design import build_design

    try:
        points = build_design(vehicle, parameters, design, samples, seed,
                              {f: (lead, k) for f, (lead, k) in ties.items()})  # fmt: skip
    except ValueError:
        return  # the sweep reports it, with the names of the flags
    announce_study(vehicle, points, outputs, workers, scheduler)


#: The words of the summary table (the file keeps the full ones).
_SOURCE = {"limit-cycle": "cycle", "eigenvalue": "eigen"}
_STATUS = {"no-critical-speed": "none"}


def _print_summary(result, out: Path) -> None:
    from rich.table import Table

    console = stdout_console()
    rate = result.computed / result.elapsed_s if result.elapsed_s > 0 else math.nan
    click.echo(f"{result.meta['points']} points in {out}: {result.computed} computed "
               f"({fmt(rate, '.2f', 'points/s')}), {result.resumed} already there, "
               f"{result.lost} lost; {result.elapsed_s:.1f} s")  # fmt: skip
    if len(result.rows) > 40:
        return
    cols = result.columns
    table = Table()
    params = result.parameters
    shown = [(c, head, spec) for c, head, spec in (
        ("critical_speed_kmh", "V_cr km/h", ".0f"),
        ("linear_critical_speed_kmh", "V_lin km/h", ".1f"),
        ("linear_frequency_hz", "f_lin Hz", ".2f"),
        ("hunting_frequency_hz", "f Hz", ".2f")) if c in cols]  # fmt: skip
    source = "frequency_source" in cols
    for head in (*params, *(h for _, h, _ in shown), *(["f from"] if source else []), "status"):
        table.add_column(head, justify="right")
    for row in result.rows:  # short words and values: the table fits in 80 columns
        table.add_row(*(f"{row[p]:.4g}" for p in params),
                      *(fmt(row[c], spec) for c, _, spec in shown),
                      *([_SOURCE.get(row["frequency_source"], row["frequency_source"])]
                        if source else []), _STATUS.get(row["status"], row["status"]))  # fmt: skip
    console.print(table)
