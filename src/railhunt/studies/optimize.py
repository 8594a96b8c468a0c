"""The best compromise: a Pareto front of objectives by NSGA-II, on the study machinery.

:func:`optimize` runs pymoo's NSGA-II through its ask/tell interface: each generation's
designs are asked for, evaluated as one batch of points on one
:class:`railhunt.studies.runner.StudyRun` for the whole run (one results file, one cluster
or this process; the points grouped into tasks by their measured cost, each task's rows
written as it finishes) and told back. The algorithm's random generator is seeded,
and its decisions depend only on the objectives it is told, so a run resumed with the same
seed asks for the same designs: the points already in the file are read back (exactly:
floats are written with ``repr``) instead of computed, and the run reaches the same front.

Objectives are ``"max COLUMN"`` or ``"min COLUMN"``; constraints ``"COLUMN >= VALUE"`` or
``"COLUMN <= VALUE"``. A design that has no value for an objective or constraint (a failed
run; an unbracketed critical speed is capped as in :mod:`railhunt.studies.sensitivity`) is
infeasible: it violates every constraint by :data:`MISSING_VIOLATION`.
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from railhunt.studies.design import Point, parse_ties, tied_values
from railhunt.studies.evaluation import Evaluation
from railhunt.studies.execute import CONNECT_TIMEOUT
from railhunt.studies.factors import check_model, parse_factors
from railhunt.studies.options import StudyOptions, resolve_run
from railhunt.studies.outputs import OutputOptions, options_from
from railhunt.studies.pareto_result import ParetoResult, fronts, hypervolumes, non_dominated
from railhunt.studies.runner import StudyRun
from railhunt.studies.sensitivity import capped_value
from railhunt.vehicle import Vehicle

__all__ = ["ParetoResult", "optimize", "parse_constraint", "parse_objective"]

#: Constraint violation of a design without a value (and its objectives' stand-in).
MISSING_VIOLATION = 1e15

_CONSTRAINT = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*(>=|<=)\s*(\S+)\s*$")


def parse_objective(text: str) -> tuple[str, str]:
    """``"max critical_speed_kmh"`` -> ``("max", "critical_speed_kmh")``."""
    parts = str(text).split()
    if len(parts) != 2 or parts[0] not in ("max", "min"):
        raise ValueError(f"objective {text!r} is invalid: write 'max COLUMN' or 'min COLUMN', "
                         "e.g. 'max critical_speed_kmh'")  # fmt: skip
    return parts[0], parts[1]


def parse_constraint(text: str) -> tuple[str, str, float]:
    """``"linear_critical_speed_kmh >= 385"`` -> ``("linear_critical_speed_kmh", ">=", 385.0)``."""
    m = _CONSTRAINT.match(str(text))
    value = None
    if m:
        try:
            value = float(m.group(3))
        except ValueError:
            value = None
    if value is None or not math.isfinite(value):
        raise ValueError(f"constraint {text!r} is invalid: write 'COLUMN >= VALUE' or "
                         "'COLUMN <= VALUE', e.g. 'linear_critical_speed_kmh >= 385'")  # fmt: skip
    return m.group(1), m.group(2), value  # type: ignore[union-attr]


def _pymoo() -> tuple[Any, ...]:
    from railhunt.results import optional_import

    optional_import("pymoo", "studies", "railhunt.optimize()")
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.evaluator import Evaluator
    from pymoo.core.problem import Problem
    from pymoo.problems.static import StaticProblem

    return NSGA2, Evaluator, Problem, StaticProblem


def _value(row: Mapping[str, Any] | None, column: str) -> float:
    if row is None:
        return math.nan
    value = float(row.get(column, math.nan))
    if math.isnan(value):
        cap = capped_value(column, row)
        return math.nan if cap is None else cap
    return value


def objectives_of(row: Mapping[str, Any] | None, objectives: Sequence[tuple[str, str]],
                  constraints: Sequence[tuple[str, str, float]],
                  ) -> tuple[np.ndarray, np.ndarray, bool]:  # fmt: skip
    """Minimisation form of a row: ``F`` (max negated), ``G`` (<= 0 feasible), has values."""
    f = np.empty(len(objectives))
    g = np.empty(len(constraints))
    ok = True
    for k, (sense, col) in enumerate(objectives):
        v = _value(row, col)
        ok &= math.isfinite(v)
        f[k] = MISSING_VIOLATION if not math.isfinite(v) else (-v if sense == "max" else v)
    for k, (col, op, bound) in enumerate(constraints):
        v = _value(row, col)
        ok &= math.isfinite(v)
        g[k] = MISSING_VIOLATION if not math.isfinite(v) else (bound - v if op == ">=" else
                                                              v - bound)  # fmt: skip
    return f, g, ok


def optimize(
    model: Vehicle | Callable[..., Mapping[str, Any]],
    factors: Mapping[str, object],
    objectives: Sequence[str] = ("max critical_speed_kmh", "min wear_number"),
    constraints: Sequence[str] = (),
    *,
    population: int = 20,
    generations: int = 10,
    seed: int = 0,
    ties: Mapping[str, object] | None = None,
    out: str | Path | None = None,
    resume: bool = False,
    overwrite: bool = False,
    client: Any = None,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: bool | Callable[[int, int], None] = False,
    connect_timeout: float = CONNECT_TIMEOUT,
    output_options: OutputOptions | Mapping[str, Any] | None = None,
    excitation: object = None,
    creep_law: str | None = None,
    wait_for_workers: bool | float = False,
    run: StudyOptions | None = None,
) -> ParetoResult:
    """Pareto front of ``objectives`` over the ``factors`` by NSGA-II (pymoo).

    Every generation's designs are evaluated as one batch on one results file and one
    cluster (or in this process) for the whole run. The result's ``timings`` (and the
    ``timings`` of the results file's description) give the time spent in pymoo (asking
    for and being told a generation's designs), in the evaluations (in this process) and
    in railhunt's machinery around them, in s.

    Parameters
    ----------
    model : Vehicle or callable
        A vehicle (factors are its parameters; the starting vehicle is evaluated too and
        marked in the figure), or a function of the factors returning a dict.
    factors : Mapping
        Name -> ``(low, high)``, ``("uniform", low, high)`` or ``("tolerance", t)`` (SI).
    objectives : sequence of str
        ``"max COLUMN"`` / ``"min COLUMN"``: results columns (see
        :func:`railhunt.sensitivity`) or the function's keys. At least two.
    constraints : sequence of str
        ``"COLUMN >= VALUE"`` / ``"COLUMN <= VALUE"``.
    population, generations : int
        NSGA-II's population size and number of generations (the first is the random
        initial population).
    seed : int
        Seed of NSGA-II's generator: the same seed gives the same designs and front.
    ties, out, resume, overwrite, client, scheduler, workers, progress, connect_timeout
        As in :func:`railhunt.sensitivity`.
    output_options, excitation, creep_law, wait_for_workers : optional
        As in :func:`railhunt.sensitivity`.
    run : StudyOptions, optional
        How the study runs, in one object (:class:`railhunt.StudyOptions`), instead of
        ``out`` ... ``wait_for_workers`` (giving both is an error naming the keyword).

    Returns
    -------
    ParetoResult
    """
    check_model(model)
    objs = [parse_objective(o) for o in objectives]
    cons = [parse_constraint(c) for c in constraints]
    if len(objs) < 2:
        raise ValueError(f"objectives = {list(objectives)!r}: give at least two (a front of "
                         "one objective is a single point)")  # fmt: skip
    seen: dict[str, str] = {}
    for text, (_, column) in zip(objectives, objs, strict=True):
        if column in seen:
            raise ValueError(f"objective {text!r} is about {column}, as {seen[column]!r} is: "
                             "each objective needs its own column (a front of one column "
                             "against itself is a single point or every design)")  # fmt: skip
        seen[column] = text
    for name, value, low in (("population", population, 4), ("generations", generations, 1)):
        if isinstance(value, bool) or int(value) != value or not low <= value <= 100000:
            raise ValueError(f"{name} = {value!r} is invalid: must be an integer in "
                             f"[{low}, 100000]")  # fmt: skip
    options_run = resolve_run(run, out=out, resume=resume, overwrite=overwrite, client=client,
                              scheduler=scheduler, workers=workers, progress=progress,
                              connect_timeout=connect_timeout,
                              wait_for_workers=wait_for_workers)  # fmt: skip
    out_path = options_run.out
    facs = parse_factors(model, factors, allow_normal=False)
    names = [f.name for f in facs]
    tie_map = parse_ties(ties, model.parameters) if isinstance(model, Vehicle) else {}
    columns = list(dict.fromkeys([c for _, c in objs] + [c for c, _, _ in cons]))
    options = options_from(output_options)
    nominal = model.as_dict() if isinstance(model, Vehicle) else None
    param_cols = list(tied_values({n: 0.0 for n in names}, tie_map))
    evaluation = Evaluation(model, names, param_cols, columns, options, excitation, creep_law)
    from railhunt._cache import source_hash
    from railhunt._version import __version__

    meta: dict[str, Any] = {"study": "optimize", "railhunt": __version__,
                            "source": source_hash(), "algorithm": "NSGA-II (pymoo)",
                            "factors": {f.name: f.describe() for f in facs},
                            "objectives": [f"{s} {c}" for s, c in objs],
                            "constraints": [f"{c} {op} {v!r}" for c, op, v in cons],
                            "population": int(population), "generations": int(generations),
                            "seed": int(seed), "parameter_columns": param_cols,
                            "ties": {f: [lf[0], lf[1]] for f, lf in tie_map.items()},
                            **evaluation.meta}  # fmt: skip
    NSGA2, Evaluator, Problem, StaticProblem = _pymoo()
    lower = np.array([f.a for f in facs])
    upper = np.array([f.b for f in facs])
    problem = Problem(n_var=len(facs), n_obj=len(objs), n_ieq_constr=len(cons), xl=lower,
                      xu=upper)  # fmt: skip
    algorithm = NSGA2(pop_size=int(population))
    algorithm.setup(problem, termination=("n_gen", int(generations)), seed=int(seed),
                    verbose=False)  # fmt: skip
    rows: dict[int, dict[str, Any]] = {}
    designs: list[tuple[int, int]] = []  # (point, generation)
    total_points = int(population) * int(generations) + (nominal is not None)
    timings = {"pymoo_s": 0.0, "evaluations_s": 0.0, "worker_evaluations_s": 0.0,
               "study_s": 0.0}
    history: list[list[int]] = []
    start = None
    began = time.perf_counter()
    with StudyRun(meta, options_run, label="optimize", total=total_points,
                  warm_up=evaluation.warm_up) as study:  # fmt: skip

        def run(points: list[Point], label: str) -> None:
            evaluation.check(points)
            study.label(label)
            study.run(evaluation.items(points), evaluation.task)
            for p in points:
                row = study.rows.get(p.index)
                if row is None:
                    continue
                if any(float(row[k]) != v for k, v in p.values.items()):
                    raise ValueError(f"{out_path}: point {p.index} holds other parameter "
                                     "values than this run asks for: another optimisation "
                                     "wrote it")  # fmt: skip
                rows[p.index] = row

        next_point = 0
        if nominal is not None:
            p0 = Point(0, "start", tied_values({n: float(nominal[n]) for n in names}, tie_map))
            run([p0], "start")
            start = rows.get(0)
            next_point = 1
        for gen in range(int(generations)):
            t0 = time.perf_counter()
            pop = algorithm.ask()
            x = pop.get("X")
            timings["pymoo_s"] += time.perf_counter() - t0
            points = [Point(next_point + i, f"generation {gen}",
                            tied_values(dict(zip(names, map(float, xi), strict=True)),
                                        tie_map))
                      for i, xi in enumerate(x)]  # fmt: skip
            next_point += len(points)
            run(points, f"generation {gen + 1}/{generations}")
            f = np.empty((len(points), len(objs)))
            g = np.empty((len(points), len(cons)))
            for i, p in enumerate(points):
                f[i], g[i], _ = objectives_of(rows.get(p.index), objs, cons)
                designs.append((p.index, gen))
            t0 = time.perf_counter()
            static = StaticProblem(problem, F=f, G=g) if cons else StaticProblem(problem, F=f)
            Evaluator().eval(static, pop)
            algorithm.tell(infills=pop)
            timings["pymoo_s"] += time.perf_counter() - t0
            history.append([p.index for p in points])
        study.complete = not study.lost and all(p in study.rows for p in range(total_points))
        timings["evaluations_s"] = study.engine.evaluation_s
        timings["worker_evaluations_s"] = study.engine.worker_evaluation_s
        timings["study_s"] = time.perf_counter() - began
        timings["railhunt_s"] = max(0.0, timings["study_s"] - timings["pymoo_s"]
                                    - timings["evaluations_s"])  # fmt: skip
        if study.store is not None:
            study.store.note(timings=timings)
    result = _result(rows, designs, history, start, names, param_cols, objs, cons, meta, out_path)
    result.timings = timings
    return result


def _result(rows: dict[int, dict[str, Any]], designs: list[tuple[int, int]],
            history: list[list[int]], start: dict[str, Any] | None, names: list[str],
            param_cols: list[str], objs: list[tuple[str, str]],
            cons: list[tuple[str, str, float]], meta: dict[str, Any],
            out: str | Path | None) -> ParetoResult:  # fmt: skip
    from railhunt.results import optional_import

    pd = optional_import("pandas", "studies", "railhunt.optimize()")
    records = []
    fmin = []
    feasible = []
    for point, gen in designs:
        row = rows.get(point)
        f, g, ok = objectives_of(row, objs, cons)
        feas = bool(ok and np.all(g <= 0))
        rec = {"point": point, "generation": gen}
        rec.update({c: (row or {}).get(c, math.nan) for c in param_cols})
        rec.update({c: _value(row, c) for c in dict.fromkeys([c for _, c in objs]
                                                             + [c for c, _, _ in cons])})
        rec["feasible"] = feas
        rec["status"] = (row or {}).get("status", "lost")
        records.append(rec)
        fmin.append(f)
        feasible.append(feas)
    evaluated = pd.DataFrame.from_records(records)
    fmin_a = np.array(fmin)
    feas_a = np.array(feasible, dtype=bool)
    gens = evaluated["generation"].to_numpy()
    by_generation = fronts(fmin_a, feas_a, gens, len(history))
    best = by_generation[-1] if by_generation else non_dominated(fmin_a, feas_a)
    front = evaluated.iloc[best].reset_index(drop=True)
    hv = hypervolumes(fmin_a, feas_a, gens, len(history), by_generation)
    start_rec = None
    if start is not None:
        start_rec = {c: start.get(c, math.nan) for c in param_cols}
        start_rec.update({c: _value(start, c) for _, c in objs})
    return ParetoResult(names, [c for _, c in objs], [s for s, _ in objs],
                        [f"{c} {op} {v:g}" for c, op, v in cons], front, evaluated, hv,
                        start_rec, meta, Path(out) if out else None)  # fmt: skip
