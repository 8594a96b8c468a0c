"""The paper's Table 1 study: sweep values covering the three sections of each parameter.

:func:`table1_values` gives evenly spaced values over one parameter's sections,
:func:`table1_study` the parameters and ties of the whole study for :func:`railhunt.sweep`
(the paper's Figs. 10-11). The table itself is the paper's
(:func:`railhunt.paper2019.load_table1`, ``railhunt/paper2019/table1.toml``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from railhunt.paper2019.table1 import Table1Parameter, load_table1

__all__ = ["table1_study", "table1_values"]


def _table_entry(name: str, table: Mapping[str, Table1Parameter]) -> Table1Parameter:
    if name in table:
        return table[name]
    for entry in table.values():
        if name in entry.ties:
            raise ValueError(f"{name!r} follows {entry.name!r} in Table 1; use {entry.name!r}")
    raise ValueError(f"{name!r} is not a Table 1 parameter (valid: {', '.join(table)})")


def table1_values(
    name: str,
    points_per_section: int = 5,
    table: Mapping[str, Table1Parameter] | None = None,
) -> np.ndarray:
    """Evenly spaced sweep values covering a parameter's three Table 1 sections.

    Parameters
    ----------
    name : str
        Table 1 parameter (``"C_d1"``, ``"K_d"``, ``"C_d2"``, ``"mu"``, ``"K_px"``,
        ``"f11"``, ``"C_sy"``).
    points_per_section : int
        Points per section, both ends included (at least 2). Neighbouring sections share
        their boundary, so the result has ``3 * (points_per_section - 1) + 1`` values.
    table : Mapping[str, Table1Parameter], optional
        Another table (default: :func:`load_table1`).

    Returns
    -------
    numpy.ndarray
        Ascending values in SI units, every section boundary included exactly once.
    """
    entry = _table_entry(name, load_table1() if table is None else table)
    n = int(points_per_section)
    if n != points_per_section or n < 2:
        raise ValueError(
            f"points_per_section = {points_per_section!r} is invalid: must be an integer >= 2 "
            "(each section's two ends)"
        )
    parts = [np.linspace(lo, hi, n) for lo, hi in entry.sections]
    return np.concatenate([parts[0], *(part[1:] for part in parts[1:])])


def table1_study(
    points_per_section: int = 5,
    names: Sequence[str] | None = None,
) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """The paper's parameter study: every Table 1 parameter over its three sections.

    Parameters
    ----------
    points_per_section : int
        Points per section, both ends included (see :func:`table1_values`).
    names : sequence of str, optional
        A subset of the Table 1 parameters (default: all seven, in the paper's order).

    Returns
    -------
    parameters : dict
        Name -> SI values, for ``railhunt.sweep(vehicle, parameters, ties=ties)`` with the
        default ``design="lines"``.
    ties : dict
        Follower -> leader (``{"f22": "f11"}``: the paper sets f22 = f11).
    """
    table = load_table1()
    chosen = list(table) if names is None else [_table_entry(n, table).name for n in names]
    parameters = {n: table1_values(n, points_per_section, table) for n in chosen}
    ties = {follower: n for n in chosen for follower in table[n].ties}
    return parameters, ties
