"""The change of V_cr and f per Table 1 section of each parameter (the paper's Fig. 12).

Table 1 of the paper divides the range of each of seven parameters (C_d1, K_d, C_d2, mu,
K_px, f11 = f22, C_sy) into three sections; Fig. 12 compares, per parameter and per
section, the change of the nonlinear critical speed (ΔV_cr) and of the hunting frequency
(Δf) over the section. :func:`section_changes` computes ΔV_cr and Δf from the
one-parameter lines of a results file (see :func:`railhunt.sweep`).

The study is split by theme; this module re-exports the names of the other two, so that
``railhunt.studies.sections`` keeps offering all of them:

- the table is the paper's: :func:`load_table1`, :class:`Table1Parameter`
  (:mod:`railhunt.paper2019.table1`, shipped as ``railhunt/paper2019/table1.toml``);
- the study's sweep values: :func:`table1_values`, :func:`table1_study`
  (:mod:`railhunt.studies.table1_design`);
- the lines of a results file: :func:`result_rows`, :func:`sweep_lines`,
  :func:`sweep_line`, :class:`SweepLine` (:mod:`railhunt.studies.lines`).

Definitions (the paper only says "the change within the range"):

- **ΔV_cr of a section** is the total variation of V_cr over the section: the sum of
  ``|ΔV_cr|`` between consecutive points of the line, the section's ends included. For a
  monotone curve it equals ``|V_cr(end) - V_cr(start)|``; for a curve that rises and falls
  (K_d, Fig. 10c) it counts both. Where a section boundary falls between two points, V_cr
  is interpolated linearly there, so the three sections add up exactly to the total.
- **Δf of a section** is the same for the hunting frequency, with the frequency jump
  removed as the paper does: an increment between neighbouring points whose
  ``frequency_source`` differs (eigenvalue on one side, limit cycle on the other) is the
  jump and is not counted.
- Points without a number (NaN: no critical speed bracketed, a failed run, a run that left
  the track) are skipped, joining their neighbours, and listed in the result's notes.

Values are SI inside (N*s/m, N/m, N, -); display units (kN*s/m, MN/m, MN) only in
:attr:`Table1Parameter.unit` and the reports.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from railhunt.paper2019.table1 import Table1Parameter, load_table1
from railhunt.studies.lines import (
    FREQUENCY_COLUMN,
    MULTI_PARAMETER_DESIGNS,
    SOURCE_COLUMN,
    SPEED_COLUMN,
    SweepLine,
    result_rows,
    sweep_line,
    sweep_lines,
)
from railhunt.studies.lines import FREQUENCY_SPEED_COLUMN as FREQUENCY_SPEED_COLUMN
from railhunt.studies.table1_design import table1_study, table1_values

__all__ = [
    "MULTI_PARAMETER_DESIGNS",
    "ParameterSections",
    "SectionChange",
    "SectionTable",
    "SweepLine",
    "Table1Parameter",
    "load_table1",
    "result_rows",
    "section_changes",
    "sweep_line",
    "sweep_lines",
    "table1_study",
    "table1_values",
]

#: Relative tolerance for "a point lies on a section boundary / covers the section".
_REL_TOL = 1e-9

DEFINITION = (
    "ΔV_cr of a section: total variation of the nonlinear critical speed over the section "
    "(sum of |ΔV_cr| between consecutive points, section ends included, linear between "
    "points; |V_cr(end) - V_cr(start)| for a monotone curve). Δf: the same for the hunting "
    "frequency, an increment between neighbours whose frequency source differs (the jump) "
    "removed. Points without a number are skipped."
)


# --------------------------------------------------------------------------- sections


@dataclass(frozen=True)
class SectionChange:
    """ΔV_cr and Δf over one section of one parameter.

    Attributes
    ----------
    section : int
        1, 2 or 3.
    lower, upper : float
        The section's ends (SI units).
    speed_change_kmh : float
        ΔV_cr (km/h): total variation of the nonlinear critical speed over the section;
        NaN where the line has no two points with a critical speed there.
    frequency_change_hz : float
        Δf (Hz): total variation of the hunting frequency, the jump removed; NaN likewise.
    speed_share, frequency_share : float
        This section's part of the parameter's total (0 to 1); NaN when the total is 0 or
        unknown.
    points : int
        Points of the line within the section (ends included).
    coverage : float
        Part of the section spanned by the line's points with a critical speed (0 to 1);
        below 1 the line starts or ends inside it.
    jumps_removed : int
        Frequency jumps (source changes between neighbours) left out of Δf here.
    speed_net_change_kmh : float
        ``|V_cr(upper) - V_cr(lower)|`` (km/h, ends interpolated, over the covered part):
        equal to ΔV_cr where V_cr is monotone over the section. Where it is much smaller,
        V_cr rises and falls there, or the search's resolution (1 km/h by default) adds
        wiggles to a flat stretch.
    """

    section: int
    lower: float
    upper: float
    speed_change_kmh: float
    frequency_change_hz: float
    speed_share: float
    frequency_share: float
    points: int
    coverage: float
    jumps_removed: int
    speed_net_change_kmh: float = math.nan

    def to_dict(self, scale: float = 1.0) -> dict[str, Any]:
        """JSON-ready numbers (NaN as None); ``scale`` gives the ends in display units too."""
        data = {
            "section": self.section,
            "lower_si": self.lower,
            "upper_si": self.upper,
            "lower": float(f"{self.lower / scale:.12g}"),
            "upper": float(f"{self.upper / scale:.12g}"),
            "speed_change_kmh": self.speed_change_kmh,
            "speed_share": self.speed_share,
            "speed_net_change_kmh": self.speed_net_change_kmh,
            "frequency_change_hz": self.frequency_change_hz,
            "frequency_share": self.frequency_share,
            "points": self.points,
            "coverage": self.coverage,
            "jumps_removed": self.jumps_removed,
        }
        return {k: _nan_to_none(v) for k, v in data.items()}


@dataclass(frozen=True)
class ParameterSections:
    """ΔV_cr and Δf of one parameter, per Table 1 section and in total.

    Attributes
    ----------
    parameter : str
        The parameter (a Table 1 name).
    unit : str
        Its display unit.
    scale : float
        SI size of one display unit.
    figure : str
        The paper's panel (``"10a"`` ...).
    frequency_speed_kmh : float
        Speed of the frequencies in the results (km/h; Table 1's when not in the file).
    sections : tuple of SectionChange
        Sections 1, 2, 3.
    speed_change_kmh : float
        Total ΔV_cr over Table 1's range (km/h): the sum of the sections (of those the
        line reaches; NaN when it reaches none).
    frequency_change_hz : float
        Total Δf over the range, jumps removed (Hz): the sum of the sections likewise.
    skipped : tuple of float
        Parameter values (SI) of the points skipped for want of a number.
    notes : tuple of str
        Skipped points, partial coverage, points outside the range, and the like.
    """

    parameter: str
    unit: str
    scale: float
    figure: str
    frequency_speed_kmh: float
    sections: tuple[SectionChange, ...]
    speed_change_kmh: float
    frequency_change_hz: float
    skipped: tuple[float, ...]
    notes: tuple[str, ...]

    @property
    def complete(self) -> bool:
        """Every section fully covered and no point skipped."""
        return not self.skipped and all(s.coverage >= 1 - _REL_TOL for s in self.sections)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready numbers (NaN as None)."""
        return {
            "parameter": self.parameter,
            "unit": self.unit,
            "scale": self.scale,
            "figure": self.figure,
            "frequency_speed_kmh": _nan_to_none(self.frequency_speed_kmh),
            "speed_change_kmh": _nan_to_none(self.speed_change_kmh),
            "frequency_change_hz": _nan_to_none(self.frequency_change_hz),
            "complete": self.complete,
            "skipped_si": list(self.skipped),
            "notes": list(self.notes),
            "sections": [s.to_dict(self.scale) for s in self.sections],
        }


