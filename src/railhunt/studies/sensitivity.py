"""Global sensitivity: which parameters move an output when all of them vary together.

:func:`sensitivity` draws a sample of the factors with SALib (Saltelli's extension of
Sobol' sequences for ``method="sobol"``, Morris trajectories for ``"morris"``), evaluates
every point on the study machinery (:func:`railhunt.studies.runner.run_study`: Dask, the
results file written as points finish, resume) and analyses the outputs with SALib:
Sobol' first-order ``S1`` and total ``ST`` indices with bootstrap confidence intervals,
or Morris' ``mu_star`` (with its interval) and ``sigma``.

**Points without a value.** Sobol's estimators need, for each base sample, its whole
block of ``D + 2`` points (``A``, the ``D`` mixed rows, ``B``); Morris' need whole
trajectories of ``D + 1`` points. So:

- a critical speed that the search did not bracket is **capped** at the edge of the search
  (``stable at every speed tried, up to 800 km/h`` counts as 800 km/h; hunting at every
  speed down to 20 km/h as 20 km/h); a linear critical speed with no Hopf point up to the
  search's 1000 km/h counts as 1000 km/h, and a fold speed without a Hopf point below
  2000 km/h (no limit cycle there at all) as 2000 km/h. These are counted in ``capped``;
- any other point without a value (a failed run, no fold found, a point lost) has its
  **whole block (trajectory) dropped**, counted in ``dropped``: the indices are those of
  the remaining base samples, never computed over a NaN.

An output that does not vary over the sample has no indices (0/0): they are NaN and the
result's ``notes`` say so.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from railhunt.studies.design import Point, parse_ties, tied_values
from railhunt.studies.evaluation import Evaluation
from railhunt.studies.execute import CONNECT_TIMEOUT
from railhunt.studies.factors import Factor, check_model, parse_factors
from railhunt.studies.options import StudyOptions, resolve_run
from railhunt.studies.outputs import OutputOptions, options_from
from railhunt.studies.runner import run_study
from railhunt.studies.sensitivity_result import SensitivityResult
from railhunt.studies.store import STATUS_NO_CRITICAL_SPEED, SweepResults
from railhunt.vehicle import Vehicle

__all__ = ["METHODS", "SensitivityResult", "sensitivity"]

METHODS = ("sobol", "morris")
#: Morris grid levels.
MORRIS_LEVELS = 4
#: The linear critical speed's search limit (km/h): no Hopf point below counts as this.
LINEAR_CAP_KMH = 1000.0


def _salib(what: str) -> Any:
    from railhunt.results import optional_import

    return optional_import(f"SALib.{what}", "studies", "railhunt.sensitivity()")


def problem_of(factors: Sequence[Factor]) -> dict[str, Any]:
    """SALib's problem description of the factors."""
    return {"num_vars": len(factors), "names": [f.name for f in factors],
            "bounds": [[f.a, f.b] for f in factors],
            "dists": ["unif" if f.dist == "uniform" else "norm" for f in factors]}  # fmt: skip


def sample_of(method: str, factors: Sequence[Factor], samples: int, seed: int) -> np.ndarray:
    """The SALib sample (one row per point, factors in order)."""
    problem = problem_of(factors)
    if method == "sobol":
        return _salib("sample.sobol").sample(problem, samples, calc_second_order=False,
                                              seed=seed)  # fmt: skip
    if any(f.dist != "uniform" for f in factors):
        raise ValueError("method='morris' samples a grid in ranges: give every factor a range "
                         "or a tolerance, not a normal distribution")  # fmt: skip
    return _salib("sample.morris").sample(problem, samples, num_levels=MORRIS_LEVELS, seed=seed)


def check_samples(method: str, samples: int) -> int:
    """``samples`` checked for ``method`` (an integer >= 2; a power of 2 for Sobol)."""
    if isinstance(samples, bool) or int(samples) != samples or not 2 <= samples <= 2**20:
        raise ValueError(f"samples = {samples!r} is invalid: must be an integer in [2, 2^20]")
    samples = int(samples)
    if method == "sobol" and samples & (samples - 1):
        raise ValueError(f"samples = {samples} is invalid for method='sobol': Sobol' sequences "
                         "need a power of 2 (e.g. 64, 128, 256)")  # fmt: skip
    return samples


_CAP = re.compile(r"(?:up|down) to ([0-9.eE+-]+) km/h")
_NO_HOPF = re.compile(r"stays stable up to ([0-9.eE+-]+) km/h: no Hopf point")


def capped_value(column: str, row: Mapping[str, Any]) -> float | None:
    """The value a row's unbracketed critical speed is capped at, or None (module doc)."""
    if column == "critical_speed_kmh" and row.get("status") == STATUS_NO_CRITICAL_SPEED:
        match = _CAP.search(str(row.get("message", "")))
        return float(match.group(1)) if match else None
    if column == "linear_critical_speed_kmh" and row.get("status") == "ok" \
            and math.isnan(float(row.get(column, math.nan))):  # fmt: skip
        return LINEAR_CAP_KMH
    if column == "fold_speed_kmh" and row.get("status") == "failed":
        match = _NO_HOPF.search(str(row.get("message", "")))
        return float(match.group(1)) if match else None
    return None


