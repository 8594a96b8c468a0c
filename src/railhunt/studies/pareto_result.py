"""The outcome of an optimisation: the Pareto front, every design, the hypervolume."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from railhunt.results import Columns, ResultDisplay, Row


def non_dominated(f: np.ndarray, feasible: np.ndarray) -> np.ndarray:
    """Indices of the feasible rows of ``f`` (minimised objectives) that no other feasible
    row dominates, in row order; duplicates of a front design are kept once (the first)."""
    idx = np.flatnonzero(feasible)
    if idx.size == 0:
        return np.array([], dtype=int)
    fo = f[idx]
    dominated = np.zeros(idx.size, dtype=bool)
    block = 256
    for start in range(0, idx.size, block):
        mine = fo[start:start + block, None, :]  # (b, 1, k) against every row (1, m, k)
        no_worse = np.all(fo[None, :, :] <= mine, axis=2)
        better = np.any(fo[None, :, :] < mine, axis=2)
        dominated[start:start + block] = np.any(no_worse & better, axis=1)
    kept = idx[~dominated]
    _, first = np.unique(f[kept], axis=0, return_index=True)
    return kept[np.sort(first)]


def fronts(f: np.ndarray, feasible: np.ndarray, generation: np.ndarray,
           generations: int) -> list[np.ndarray]:  # fmt: skip
    """The front after each generation (:func:`non_dominated` of every feasible design up
    to it), computed incrementally: the non-dominated set of the previous front and that
    generation's designs is the same set, in the same row order."""
    out = []
    front_idx = np.array([], dtype=int)
    for gen in range(generations):
        mask = np.zeros(len(f), dtype=bool)
        mask[front_idx] = True
        mask |= feasible & (generation == gen)
        front_idx = non_dominated(f, mask)
        out.append(front_idx)
    return out


def hypervolumes(f: np.ndarray, feasible: np.ndarray, generation: np.ndarray,
                 generations: int,
                 by_generation: list[np.ndarray] | None = None) -> list[float]:  # fmt: skip
    """Hypervolume of the front after each generation (pymoo's HV).

    Objectives are normalised by the range of the feasible designs of the whole run, and
    the reference point is 1.1 in each (10 % beyond the worst feasible value), so the
    numbers of one run compare with each other: 0 with no feasible design yet.
    ``by_generation``: the fronts of :func:`fronts`, if already computed.
    """
    from pymoo.indicators.hv import HV

    if not np.any(feasible):
        return [0.0] * generations
    fo = f[feasible]
    lo, hi = fo.min(axis=0), fo.max(axis=0)
    span = np.where(hi > lo, hi - lo, 1.0)
    indicator = HV(ref_point=np.full(f.shape[1], 1.1))
    if by_generation is None:
        by_generation = fronts(f, feasible, generation, generations)
    return [float(indicator((f[idx] - lo) / span)) if idx.size else 0.0
            for idx in by_generation]


@dataclass(repr=False)
class ParetoResult(ResultDisplay):
    """Pareto front of an optimisation (:func:`railhunt.optimize`).

    Attributes
    ----------
    factors : list of str
        The factors.
    objective_columns : list of str
        The objectives' columns.
    senses : list of str
        ``"max"`` or ``"min"`` per objective.
    constraints : list of str
        The constraints, as given.
    front : pandas.DataFrame
        The non-dominated feasible designs: ``point``, ``generation``, the parameter
        columns (SI), the objective and constraint columns, ``feasible``, ``status``.
    evaluated : pandas.DataFrame
        Every design evaluated, with the same columns.
    hypervolume : list of float
        Hypervolume of the front after each generation (normalised objectives,
        :func:`hypervolumes`).
    start : dict, optional
        The starting vehicle's parameters and objectives (vehicle models only).
    meta : dict
        The study description (the results file's sidecar).
    path : Path, optional
        The results file.
    timings : dict
        Where the run's wall time went (s): ``pymoo_s`` (NSGA-II asking for and told the
        designs), ``evaluations_s`` (the points evaluated in this process),
        ``railhunt_s`` (the rest: the study machinery, and the wait for workers),
        ``study_s`` (the whole run) and ``worker_evaluations_s`` (the time forked local
        workers spent evaluating, summed over them; 0 on a Dask cluster, which is not
        timed).
    """

    factors: list[str]
    objective_columns: list[str]
    senses: list[str]
    constraints: list[str]
    front: Any
    evaluated: Any
    hypervolume: list[float]
    start: dict[str, float] | None = None
    meta: dict[str, Any] = field(default_factory=dict, repr=False)
    path: Path | None = None
    timings: dict[str, float] = field(default_factory=dict, repr=False)

    def _summary(self) -> list[Row]:
        rows: list[Row] = [("factors", ", ".join(self.factors), ""),
                           ("objectives", ", ".join(f"{s} {c}" for s, c in
                                                    zip(self.senses, self.objective_columns,
                                                        strict=True)), ""),
                           ("constraints", ", ".join(self.constraints) or "-", ""),
                           ("designs evaluated", len(self.evaluated), ""),
                           ("feasible", int(self.evaluated["feasible"].sum()), ""),
                           ("on the front", len(self.front), "")]  # fmt: skip
        for c in self.objective_columns:
            if len(self.front):
                rows.append((f"front {c}", f"{self.front[c].min():.4g} to "
                             f"{self.front[c].max():.4g}", ""))  # fmt: skip
        if self.hypervolume:
            rows.append(("hypervolume, last generation", self.hypervolume[-1], ""))
        if self.path is not None:
            rows.append(("file", str(self.path), ""))
        return rows

    def _columns(self) -> Columns:
        """The front, one row per design."""
        return {c: (self.front[c].tolist(), "") for c in self.front.columns}

    def to_dataframe(self) -> Any:
        """The front (a copy)."""
        return self.front.copy()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the front's designs, the hypervolume by generation, the start."""
        def clean(v: Any) -> Any:
            if isinstance(v, (np.floating, float)):
                return None if math.isnan(float(v)) else float(v)
            if isinstance(v, (np.integer,)):
                return int(v)
            if isinstance(v, np.bool_):
                return bool(v)
            return v

        return {"factors": self.factors,
                "objectives": [f"{s} {c}" for s, c in zip(self.senses, self.objective_columns,
                                                          strict=True)],
                "constraints": self.constraints,
                "front": [{k: clean(v) for k, v in r.items()}
                          for r in self.front.to_dict(orient="records")],
                "evaluated": len(self.evaluated),
                "hypervolume": self.hypervolume,
                "start": None if self.start is None else
                {k: clean(v) for k, v in self.start.items()}}  # fmt: skip

    def figure(self, path: str | None = None) -> Any:
        """The front with the starting vehicle marked
        (:func:`railhunt.plots.sensitivity.plot_pareto`)."""
        from railhunt.plots.sensitivity import plot_pareto

        return plot_pareto(self, path)