@dataclass(frozen=True)
class SectionTable:
    """ΔV_cr and Δf per parameter and section (the paper's Fig. 12); see the module doc.

    Iterating gives the :class:`ParameterSections` in Table 1's order; ``table["C_d1"]``
    picks one.
    """

    parameters: tuple[ParameterSections, ...]
    notes: tuple[str, ...] = ()

    def __iter__(self) -> Iterator[ParameterSections]:
        return iter(self.parameters)

    def __len__(self) -> int:
        return len(self.parameters)

    def __getitem__(self, name: str) -> ParameterSections:
        for entry in self.parameters:
            if entry.parameter == name:
                return entry
        raise KeyError(f"{name!r} is not in this table (parameters: {', '.join(self.names)})")

    @property
    def names(self) -> list[str]:
        """The parameters, in Table 1's order."""
        return [entry.parameter for entry in self.parameters]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the definition, the notes and every parameter's numbers (NaN as None)."""
        return {
            "definition": DEFINITION,
            "notes": list(self.notes),
            "parameters": [entry.to_dict() for entry in self.parameters],
        }


def _nan_to_none(value: Any) -> Any:
    if isinstance(value, float) and math.isnan(value):
        return None
    return value


def _variation(
    x: np.ndarray,
    y: np.ndarray,
    lower: float,
    upper: float,
    source: Sequence[str] | None = None,
) -> tuple[float, int, float]:
    """Total variation of the piecewise-linear ``y(x)`` over ``[lower, upper]``.

    ``x`` ascending and ``y`` finite. Segments whose ends differ in ``source`` are jumps
    and left out. Returns the variation, the number of jumps left out and the length of
    ``[lower, upper]`` spanned by the points (0 when fewer than two). A jump segment that
    straddles a boundary is counted in the section holding its midpoint (half-open
    ``[lower, upper)``), so that each jump is counted once.
    """
    total, jumps = 0.0, 0
    for i in range(x.size - 1):
        a, b = float(x[i]), float(x[i + 1])
        left, right = max(a, lower), min(b, upper)
        if b <= a or right <= left:
            continue
        if source is not None and source[i] != source[i + 1]:
            mid = 0.5 * (a + b)
            jumps += int(lower <= mid < upper or (mid == upper == float(x[-1])))
            continue
        part = 1.0 if (left, right) == (a, b) else (right - left) / (b - a)
        total += abs(float(y[i + 1]) - float(y[i])) * part
    span = 0.0
    if x.size >= 2:
        span = max(0.0, min(upper, float(x[-1])) - max(lower, float(x[0])))
    return total, jumps, span


