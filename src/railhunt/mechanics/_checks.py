"""One-line validation of scalar and array arguments: ``name = value is invalid: must be ...``."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["check_range", "check_array"]


def check_range(name: str, value: Any, low: float, high: float, unit: str = "",
                low_open: bool = False, high_open: bool = False) -> float:
    """``float(value)`` if it is a finite real number in the range, else ``ValueError``."""
    ok = isinstance(value, int | float | np.integer | np.floating) and not isinstance(
        value, bool) and math.isfinite(value)
    ok = ok and (value > low if low_open else value >= low)
    ok = ok and (value < high if high_open else value <= high)
    if not ok:
        lb = "(" if low_open else "["
        rb = ")" if high_open else "]"
        raise ValueError(f"{name} = {value!r}{(' ' + unit) if unit else ''} is invalid: "
                         f"must be in {lb}{low:g}, {high:g}{rb}")
    return float(value)


def check_array(name: str, value: Any, low: float = -math.inf, high: float = math.inf,
                unit: str = "", low_open: bool = False, high_open: bool = False,
                what: str = "") -> np.ndarray:
    """``value`` as a float array whose every entry is finite and in the range.

    The message names the first offending entry (and its index for an array).
    """
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} is invalid: must be a real number or an "
                         "array of real numbers") from None
    bad = ~np.isfinite(arr)
    bad |= (arr <= low) if low_open else (arr < low)
    bad |= (arr >= high) if high_open else (arr > high)
    if bad.any():
        idx = np.argwhere(bad)[0]
        v = arr[tuple(idx)] if arr.ndim else arr[()]
        where = f"[{', '.join(str(int(i)) for i in idx)}]" if arr.ndim else ""
        if what:
            rule = what
        elif math.isinf(low) and math.isinf(high):
            rule = "finite"
        else:
            lb = "(" if low_open else "["
            rb = ")" if high_open else "]"
            rule = f"finite and in {lb}{low:g}, {high:g}{rb}"
        raise ValueError(f"{name}{where} = {float(v)!r}{(' ' + unit) if unit else ''} is "
                         f"invalid: must be {rule}")
    return arr
