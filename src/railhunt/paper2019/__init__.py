"""The 2019 hunting paper in one home: its vehicle, Table 1, captions, quotations, numbers.
Data files (TOML) lie next to this module; railhunt.studies compares its results to them.

The paper is *Numerical Investigation into the Critical Speed and Frequency of the Hunting
Motion in Railway Vehicle System* (Mathematical Problems in Engineering, 2019). What
railhunt takes from it lives here, and only here:

=====================  ==================================================================
:func:`vehicle`        the vehicle of its Table 2 (``Vehicle.paper2019()``; the file is
                       ``railhunt/data/vehicles/paper2019.toml``)
``TABLE1``             its Table 1: the ranges of the seven parameters of Figs. 10-12, in
                       three sections (:func:`load_table1`, ``table1.toml``)
``CITATION``           the paper as the report cites it
``CAPTIONS``           its captions of Figs. 6-8 and 10-13 (``paper.toml``)
``QUOTATIONS``         the sentences its headline numbers are taken from (``paper.toml``)
``EXPECTED``           the headline numbers and statements ``railhunt reproduce``
                       compares against, with where the paper states them, the
                       tolerance and railhunt's note on a difference (``expected.toml``)
``NOTES``              those notes, by key
:data:`NO_BLOWOFF`     the blow-off force that stands for the paper's "F_u tends to
                       infinity" (a linear yaw damper)
=====================  ==================================================================

The upper-case names are read when first used (``import railhunt.paper2019`` reads no
file).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from railhunt.paper2019.expected import (
    Expected,
    captions,
    citation,
    expected,
    notes,
    quotations,
)
from railhunt.paper2019.table1 import Table1Parameter, load_table1

if TYPE_CHECKING:
    from railhunt.vehicle import Vehicle

__all__ = ["CAPTIONS", "CITATION", "EXPECTED", "NOTES", "NO_BLOWOFF", "QUOTATIONS", "TABLE1",
           "Expected", "Table1Parameter", "captions", "citation", "expected", "load_table1",
           "notes", "quotations", "vehicle"]  # fmt: skip

#: Blow-off force (N) that stands for "no blow-off": the paper's "F_u tends to infinity,
#: namely, with a linear damping coefficient" (Fig. 13); ``inf`` kN on the command line.
NO_BLOWOFF = 1e12

_LAZY = {
    "TABLE1": load_table1,
    "CITATION": citation,
    "CAPTIONS": captions,
    "QUOTATIONS": quotations,
    "NOTES": notes,
    "EXPECTED": expected,
}


def vehicle() -> Vehicle:
    """The paper's vehicle (its Table 2): ``Vehicle.paper2019()``.

    Returns
    -------
    Vehicle
        The shipped ``paper2019`` vehicle (``railhunt/data/vehicles/paper2019.toml``).
    """
    from railhunt.vehicle import Vehicle

    return Vehicle.paper2019()


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return _LAZY[name]()
    raise AttributeError(f"module 'railhunt.paper2019' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(list(globals()) + list(_LAZY))
