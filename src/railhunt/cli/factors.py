"""Factors on the command line of ``sensitivity`` and ``optimize``: ``NAME --from A --to B``
or ``NAME --tolerance T``, each NAME followed by its own range.

click collects repeated options without their position among the arguments, so
:class:`FactorCommand` reads the order itself: each ``--from``, ``--to`` or ``--tolerance``
belongs to the NAME before it.
"""

from __future__ import annotations

from typing import Any

import click

from railhunt.cli.errors import CliError
from railhunt.cli.options import cant_option
from railhunt.cli.rules import Command

__all__ = ["FACTOR_FLAGS", "FactorCommand", "curve_flags", "factors_from", "output_columns",
           "output_options_from"]

#: The flags that describe the NAME before them.
FACTOR_FLAGS = ("--from", "--to", "--tolerance")


class FactorCommand(Command):
    """A :class:`railhunt.cli.rules.Command` that records, in ``ctx.meta["factor_specs"]``,
    each NAME with the ``--from``/``--to``/``--tolerance`` values that follow it."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        takes_value = set()
        for param in self.params:
            if isinstance(param, click.Option) and not param.is_flag and not param.count:
                takes_value.update(param.opts)
        specs: list[tuple[str, dict[str, str]]] = []
        i = 0
        while i < len(args):
            token = args[i]
            if token == "--":
                break
            flag, eq, inline = token.partition("=")
            if flag in FACTOR_FLAGS:
                value = inline if eq else (args[i + 1] if i + 1 < len(args) else None)
                if not specs:
                    raise click.UsageError(f"{flag} must follow the NAME it is about, e.g. "
                                           "C_d1 --from 100e3 --to 600e3")  # fmt: skip
                if value is None:
                    raise click.UsageError(f"{flag} needs a value")
                if flag in specs[-1][1]:
                    raise click.UsageError(f"{specs[-1][0]}: {flag} is given twice")
                specs[-1][1][flag] = value
                i += 1 if eq else 2
                continue
            if token.startswith("-"):
                i += 2 if (flag in takes_value and not eq) else 1
                continue
            specs.append((token, {}))
            i += 1
        ctx.meta["factor_specs"] = specs
        return super().parse_args(ctx, args)


def _float(name: str, flag: str, text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise CliError(f"{name} {flag} {text!r} is not a number") from None


def factors_from(ctx: click.Context) -> dict[str, object]:
    """NAME -> ``(low, high)`` or ``("tolerance", t)`` from the recorded specs."""
    specs = ctx.meta.get("factor_specs", [])
    if not specs:
        raise CliError("give the factors: NAME --from A --to B, or NAME --tolerance T "
                       "(e.g. C_d1 --from 100e3 --to 600e3 K_px --tolerance 0.1)")  # fmt: skip
    out: dict[str, object] = {}
    for name, flags in specs:
        if name in out:
            raise CliError(f"{name} is given twice")
        if "--tolerance" in flags:
            if "--from" in flags or "--to" in flags:
                raise CliError(f"{name}: give --from/--to or --tolerance, not both")
            out[name] = ("tolerance", _float(name, "--tolerance", flags["--tolerance"]))
        elif "--from" in flags and "--to" in flags:
            out[name] = (_float(name, "--from", flags["--from"]),
                         _float(name, "--to", flags["--to"]))  # fmt: skip
        else:
            raise CliError(f"{name}: give its range with --from A --to B, or --tolerance T "
                           "(e.g. --tolerance 0.1 for ±10 %)")  # fmt: skip
    return out


def output_options_from(curve_radius: float | None, cant: float | None, curve_speed: float | None,
                        damping_range: tuple[float, float] | None) -> Any:  # fmt: skip
    """The :class:`railhunt.studies.outputs.OutputOptions` of the curve and damping flags."""
    from railhunt.studies.outputs import OutputOptions

    # --cant is in mm, as in every command with a curve (the edge converts to SI).
    kwargs: dict[str, Any] = {"curve_radius": curve_radius,
                              "curve_cant": 0.0 if cant is None else cant * 1e-3,
                              "curve_speed_kmh": curve_speed}  # fmt: skip
    if damping_range is not None:
        kwargs["damping_range_kmh"] = tuple(damping_range)
    try:
        return OutputOptions(**kwargs)
    except ValueError as exc:
        text = str(exc).replace("curve_radius", "--curve-radius").replace(
            "curve_cant", "--cant").replace("curve_speed_kmh", "--curve-speed").replace(
            "damping_range_kmh", "--damping-range")  # fmt: skip
        raise CliError(text) from None


def factor_flags(func: Any) -> Any:
    """The factors of a study: ``NAME ... --from A --to B | --tolerance T`` (read back by
    :func:`factors_from`), for ``railhunt sensitivity`` and ``railhunt optimize``."""
    func = click.option("--tolerance", "tolerances", type=float, multiple=True, metavar="T",
                        help="The preceding NAME varies within ±T of the vehicle's value "
                        "(fraction).")(func)  # fmt: skip
    func = click.option("--to", "tos", type=float, multiple=True, metavar="VALUE",
                        help="End of the preceding NAME's range (SI).")(func)
    func = click.option("--from", "froms", type=float, multiple=True, metavar="VALUE",
                        help="Start of the preceding NAME's range (SI).")(func)
    return click.argument("names", nargs=-1,
                          metavar="NAME --from A --to B | --tolerance T ...")(func)


def curve_flags(func: Any) -> Any:
    """``--curve-radius M``, ``--cant MM``, ``--curve-speed KMH`` and ``--damping-range``."""
    func = click.option("--damping-range", "damping_range", type=float, nargs=2,
                        metavar="LO HI",
                        help="Speed range of least_damping_ratio (km/h) [default: 50 300].")(func)
    func = click.option("--curve-speed", "curve_speed", type=float, metavar="KMH",
                        help="Speed in the curve of max_YQ, sum_Y_leading, wear_number (km/h)."
                        )(func)  # fmt: skip
    func = cant_option("Cant of that curve (mm) [default: 0].", dest="cant")(func)
    return click.option("--curve-radius", "curve_radius", type=float, metavar="M",
                        help="Radius of the curve of the curving outputs (m).")(func)


def output_columns(text: str, flag: str) -> tuple[str, ...]:
    """The results columns of a comma-separated ``flag`` value, checked."""
    from railhunt.studies.factors import COLUMN_OUTPUT

    chosen = tuple(dict.fromkeys(o.strip() for o in text.split(",") if o.strip()))
    bad = [o for o in chosen if o not in COLUMN_OUTPUT]
    if bad or not chosen:
        raise CliError(f"{flag} {text}: choose from {', '.join(COLUMN_OUTPUT)}")
    return chosen
