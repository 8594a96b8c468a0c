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

from railhunt.quantities.formatting import fmt_value

__all__ = [
    "CONTACT_ANGLE",
    "CONTACT_HALF_DISTANCE",
    "FINITE",
    "FRICTION",
    "NAMED_RULES",
    "NONNEGATIVE",
    "POSITIVE",
    "ROLLING_RADIUS",
    "contains",
    "narrower",
    "rule_name",
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

CONTACT_HALF_DISTANCE = Rule(
    lower=0.5,
    lower_strict=True,
    upper=1.0,
    reason="half the contact-point distance in m (0.7465 for standard gauge)",
)
FRICTION = Rule(
    lower=0.0,
    lower_strict=True,
    upper=1.5,
    reason="a friction coefficient above 1.5 is not physical",
)
ROLLING_RADIUS = Rule(
    lower=0.2,
    lower_strict=True,
    upper=0.7,
    reason="rolling radius in m (a value in mm is a common mistake)",
)
CONTACT_ANGLE = Rule(
    lower=0.0,
    lower_strict=True,
    upper=math.pi / 2,
    upper_strict=True,
    upper_label="pi/2",
    reason="a contact angle in rad",
)

#: Rules a layout file's parameter table may name with ``rule = "..."``.
NAMED_RULES: Mapping[str, Rule] = MappingProxyType({
    "finite": FINITE,
    "positive": POSITIVE,
    "nonnegative": NONNEGATIVE,
    "contact_half_distance": CONTACT_HALF_DISTANCE,
    "friction": FRICTION,
    "rolling_radius": ROLLING_RADIUS,
    "contact_angle": CONTACT_ANGLE,
})  # fmt: skip


def rule_name(rule: Rule) -> str | None:
    """The name of a rule in :data:`NAMED_RULES`, if it is one."""
    for name, known in NAMED_RULES.items():
        if known == rule:
            return name
    return None


def narrower(rule: Rule, other: Rule) -> Rule:
    """The rule that both ``rule`` and ``other`` hold: the tighter bound on each side, with
    the reason of the rule that sets it (``rule``'s when both are as tight)."""
    if contains(other, rule):
        return rule
    if contains(rule, other):
        return other
    lo, lo_strict, lo_from = rule.lower, rule.lower_strict, rule
    if other.lower is not None and (lo is None or other.lower > lo
                                    or (other.lower == lo and other.lower_strict)):  # fmt: skip
        lo, lo_strict, lo_from = other.lower, other.lower_strict, other
    hi, hi_strict, hi_label, hi_from = rule.upper, rule.upper_strict, rule.upper_label, rule
    if other.upper is not None and (hi is None or other.upper < hi
                                    or (other.upper == hi and other.upper_strict)):  # fmt: skip
        hi, hi_strict, hi_label, hi_from = (other.upper, other.upper_strict, other.upper_label,
                                            other)  # fmt: skip
    reasons = [r.reason for r in dict.fromkeys((lo_from, hi_from)) if r.reason]
    return Rule(lower=lo, lower_strict=lo_strict, upper=hi, upper_strict=hi_strict,
                reason="; ".join(dict.fromkeys(reasons)), upper_label=hi_label)  # fmt: skip


def contains(outer: Rule, inner: Rule) -> bool:
    """Whether every value ``inner`` accepts is accepted by ``outer``."""
    if outer.lower is not None:
        if inner.lower is None or inner.lower < outer.lower:
            return False
        if inner.lower == outer.lower and outer.lower_strict and not inner.lower_strict:
            return False
    if outer.upper is not None:
        if inner.upper is None or inner.upper > outer.upper:
            return False
        if inner.upper == outer.upper and outer.upper_strict and not inner.upper_strict:
            return False
    return True


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
