"""Parameter studies: V_cr and f against each parameter (Figs. 10-11), Table 1 sections (12)."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from railhunt.studies.sections import SectionTable, SweepLine


from railhunt.plots.figure import new_figure, save_figure

_SECTION_COLOURS = ("#1f4e79", "#5b9bd5", "#bdd7ee")


def _display_unit(name: str) -> tuple[str, float, str]:
    """Axis label, SI size of the display unit and tick-label name of a swept parameter."""
    from railhunt.paper2019.table1 import load_table1
    from railhunt.vehicle import PARAMETERS

    entry = load_table1().get(name)
    if entry is not None:
        return entry.label, entry.scale, " = ".join((name, *entry.ties))
    unit = PARAMETERS[name].unit if name in PARAMETERS else ""
    return (f"{name} ({unit})" if unit and unit != "1" else name), 1.0, name


def plot_sweep(
    results: object,
    path: str | os.PathLike[str],
    parameters: list[str] | tuple[str, ...] | None = None,
) -> Path:
    """Critical speed and hunting frequency against each swept parameter (Figs. 10, 11).

    One panel per one-parameter line of the results, lettered (a), (b), ...: the
    parameter in its display unit (Table 1's: kN*s/m, MN/m, MN) on x; the nonlinear
    critical speed V_cr (km/h) black solid on the left axis; the hunting frequency (Hz,
    at the speed the sweep computed it) blue on a twin right axis, solid between
    neighbours from the same source (eigenvalue or limit cycle) and dashed where the
    source changes (the frequency jump). Points without a number are skipped (marked x
    on the axis for V_cr).

    Parameters
    ----------
    results : str, os.PathLike, SweepResults or sequence of dict
        Results of a one-parameter-at-a-time sweep (design ``"lines"``); see
        :func:`railhunt.studies.sections.result_rows`.
    path : str or os.PathLike
        Output file; the format follows the suffix.
    parameters : sequence of str, optional
        The lines to draw, in this order (default: every line of the results).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        The results hold a grid / random / Latin-hypercube design (several parameters
        varied at once: one parameter's curve would mix the others' changes), a
        requested parameter is not one of the lines, or the results have neither the
        critical speed nor the hunting frequency.
    """
    return save_figure(sweep_figure(results, parameters), path)


def sweep_figure(
    results: object,
    parameters: list[str] | tuple[str, ...] | None = None,
) -> Figure:
    """The figure of :func:`plot_sweep`, not saved (the same checks and errors)."""
    from railhunt.studies.sections import sweep_lines

    lines = sweep_lines(results)
    names = list(lines) if parameters is None else list(parameters)
    if not names:
        raise ValueError(f"no parameter to plot (lines: {', '.join(lines)})")
    for name in names:
        if name not in lines:
            raise ValueError(f"no line {name!r} in the results (lines: {', '.join(lines)})")
    columns = next(iter(lines.values())).columns
    if not {"critical_speed_kmh", "hunting_frequency_hz"} & columns:
        raise ValueError("the results hold neither critical_speed nor hunting_frequency (the "
                         "sweep's outputs): nothing to draw for Figs. 10/11")  # fmt: skip
    n = len(names)
    cols = n if n <= 3 else (2 if n == 4 else 3)
    rows = int(math.ceil(n / cols))
    fig = new_figure(4.6 * cols, 3.7 * rows)
    for k, name in enumerate(names):
        ax = fig.add_subplot(rows, cols, k + 1)
        _sweep_panel(ax, lines[name], f"({chr(ord('a') + k)})")
    _sweep_legend(fig)
    return fig


def _sweep_panel(ax: Axes, line: SweepLine, letter: str) -> None:
    label, scale, _ = _display_unit(line.parameter)
    x = np.asarray(line.values, dtype=float) / scale
    v = np.asarray(line.critical_speed_kmh, dtype=float)
    f = np.asarray(line.frequency_hz, dtype=float)
    ok = np.isfinite(v)
    ax.plot(x[ok], v[ok], "k-o", lw=1.6, ms=3)
    if np.any(~ok & np.isfinite(x)):
        ax.plot(x[~ok], np.zeros(np.count_nonzero(~ok)), "x", color="0.4", ms=6, clip_on=False,
                transform=ax.get_xaxis_transform())  # fmt: skip
    ax.set_xlabel(label)
    ax.set_ylabel("critical speed V_cr (km/h)")
    ax.set_title(f"{letter} {label.split(' (')[0]}", loc="left")
    ax.grid(True, alpha=0.3)

    ax_f = ax.twinx()
    blue = "tab:blue"
    jumps = set(line.jumps())
    finite = np.flatnonzero(np.isfinite(f))
    run: list[int] = []
    for i, j in zip(finite, [*finite[1:], -1], strict=False):
        run.append(int(i))
        if j < 0 or int(i) in jumps:
            ax_f.plot(x[run], f[run], "-s", color=blue, lw=1.4, ms=3)
            if j >= 0:
                ax_f.plot(x[[i, j]], f[[i, j]], "--", color=blue, lw=1.4)
            run = []
    speed = line.frequency_speed_kmh
    at = f" at {speed:g} km/h" if math.isfinite(speed) else ""
    ax_f.set_ylabel(f"hunting frequency f{at} (Hz)", color=blue)
    ax_f.tick_params(axis="y", colors=blue)


def _sweep_legend(fig: Figure) -> None:
    from matplotlib.lines import Line2D

    blue = "tab:blue"
    handles = [
        Line2D([], [], color="k", marker="o", ms=3, label="critical speed V_cr (left axis)"),
        Line2D([], [], color=blue, marker="s", ms=3, label="hunting frequency f (right axis)"),
        Line2D([], [], color=blue, ls="--", label="jump of f (source changes)"),
    ]
    fig.legend(handles=handles, loc="outside upper center", ncols=3, fontsize="small")


def plot_sections(section_table: SectionTable, path: str | os.PathLike[str]) -> Path:
    """ΔV_cr and Δf per parameter and Table 1 section, like the paper's Fig. 12.

    (a) ΔV_cr (km/h) and (b) Δf (Hz, the frequency jump removed): one stacked bar per
    parameter, sections 1, 2, 3 from the bottom, the total above each bar. A parameter
    whose line does not cover all its sections or skipped points is marked with ``*``.

    Parameters
    ----------
    section_table : SectionTable
        Output of :func:`railhunt.studies.sections.section_changes`.
    path : str or os.PathLike
        Output file; the format follows the suffix.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(sections_figure(section_table), path)


def sections_figure(section_table: SectionTable) -> Figure:
    """The figure of :func:`plot_sections`, not saved."""
    entries = list(section_table)
    if not entries:
        raise ValueError("the section table is empty: nothing to plot")
    n = len(entries)
    fig = new_figure(max(6.0, 1.0 * n + 2.5), 7.0)
    ax_v, ax_f = fig.subplots(2, 1)
    x = np.arange(n)
    names = [_display_unit(e.parameter)[2] + ("" if e.complete else "*") for e in entries]
    for ax, attr, symbol, unit, title in (
        (ax_v, "speed_change_kmh", "ΔV_cr", "km/h", "(a) change of critical speed ΔV_cr"),
        (ax_f, "frequency_change_hz", "Δf", "Hz",
         "(b) change of hunting frequency Δf, the jump removed"),
    ):  # fmt: skip
        bottom = np.zeros(n)
        for k in range(3):
            h = np.array([getattr(e.sections[k], attr) if k < len(e.sections) else math.nan
                          for e in entries])  # fmt: skip
            h = np.where(np.isfinite(h), h, 0.0)
            ax.bar(x, h, 0.6, bottom=bottom, color=_SECTION_COLOURS[k], edgecolor="k", lw=0.5,
                   label=f"section {k + 1}")  # fmt: skip
            bottom += h
        for xi, e, top in zip(x, entries, bottom, strict=True):
            total = getattr(e, attr)
            text = "n/a" if not math.isfinite(total) else f"{total:.3g}"
            ax.annotate(text, (xi, top), xytext=(0, 2), textcoords="offset points",
                        ha="center", va="bottom", fontsize=8)  # fmt: skip
        ax.set_xticks(x, names)
        ax.set_ylabel(f"{symbol} ({unit})")
        ax.set_title(title, loc="left")
        ax.set_ylim(0, max(float(bottom.max()), 1e-9) * 1.3)
        ax.grid(True, axis="y", alpha=0.3)
        ax.legend(fontsize="small", loc="upper left", ncols=3)
    if not all(e.complete for e in entries):
        ax_f.set_xlabel("* the line does not cover every section, or points were skipped",
                        fontsize=8, color="0.3")  # fmt: skip
    return fig