def _net_change(x: np.ndarray, y: np.ndarray, lower: float, upper: float) -> float:
    """``|y(b) - y(a)|`` over the part ``[a, b]`` of ``[lower, upper]`` the points span."""
    if x.size < 2:
        return math.nan
    a, b = max(lower, float(x[0])), min(upper, float(x[-1]))
    if b <= a:
        return math.nan
    return abs(float(np.interp(b, x, y)) - float(np.interp(a, x, y)))


def _sum_known(parts: Iterator[float]) -> float:
    """Sum of the numbers that are not NaN (NaN when none is)."""
    known = [p for p in parts if not math.isnan(p)]
    return math.fsum(known) if known else math.nan


def _share(part: float, total: float) -> float:
    if not (math.isfinite(part) and math.isfinite(total)) or total <= 0.0:
        return math.nan
    return part / total


def _parameter_sections(line: SweepLine, entry: Table1Parameter) -> ParameterSections:
    x = line.values
    notes: list[str] = []

    def shown(values: Sequence[float]) -> str:
        return ", ".join(f"{v / entry.scale:g}" for v in values) + (
            "" if entry.unit == "-" else f" {entry.unit}"
        )

    has_speed = SPEED_COLUMN in line.columns
    has_freq = FREQUENCY_COLUMN in line.columns and SOURCE_COLUMN in line.columns
    if not has_speed:
        notes.append(f"no {SPEED_COLUMN} column: ΔV_cr unknown")
    if not has_freq:
        notes.append(f"no {FREQUENCY_COLUMN}/{SOURCE_COLUMN} columns: Δf unknown")
    ok_v = np.isfinite(line.critical_speed_kmh) & np.isfinite(x)
    ok_f = np.isfinite(line.frequency_hz) & np.isfinite(x)
    usable = np.isfinite(x)
    if has_speed:
        usable &= ok_v
    if has_freq:
        usable &= ok_f
    skipped = [float(v) for v in x[~usable & np.isfinite(x)]]
    for label, ok, present in (("critical speed", ok_v, has_speed),
                               ("hunting frequency", ok_f, has_freq)):  # fmt: skip
        bad = np.flatnonzero(~ok & np.isfinite(x))
        if present and bad.size:
            why = sorted({line.status[i] or "?" for i in bad})
            notes.append(
                f"skipped {bad.size} point(s) without a {label} at {entry.name} = "
                f"{shown(x[bad])} (status: {', '.join(why)})"
            )
    lo, hi = entry.boundaries[0], entry.boundaries[-1]
    tol = _REL_TOL * (hi - lo)
    outside = x[np.isfinite(x) & ((x < lo - tol) | (x > hi + tol))]
    if outside.size:
        notes.append(f"{outside.size} point(s) outside Table 1's range ignored: {shown(outside)}")

    xv, yv = x[ok_v], line.critical_speed_kmh[ok_v]
    xf, yf = x[ok_f], line.frequency_hz[ok_f]
    sf = [s for s, keep in zip(line.frequency_source, ok_f, strict=True) if keep]
    for i in range(xf.size - 1):
        if has_freq and sf[i] != sf[i + 1]:
            notes.append(
                f"frequency jump ({sf[i]} {yf[i]:.3g} Hz -> {sf[i + 1]} {yf[i + 1]:.3g} Hz) "
                f"between {shown((xf[i],))} and {shown((xf[i + 1],))} left out of Δf"
            )
    raw = []
    for k, (lower, upper) in enumerate(entry.sections, 1):
        dv, _, span_v = _variation(xv, yv, lower, upper)
        df, jumps, span_f = _variation(xf, yf, lower, upper, sf)
        length = upper - lower
        dv = dv if has_speed and span_v > 0 else math.nan
        df = df if has_freq and span_f > 0 else math.nan
        coverage = (span_v if has_speed else span_f) / length
        if coverage < 1 - _REL_TOL:
            what = "not covered" if coverage <= 0 else f"{100 * coverage:.0f} % covered"
            notes.append(f"section {k} ({shown((lower, upper))}): {what} by the line")
        inside = int(np.count_nonzero((x >= lower - tol) & (x <= upper + tol)))
        net = _net_change(xv, yv, lower, upper) if has_speed else math.nan
        raw.append((k, lower, upper, dv, df, inside, min(coverage, 1.0), jumps, net))
    total_v = _sum_known(r[3] for r in raw)
    total_f = _sum_known(r[4] for r in raw)
    sections = tuple(
        SectionChange(k, lower, upper, dv, df, _share(dv, total_v), _share(df, total_f),
                      inside, coverage, jumps, net)  # fmt: skip
        for k, lower, upper, dv, df, inside, coverage, jumps, net in raw
    )
    speed = line.frequency_speed_kmh
    if math.isfinite(speed) and not math.isclose(speed, entry.frequency_speed_kmh):
        notes.append(
            f"frequencies at {speed:g} km/h; the paper's Fig. {entry.figure} uses "
            f"{entry.frequency_speed_kmh:g} km/h"
        )
    return ParameterSections(
        parameter=entry.name,
        unit=entry.unit,
        scale=entry.scale,
        figure=entry.figure,
        frequency_speed_kmh=speed if math.isfinite(speed) else entry.frequency_speed_kmh,
        sections=sections,
        speed_change_kmh=total_v,
        frequency_change_hz=total_f,
        skipped=tuple(skipped),
        notes=tuple(notes),
    )


