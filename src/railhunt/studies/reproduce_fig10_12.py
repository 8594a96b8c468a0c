"""Reproduction step for the paper's Figs. 10-12: the Table 1 study and its sections.

The Table 1 study (:func:`railhunt.studies.table1.table1_study`) is run by
:func:`railhunt.sweep` (one line per parameter, f22 tied to f11) into ``sweep.csv``;
Figs. 10 and 11 plot the lines (:func:`railhunt.plots.plot_sweep`), Fig. 12 the change of
V_cr and f per section (:func:`railhunt.studies.sections.section_changes`,
:func:`railhunt.plots.plot_sections`). :func:`sweep_headline` compares the lines with the
paper's numbers, trends and bounds (:data:`railhunt.paper2019.EXPECTED`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

import railhunt.paper2019 as paper2019
from railhunt.studies.records import (
    Context,
    Headline,
    Step,
    claim,
    compare,
    compare_within,
    not_judged,
)

__all__ = ["FIG10_LINES", "FIG11_LINES", "fig10_12", "sweep_headline"]

#: Yaw damper parameters (the paper's Fig. 10) and the others of Fig. 11, in figure order.
FIG10_LINES = ("C_d1", "C_d2", "K_d")
FIG11_LINES = ("mu", "f11", "K_px", "C_sy")


#: Why a coarse run does not judge a bound on a change over Table 1's range.
COARSE_BOUND = ("a coarse run (--quick): the change over a section is a total variation, "
                "which only grows with more points, so only a value already beyond the bound "
                "gives a verdict")
#: Why a coarse run does not judge where the frequency jumps.
COARSE_JUMP = ("a coarse run (--quick): the jump lies between {low:.4g} and {high:.4g} {unit}, "
               "partly inside the paper's tolerance")


def sweep_headline(results: Any, coarse: bool = False) -> list[Headline]:
    """Headline rows of Figs. 10–12 from the results of a one-parameter-at-a-time sweep.

    Parameters
    ----------
    results : railhunt.studies.store.SweepResults
        A ``design="lines"`` sweep over the paper's seven parameters (``C_d1``, ``C_d2``,
        ``K_d``, ``mu``, ``f11`` with ``f22`` tied, ``K_px``, ``C_sy``), with the outputs
        ``critical_speed`` and ``hunting_frequency``. Only ``.lines``, ``.line(name)`` and
        ``.column(name)`` are used.

    Returns
    -------
    list of Headline
        Rows for the lines present: V_cr at the largest C_d1 and K_px (km/h), f at the
        largest K_px (Hz), the C_d1 and C_d2 of the frequency jump (kN·s/m: midpoint of the
        first neighbours whose ``frequency_source`` differs), ΔV_cr over each line
        (total variation over the Table 1 sections, km/h), Δf over the K_px and C_sy
        lines with the jumps left out (Hz; both from
        :func:`railhunt.studies.sections.section_changes`), and the paper's trends of
        Figs. 10-11 judged on each line's first and last points.

        With ``coarse`` (the ``--quick`` run's few points per section) a row the
        resolution cannot judge says "not judged at this resolution" instead of a verdict:
        a bound "> x" that the coarse total variation does not reach yet, a bound "< x"
        that it meets so far, or a jump whose bracket reaches across the tolerance.
    """
    from railhunt.studies.lines import sweep_lines
    from railhunt.studies.sections import section_changes

    table = paper2019.TABLE1
    paper = paper2019.EXPECTED
    lines = sweep_lines(results)
    sections = section_changes(results)
    rows: list[Headline] = []

    def jump_at(name: str) -> tuple[float, float, float]:
        """Display values of the first neighbours whose frequency source differs, and their
        midpoint (NaN when the line has no jump)."""
        line = lines[name]
        jumps = line.jumps()
        if not jumps:
            return math.nan, math.nan, math.nan
        i = jumps[0]
        idx = np.flatnonzero(np.isfinite(line.frequency_hz))
        j = int(idx[np.searchsorted(idx, i) + 1])
        low, high = line.values[i] / table[name].scale, line.values[j] / table[name].scale
        return low, high, 0.5 * (low + high)

    def jump_row(key: str, name: str) -> Headline:
        low, high, mid = jump_at(name)
        if not coarse:
            return compare(paper[key], mid)
        why = COARSE_JUMP.format(low=low, high=high, unit=paper[key].unit)
        return compare_within(paper[key], mid, low, high, why)

    if "C_d1" in lines:
        c_d1 = lines["C_d1"]
        rows += [compare(paper["fig10a_vcr_large_cd1_kmh"], c_d1.critical_speed_kmh[-1]),
                 jump_row("fig10a_jump_cd1", "C_d1")]  # fmt: skip
    if "C_d2" in lines:
        rows.append(jump_row("fig10b_jump_cd2", "C_d2"))
    if "K_px" in lines:
        k_px = lines["K_px"]
        rows += [compare(paper["fig11c_vcr_large_kpx_kmh"], k_px.critical_speed_kmh[-1]),
                 compare(paper["fig11c_f_large_kpx_hz"], k_px.frequency_hz[-1])]  # fmt: skip
    for row in paper.values():
        if row.kind != "trend" or row.line not in lines:
            continue
        line = lines[row.line]
        y = line.critical_speed_kmh if row.output == "critical_speed" else line.frequency_hz
        ok = np.isfinite(y)
        if np.count_nonzero(ok) < 2:
            continue
        first, last = float(y[ok][0]), float(y[ok][-1])
        holds = last > first if row.paper == "rises" else last < first
        rows.append(claim(row, f"{first:.3g} → {last:.3g}", holds))
    for row in paper.values():
        if row.kind != "bound" or row.line not in lines:
            continue
        part = sections[row.line]
        value = (part.speed_change_kmh if row.output == "critical_speed" else
                 part.frequency_change_hz)  # fmt: skip
        side, bound = row.bound
        holds = value > bound if side == ">" else value < bound
        if coarse and holds == (side == "<"):  # could still change with more points
            rows.append(not_judged(row, value, COARSE_BOUND))
        else:
            rows.append(claim(row, value, holds))
    return rows


def _sweep_shows(results: Any) -> str:
    """One sentence per line of the study: V_cr and f at its ends, and where f jumps."""
    from railhunt.studies.lines import sweep_lines

    table = paper2019.TABLE1
    parts = []
    for name, line in sweep_lines(results).items():
        entry = table[name]
        ok = np.isfinite(line.critical_speed_kmh)
        v = line.critical_speed_kmh[ok]
        x = line.values / entry.scale
        text = (f"{entry.label}: V_cr {v[0]:.0f} → {v[-1]:.0f} km/h" if v.size else
                f"{entry.label}: no critical speed")  # fmt: skip
        f = line.frequency_hz[np.isfinite(line.frequency_hz)]
        if f.size:
            text += f", f {f[0]:.2f} → {f[-1]:.2f} Hz at {line.frequency_speed_kmh:g} km/h"
        jumps = line.jumps()
        if jumps:
            i = jumps[0]
            text += f" (jump after {x[i]:.3g} {entry.unit})"
        parts.append(text)
    return "; ".join(parts) + "."


def fig10_12(ctx: Context) -> Step:
    """Figs. 10-12: the Table 1 sweep, its lines (Figs. 10, 11) and sections (Fig. 12)."""
    from railhunt.plots import plot_sections, plot_sweep
    from railhunt.studies.sections import section_changes
    from railhunt.studies.sweep import sweep
    from railhunt.studies.table1_design import table1_study

    caption = " ".join(f"Fig. {n}: {paper2019.CAPTIONS[f'fig{n}']}" for n in (10, 11, 12))
    step = Step("fig10-12", "Figs. 10–12: parameter lines over Table 1 and their sections",
                caption)

    n = ctx.settings.sweep_points_per_section
    params, ties = table1_study(n, FIG10_LINES + FIG11_LINES)
    # Without a client reproduce runs in this one process, and so does the sweep.
    results = sweep(ctx.vehicle, params, ties=ties, out=ctx.out_dir / "sweep.csv",
                    overwrite=True, client=ctx.client,
                    workers=1 if ctx.client is None else None)  # fmt: skip
    step.figures += [plot_sweep(results, ctx.out_dir / "fig10.png", parameters=FIG10_LINES),
                     plot_sweep(results, ctx.out_dir / "fig11.png", parameters=FIG11_LINES),
                     plot_sections(section_changes(results), ctx.out_dir / "fig12.png")]
    step.headline = sweep_headline(results, coarse=ctx.settings.coarse)
    step.shows = _sweep_shows(results)
    step.how = (f"railhunt.sweep over Table 1 ({n} points per section, f22 tied to f11; "
                "frequency after an 8 mm release at 300 km/h for the yaw-damper lines and "
                "350 km/h otherwise), results in sweep.csv; ΔV_cr and Δf (jump removed) by "
                "railhunt.studies.sections.section_changes.")
    return step

