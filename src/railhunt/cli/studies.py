"""``railhunt sections`` and ``railhunt plot``: a sweep's Table 1 sections and Figs. 10-12."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any

import click

from railhunt.cli import CliError, _check_outputs, _fmt, _json_safe, _stdout_console, main

_RESULTS = click.argument(
    "results",
    metavar="RESULTS",
    type=click.Path(exists=True, dir_okay=False, path_type=Path),
)


def _load(results: Path, what: str) -> Any:
    """Run ``what(results)``; invalid files become one ``railhunt: error:`` line."""
    try:
        return what(results)
    except OSError as exc:
        raise CliError(f"{results}: {exc.strerror or exc}") from None
    except (ValueError, KeyError, ImportError) as exc:  # ImportError: Parquet without pyarrow
        text = str(exc.args[0]) if isinstance(exc, KeyError) and exc.args else str(exc)
        if str(results) not in text:
            text = f"{results}: {text}"
        raise CliError(text) from None


def _share(value: float) -> str:
    return "" if not math.isfinite(value) else f"{100 * value:.0f} %"


@main.command(short_help="ΔV_cr and Δf per Table 1 section of a sweep (Fig. 12).")
@_RESULTS
@click.option("--png", "png_file", type=click.Path(dir_okay=False, path_type=Path),
              metavar="FILE", help="Draw the paper's Fig. 12: (a) ΔV_cr and (b) Δf, stacked "
              "bars per parameter by section.")  # fmt: skip
@click.option("--csv", "csv_file", type=click.Path(dir_okay=False, path_type=Path),
              metavar="FILE", help="Write one row per parameter and section (SI and display "
              "units, km/h, Hz, shares).")  # fmt: skip
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON on stdout.")
def sections(results: Path, png_file: Path | None, csv_file: Path | None,
             as_json: bool) -> None:  # fmt: skip
    """Change of critical speed and frequency per Table 1 section (Fig. 12).

    \b
    RESULTS is the file written by a one-parameter-at-a-time sweep ('railhunt
    sweep', design 'lines'). Each line named after a parameter of the paper's
    Table 1 (C_d1, K_d, C_d2, mu, K_px, f11 = f22, C_sy) is divided into the
    table's three sections. Per section:

    \b
      ΔV_cr  total variation of the nonlinear critical speed over the section
             (km/h): sum of |ΔV_cr| between neighbouring points, the section's
             ends included (|V_cr(end) - V_cr(start)| where it is monotone);
      Δf     the same for the hunting frequency (Hz), with the frequency jump
             (neighbours from different sources: eigenvalue / limit cycle)
             removed, as the paper does.

    Points without a number are skipped and reported. Prints a table with each
    section's share of the parameter's total; --png draws Fig. 12.
    """
    _check_outputs(png=png_file, csv=csv_file)
    from railhunt.studies.sections import section_changes

    table = _load(results, section_changes)
    if png_file is not None:
        from railhunt.plots import plot_sections

        try:
            plot_sections(table, png_file)
        except OSError as exc:
            raise CliError(f"cannot write --png {png_file}: {exc.strerror or exc}") from None
    if csv_file is not None:
        _write_sections_csv(table, csv_file)
    if as_json:
        data = table.to_dict()
        data["results"] = str(results)
        click.echo(json.dumps(_json_safe(data), indent=2))
        return
    from rich.table import Table

    out = _stdout_console()
    grid = Table(title=f"change per Table 1 section: {results}")
    for head in ("parameter", "sec.", "range", "ΔV_cr (km/h)", "share", "Δf (Hz)", "share",
                 "points"):  # fmt: skip
        grid.add_column(head, justify="left" if head in ("parameter", "range") else "right",
                        no_wrap=head in ("parameter", "range"))  # fmt: skip
    for entry in table:
        first = (entry.parameter, "" if entry.unit == "-" else f"({entry.unit})",
                 f"Fig. {entry.figure}")  # fmt: skip
        for s in entry.sections:
            span = f"{s.lower / entry.scale:g}–{s.upper / entry.scale:g}"
            if s.coverage < 1 - 1e-9:
                span += f" ({100 * s.coverage:.0f} %)"
            grid.add_row(first[s.section - 1], str(s.section), span,
                         _fmt(s.speed_change_kmh, ".1f"), _share(s.speed_share),
                         _fmt(s.frequency_change_hz, ".3f"), _share(s.frequency_share),
                         str(s.points))  # fmt: skip
        grid.add_row("", "total", f"f at {entry.frequency_speed_kmh:g} km/h",
                     _fmt(entry.speed_change_kmh, ".1f"), "",
                     _fmt(entry.frequency_change_hz, ".3f"), "", "", style="bold",
                     end_section=True)  # fmt: skip
    out.print(grid)
    out.print("ΔV_cr: total variation of V_cr over the section; Δf: the same, the frequency "
              "jump removed. Range in the parameter's unit; (n %): part of the section "
              "covered by the sweep.")  # fmt: skip
    for entry in table:
        for note in entry.notes:
            out.print(f"[yellow]{entry.parameter}: {note}[/yellow]")
    for note in table.notes:
        out.print(f"[yellow]{note}[/yellow]")
    for f in (png_file, csv_file):
        if f is not None:
            out.print(f"wrote {f}")


def _write_sections_csv(table: Any, path: Path) -> None:
    header = ["parameter", "section", "lower_si", "upper_si", "lower", "upper", "unit",
              "speed_change_kmh", "speed_share", "speed_net_change_kmh", "frequency_change_hz",
              "frequency_share", "points", "coverage", "jumps_removed"]  # fmt: skip
    try:
        with open(path, "w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(header)
            for entry in table:
                for s in entry.sections:
                    d = s.to_dict(entry.scale)
                    writer.writerow([entry.parameter, s.section, repr(s.lower), repr(s.upper),
                                     d["lower"], d["upper"], entry.unit,
                                     *(repr(float(getattr(s, k))) for k in
                                       ("speed_change_kmh", "speed_share",
                                        "speed_net_change_kmh", "frequency_change_hz",
                                        "frequency_share")),
                                     s.points, repr(s.coverage), s.jumps_removed])  # fmt: skip
    except OSError as exc:
        raise CliError(f"cannot write --csv {path}: {exc.strerror or exc}") from None


@main.command(short_help="Draw V_cr and frequency against swept parameters (Figs. 10, 11).")
@_RESULTS
@click.option("--out", "out_file", type=click.Path(dir_okay=False, path_type=Path),
              required=True, metavar="FILE", help="Figure to write (PNG, PDF, SVG ...).")
@click.option("--parameter", "parameters", multiple=True, metavar="NAME",
              help="Draw only this line (repeatable, in this order). Default: every line "
              "of RESULTS.")  # fmt: skip
def plot(results: Path, out_file: Path, parameters: tuple[str, ...]) -> None:
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
    _check_outputs(out=out_file)
    from railhunt.plots import plot_sweep
    from railhunt.studies.sections import sweep_lines

    lines = _load(results, sweep_lines)
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
    _stdout_console().print(f"wrote {out_file} ({drawn})")
