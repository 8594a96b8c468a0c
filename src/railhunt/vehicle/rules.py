"""The vocabulary of parameter tables (rules, parameter specs, the ``parameter`` field): kept
importable from here; its home is :mod:`railhunt.quantities.rules`, below both the vehicle
and the layout packages."""

from railhunt.quantities.rules import (
    FINITE,
    NONNEGATIVE,
    POSITIVE,
    DerivedSpec,
    ParameterSpec,
    Rule,
    parameter,
    parameter_specs,
)

__all__ = ["FINITE", "NONNEGATIVE", "POSITIVE", "DerivedSpec", "ParameterSpec", "Rule",
           "parameter", "parameter_specs"]  # fmt: skip
