"""Figures of the global studies: sensitivity indices with their intervals, Pareto fronts."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from railhunt.plots.figure import new_figure, save_figure

__all__ = ["plot_pareto", "plot_sensitivity"]


def plot_sensitivity(result: Any, path: str | os.PathLike[str] | None = None) -> Figure | Path:
    """Bars of each output's indices per factor, with their confidence intervals.

    One panel per output. Sobol: first-order ``S1`` and total ``ST`` side by side, the
    bootstrap interval (``S1_conf``, ``ST_conf``) as error bars. Morris: ``mu_star`` with
    its interval, and ``sigma`` as a second bar.

    Parameters
    ----------
    result : SensitivityResult
        From :func:`railhunt.sensitivity`.
    path : path-like, optional
        Write the figure there (PNG, SVG, PDF by suffix); default return the figure.

    Returns
    -------
    Figure or Path
    """
    outputs = result.outputs
    factors = result.factors
    fig = new_figure(3.2 + 0.55 * len(factors), 2.6 * len(outputs) + 0.4)
    axes = fig.subplots(len(outputs), 1, squeeze=False)[:, 0]
    sobol = result.method == "sobol"
    pairs = (("S1", "S1_conf", "first order S1"), ("ST", "ST_conf", "total ST")) if sobol \
        else (("mu_star", "mu_star_conf", "mu*"), ("sigma", None, "sigma"))  # fmt: skip
    x = np.arange(len(factors))
    width = 0.38
    for ax, out in zip(axes, outputs, strict=True):
        for k, (key, conf, label) in enumerate(pairs):
            values = [result.index(out, f, key) for f in factors]
            err = [result.index(out, f, conf) for f in factors] if conf else None
            ax.bar(x + (k - 0.5) * width, values, width, yerr=err, capsize=3, label=label,
                   color=("#1f4e79", "#9dc3e6")[k], edgecolor="black", linewidth=0.5)
        ax.set_xticks(x, factors)
        ax.axhline(0.0, color="black", linewidth=0.6)
        ax.set_ylabel("index" if sobol else out)
        ax.set_title(out, fontsize=9)
        ax.legend(fontsize=8, frameon=False)
    fig.suptitle(f"{'Sobol' if sobol else 'Morris'} indices, {result.points} points", fontsize=10)
    return fig if path is None else save_figure(fig, path)


def plot_pareto(result: Any, path: str | os.PathLike[str] | None = None) -> Figure | Path:
    """The Pareto front of a two-objective optimisation, the starting vehicle marked.

    Every evaluated design grey (infeasible ones as crosses), the non-dominated feasible
    designs as a line of dots, and the starting vehicle as a star.

    Parameters
    ----------
    result : ParetoResult
        From :func:`railhunt.optimize` (two objectives are drawn: the first two).
    path : path-like, optional
        Write the figure there; default return the figure.
    """
    obj = result.objective_columns[:2]
    if len(obj) < 2:
        raise ValueError("a Pareto figure needs two objectives")
    fig = new_figure(5.0, 4.0)
    ax = fig.subplots()
    ev = result.evaluated
    feas = ev["feasible"].to_numpy(dtype=bool)
    ax.scatter(ev[obj[0]][feas], ev[obj[1]][feas], s=8, color="0.7", label="evaluated")
    if np.any(~feas):
        ax.scatter(ev[obj[0]][~feas], ev[obj[1]][~feas], s=10, marker="x", color="0.8",
                   label="infeasible")
    front = result.front.sort_values(obj[0])
    ax.plot(front[obj[0]], front[obj[1]], "o-", color="#1f4e79", markersize=4,
            label="Pareto front")
    if result.start is not None:
        ax.plot(result.start[obj[0]], result.start[obj[1]], "*", color="#c00000", markersize=12,
                label="starting vehicle")
    senses = dict(zip(result.objective_columns, result.senses, strict=True))
    ax.set_xlabel(f"{obj[0]} ({senses[obj[0]]})")
    ax.set_ylabel(f"{obj[1]} ({senses[obj[1]]})")
    ax.legend(fontsize=8, frameon=False)
    return fig if path is None else save_figure(fig, path)
