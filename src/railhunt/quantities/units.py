"""Unit texts of vehicle and layout files: read, converted to SI, or refused.

A unit is a product of symbols with integer or fractional powers, ``"N*s/m"``,
``"kg*m^2"``, ``"1/m^4"``, ``"kN/m"``, ``"N*m/rad"``: symbols joined by ``*`` and ``/``
(everything after a ``/`` divides), each with an optional ``^p``. :func:`parse_unit`
gives its scale to SI, its dimension (powers of kg, m, s) and its SI spelling
(``"kN/m"`` -> ``1e3``, ``"N/m"``). The radian is SI's dimensionless unit: ``"N*m/rad"``
and ``"N*m"`` are the same dimension. An unknown symbol is an error naming the known ones.

:func:`dimension_text` writes a dimension back as a unit (for messages).
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from typing import NamedTuple

__all__ = ["SYMBOLS", "Unit", "UnitError", "dimension_text", "parse_unit", "same_dimension",
           "to_si"]  # fmt: skip

#: Dimension: powers of (kg, m, s).
Dimension = tuple[float, float, float]

_NONE: Dimension = (0.0, 0.0, 0.0)
_KG: Dimension = (1.0, 0.0, 0.0)
_M: Dimension = (0.0, 1.0, 0.0)
_S: Dimension = (0.0, 0.0, 1.0)
_N: Dimension = (1.0, 1.0, -2.0)
_PA: Dimension = (1.0, -1.0, -2.0)

#: Known symbols: scale to SI, dimension, SI symbol.
SYMBOLS: dict[str, tuple[float, Dimension, str]] = {
    "1": (1.0, _NONE, "1"), "rad": (1.0, _NONE, "rad"), "mrad": (1e-3, _NONE, "rad"),
    "deg": (math.pi / 180.0, _NONE, "rad"),
    "kg": (1.0, _KG, "kg"), "g": (1e-3, _KG, "kg"), "t": (1e3, _KG, "kg"),
    "m": (1.0, _M, "m"), "mm": (1e-3, _M, "m"), "cm": (1e-2, _M, "m"), "km": (1e3, _M, "m"),
    "s": (1.0, _S, "s"), "ms": (1e-3, _S, "s"), "h": (3600.0, _S, "s"),
    "N": (1.0, _N, "N"), "kN": (1e3, _N, "N"), "MN": (1e6, _N, "N"),
    "Pa": (1.0, _PA, "Pa"), "kPa": (1e3, _PA, "Pa"), "MPa": (1e6, _PA, "Pa"),
    "GPa": (1e9, _PA, "Pa"),
}  # fmt: skip

_POWER = r"(?:\^\s*\(?\s*(-?\d+(?:\.\d+)?(?:/\d+)?)\s*\)?)?"
_TOKEN = re.compile(r"\s*([*/])?\s*([A-Za-z]+|1)\s*" + _POWER)


class UnitError(ValueError):
    """A unit text that is not a product of known symbols (the message names them)."""


class Unit(NamedTuple):
    """A unit read from a file.

    Attributes
    ----------
    scale : float
        Factor from the unit to SI (``1e3`` for ``"kN/m"``).
    dimension : tuple of float
        Powers of kg, m and s.
    si : str
        The same unit in SI symbols (``"N/m"`` for ``"kN/m"``).
    """

    scale: float
    dimension: Dimension
    si: str


def _power(text: str | None) -> float:
    if text is None:
        return 1.0
    if "/" in text:
        num, den = text.split("/")
        return float(num) / float(den)
    return float(text)


@lru_cache(maxsize=1024)
def parse_unit(text: str) -> Unit:
    """The scale, dimension and SI spelling of a unit text.

    Raises
    ------
    UnitError
        A symbol is unknown or the text is not a product of symbols.
    """
    source = text.strip()
    if not source:
        raise UnitError("an empty unit: write the unit, e.g. \"N/m\", or leave the key out")
    pos, scale, dim, si = 0, 1.0, [0.0, 0.0, 0.0], []
    divide = False
    first = True
    while pos < len(source):
        m = _TOKEN.match(source, pos)
        if m is None or m.end() == pos or (first and m.group(1) == "*"):
            raise UnitError(f"unit {text!r} is not a product of symbols such as N*s/m or "
                            "kg*m^2")  # fmt: skip
        op, symbol, power = m.group(1), m.group(2), _power(m.group(3))
        if op is None and not first:
            raise UnitError(f"unit {text!r}: join the symbols with * or /")
        if op == "/":
            divide = True
        if symbol not in SYMBOLS:
            raise UnitError(f"unit {text!r}: {symbol!r} is not a unit railhunt knows; known: "
                            f"{', '.join(SYMBOLS)} (joined by * and /, powers by ^)")  # fmt: skip
        sym_scale, sym_dim, sym_si = SYMBOLS[symbol]
        sign = -1.0 if divide else 1.0
        scale *= sym_scale ** (sign * power)
        for k in range(3):
            dim[k] += sign * power * sym_dim[k]
        written = sym_si + (f"^{m.group(3)}" if m.group(3) else "")
        si.append(("/" if op == "/" else "*" if op == "*" else "") + written)
        pos = m.end()
        first = False
    return Unit(scale, (dim[0], dim[1], dim[2]), "".join(si))


def dimension_text(dim: Dimension) -> str:
    """A dimension as a unit text in kg, m and s (``"kg*m/s^2"``; ``"1"`` dimensionless)."""
    known = {_N: "N", _PA: "Pa", _NONE: "1"}
    if dim in known:
        return known[dim]
    up, down = [], []
    for sym, p in zip(("kg", "m", "s"), dim, strict=True):
        if p == 0:
            continue
        q = abs(p)
        text = sym if q == 1 else f"{sym}^{q:g}"
        (up if p > 0 else down).append(text)
    return ("*".join(up) or "1") + ("/" + "/".join(down) if down else "")


def same_dimension(a: Dimension, b: Dimension) -> bool:
    """Whether two dimensions are equal (to rounding of fractional powers)."""
    return all(abs(x - y) < 1e-9 for x, y in zip(a, b, strict=True))


def to_si(value: float, scale: float) -> float:
    """``value`` in a unit of ``scale`` (to SI), in SI: divided by the whole number ``1 /
    scale`` where there is one (9.1 mm is 0.0091 m, as written, not 9.1 * 0.001)."""
    if scale < 1.0:
        inverse = round(1.0 / scale)
        if abs(inverse * scale - 1.0) < 1e-12:
            return float(value) / inverse
    return float(value) * scale
