"""``railhunt plot``: V_cr and hunting frequency against each swept parameter (Figs. 10, 11)."""

from __future__ import annotations

from pathlib import Path

import click

from railhunt.cli.errors import CliError
from railhunt.cli.files import OutputPath
from railhunt.cli.options import check_outputs, load_results, overwrite_option, results_argument
from railhunt.cli.output import stdout_console
from railhunt.cli.rules import command


@command("plot", short_help="Draw V_cr and frequency against swept parameters (Figs. 10, 11).")
@results_argument
@click.option("--out", "out_file", type=OutputPath(),
              required=True, metavar="FILE", help="Figure to write (PNG, PDF, SVG ...).")
@click.option("--parameter", "parameters", multiple=True, metavar="NAME",
              help="Draw only this line (repeatable, in this order). Default: every line "
              "of RESULTS.")  # fmt: skip
@overwrite_option
def plot_command(results: Path, out_file: Path, parameters: tuple[str, ...],
                 overwrite: bool) -> None:  # fmt: skip
    """Critical speed and hunting frequency against each swept parameter (Figs. 10, 11).

    \b
    RESULTS is the file written by a one-parameter-at-a-time sweep ('railhunt
    sweep', design 'lines'). One panel per line, (a), (b), ...: the parameter
    in the paper's display unit (kN*s/m, MN/m, MN) on x, the nonlinear critical
    speed V_cr (km/h) black on the left axis, the hunting frequency (Hz) blue
    on the right axis, dashed where its source changes between neighbours
    (the frequency jump at blow-off of the yaw damper). Grid and random designs
    vary several parameters at once and cannot be drawn this way.
    """
    check_outputs(overwrite=overwrite, out=out_file)
    from railhunt.plots import plot_sweep
    from railhunt.studies.sections import sweep_lines

    lines = load_results(results, sweep_lines)
    for name in parameters:
        if name not in lines:
            raise CliError(f"--parameter {name}: no such line in {results} "
                           f"(lines: {', '.join(lines)})")  # fmt: skip
    try:
        plot_sweep(results, out_file, list(parameters) or None)
    except OSError as exc:
        raise CliError(f"cannot write --out {out_file}: {exc.strerror or exc}") from None
    except ValueError as exc:
        raise CliError(f"{results}: {exc}") from None
    drawn = ", ".join(parameters or lines)
    stdout_console().print(f"wrote {out_file} ({drawn})")
