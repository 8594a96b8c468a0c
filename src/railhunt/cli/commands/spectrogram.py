"""``railhunt spectrogram``: STFT of a measured signal and its dominant frequency band."""

from __future__ import annotations

import json
from pathlib import Path

import click

from railhunt.cli.errors import CliError, user_input
from railhunt.cli.options import check_outputs, file_option, number_range, overwrite_option
from railhunt.cli.output import json_safe, stdout_console, traced
from railhunt.cli.rules import Excludes, Ordered, Requires, command

RULES = (
    Ordered("--fmin", "--fmax", "--fmin {fmin:g} Hz is invalid: must be below --fmax {fmax:g} Hz",
            strict=True),
    Requires("--full-range", "--png", "{a} only applies with {b} (it sets the plotted range)"),
    Excludes("--full-range", "--fmax", "{a} and {b} exclude each other: --fmax {fmax:g} Hz "
             "already sets the top of the plot"),
)


@command("spectrogram", rules=RULES,
         short_help="STFT of a measured signal: dominant frequency band over time.")
@click.argument("csv_file", metavar="FILE.csv", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--channel",
    required=True,
    metavar="NAME",
    help="Column to analyse (its header, with or without a '[unit]' suffix), e.g. y_w1.",
)
@click.option(
    "--window",
    type=float,
    default=2.0,
    show_default=True,
    metavar="S",
    callback=number_range("s", 0.0, 1e4),
    help="Length of each STFT window (s); the frequency resolution is 1/window Hz.",
)
@click.option(
    "--fmin",
    type=float,
    default=None,
    metavar="HZ",
    callback=number_range("Hz", 0.0, 1e6, low_open=False, optional=True),
    help="Lowest frequency searched for the dominant band (Hz). Default: the first bin "
    "above 0 Hz.",
)
@click.option(
    "--fmax",
    type=float,
    default=None,
    metavar="HZ",
    callback=number_range("Hz", 0.0, 1e6, optional=True),
    help="Highest frequency searched for the dominant band, and the top of the --png plot "
    "(Hz). Default: the search goes to the Nyquist frequency; the plot shows 0-20 Hz, or up to "
    "twice the dominant bands' upper edge when they lie higher.",
)
@click.option("--full-range", "full_range", is_flag=True,
              help="Plot every frequency up to the Nyquist frequency (--png).")
@file_option("--png", "png_file",
             "Draw the STFT amplitude map (time vs frequency, like the paper's Fig. 9a).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object instead of a table.")
@overwrite_option
def spectrogram_command(
    csv_file: Path,
    channel: str,
    window: float,
    fmin: float | None,
    fmax: float | None,
    png_file: Path | None,
    as_json: bool,
    full_range: bool = False,
    overwrite: bool = False,
) -> None:
    """Short-time Fourier transform of one channel of a CSV record.

    \b
    FILE.csv has a header row, a time column named 't' or 'time' (s, e.g.
    't [s]'; 't [ms]' and 't [min]' are converted) and the signal in the
    column given by --channel (any unit, e.g. a car-body or bogie-frame
    acceleration in m/s^2, or a channel of 'railhunt simulate --csv'). The
    record must be uniformly sampled and hold at least two windows. Hann
    windows of --window s overlap by 75 %.

    \b
    Prints the dominant frequency band over time: stretches where the
    frequency of the largest STFT amplitude stays within one bin, each with
    its half-power band and peak amplitude. A hunting bogie shows up as a
    steady band at the hunting frequency (a few Hz); after a yaw damper blows
    off it jumps higher (the paper's Fig. 8-9).
    """
    check_outputs(overwrite=overwrite, png=png_file)
    if not csv_file.exists():
        raise CliError(f"FILE.csv {csv_file}: no such file")
    from railhunt.analysis.spectrogram import dominant_bands, read_channel, stft
    from railhunt.plots.spectrogram import plot_spectrogram

    with user_input():
        t, y, name = read_channel(csv_file, channel)
    with user_input(f"{csv_file}: "):
        spec = stft(t, y, window=window)
        bands = dominant_bands(spec, fmin=fmin, fmax=fmax)
    unit = name[name.rindex("[") + 1 : -1] if name.endswith("]") and "[" in name else ""
    if as_json:
        data = {
            "file": str(csv_file),
            "channel": name,
            "sampling_hz": 1.0 / float(t[1] - t[0]),
            "window_s": spec.window,
            "resolution_hz": spec.resolution,
            "bands": [
                {"start_s": b.start, "end_s": b.end, "frequency_hz": b.frequency,
                 "low_hz": b.low, "high_hz": b.high, "amplitude": b.amplitude,
                 "no_signal": b.no_signal}
                for b in bands
            ],  # fmt: skip
        }
        click.echo(json.dumps(json_safe(_with_source(traced(data), csv_file)), allow_nan=False))
    else:
        from rich.markup import escape
        from rich.table import Table

        title = (f"dominant frequency of {escape(name)} in {escape(csv_file.name)} "
                 f"(window {spec.window:g} s, bins {spec.resolution:.3g} Hz)")  # fmt: skip
        table = Table(title=title)
        for head in ("from (s)", "to (s)", "frequency (Hz)", "band (Hz)",
                     f"peak amplitude{f' ({unit})' if unit else ''}"):  # fmt: skip
            table.add_column(head, justify="right")
        for b in bands:
            if b.no_signal:
                table.add_row(f"{b.start:.2f}", f"{b.end:.2f}", "no signal", "-", "0")
            else:
                table.add_row(f"{b.start:.2f}", f"{b.end:.2f}", f"{b.frequency:.3g}",
                              f"{b.low:.3g}-{b.high:.3g}", f"{b.amplitude:.4g}")  # fmt: skip
        stdout_console().print(table)
        heard = [b for b in bands if not b.no_signal]
        if not heard:
            stdout_console().print(
                f"no signal: {escape(name)} is constant over the whole record (no vibration, "
                "so no dominant frequency)"
            )
        else:
            strongest = max(heard, key=lambda b: b.amplitude)
            stdout_console().print(
                f"strongest: {strongest.frequency:.3g} Hz between {strongest.start:.2f} s and "
                f"{strongest.end:.2f} s (peak amplitude {strongest.amplitude:.4g}"
                f"{f' {unit}' if unit else ''})"
            )
    if png_file is not None:
        with user_input("cannot write --png: "):
            plot_spectrogram(spec, png_file, title=f"STFT of {name}", unit=unit, bands=bands,
                             fmax=fmax, full_range=full_range)  # fmt: skip
        if not as_json:
            click.echo(f"png: {png_file}")


def _with_source(data: dict, csv_file: Path) -> dict:
    """``data`` with the provenance of the record analysed (``source``): the metadata
    sidecar ``FILE.csv.meta.json`` that 'railhunt simulate --csv' writes, if there is one."""
    from railhunt.cli.files import sidecar_path

    side = sidecar_path(csv_file)
    try:
        meta = json.loads(side.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return data
    keep = ("railhunt_version", "vehicle", "vehicle_fingerprint", "command")
    return {**data, "source": {k: meta[k] for k in keep if k in meta}}
