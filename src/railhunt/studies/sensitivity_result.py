"""The outcome of a sensitivity study: indices per output and factor, and their display."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from railhunt.results import Columns, ResultDisplay, Row
from railhunt.studies.store import SweepResults

#: Index columns of each method, in table order.
INDEX_KEYS = {"sobol": ("S1", "S1_conf", "ST", "ST_conf"),
              "morris": ("mu_star", "mu_star_conf", "sigma")}  # fmt: skip


@dataclass(repr=False)
class SensitivityResult(ResultDisplay):
    """Sensitivity indices of a study (:func:`railhunt.sensitivity`).

    Attributes
    ----------
    method : {"sobol", "morris"}
        How they were computed.
    outputs : list of str
        The outputs analysed.
    factors : list of str
        The factors, in sample order.
    indices : list of dict
        One per output and factor: ``output``, ``factor`` and ``S1``, ``S1_conf``, ``ST``,
        ``ST_conf`` (Sobol; the ``_conf`` are half-widths of the bootstrap intervals) or
        ``mu_star``, ``mu_star_conf``, ``sigma`` (Morris, in the output's unit).
    dropped : dict
        Output -> points left out (whole Saltelli blocks or Morris trajectories with a
        point without a value).
    capped : dict
        Output -> points whose unbracketed critical speed was capped at the search's edge.
    points : int
        Points of the sample.
    study : SweepResults
        The evaluated points (the results file's rows).
    notes : list of str
        What else the reader must know (an output without variance, points lost).
    """

    method: str
    outputs: list[str]
    factors: list[str]
    indices: list[dict[str, Any]]
    dropped: dict[str, int]
    capped: dict[str, int]
    points: int
    study: SweepResults = field(repr=False)
    notes: list[str] = field(default_factory=list)

    @property
    def keys(self) -> tuple[str, ...]:
        """The index names of the method."""
        return INDEX_KEYS[self.method]

    @property
    def path(self) -> Path | None:
        """The results file."""
        return self.study.path

    def index(self, output: str, factor: str, key: str) -> float:
        """One index, e.g. ``result.index("critical_speed_kmh", "C_d1", "ST")``."""
        for row in self.indices:
            if row["output"] == output and row["factor"] == factor:
                return float(row[key])
        raise KeyError(f"no indices for output {output!r} and factor {factor!r}")

    def ranking(self, output: str) -> list[str]:
        """Factors by decreasing total index (Sobol) or ``mu_star`` (Morris)."""
        key = "ST" if self.method == "sobol" else "mu_star"
        rows = [r for r in self.indices if r["output"] == output]
        rows.sort(key=lambda r: -r[key] if math.isfinite(r[key]) else math.inf)
        return [r["factor"] for r in rows]

    def _summary(self) -> list[Row]:
        rows: list[Row] = [("method", self.method, ""), ("factors", ", ".join(self.factors), ""),
                           ("points", self.points, "")]  # fmt: skip
        key = "ST" if self.method == "sobol" else "mu_star"
        for out in self.outputs:
            top = self.ranking(out)[:3]
            text = ", ".join(f"{f} {self.index(out, f, key):.2f}" for f in top)
            rows.append((f"{out}: largest {key}", text, ""))
            if self.dropped.get(out) or self.capped.get(out):
                rows.append((f"{out}: dropped / capped",
                             f"{self.dropped.get(out, 0)} / {self.capped.get(out, 0)}", ""))
        rows += [("note", n, "") for n in self.notes]
        if self.path is not None:
            rows.append(("file", str(self.path), ""))
        return rows

    def _columns(self) -> Columns:
        """One row per output and factor."""
        cols: Columns = {"output": ([r["output"] for r in self.indices], ""),
                         "factor": ([r["factor"] for r in self.indices], "")}  # fmt: skip
        for key in self.keys:
            cols[key] = ([r[key] for r in self.indices], "1" if self.method == "sobol" else "")
        return cols

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``indices`` (NaN as None), counts and notes."""
        def clean(v: Any) -> Any:
            return None if isinstance(v, float) and math.isnan(v) else v

        return {"method": self.method, "outputs": self.outputs, "factors": self.factors,
                "points": self.points,
                "indices": [{k: clean(v) for k, v in r.items()} for r in self.indices],
                "dropped": self.dropped, "capped": self.capped, "notes": self.notes,
                "computed": self.study.computed, "resumed": self.study.resumed,
                "lost": self.study.lost}  # fmt: skip

    def figure(self, path: str | None = None) -> Any:
        """Bars of the indices with their intervals (:func:`railhunt.plots.sensitivity`)."""
        from railhunt.plots.sensitivity import plot_sensitivity

        return plot_sensitivity(self, path)
