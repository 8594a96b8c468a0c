"""How a result shows itself: a short summary, an HTML table, and tidy tables.

Every result object of railhunt (critical speeds, eigenvalues, a run, a bifurcation
diagram, a hunting frequency, a study, a contact geometry, a curving state, ...) inherits
:class:`ResultDisplay` and says two things about itself:

``_summary()``
    a few ``(label, value, unit)`` rows: what an engineer reads first;
``_columns()``
    its data as named columns, ``{name: (values, unit)}``, one row per trial, speed,
    sample, orbit, wheel ... (a scalar value is one row).

From those two, this module makes ``repr()`` (a few lines, never the arrays),
``_repr_html_()`` (the table a notebook shows) and ``to_dataframe()`` (a pandas
``DataFrame``; the units are in ``DataFrame.attrs["units"]``). A simulation also gives
``to_xarray()`` (:meth:`ResultDisplay._dataset`). pandas and xarray are optional: they are
imported only when a table is asked for, and a missing one raises an ``ImportError`` that
names the extra to install (``pip install 'railhunt[pandas]'``).
"""

from __future__ import annotations

import html
import importlib
import math
import numbers
from collections.abc import Mapping
from types import ModuleType
from typing import Any, ClassVar

import numpy as np

__all__ = ["Columns", "ResultDisplay", "Row", "format_value", "optional_import"]

#: One line of a summary: label, value, unit (``""`` when it has none).
Row = tuple[str, Any, str]
#: A result's data: column name -> (values, unit). Values are sequences of equal length,
#: or scalars (broadcast to the length of the others, or one row).
Columns = dict[str, tuple[Any, str]]


def optional_import(module: str, extra: str, needed_for: str) -> ModuleType:
    """Import an optional dependency, or say which extra installs it.

    Parameters
    ----------
    module : str
        Module to import (``"pandas"``, ``"xarray"``).
    extra : str
        The railhunt extra that installs it (``pip install 'railhunt[EXTRA]'``).
    needed_for : str
        What needs it, for the message (``"to_dataframe()"``).

    Raises
    ------
    ImportError
        When the module is not installed; the message names the extra.
    """
    try:
        return importlib.import_module(module)
    except ImportError:
        raise ImportError(
            f"{needed_for} needs {module}, which is not installed: "
            f"pip install 'railhunt[{extra}]' (or pip install {module})"
        ) from None


def format_value(value: Any) -> str:
    """A value as a summary shows it: 4 significant digits, yes/no, ``a+bj``."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        x = float(value)
        return "nan" if math.isnan(x) else f"{x:.4g}"
    if isinstance(value, numbers.Complex):
        z = complex(value)
        return f"{z.real:.4g}{z.imag:+.4g}j"
    if value is None:
        return "-"
    return str(value)


def _length(values: Any) -> int | None:
    if isinstance(values, (str, bytes)) or np.ndim(values) == 0:
        return None
    return len(values)


def _broadcast(columns: Columns) -> dict[str, Any]:
    """The columns with scalars repeated to the common length (one row if all scalar)."""
    lengths = {n for n in (_length(v) for v, _ in columns.values()) if n is not None}
    if len(lengths) > 1:
        raise ValueError(f"columns of unequal length: {sorted(lengths)}")
    n = lengths.pop() if lengths else 1
    return {name: (list(v) if _length(v) is not None else [v] * n)
            for name, (v, _) in columns.items()}  # fmt: skip


class ResultDisplay:
    """Summary ``repr``, notebook HTML table and ``to_dataframe()`` for a result class.

    A subclass defines ``_summary()`` and ``_columns()`` (module docstring) and, for a
    time series, sets ``_index`` to the column that indexes the table. A dataclass
    subclass must be declared with ``@dataclass(repr=False)`` so that its generated
    ``__repr__`` does not replace this one.
    """

    __slots__ = ()
    #: Column used as the DataFrame's index (None: a plain range index).
    _index: ClassVar[str | None] = None

    def _summary(self) -> list[Row]:
        raise NotImplementedError

    def _columns(self) -> Columns:
        raise NotImplementedError

    def __repr__(self) -> str:
        rows = self._summary()
        width = max((len(label) for label, _, _ in rows), default=0)
        lines = [type(self).__name__]
        for label, value, unit in rows:
            text = format_value(value)
            lines.append(f"  {label:<{width}}  {text} {unit}".rstrip())
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        cells = []
        for label, value, unit in self._summary():
            cells.append(
                f"<tr><td style='text-align:left'>{html.escape(label)}</td>"
                f"<td style='text-align:right'>{html.escape(format_value(value))}</td>"
                f"<td style='text-align:left'>{html.escape(unit)}</td></tr>"
            )
        return (
            "<table class='railhunt-result'>"
            f"<caption style='text-align:left'><b>{html.escape(type(self).__name__)}</b>"
            "</caption><thead><tr><th style='text-align:left'>quantity</th>"
            "<th style='text-align:right'>value</th><th style='text-align:left'>unit</th>"
            f"</tr></thead><tbody>{''.join(cells)}</tbody></table>"
        )

    def to_dataframe(self) -> Any:
        """The result's data as a tidy pandas ``DataFrame`` (needs ``railhunt[pandas]``).

        Returns
        -------
        pandas.DataFrame
            One column per quantity, SI units (speeds in km/h where the column says
            ``_kmh``); ``df.attrs["units"]`` maps each column to its unit.
        """
        pd = optional_import("pandas", "pandas", f"{type(self).__name__}.to_dataframe()")
        columns = self._columns()
        frame = pd.DataFrame(_broadcast(columns))
        if self._index is not None:
            frame = frame.set_index(self._index)
        frame.attrs["units"] = {name: unit for name, (_, unit) in columns.items()}
        return frame

    def _dataset(self, attrs: Mapping[str, Any]) -> Any:
        """The columns as an ``xarray.Dataset`` over ``_index`` (needs ``railhunt[xarray]``).

        Each column becomes a variable with its unit in ``attrs["units"]``; ``attrs`` are
        the dataset's attributes.
        """
        xr = optional_import("xarray", "xarray", f"{type(self).__name__}.to_xarray()")
        if self._index is None:
            raise TypeError(f"{type(self).__name__} has no index to be a dataset's coordinate")
        columns = self._columns()
        data = _broadcast(columns)
        dim = self._index
        coord = xr.Variable(dim, np.asarray(data[dim]), attrs={"units": columns[dim][1]})
        variables = {name: xr.Variable(dim, np.asarray(values), attrs={"units": columns[name][1]})
                     for name, values in data.items() if name != dim}  # fmt: skip
        return xr.Dataset(variables, coords={dim: coord}, attrs=dict(attrs))