def section_changes(
    results: Any, table: Mapping[str, Table1Parameter] | None = None
) -> SectionTable:
    """ΔV_cr and Δf per parameter and per Table 1 section (the paper's Fig. 12).

    Parameters
    ----------
    results : str, os.PathLike, SweepResults or sequence of dict
        Results of a one-parameter-at-a-time sweep (design ``"lines"``): a file, a
        :class:`~railhunt.studies.store.SweepResults` or its rows (see
        :func:`result_rows`). Each line named after a Table 1 parameter is analysed over
        that parameter's sections; other lines are listed in the notes.
    table : Mapping[str, Table1Parameter], optional
        The sections (default: the paper's Table 1, :func:`load_table1`).

    Returns
    -------
    SectionTable
        Per parameter (Table 1's order) and section: ΔV_cr (km/h), Δf (Hz), their shares
        of the parameter's totals and how well the line covers the section. ΔV_cr is the
        total variation of V_cr over the section (``|V_cr(end) - V_cr(start)|`` for a
        monotone curve); Δf the same with the frequency jump removed; see the module doc.

    Raises
    ------
    ValueError
        No line of the results is a Table 1 parameter, or the results are not lines.
    """
    table = load_table1() if table is None else table
    lines = sweep_lines(results)
    known = [name for name in table if name in lines]
    if not known:
        raise ValueError(
            f"no line of the results is a Table 1 parameter (lines: {', '.join(lines)}; "
            f"Table 1: {', '.join(table)})"
        )
    notes = []
    others = [name for name in lines if name not in table]
    if others:
        notes.append(f"line(s) not in Table 1, not analysed: {', '.join(others)}")
    return SectionTable(
        parameters=tuple(_parameter_sections(lines[name], table[name]) for name in known),
        notes=tuple(notes),
    )
