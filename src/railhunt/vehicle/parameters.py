"""The checks of vehicle parameters against the table of :mod:`railhunt.vehicle.table`.

Each vehicle parameter is written once, as a field of
:class:`~railhunt.vehicle.table.VehicleFields` (the fields of
:class:`~railhunt.vehicle.Vehicle`): name, SI unit, rule and meaning on one line,
``M_c: float = parameter("kg", POSITIVE, "Car body mass")``. Everything else follows from
that line: :data:`PARAMETERS` (and so the order of parameters everywhere), the checks of
:func:`validate_value` and :func:`validate_all` here, the attribute of ``Vehicle``, the
keys accepted in vehicle files and the documentation table.

Adding a parameter: one line in the table (in the place where it belongs in the order),
and its value in each shipped vehicle file (``railhunt/data/vehicles/*.toml``). Give it a
``default=`` if vehicle files written before it existed must still load: a complete file
(without ``base``) that lacks it then gets the default.
"""

import numbers
from collections.abc import Mapping

from railhunt.quantities.formatting import fmt_value
from railhunt.quantities.rules import ParameterSpec
from railhunt.vehicle.errors import (
    DerivedParameterError,
    MissingParametersError,
    ParameterError,
    UnknownParameterError,
)

# The table itself (VehicleFields, PARAMETERS, DERIVED, suggest, ...) lives in
# railhunt.vehicle.table, below the error types that name its parameters; its names are
# importable from here as before.
from railhunt.vehicle.table import (  # noqa: F401
    _CONSISTENCY,
    CONTACT_ANGLE,
    CONTACT_HALF_DISTANCE,
    DERIVED,
    FRICTION,
    PARAMETERS,
    ROLLING_RADIUS,
    VehicleFields,
    derived_values,
    suggest,
)

__all__ = [
    "DERIVED",
    "PARAMETERS",
    "VehicleFields",
    "derived_values",
    "missing_parameters",
    "validate_all",
    "validate_with",
    "validate_value",
]

# --------------------------------------------------------------------------- validation


def as_float(name: str, value: object, unit: str | None, meaning: str) -> float:
    """Convert a real number (not bool) to float, or raise :class:`ParameterError`."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ParameterError(
            name, value, f"a real number, not {type(value).__name__}", unit, meaning=meaning
        )
    try:
        return float(value)
    except (OverflowError, ValueError, TypeError):
        raise ParameterError(name, value, "finite", unit, meaning=meaning) from None


def missing_parameters(names: Mapping[str, object]) -> tuple[str, ...]:
    """Parameters absent from ``names`` that have no default, in :data:`PARAMETERS` order.

    Parameters
    ----------
    names : Mapping[str, object]
        A parameter set (only its keys are used).

    Returns
    -------
    tuple of str
    """
    return tuple(n for n, spec in PARAMETERS.items() if n not in names and spec.default is None)


def validate_value(name: str, value: object) -> float:
    """Check one parameter value against its rule.

    Parameters
    ----------
    name : str
        Parameter name (a key of :data:`PARAMETERS`).
    value : object
        Candidate value in the parameter's SI unit: an int or float (not a bool).

    Returns
    -------
    float
        The value as a float.

    Raises
    ------
    UnknownParameterError
        ``name`` is not a parameter.
    DerivedParameterError
        ``name`` is a derived quantity (``v_u`` or ``N``).
    ParameterError
        The value is not a real number, not finite, or out of range.
    """
    if name in DERIVED:
        raise DerivedParameterError(name, value)
    spec = PARAMETERS.get(name)
    if spec is None:
        raise UnknownParameterError(name, value)
    x = as_float(name, value, spec.unit, spec.meaning)
    if not spec.rule.accepts(x):
        raise ParameterError(name, value, str(spec.rule), spec.unit, meaning=spec.meaning)
    return x


def validate_all(params: Mapping[str, object]) -> dict[str, float]:
    """Check a complete parameter set: names, every value, and consistency rules.

    Parameters
    ----------
    params : Mapping[str, object]
        Every name of :data:`PARAMETERS` mapped to its SI value (a parameter with a
        :attr:`~ParameterSpec.default` may be left out: it takes the default).

    Returns
    -------
    dict[str, float]
        The values as floats, in :data:`PARAMETERS` order.

    Raises
    ------
    UnknownParameterError, DerivedParameterError
        A name is not a parameter.
    MissingParametersError
        Some parameters are absent (all of them are listed).
    ParameterError
        A value breaks its rule, or a consistency rule (``l > l1``) is broken.
    """
    for name in params:
        if name not in PARAMETERS:
            if name in DERIVED:
                raise DerivedParameterError(name, params[name])
            raise UnknownParameterError(name, params[name])
    missing = missing_parameters(params)
    if missing:
        raise MissingParametersError(missing)
    given = {name: params[name] if name in params else spec.default
             for name, spec in PARAMETERS.items()}  # fmt: skip
    out = {name: validate_value(name, value) for name, value in given.items()}
    for name, other, predicate, text in _CONSISTENCY:
        if not predicate(out):
            spec = PARAMETERS[name]
            rule = text.format(**{other: fmt_value(out[other])})
            raise ParameterError(name, given[name], rule, spec.unit, meaning=spec.meaning)
    return out


def validate_with(params: Mapping[str, object], specs: Mapping[str, ParameterSpec],
                  consistency: tuple = ()) -> dict[str, float]:  # fmt: skip
    """Check a complete parameter set against a vehicle's own parameter table.

    Like :func:`validate_all`, for any layout: ``specs`` are the layout's parameters and
    ``consistency`` its rules between them (``parameter > other``).

    Parameters
    ----------
    params : Mapping[str, object]
        SI values by name (a parameter with a default may be left out).
    specs : Mapping[str, ParameterSpec]
        The layout's parameters, in order.
    consistency : tuple of ConsistencyRule
        ``(parameter, other, reason)`` rules.

    Returns
    -------
    dict[str, float]
        The values as floats, in ``specs`` order.
    """
    known = tuple(specs)
    for name in params:
        if name not in specs:
            if name in DERIVED:
                raise DerivedParameterError(name, params[name])
            raise UnknownParameterError(name, params[name], known=known)
    missing = tuple(n for n, s in specs.items() if n not in params and s.default is None)
    if missing:
        raise MissingParametersError(missing)
    out: dict[str, float] = {}
    for name, spec in specs.items():
        value = params[name] if name in params else spec.default
        x = as_float(name, value, spec.unit or None, spec.meaning)
        if not spec.rule.accepts(x):
            raise ParameterError(name, value, str(spec.rule), spec.unit or None,
                                 meaning=spec.meaning)  # fmt: skip
        out[name] = x
    for rule in consistency:
        if not out[rule.parameter] > out[rule.other]:
            spec = specs[rule.parameter]
            unit = f" {spec.unit}" if spec.unit and spec.unit != "1" else ""
            text = f"> {rule.other} = {fmt_value(out[rule.other])}{unit}"
            if rule.reason:
                text += f" ({rule.reason})"
            given = params.get(rule.parameter, spec.default)
            raise ParameterError(rule.parameter, given, text, spec.unit, meaning=spec.meaning)
    return out
