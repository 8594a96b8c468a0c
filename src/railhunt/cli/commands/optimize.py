"""``railhunt optimize``: the Pareto front of objectives over factors, by NSGA-II."""

from __future__ import annotations

import json
from pathlib import Path

import click

from railhunt.cli.commands.sweep import parse_tie_option
from railhunt.cli.errors import CliError
from railhunt.cli.factors import (
    FactorCommand,
    curve_flags,
    factor_flags,
    factors_from,
    output_columns,
    output_options_from,
)
from railhunt.cli.options import build_vehicle, vehicle_options
from railhunt.cli.output import fmt, json_safe, stdout_console, traced
from railhunt.cli.study import (
    STUDY_RULES,
    announce_study,
    check_study_outputs,
    check_workers_option,
    running_study,
    scheduler_client,
    study_options,
    study_run,
)

_HELP = """\
The best compromise between objectives: a Pareto front by NSGA-II.

\b
Each NAME is a vehicle parameter followed by its range: --from A --to B
(SI) or --tolerance T (±T of the vehicle's value). --objective "max COLUMN"
or "min COLUMN" (at least two) and --constraint "COLUMN >= VALUE" (or <=)
name results columns, as 'railhunt sensitivity' lists them. NSGA-II (pymoo)
evolves --population designs over --generations; each generation is
evaluated on all cores (or --scheduler) and written to --out as its points
finish. --resume with the same --seed reaches the same front. The starting
vehicle is evaluated too and marked in --png.

\b
Example:
  railhunt optimize K_px --from 2e6 --to 40e6 C_d1 --tolerance 0.3 \\
      --objective "max linear_critical_speed_kmh" --objective "min wear_number" \\
      --constraint "linear_critical_speed_kmh >= 385" --curve-radius 600 \\
      --cant 150 --curve-speed 120 --population 16 --generations 8 \\
      --out pareto.csv --png pareto.png
"""


@click.command("optimize", cls=FactorCommand, rules=STUDY_RULES, help=_HELP,
               short_help="Pareto front of objectives by NSGA-II.")
@factor_flags
@click.option("--objective", "objectives", multiple=True, metavar="'max|min COLUMN'",
              help="An objective (repeat: at least two).")
@click.option("--constraint", "constraints", multiple=True, metavar="'COLUMN >= VALUE'",
              help="A constraint, >= or <= (repeatable).")
@click.option("--population", type=int, default=20, show_default=True, metavar="N",
              help="Designs per generation.")
@click.option("--generations", type=int, default=10, show_default=True, metavar="N",
              help="Generations (the first is random).")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of NSGA-II.")
@click.option("--tie", "ties", multiple=True, callback=parse_tie_option, metavar="F=L",
              help="F follows L at every point: f22=f11, or f22=0.9*f11 (repeatable).")
@curve_flags
@study_options()
@click.option("--png", type=click.Path(dir_okay=False, path_type=Path), metavar="FILE",
              help="Write the figure of the front with the starting vehicle.")
@click.option("--json", "as_json", is_flag=True, help="Print JSON instead of a table.")
@vehicle_options
@click.pass_context
def optimize_command(ctx, names, froms, tos, tolerances, objectives, constraints, population,
                     generations, seed, ties, curve_radius, cant, curve_speed, damping_range,
                     out, resume, overwrite, workers, scheduler, connect_timeout, png, as_json,
                     vehicle_file, sets) -> None:  # fmt: skip
    """``railhunt optimize`` (help text: ``_HELP``)."""
    from railhunt import optimize
    from railhunt.studies.design import Point
    from railhunt.studies.factors import vehicle_outputs
    from railhunt.studies.optimize import parse_constraint, parse_objective

    check_workers_option(workers)
    if len(objectives) < 2:
        raise CliError("--objective is needed at least twice (one column each), e.g. 'max "
                       "critical_speed_kmh' and 'min wear_number'")  # fmt: skip
    with running_study(out):
        cols = [parse_objective(o)[1] for o in objectives]
        cols += [parse_constraint(c)[0] for c in constraints]
    columns = output_columns(",".join(cols), "--objective/--constraint")
    check_study_outputs(out, resume, overwrite, png=png)
    vehicle = build_vehicle(vehicle_file, sets)
    factors = factors_from(ctx)
    options = output_options_from(curve_radius, cant, curve_speed, damping_range)
    with running_study(out), scheduler_client(scheduler, connect_timeout) as client:
        if population > 0 and generations > 0:
            corners = [Point(i, "estimate", {}) for i in range(population * generations + 1)]
            announce_study(vehicle, corners, vehicle_outputs(columns), workers, scheduler,
                           what="designs")  # fmt: skip
        result = optimize(vehicle, factors, objectives, constraints, population=population,
                          generations=generations, seed=seed, ties=ties,
                          output_options=options,
                          run=study_run(out, resume, overwrite, workers, client))  # fmt: skip
    if png is not None:
        result.figure(png)
    if as_json:
        data = {"file": str(out), **result.to_dict()}
        if png is not None:
            data["png"] = str(png)
        click.echo(json.dumps(json_safe(traced(data, vehicle)), indent=1))
    else:
        _print(result)
    _report_lost(result, out)


def _report_lost(result, out) -> None:
    """Exit with status 1 when designs were lost (they can be resumed) or every design
    failed (the front is empty for want of values, not of good designs)."""
    status = result.evaluated["status"] if len(result.evaluated) else []
    lost = int(sum(s == "lost" for s in status))
    failed = int(sum(s == "failed" for s in status))
    if lost:
        how = ("run the same command with --resume to compute them" if out is not None
               else "run the command again")  # fmt: skip
        click.echo(f"railhunt: {lost} designs were lost; {how}", err=True)
        raise SystemExit(1)
    if len(status) and failed == len(status):
        where = f": their messages are in {out}" if out is not None else ""
        click.echo(f"railhunt: error: every one of the {failed} designs failed{where}",
                   err=True)  # fmt: skip
        raise SystemExit(1)


def _print(result) -> None:
    from rich.table import Table

    click.echo(f"{len(result.evaluated)} designs evaluated, "
               f"{int(result.evaluated['feasible'].sum())} feasible, {len(result.front)} on "
               f"the front; hypervolume {fmt(result.hypervolume[-1], '.4g')}")  # fmt: skip
    table = Table()
    cols = [*result.factors, *result.objective_columns]
    for head in cols:
        table.add_column(head, justify="right")
    for _, row in result.front.iterrows():
        table.add_row(*(f"{row[c]:.6g}" for c in cols))
    if result.start is not None:
        table.add_row(*(f"{result.start[c]:.6g}" for c in cols), style="bold")
    stdout_console().print(table)
    if result.start is not None:
        click.echo("(last row, bold: the starting vehicle)")