def output_values(rows: Sequence[Mapping[str, Any]], column: str,
                  total: int) -> tuple[np.ndarray, int]:  # fmt: skip
    """One output over all ``total`` points (NaN where missing) and how many were capped."""
    y = np.full(total, math.nan)
    capped = 0
    for row in rows:
        value = float(row.get(column, math.nan))
        if math.isnan(value):
            cap = capped_value(column, row)
            if cap is not None:
                value, capped = cap, capped + 1
        y[int(row["point"])] = value
    return y, capped


def analyse(method: str, factors: Sequence[Factor], x: np.ndarray, y: np.ndarray, seed: int,
            num_resamples: int = 100, conf_level: float = 0.95,
            ) -> tuple[dict[str, np.ndarray], int]:  # fmt: skip
    """SALib's indices of one output; whole blocks with a NaN are dropped first.

    Returns
    -------
    indices : dict
        ``S1, S1_conf, ST, ST_conf`` (Sobol) or ``mu_star, mu_star_conf, sigma`` (Morris),
        one value per factor.
    dropped : int
        Points dropped (whole blocks).
    """
    d = len(factors)
    block = d + 2 if method == "sobol" else d + 1
    blocks = y.reshape(-1, block)
    keep = ~np.any(np.isnan(blocks), axis=1)
    dropped = int(np.sum(~keep)) * block
    if int(np.sum(keep)) < 2:
        raise ValueError(f"only {int(np.sum(keep))} of {blocks.shape[0]} base samples have "
                         "every point's value: too few for the indices")  # fmt: skip
    problem = problem_of(factors)
    y_kept = blocks[keep].ravel()
    import warnings

    # A generator, not the int: SALib's Sobol analysis ignores a seed of 0 (``if seed:``)
    # and would draw its bootstrap from numpy's global state.
    rng = np.random.default_rng(seed)
    with warnings.catch_warnings(), np.errstate(divide="ignore", invalid="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        if method == "sobol":
            res = _salib("analyze.sobol").analyze(problem, y_kept, calc_second_order=False,
                                                  num_resamples=num_resamples,
                                                  conf_level=conf_level, seed=rng)  # fmt: skip
            keys = ("S1", "S1_conf", "ST", "ST_conf")
        else:
            x_kept = x.reshape(-1, block, d)[keep].reshape(-1, d)
            res = _salib("analyze.morris").analyze(problem, x_kept, y_kept,
                                                   num_resamples=num_resamples,
                                                   conf_level=conf_level,
                                                   num_levels=MORRIS_LEVELS, seed=rng)  # fmt: skip
            keys = ("mu_star", "mu_star_conf", "sigma")
    return {k: np.asarray(res[k], dtype=float) for k in keys}, dropped


def sensitivity(
    model: Vehicle | Callable[..., Mapping[str, Any]],
    factors: Mapping[str, object],
    outputs: Sequence[str] = ("critical_speed_kmh",),
    *,
    method: str = "sobol",
    samples: int = 256,
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
    num_resamples: int = 100,
    conf_level: float = 0.95,
    output_options: OutputOptions | Mapping[str, Any] | None = None,
    frequency_speed_kmh: float | None = None,
    excitation: object = None,
    creep_law: str | None = None,
    wait_for_workers: bool | float = False,
    run: StudyOptions | None = None,
) -> SensitivityResult:
    """Sobol' or Morris sensitivity indices of a model's outputs to its factors.

    Parameters
    ----------
    model : Vehicle or callable
        A vehicle (factors are its parameters), or a function of the factors (keywords)
        returning a dict with the ``outputs``.
    factors : Mapping
        Name -> ``(low, high)``, ``("uniform", low, high)``, ``("normal", mean, std)`` or
        ``("tolerance", t)`` (SI; :mod:`railhunt.studies.factors`). At least two.
    outputs : sequence of str
        For a vehicle, results columns: ``critical_speed_kmh``, ``linear_critical_speed_kmh``,
        ``linear_frequency_hz``, ``hunting_frequency_hz``, ``fold_speed_kmh``,
        ``least_damping_ratio``, ``max_YQ``, ``sum_Y_leading``, ``wear_number``; for a
        function, keys of its dict.
    method : {"sobol", "morris"}
        Saltelli/Sobol' (``samples`` base samples, a power of 2: ``samples * (D + 2)``
        points) or Morris (``samples`` trajectories: ``samples * (D + 1)`` points).
    samples : int
        Base samples (Sobol) or trajectories (Morris).
    seed : int
        Seed of the sample and of the bootstrap: the same seed gives the same indices.
    ties : Mapping, optional
        Parameters that follow a factor, as in :func:`railhunt.sweep` (``{"f22": "f11"}``).
    out, resume, overwrite : optional
        Results file written as points finish; continue it; replace it.
    client, scheduler, workers, connect_timeout : optional
        Where the points run, as in :func:`railhunt.sweep` (``workers=1``: in this process).
    progress : bool or callable
        A progress bar on stderr, or ``progress(done, total)``.
    num_resamples, conf_level : optional
        Bootstrap resamples and confidence level of the intervals.
    output_options : OutputOptions or Mapping, optional
        The curve of the curving outputs, the speed range of ``least_damping_ratio``.
    frequency_speed_kmh, excitation, creep_law : optional
        As in :func:`railhunt.sweep` (vehicle models only).
    wait_for_workers : bool or float
        As in :func:`railhunt.sweep`.
    run : StudyOptions, optional
        How the study runs, in one object (:class:`railhunt.StudyOptions`), instead of
        ``out`` ... ``wait_for_workers`` (giving both is an error naming the keyword).

    Returns
    -------
    SensitivityResult
    """
    check_model(model)
    if method not in METHODS:
        raise ValueError(f"method = {method!r} is invalid: must be one of {', '.join(METHODS)}")
    samples = check_samples(method, samples)
    options_run = resolve_run(run, out=out, resume=resume, overwrite=overwrite, client=client,
                              scheduler=scheduler, workers=workers, progress=progress,
                              connect_timeout=connect_timeout,
                              wait_for_workers=wait_for_workers)  # fmt: skip
    outputs = tuple(outputs)
    if not outputs or isinstance(outputs[0], (list, tuple)):
        raise ValueError(f"outputs = {list(outputs)!r} is invalid: give one or more names")
    facs = parse_factors(model, factors)
    tie_map = parse_ties(ties, model.parameters) if isinstance(model, Vehicle) else {}
    if ties and not isinstance(model, Vehicle):
        raise ValueError("ties apply to a vehicle's parameters, not to a model function")
    names = [f.name for f in facs]
    for follower, (leader, _) in tie_map.items():
        if follower in names:
            raise ValueError(f"{follower} is both a factor and tied to {leader}: drop one")
        if leader not in names:
            raise ValueError(f"tie {follower} = {leader}: {leader} is not a factor")
    x = sample_of(method, facs, samples, seed)
    points = [Point(i, method, tied_values({n: float(v) for n, v in zip(names, row, strict=True)},
                                     tie_map)) for i, row in enumerate(x)]  # fmt: skip
    param_cols = list(points[0].values)
    options = options_from(output_options)
    meta: dict[str, Any] = {"study": "sensitivity", "method": method, "samples": samples,
                            "seed": seed, "factors": {f.name: f.describe() for f in facs},
                            "outputs": list(outputs), "points": len(points),
                            "parameter_columns": param_cols}  # fmt: skip
    from railhunt._cache import source_hash
    from railhunt._version import __version__

    meta.update(railhunt=__version__, source=source_hash())
    if isinstance(model, Vehicle):
        meta.update(ties={f: [lf[0], lf[1]] for f, lf in tie_map.items()})
    evaluation = Evaluation(model, names, param_cols, outputs, options, excitation, creep_law,
                            frequency_speed_kmh)  # fmt: skip
    evaluation.check(points)
    meta.update(evaluation.meta)
    items = evaluation.items(points)
    task, warm = evaluation.task, evaluation.warm_up
    study = run_study(items, task, meta, label=method, run=options_run, warm_up=warm)
    return analyse_study(study, method, facs, x, outputs, seed, num_resamples, conf_level)


def analyse_study(study: SweepResults, method: str, factors: Sequence[Factor], x: np.ndarray,
                  outputs: Sequence[str], seed: int, num_resamples: int = 100,
                  conf_level: float = 0.95) -> SensitivityResult:  # fmt: skip
    """The indices of every output of a finished (or partly finished) study."""
    rows: list[dict[str, Any]] = []
    dropped: dict[str, int] = {}
    capped: dict[str, int] = {}
    notes: list[str] = []
    total = x.shape[0]
    for column in outputs:
        y, capped[column] = output_values(study.rows, column, total)
        try:
            indices, dropped[column] = analyse(method, factors, x, y, seed, num_resamples,
                                               conf_level)  # fmt: skip
        except ValueError as exc:
            failed = next((r for r in study.rows if r.get("status") == "failed"), None)
            if failed is None:
                raise
            raise ValueError(f"{exc} (point {failed['point']} failed: "
                             f"{failed.get('message', '')})") from None  # fmt: skip
        finite = y[np.isfinite(y)]
        if finite.size and np.ptp(finite) == 0:
            notes.append(f"{column} is the same at every point: it has no indices (NaN)")
        for k, f in enumerate(factors):
            rows.append({"output": column, "factor": f.name,
                         **{key: float(v[k]) for key, v in indices.items()}})  # fmt: skip
    missing = total - len(study.rows)
    if missing:
        notes.append(f"{missing} point(s) not computed (lost): resume the study to add them")
    return SensitivityResult(method, list(outputs), [f.name for f in factors], rows, dropped,
                             capped, total, study, notes)  # fmt: skip
