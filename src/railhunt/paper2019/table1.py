"""The paper's Table 1: the ranges of the seven parameters of its Figs. 10-12, in sections.

Table 1 divides the range of each of seven parameters (C_d1, K_d, C_d2, mu, K_px,
f11 = f22, C_sy) into three sections; Figs. 10 and 11 sweep each range and Fig. 12
compares the change of the critical speed and of the hunting frequency per section. The
table ships as ``table1.toml`` next to this module, in the paper's display units;
:func:`load_table1` reads it, checks every entry against the vehicle's parameters and
converts the boundaries to SI units (N*s/m, N/m, N, -).
"""

from __future__ import annotations

import functools
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from importlib import resources
from types import MappingProxyType
from typing import Any

__all__ = ["Table1Parameter", "load_table1"]


@dataclass(frozen=True)
class Table1Parameter:
    """One parameter of the paper's Table 1.

    Attributes
    ----------
    name : str
        Vehicle parameter name (``"C_d1"``, ``"K_d"``, ``"C_d2"``, ``"mu"``, ``"K_px"``,
        ``"f11"``, ``"C_sy"``).
    meaning : str
        What the parameter is.
    unit : str
        Display unit (``"kN*s/m"``, ``"MN/m"``, ``"MN"``, ``"-"``).
    scale : float
        Size of one display unit in SI: ``SI value = display value * scale``.
    boundaries : tuple of float
        The four section boundaries in SI units; section ``k`` (1-based) runs from
        ``boundaries[k - 1]`` to ``boundaries[k]``.
    figure : str
        The panel of the paper that sweeps it (``"10a"`` ... ``"11d"``).
    frequency_speed_kmh : float
        Speed at which the paper computes the hunting frequency (km/h): 300 for the yaw
        damper parameters (Fig. 10), 350 for the others (Fig. 11).
    ties : tuple of str
        Parameters set equal to this one at every point (``("f22",)`` for f11).
    paper_boundaries : tuple of float or None
        The boundaries as printed in the paper (display unit), where railhunt departs
        from them (C_d2: the paper's 0 is 1 kN*s/m here); None otherwise.
    note : str
        Why railhunt departs from the paper ("" when it does not).
    """

    name: str
    meaning: str
    unit: str
    scale: float
    boundaries: tuple[float, ...]
    figure: str
    frequency_speed_kmh: float
    ties: tuple[str, ...] = ()
    paper_boundaries: tuple[float, ...] | None = None
    note: str = ""

    @property
    def sections(self) -> tuple[tuple[float, float], ...]:
        """The three sections ``(lower, upper)`` in SI units."""
        b = self.boundaries
        return tuple((b[k], b[k + 1]) for k in range(len(b) - 1))

    @property
    def display_boundaries(self) -> tuple[float, ...]:
        """The section boundaries in the display unit."""
        return tuple(float(f"{v / self.scale:.12g}") for v in self.boundaries)

    @property
    def label(self) -> str:
        """Axis label: the name with its ties and the display unit, e.g. ``f11 = f22 (MN)``."""
        name = " = ".join((self.name, *self.ties))
        return name if self.unit == "-" else f"{name} ({self.unit})"


@functools.cache
def load_table1() -> Mapping[str, Table1Parameter]:
    """The paper's Table 1 as shipped in ``railhunt/paper2019/table1.toml``.

    Returns
    -------
    Mapping[str, Table1Parameter]
        Read-only mapping from parameter name to its entry, in the paper's order
        (C_d1, K_d, C_d2, mu, K_px, f11, C_sy). Boundaries in SI units.
    """
    ref = resources.files("railhunt.paper2019") / "table1.toml"
    data = tomllib.loads(ref.read_text(encoding="utf-8"))
    return MappingProxyType({name: _parse_entry(name, entry) for name, entry in data.items()})


def _parse_entry(name: str, entry: Mapping[str, Any]) -> Table1Parameter:
    """Check one Table 1 entry against the vehicle's parameters and convert it to SI."""
    from railhunt.vehicle import PARAMETERS, validate_value

    def bad(why: str) -> RuntimeError:
        return RuntimeError(f"railhunt installation error: table1.toml [{name}]: {why}")

    if name not in PARAMETERS:
        raise bad("not a vehicle parameter")
    scale = float(entry["scale"])
    shown = [float(v) for v in entry["boundaries"]]
    if len(shown) != 4 or any(b <= a for a, b in zip(shown, shown[1:], strict=False)):
        raise bad(f"boundaries {shown} must be 4 increasing numbers")
    boundaries = tuple(float(f"{v * scale:.12g}") for v in shown)
    for value in boundaries:
        try:
            validate_value(name, value)
        except ValueError as exc:
            raise bad(str(exc)) from None
    ties = tuple(entry.get("ties", ()))
    for tied in ties:
        if tied not in PARAMETERS:
            raise bad(f"tied parameter {tied!r} is not a vehicle parameter")
    paper = entry.get("paper_boundaries")
    return Table1Parameter(
        name=name,
        meaning=str(entry["meaning"]),
        unit=str(entry["unit"]),
        scale=scale,
        boundaries=boundaries,
        figure=str(entry["figure"]),
        frequency_speed_kmh=float(entry["frequency_speed_kmh"]),
        ties=ties,
        paper_boundaries=None if paper is None else tuple(float(v) for v in paper),
        note=" ".join(str(entry.get("note", "")).split()),
    )
