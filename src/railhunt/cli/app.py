"""The ``railhunt`` command group: ``--version``, the help listing every command, errors.

The interface converts units at its edge (defect amplitudes in mm, speeds in km/h) and
calls the Python API in SI units. Every input error ends the program with one line on
stderr starting with ``railhunt: error:`` and exit status 2. The library (and numba's
compiled code) is imported inside the commands, so ``railhunt --help`` stays fast.
"""

from __future__ import annotations

from typing import Any

import click

import railhunt
from railhunt.cli.commands import COMMANDS
from railhunt.cli.errors import DEBUG_ENV, DEBUG_KEY, PROG, no_tracebacks, one_line_usage_errors

__all__ = ["main"]

_INTRO = """\
Hunting stability of a high-speed railway vehicle (17-DOF lateral model).

\b
Hunting is the self-excited lateral oscillation of a railway vehicle. The
coned wheel treads steer each wheelset back towards the track centre, so at
low speed a lateral disturbance dies out. Above a critical speed the creep
forces between wheel and rail feed energy into this motion instead: the
wheelsets and bogies swing from side to side on a limit cycle of a few Hz,
wearing wheels and rails and risking flange contact and derailment.
"""

_NOTES = """\
\b
Units: speeds in km/h; defect amplitudes and displacements in mm;
wavelengths in m; times in s; frequencies in Hz. Vehicle parameters
(--vehicle FILE, --set NAME=VALUE) are always SI (kg, N/m, N*s/m, m, ...),
exactly as in the vehicle TOML files.

\b
Output files: an output file that exists is not replaced; the command stops
before it computes anything unless --overwrite is given (a study's --out may
also be continued with --resume). Every output path is checked before the
work starts. Every CSV file gets its metadata beside it (FILE.meta.json; a
study's results file FILE.sweep.json) and every JSON output carries
railhunt_version, the vehicle's name and vehicle_fingerprint (a hash of its
parameters), so that a number can be traced.

\b
Long runs: a command whose estimated work exceeds a minute says so on stderr
before it starts ('railhunt: note: this will take about ...'); the estimates
fall within a factor of about 1.6 of the measured time on the reference machine
(python benchmarks/workload.py). A run estimated at more than an hour is refused
unless --yes is given, naming what sets its step.
\b
Errors: an unexpected error is one line too; RAILHUNT_DEBUG=1 or
'railhunt --debug COMMAND' shows its traceback.

\b
Examples:
  railhunt simulate --speed 320 --png run.png
  railhunt eigen --from 100 --to 500 --png locus.png
  railhunt critical-speed --set C_d1=150e3 --json

'railhunt COMMAND --help' explains a command and its options. Input errors are
reported as one 'railhunt: error:' line with exit status 2.
"""


class Group(click.Group):
    """The ``railhunt`` group: one-line usage errors (exit 2) from any command, and a help
    that lists the commands in the order they were added, each by its ``short_help``."""

    def make_context(
        self,
        info_name: str | None,
        args: list[str],
        parent: click.Context | None = None,
        **extra: Any,
    ) -> click.Context:
        with one_line_usage_errors():
            return super().make_context(info_name, args, parent, **extra)

    def invoke(self, ctx: click.Context) -> Any:
        with no_tracebacks(ctx), one_line_usage_errors():
            return super().invoke(ctx)

    def list_commands(self, ctx: click.Context) -> list[str]:
        """The commands in the order they were added (see ``railhunt.cli.commands``)."""
        return list(self.commands)

    def format_help(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """Usage, the introduction, the commands, units and examples, then the options."""
        self.format_usage(ctx, formatter)
        self.format_help_text(ctx, formatter)
        self.format_commands(ctx, formatter)
        self.format_epilog(ctx, formatter)
        click.Command.format_options(self, ctx, formatter)


@click.group(
    PROG,
    cls=Group,
    help=_INTRO,
    epilog=_NOTES,
    context_settings={"help_option_names": ["-h", "--help"]},
)
@click.version_option(railhunt.__version__, prog_name=PROG)
@click.option("--debug", is_flag=True, expose_value=False, is_eager=True,
              callback=lambda ctx, param, value: ctx.meta.__setitem__(DEBUG_KEY, value),
              help=f"Show the traceback of an unexpected error (or set {DEBUG_ENV}=1).")
def main() -> None:
    """Entry point of the railhunt command (help text: ``_INTRO`` and ``_NOTES``)."""


for _command in COMMANDS:
    main.add_command(_command)
