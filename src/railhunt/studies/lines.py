"""The one-parameter lines of a sweep's results, in ascending parameter value.

A one-parameter-at-a-time sweep (design ``"lines"``, see :func:`railhunt.sweep`) varies
each parameter alone; its results file holds one line per parameter. :func:`sweep_lines`
reads every line as a :class:`SweepLine` (values, critical speeds, frequencies, their
sources) for the paper's Figs. 10-11 (:func:`railhunt.plots.plot_sweep`) and the Table 1
sections of Fig. 12 (:func:`railhunt.studies.sections.section_changes`). Values are SI,
speeds km/h, frequencies Hz.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from railhunt.analysis.frequency import frequency_kind
from railhunt.studies.design import DESIGNS

__all__ = [
    "FREQUENCY_COLUMN",
    "FREQUENCY_SPEED_COLUMN",
    "MULTI_PARAMETER_DESIGNS",
    "SOURCE_COLUMN",
    "SPEED_COLUMN",
    "SweepLine",
    "result_rows",
    "sweep_line",
    "sweep_lines",
]

#: Values of the ``line`` column of designs that are not one-parameter lines.
MULTI_PARAMETER_DESIGNS = tuple(d for d in DESIGNS if d != "lines")
#: Results columns read here (see the results-file schema of :func:`railhunt.sweep`).
SPEED_COLUMN = "critical_speed_kmh"
FREQUENCY_COLUMN = "hunting_frequency_hz"
SOURCE_COLUMN = "frequency_source"
FREQUENCY_SPEED_COLUMN = "frequency_speed_kmh"


def result_rows(results: Any) -> list[dict[str, Any]]:
    """The rows of a results file as dicts (one per sweep point, sorted by point).

    Parameters
    ----------
    results : str, os.PathLike, SweepResults or sequence of dict
        A results file (CSV, or Parquet where the store supports it), an object with a
        ``rows`` attribute (:class:`railhunt.studies.store.SweepResults`), or the rows.

    Returns
    -------
    list of dict
        Column name to value: ``point`` int; ``line``, ``status``, ``frequency_source``,
        ``message`` str; every other column float (SI units, speeds km/h, Hz).
    """
    if isinstance(results, str | os.PathLike):
        rows = _read_results(Path(results))
    else:
        rows = [dict(row) for row in getattr(results, "rows", results)]
    return sorted(rows, key=lambda row: int(row.get("point", 0)))


def _read_results(path: Path) -> list[dict[str, Any]]:
    """Rows of a results file (:func:`railhunt.studies.store.read_results`)."""
    from railhunt.studies.store import read_results

    return [dict(row) for row in read_results(path).rows]


@dataclass(frozen=True)
class SweepLine:
    """The points of one one-parameter line of a sweep, in ascending parameter value.

    Attributes
    ----------
    parameter : str
        The swept parameter.
    values : numpy.ndarray
        Its values (SI units), ascending.
    critical_speed_kmh : numpy.ndarray
        Nonlinear critical speed (km/h); NaN where not found or not computed.
    frequency_hz : numpy.ndarray
        Hunting frequency (Hz); NaN where not found or not computed.
    frequency_source : tuple of str
        ``"eigenvalue"``, ``"limit-cycle"`` or ``"limit-exceeded"`` per point ("" if none):
        the kind of the file's source (:func:`railhunt.analysis.frequency.frequency_kind`;
        both estimates of a limit cycle's frequency are ``"limit-cycle"``).
    status : tuple of str
        Each point's status (``"ok"``, ``"no-critical-speed"``, ``"failed"``).
    points : tuple of int
        Each point's index in the sweep.
    frequency_speed_kmh : float
        Speed at which the frequencies were computed (km/h); NaN if not in the file.
    columns : frozenset of str
        The output columns present in the results.
    """

    parameter: str
    values: np.ndarray
    critical_speed_kmh: np.ndarray
    frequency_hz: np.ndarray
    frequency_source: tuple[str, ...]
    status: tuple[str, ...]
    points: tuple[int, ...]
    frequency_speed_kmh: float
    columns: frozenset[str]

    def jumps(self) -> list[int]:
        """Indices ``i`` where points ``i`` and ``i + 1`` (with frequencies) change source.

        NaN frequencies are skipped, so ``i + 1`` is the next point with a frequency.
        """
        idx = np.flatnonzero(np.isfinite(self.frequency_hz))
        return [
            int(a)
            for a, b in zip(idx, idx[1:], strict=False)
            if self.frequency_source[a] != self.frequency_source[b]
        ]


def sweep_lines(results: Any) -> dict[str, SweepLine]:
    """Every one-parameter line of a sweep's results.

    Parameters
    ----------
    results : str, os.PathLike, SweepResults or sequence of dict
        See :func:`result_rows`.

    Returns
    -------
    dict
        Line name (the swept parameter) to :class:`SweepLine`, in order of first appearance.

    Raises
    ------
    ValueError
        The results are empty, or hold a grid / random / Latin-hypercube design (not
        one-parameter lines), or a line's parameter has no column.
    """
    rows = result_rows(results)
    if not rows:
        raise ValueError("the results hold no points")
    names = list(dict.fromkeys(str(row.get("line", "")) for row in rows))
    designs = [n for n in names if n in MULTI_PARAMETER_DESIGNS]
    if designs:
        raise ValueError(
            f"the results hold a {designs[0]!r} design (several parameters varied at once); "
            "sections and Figs. 10/11 need one-parameter-at-a-time lines (design 'lines')"
        )
    columns = frozenset().union(*(row.keys() for row in rows))
    out = {}
    for name in names:
        if name not in columns:
            raise ValueError(f"line {name!r} has no column of parameter values")
        out[name] = _make_line(name, [row for row in rows if row.get("line") == name], columns)
    return out


def sweep_line(results: Any, name: str) -> SweepLine:
    """One one-parameter line of a sweep's results (see :func:`sweep_lines`)."""
    lines = sweep_lines(results)
    if name not in lines:
        raise ValueError(f"no line {name!r} in the results (lines: {', '.join(lines)})")
    return lines[name]


def _make_line(name: str, rows: list[dict[str, Any]], columns: frozenset[str]) -> SweepLine:
    def floats(key: str) -> np.ndarray:
        return np.array([_as_float(row.get(key)) for row in rows], dtype=float)

    values = floats(name)
    order = np.argsort(values, kind="stable")
    rows = [rows[i] for i in order]
    speeds = {_as_float(row.get(FREQUENCY_SPEED_COLUMN)) for row in rows}
    speeds = {s for s in speeds if math.isfinite(s)}
    return SweepLine(
        parameter=name,
        values=values[order],
        critical_speed_kmh=floats(SPEED_COLUMN),
        frequency_hz=floats(FREQUENCY_COLUMN),
        frequency_source=tuple(frequency_kind(str(row.get(SOURCE_COLUMN) or ""))
                               for row in rows),  # fmt: skip
        status=tuple(str(row.get("status") or "") for row in rows),
        points=tuple(int(row.get("point", k)) for k, row in enumerate(rows)),
        frequency_speed_kmh=speeds.pop() if len(speeds) == 1 else math.nan,
        columns=columns,
    )


def _as_float(value: Any) -> float:
    if value is None or value == "":
        return math.nan
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan

