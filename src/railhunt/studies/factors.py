"""Factors of a sensitivity study or an optimisation, and what a model is.

A *factor* is a parameter that varies, given as

- a range ``(low, high)`` or ``("uniform", low, high)``: uniform between the two (SI);
- ``("normal", mean, std)``: normally distributed (sensitivity studies only);
- ``("tolerance", t)``: uniform within ``±t`` (a fraction, e.g. 0.1 = ±10 %) of the
  vehicle's value.

A *model* is a :class:`railhunt.Vehicle` (the factors are its parameters, set with
:meth:`Vehicle.replace`, and the outputs are results columns of
:func:`railhunt.sweep`) or a plain Python function of the factors, by keyword, returning
a dict of outputs (so the machinery can be checked on functions with known answers).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from railhunt.studies.store import OUTPUT_COLUMNS, TEXT_COLUMNS
from railhunt.vehicle import UnknownParameterError, Vehicle

#: Results column -> the sweep output that gives it.
COLUMN_OUTPUT = {col: name for name, cols in OUTPUT_COLUMNS.items() for col in cols
                 if col not in TEXT_COLUMNS and col != "frequency_speed_kmh"}  # fmt: skip


@dataclass(frozen=True)
class Factor:
    """One varied parameter.

    Attributes
    ----------
    name : str
        Parameter name (a vehicle parameter, or a keyword of the model function).
    dist : {"uniform", "normal"}
        Its distribution.
    a, b : float
        ``low, high`` (uniform) or ``mean, std`` (normal), SI.
    """

    name: str
    dist: str
    a: float
    b: float

    @property
    def bounds(self) -> tuple[float, float]:
        """``(low, high)`` of a uniform factor."""
        return self.a, self.b

    def describe(self) -> list[Any]:
        """JSON form: ``[dist, a, b]``."""
        return [self.dist, self.a, self.b]


def _number(value: object, what: str) -> float:
    try:
        x = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{what} = {value!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{what} = {value!r} is invalid: must be finite")
    return x


def parse_factor(name: str, spec: object, nominal: Mapping[str, float] | None,
                 allow_normal: bool = True) -> Factor:  # fmt: skip
    """A :class:`Factor` from its specification (module docstring).

    Parameters
    ----------
    name : str
        The factor's name.
    spec : tuple
        ``(low, high)``, ``("uniform", low, high)``, ``("normal", mean, std)`` or
        ``("tolerance", t)``.
    nominal : Mapping, optional
        The vehicle's parameter values (None for a model function: no tolerance then).
    allow_normal : bool
        Whether a normal distribution is accepted (not in an optimisation: it needs bounds).
    """
    items = list(spec) if isinstance(spec, (tuple, list)) else [spec]
    kind = items[0] if items and isinstance(items[0], str) else None
    if kind is None and len(items) == 2:
        kind, items = "uniform", ["uniform", *items]
    if kind == "uniform" and len(items) == 3:
        lo, hi = _number(items[1], f"{name} low"), _number(items[2], f"{name} high")
        if not lo < hi:
            raise ValueError(f"{name} = ({lo:g}, {hi:g}): low must be below high")
        return Factor(name, "uniform", lo, hi)
    if kind == "normal" and len(items) == 3:
        if not allow_normal:
            raise ValueError(f"{name} = {spec!r}: an optimisation needs bounds; give a range "
                             "(low, high) or ('tolerance', t)")  # fmt: skip
        mean, std = _number(items[1], f"{name} mean"), _number(items[2], f"{name} std")
        if not std > 0:
            raise ValueError(f"{name} = ('normal', {mean:g}, {std:g}): std must be > 0")
        return Factor(name, "normal", mean, std)
    if kind == "tolerance" and len(items) == 2:
        if nominal is None:
            raise ValueError(f"{name} = {spec!r}: a tolerance needs a vehicle's value; a model "
                             "function takes ranges or distributions")  # fmt: skip
        t = _number(items[1], f"{name} tolerance")
        if not 0 < t < 1:
            raise ValueError(f"{name} tolerance = {t!r} is invalid: must be a fraction in (0, 1)"
                             ", e.g. 0.1 for ±10 %")  # fmt: skip
        value = float(nominal[name])
        if value == 0:
            raise ValueError(f"{name} = 0 on the vehicle: a tolerance about 0 is empty; give a "
                             "range instead")  # fmt: skip
        lo, hi = sorted((value * (1 - t), value * (1 + t)))
        return Factor(name, "uniform", lo, hi)
    raise ValueError(f"{name} = {spec!r} is invalid: give (low, high), ('uniform', low, high), "
                     "('normal', mean, std) or ('tolerance', t)")  # fmt: skip


def parse_factors(model: object, factors: Mapping[str, object],
                  allow_normal: bool = True) -> list[Factor]:  # fmt: skip
    """Check the factors against the model; a vehicle's names must be its parameters."""
    if not factors:
        raise ValueError("factors is empty: give at least one parameter to vary")
    nominal = model.as_dict() if isinstance(model, Vehicle) else None
    out = []
    for name, spec in factors.items():
        if nominal is not None and name not in nominal:
            raise UnknownParameterError(name, spec, known=tuple(nominal))
        out.append(parse_factor(name, spec, nominal, allow_normal))
    if len(out) < 2 and allow_normal:
        raise ValueError("a sensitivity study needs at least two factors")
    return out


