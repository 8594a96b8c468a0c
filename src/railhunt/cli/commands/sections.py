"""``railhunt sections``: a sweep's change of V_cr and f per Table 1 section (Fig. 12)."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.options import (
    check_outputs,
    file_option,
    load_results,
    overwrite_option,
    results_argument,
    write_sidecar,
)
from railhunt.cli.output import command_record, fmt, json_safe, stdout_console, traced
from railhunt.cli.rules import command


def _share(value: float) -> str:
    return "" if not math.isfinite(value) else f"{100 * value:.0f} %"


@command("sections", short_help="ΔV_cr and Δf per Table 1 section of a sweep (Fig. 12).")
@results_argument
@file_option("--png", "png_file", "Draw the paper's Fig. 12: (a) ΔV_cr and (b) Δf, stacked "
             "bars per parameter by section.")
@file_option("--csv", "csv_file", "Write one row per parameter and section (SI and display "
             "units, km/h, Hz, shares).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON on stdout.")
@overwrite_option
def sections_command(results: Path, png_file: Path | None, csv_file: Path | None,
                     as_json: bool, overwrite: bool) -> None:  # fmt: skip
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
    check_outputs(overwrite=overwrite, png=png_file, csv=csv_file)
    from railhunt import section_changes

    table = load_results(results, section_changes)
    if png_file is not None:
        from railhunt.plots import plot_sections

        try:
            plot_sections(table, png_file)
        except OSError as exc:
            raise CliError(f"cannot write --png {png_file}: {exc.strerror or exc}") from None
    source = results_provenance(results)
    if csv_file is not None:
        _write_sections_csv(table, csv_file)
        with user_input("cannot write --csv: "):
            write_sidecar(csv_file, traced({"source": source}), **command_record())
    if as_json:
        data = table.to_dict()
        data["results"] = str(results)
        data["source"] = source
        click.echo(json.dumps(json_safe(traced(data)), indent=2))
        return
    from rich.table import Table

    out = stdout_console()
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
                         fmt(s.speed_change_kmh, ".1f"), _share(s.speed_share),
                         fmt(s.frequency_change_hz, ".3f"), _share(s.frequency_share),
                         str(s.points))  # fmt: skip
        grid.add_row("", "total", f"f at {entry.frequency_speed_kmh:g} km/h",
                     fmt(entry.speed_change_kmh, ".1f"), "",
                     fmt(entry.frequency_change_hz, ".3f"), "", "", style="bold",
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


def results_provenance(results: Path) -> dict[str, Any]:
    """The provenance of a study's results file, from its sidecar ``<file>.sweep.json``
    (the railhunt version that computed it, the vehicle's name and fingerprint; files
    written before the sidecar held them give what it has)."""
    from railhunt.studies.store import sidecar_path

    try:
        meta = json.loads(sidecar_path(results).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    if isinstance(meta.get("provenance"), dict):
        return meta["provenance"]
    return {"railhunt_version": meta.get("railhunt")} if "railhunt" in meta else {}


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
