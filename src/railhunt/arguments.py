"""The types of the public functions' arguments, checked where they enter.

A wrong type given to a public function (``duration='1'``, ``critical_speed('paper2019')``,
``curve='4000'``) would otherwise travel until some attribute or operator deep inside
fails on it. These checks raise :class:`ArgumentTypeError` at the door instead, naming
the argument, the value, its type and what to give. It is a ``TypeError`` and, for the
callers that already catch invalid inputs as ``ValueError``, a ``ValueError`` too.
"""

from __future__ import annotations

import numbers
from collections.abc import Callable
from typing import Any

__all__ = ["ArgumentTypeError", "check_curve", "check_real", "check_vehicle"]


class ArgumentTypeError(TypeError, ValueError):
    """An argument of the wrong type: the message names it, its value and what to give."""


def _shown(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def check_real(name: str, value: Any, unit: str = "") -> float:
    """``value`` as a float if it is a real number (not a bool, not a string).

    Raises
    ------
    ArgumentTypeError
        E.g. ``duration = '1' is a str, not a number (s): give duration=1.0``.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        hint = ""
        if isinstance(value, str):
            try:
                hint = f": give {name}={float(value)!r}"
            except ValueError:
                hint = ""
        raise ArgumentTypeError(f"{name} = {_shown(value)} is a {type(value).__name__}, not a "
                                f"number{f' ({unit})' if unit else ''}{hint}")  # fmt: skip
    return float(value)


def check_vehicle(value: Any, name: str = "vehicle") -> Any:
    """``value`` if it is a :class:`railhunt.Vehicle`.

    Raises
    ------
    ArgumentTypeError
        Naming what was given; a string is taken for the name of a vehicle or a file.
    """
    from railhunt.vehicle import Vehicle

    if isinstance(value, Vehicle):
        return value
    hint = ("railhunt.Vehicle.paper2019() for the paper's vehicle, or "
            "railhunt.load_vehicle(PATH) for a vehicle file")  # fmt: skip
    if isinstance(value, str) and value.lower().endswith(".toml"):
        hint = f"the vehicle of that file, railhunt.load_vehicle({value!r})"
    elif isinstance(value, str):
        hint = ("a vehicle, not its name: railhunt.Vehicle.paper2019() for the paper's, or "
                "railhunt.load_vehicle(PATH) for a vehicle file")  # fmt: skip
    raise ArgumentTypeError(f"{name} = {_shown(value)} is a {type(value).__name__}, not a "
                            f"railhunt.Vehicle: give {hint}")  # fmt: skip


def check_curve(value: Any, name: str = "curve", *, speed_dependent: bool = False) -> Any:
    """``value`` if it is None, a :class:`railhunt.Curve` or (``speed_dependent``) a
    callable returning one for a speed.

    Raises
    ------
    ArgumentTypeError
        A radius given as a number or a string, or anything else.
    """
    from railhunt.curve import Curve

    if value is None or isinstance(value, Curve):
        return value
    if speed_dependent and isinstance(value, Callable) and not isinstance(value, type):
        return value
    what = "a railhunt.Curve" + (" (or a function of the speed returning one)"
                                 if speed_dependent else "")  # fmt: skip
    hint = ""
    try:
        radius = float(value)
    except (TypeError, ValueError):
        radius = None
    if radius is not None and not isinstance(value, bool):
        hint = f": for a curve of radius {radius:g} m give railhunt.Curve(radius={radius!r})"
    raise ArgumentTypeError(f"{name} = {_shown(value)} is a {type(value).__name__}, not "
                            f"{what}{hint}")  # fmt: skip