def check_model(model: object) -> None:
    """A model is a Vehicle or a callable."""
    if not (isinstance(model, Vehicle) or callable(model)):
        raise TypeError(f"model = {model!r} is invalid: give a railhunt.Vehicle or a function "
                        "of the factors returning a dict of outputs")  # fmt: skip


def vehicle_outputs(columns: Sequence[str]) -> tuple[str, ...]:
    """The sweep outputs that give the asked results columns (in a stable order)."""
    bad = [c for c in columns if c not in COLUMN_OUTPUT]
    if bad:
        raise ValueError(f"output {bad[0]!r} is not a results column: choose from "
                         f"{', '.join(COLUMN_OUTPUT)}")  # fmt: skip
    return tuple(dict.fromkeys(COLUMN_OUTPUT[c] for c in columns))


def function_task(item: tuple[int, dict[str, float]], function: Callable[..., Mapping[str, Any]],
                  outputs: tuple[str, ...]) -> dict[str, Any]:  # fmt: skip
    """One point of a study on a model function: its row (``status`` failed on an error or
    a missing output)."""
    from railhunt.studies.execute import interrupted
    from railhunt.studies.store import STATUS_FAILED, STATUS_OK

    index, values = item
    row: dict[str, Any] = {"point": index, "line": "function", **values}
    row.update({o: math.nan for o in outputs})
    status, message = STATUS_OK, ""
    try:
        result = function(**values)
        if not isinstance(result, Mapping):
            raise TypeError(f"the model function {function_name(function)} returned "
                            f"{result!r} ({type(result).__name__}), not a mapping of the "
                            f"outputs to their values, e.g. "
                            f"{ {o: 1.0 for o in outputs}!r}")  # fmt: skip
        missing = [o for o in outputs if o not in result]
        if missing:
            raise ValueError(f"the model function {function_name(function)} returned no "
                           f"{missing[0]!r} (it returned {', '.join(map(repr, result))})")
        for o in outputs:
            row[o] = float(result[o])
    except Exception as exc:  # noqa: BLE001 - one bad point must not end a study
        if interrupted(exc):
            raise KeyboardInterrupt from exc
        status, message = STATUS_FAILED, f"{type(exc).__name__}: {exc}"
    row["status"], row["message"] = status, message
    return row


def function_name(function: Callable[..., Any]) -> str:
    """``module.qualname`` of a model function (part of a study's description)."""
    return f"{getattr(function, '__module__', '?')}.{getattr(function, '__qualname__', '?')}"
