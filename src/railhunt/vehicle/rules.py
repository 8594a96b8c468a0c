"""The vocabulary of the parameter table: rules, parameter specs, and the ``parameter`` field.

A vehicle parameter is declared once, as a dataclass field whose metadata carries its unit,
rule and meaning (:func:`parameter`); :func:`parameter_specs` reads those fields back as
an ordered mapping name -> :class:`ParameterSpec`.
"""

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, NamedTuple

from railhunt.vehicle.formatting import fmt_value

__all__ = [
    "FINITE",
    "NONNEGATIVE",
    "POSITIVE",
    "DerivedSpec",
    "ParameterSpec",
    "Rule",
    "parameter",
    "parameter_specs",
]


@dataclass(frozen=True)
class Rule:
    """Admissible range of a parameter: always finite, optionally bounded.

    Parameters
    ----------
    lower, upper : float or None
        Bounds (``None``: unbounded on that side).
    lower_strict, upper_strict : bool
        Whether the bound itself is excluded.
    reason : str
        Why the range is what it is (shown in error messages).
    upper_label : str or None
        Text for the upper bound in messages (e.g. ``"pi/2"``).
    """

    lower: float | None = None
    lower_strict: bool = False
    upper: float | None = None
    upper_strict: bool = False
    reason: str = ""
    upper_label: str | None = None

    def accepts(self, value: float) -> bool:
        """Return whether the float ``value`` satisfies the rule."""
        if not math.isfinite(value):
            return False
        if self.lower is not None:
            if value < self.lower or (self.lower_strict and value == self.lower):
                return False
        if self.upper is not None:
            if value > self.upper or (self.upper_strict and value == self.upper):
                return False
        return True

    def __str__(self) -> str:
        lo, hi = self.lower, self.upper
        hi_text = self.upper_label or (fmt_value(hi) if hi is not None else "")
        if lo is None and hi is None:
            text = "finite"
        elif hi is None:
            text = f"finite and {'>' if self.lower_strict else '>='} {fmt_value(lo)}"
        elif lo is None:
            text = f"finite and {'<' if self.upper_strict else '<='} {hi_text}"
        else:
            left = "(" if self.lower_strict else "["
            right = ")" if self.upper_strict else "]"
            text = f"finite and in {left}{fmt_value(lo)}, {hi_text}{right}"
        return f"{text}; {self.reason}" if self.reason else text


FINITE = Rule()
POSITIVE = Rule(lower=0.0, lower_strict=True)
NONNEGATIVE = Rule(lower=0.0)


class ParameterSpec(NamedTuple):
    """Description of one vehicle parameter.

    Attributes
    ----------
    name : str
        Attribute name on :class:`~railhunt.vehicle.Vehicle` and key in vehicle files.
    unit : str
        SI unit (``"1"`` for dimensionless).
    meaning : str
        Physical meaning.
    rule : Rule
        Admissible range; ``str(rule)`` gives the text used in error messages.
    default : float or None
        SI value taken when a complete parameter set (a vehicle file without ``base``, the
        constructor, :func:`~railhunt.vehicle.validate_all`) omits the parameter; ``None``
        (every parameter so far): the parameter must be given. Give one to a parameter added
        after vehicle files existed, so that those files still load.
    """

    name: str
    unit: str
    meaning: str
    rule: Rule
    default: float | None = None


class DerivedSpec(NamedTuple):
    """Description of a derived quantity (computed from parameters, never set).

    Attributes
    ----------
    name, unit, meaning : str
        As for :class:`ParameterSpec`.
    formula : str
        How it is computed, e.g. ``"F_u / C_d1"``.
    change_instead : str
        Which parameter(s) to change to change it.
    rel_tol : float
        Relative tolerance when a vehicle file states the value as a cross-check.
    """

    name: str
    unit: str
    meaning: str
    formula: str
    change_instead: str
    rel_tol: float


_SPEC_KEY = "railhunt.vehicle.parameter"


class _Entry(NamedTuple):
    unit: str
    rule: Rule
    meaning: str
    default: float | None


def parameter(unit: str, rule: Rule, meaning: str, *, default: float | None = None) -> Any:
    """Declare a vehicle parameter as a dataclass field: one line of the parameter table.

    Use as ``M_c: float = parameter("kg", POSITIVE, "Car body mass")`` in the body of a
    ``kw_only`` dataclass; :func:`parameter_specs` reads the declarations back.

    Parameters
    ----------
    unit : str
        SI unit (``"1"`` for dimensionless).
    rule : Rule
        Admissible range.
    meaning : str
        Physical meaning (shown in error messages and tables).
    default : float, optional
        SI value for sets that omit the parameter (see :attr:`ParameterSpec.default`);
        without it the field is required.

    Returns
    -------
    dataclasses.Field
        The field, with the description in its metadata.

    Raises
    ------
    ValueError
        If ``default`` breaks ``rule``.
    """
    if default is not None:
        if isinstance(default, bool) or not rule.accepts(float(default)):
            raise ValueError(f"default {default!r} {unit} breaks the rule: {rule}")
        default = float(default)
    metadata = {_SPEC_KEY: _Entry(unit, rule, meaning, default)}
    if default is None:
        return dataclasses.field(metadata=metadata)
    return dataclasses.field(default=default, metadata=metadata)


def parameter_specs(table: type) -> Mapping[str, ParameterSpec]:
    """The parameters declared with :func:`parameter` in a dataclass, in field order.

    Parameters
    ----------
    table : type
        A dataclass; fields without :func:`parameter` metadata (e.g. ``name``) are skipped.

    Returns
    -------
    Mapping[str, ParameterSpec]
        Read-only, ordered name -> spec.
    """
    specs = {}
    for f in dataclasses.fields(table):
        entry = f.metadata.get(_SPEC_KEY)
        if entry is not None:
            specs[f.name] = ParameterSpec(f.name, entry.unit, entry.meaning, entry.rule,
                                          entry.default)  # fmt: skip
    return MappingProxyType(specs)
