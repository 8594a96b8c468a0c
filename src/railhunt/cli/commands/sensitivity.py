"""``railhunt sensitivity``: Sobol or Morris indices of outputs to factors varied together."""

from __future__ import annotations

import json
from pathlib import Path

import click

from railhunt.cli.commands.sweep import parse_tie_option
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
    report_lost,
    running_study,
    scheduler_client,
    study_options,
    study_run,
)

_HELP = """\
Which parameters move an output when all of them vary together.

\b
Each NAME is a vehicle parameter followed by its range: --from A --to B
(uniform, SI units) or --tolerance T (uniform within ±T of the vehicle's
value, e.g. 0.1 for ±10 %). Every point of the sample is a vehicle; its
outputs (--output, results columns) are computed as 'railhunt sweep' does,
and SALib gives the indices: Sobol first-order S1 and total ST with
bootstrap 95 % intervals (--method sobol: --samples N base samples, a power
of 2, N*(D+2) points), or Morris mu* and sigma (--method morris: N
trajectories, N*(D+1) points).

\b
Outputs: critical_speed_kmh, linear_critical_speed_kmh, linear_frequency_hz,
hunting_frequency_hz, fold_speed_kmh, least_damping_ratio and, in the curve
of --curve-radius/--cant at --curve-speed, max_YQ, sum_Y_leading,
wear_number. An unbracketed critical speed counts as the search's limit
(capped); a point without a value drops its whole Saltelli block (counted).

\b
The points run on all cores or --scheduler; each is written to --out as it
finishes, and --resume continues an interrupted study (same indices, bit for
bit, for the same --seed).

\b
Examples:
  railhunt sensitivity C_d1 --from 100e3 --to 600e3 K_px --tolerance 0.1 \\
      --output linear_critical_speed_kmh --samples 256 --out sobol.csv
  railhunt sensitivity mu --from 0.1 --to 0.4 f11 --tolerance 0.2 --tie f22=f11 \\
      --output critical_speed_kmh,fold_speed_kmh --samples 64 --out s.csv --png s.png
"""


def announce_points(vehicle, xs, names, columns, workers, scheduler) -> None:
    """Say before it starts that a study of these sampled points takes more than a minute."""
    from railhunt.studies.design import Point
    from railhunt.studies.factors import vehicle_outputs

    points = [Point(i, "sample", dict(zip(names, map(float, x), strict=True)))
              for i, x in enumerate(xs)]  # fmt: skip
    announce_study(vehicle, points, vehicle_outputs(columns), workers, scheduler)


@click.command("sensitivity", cls=FactorCommand, rules=STUDY_RULES, help=_HELP,
               short_help="Sobol / Morris sensitivity indices of outputs.")
@factor_flags
@click.option("--method", type=click.Choice(["sobol", "morris"]), default="sobol",
              show_default=True, help="Sobol (Saltelli sample) or Morris (trajectories).")
@click.option("--samples", type=int, default=256, show_default=True, metavar="N",
              help="Base samples (sobol, a power of 2) or trajectories (morris).")
@click.option("--seed", type=int, default=0, show_default=True,
              help="Seed of the sample and the bootstrap.")
@click.option("--output", "output", default="critical_speed_kmh", show_default=True,
              metavar="LIST", help="Comma-separated results columns to analyse.")
@click.option("--tie", "ties", multiple=True, callback=parse_tie_option, metavar="F=L",
              help="F follows L at every point: f22=f11, or f22=0.9*f11 (repeatable).")
@curve_flags
@study_options()
@click.option("--png", type=click.Path(dir_okay=False, path_type=Path), metavar="FILE",
              help="Write the figure of the indices (bars with their intervals).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON instead of a table.")
@vehicle_options
@click.pass_context
def sensitivity_command(ctx, names, froms, tos, tolerances, method, samples, seed, output, ties,
                        curve_radius, cant, curve_speed, damping_range, out, resume, overwrite,
                        workers, scheduler, connect_timeout, png, as_json, vehicle_file,
                        sets) -> None:  # fmt: skip
    """``railhunt sensitivity`` (help text: ``_HELP``)."""
    from railhunt import sensitivity
    from railhunt.studies.factors import parse_factors
    from railhunt.studies.sensitivity import check_samples, sample_of

    check_workers_option(workers)
    columns = output_columns(output, "--output")
    check_study_outputs(out, resume, overwrite, png=png)
    vehicle = build_vehicle(vehicle_file, sets)
    factors = factors_from(ctx)
    options = output_options_from(curve_radius, cant, curve_speed, damping_range)
    with running_study(out), scheduler_client(scheduler, connect_timeout) as client:
        facs = parse_factors(vehicle, factors)
        xs = sample_of(method, facs, check_samples(method, samples), seed)
        announce_points(vehicle, xs, [f.name for f in facs], columns, workers, scheduler)
        result = sensitivity(vehicle, factors, columns, method=method, samples=samples,
                             seed=seed, ties=ties, output_options=options,
                             run=study_run(out, resume, overwrite, workers,
                                           client))  # fmt: skip
    if png is not None:
        result.figure(png)
    if as_json:
        data = {"file": str(out), **result.to_dict(), "elapsed_s": result.study.elapsed_s}
        if png is not None:
            data["png"] = str(png)
        click.echo(json.dumps(json_safe(traced(data, vehicle)), indent=1))
    else:
        _print(result, out)
    report_lost(result.study)


def _print(result, out: Path) -> None:
    from rich.table import Table

    study = result.study
    click.echo(f"{result.points} points in {out}: {study.computed} computed, {study.resumed} "
               f"already there, {study.lost} lost; {study.elapsed_s:.1f} s")  # fmt: skip
    table = Table()
    for head in ("output", "factor", *result.keys):
        table.add_column(head, justify="right")
    for row in result.indices:
        table.add_row(row["output"], row["factor"], *(fmt(row[k], ".3f") for k in result.keys))
    stdout_console().print(table)
    for out_name in result.outputs:
        if result.dropped.get(out_name) or result.capped.get(out_name):
            click.echo(f"{out_name}: {result.dropped[out_name]} points dropped (whole blocks), "
                       f"{result.capped[out_name]} capped at the search's limit")  # fmt: skip
    for note in result.notes:
        click.echo(f"note: {note}")
