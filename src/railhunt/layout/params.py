"""A layout file's ``[parameters]``: named values with unit, meaning, source and rule.

Short form ``K_py = 1.5e7`` (or an expression of other parameters, ``W_half = "W / 2"``),
or a table with ``value``, ``unit``, ``meaning``, ``source`` and optionally the admissible
range: ``rule`` (one of :data:`NAMED_RULES`), or ``min`` / ``max`` (inclusive) and
``above`` / ``below`` (strict), ``reason`` (shown in messages), ``default`` (taken when a
file that starts from this vehicle leaves the parameter out) and ``greater_than`` (another
parameter this one must exceed, e.g. ``l > l1``). Without a rule a value only has to be
finite.
"""

from __future__ import annotations

import math
from typing import Any

from railhunt.layout.expressions import Expression, ExpressionError, evaluate_parameters
from railhunt.layout.parse import consistency_rule
from railhunt.layout.spec import ConsistencyRule, LayoutError, check_keys
from railhunt.vehicle.rules import FINITE, NONNEGATIVE, POSITIVE, ParameterSpec, Rule

__all__ = ["NAMED_RULES", "PARAMETER_KEYS", "ParameterTable", "parse_parameters", "rule_name"]

#: Rules a parameter table may name with ``rule = "..."``.
NAMED_RULES: dict[str, Rule] = {
    "finite": FINITE,
    "positive": POSITIVE,
    "nonnegative": NONNEGATIVE,
    "contact_half_distance": Rule(lower=0.5, lower_strict=True, upper=1.0,
                                  reason="half the contact-point distance in m (0.7465 for "
                                  "standard gauge)"),  # fmt: skip
    "friction": Rule(lower=0.0, lower_strict=True, upper=1.5,
                     reason="a friction coefficient above 1.5 is not physical"),
    "rolling_radius": Rule(lower=0.2, lower_strict=True, upper=0.7,
                           reason="rolling radius in m (a value in mm is a common mistake)"),
    "contact_angle": Rule(lower=0.0, lower_strict=True, upper=math.pi / 2, upper_strict=True,
                          upper_label="pi/2", reason="a contact angle in rad"),
}
PARAMETER_KEYS = frozenset({"value", "unit", "meaning", "source", "rule", "min", "max",
                            "above", "below", "reason", "default", "greater_than"})  # fmt: skip


def rule_name(rule: Rule) -> str | None:
    """The name of a rule in :data:`NAMED_RULES`, if it is one."""
    for name, known in NAMED_RULES.items():
        if known == rule:
            return name
    return None


class ParameterTable:
    """The parameters of a layout file, read.

    Attributes
    ----------
    specs : dict[str, ParameterSpec]
        Name -> unit, meaning, rule, default, in the file's order.
    sources : dict[str, str]
        Name -> where the value comes from.
    values : dict[str, float]
        Name -> SI value (expressions evaluated).
    consistency : tuple of ConsistencyRule
    """

    def __init__(self, specs: dict[str, ParameterSpec], sources: dict[str, str],
                 values: dict[str, float], consistency: tuple[ConsistencyRule, ...]) -> None:
        self.specs, self.sources, self.values = specs, sources, values
        self.consistency = consistency


def _rule(name: str, entry: dict[str, Any], where: str) -> Rule:
    label = f"{where}: [parameters.{name}]"
    if "rule" in entry:
        rule = NAMED_RULES.get(entry["rule"])
        if rule is None:
            raise LayoutError(f"{label}: rule = {entry['rule']!r} is unknown; use one of "
                              f"{', '.join(NAMED_RULES)}, or min/max/above/below")  # fmt: skip
        return rule
    bounds = {k: entry[k] for k in ("min", "max", "above", "below") if k in entry}
    for k, v in bounds.items():
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise LayoutError(f"{label}: {k} must be a number")
    if "min" in bounds and "above" in bounds or "max" in bounds and "below" in bounds:
        raise LayoutError(f"{label}: give min or above, max or below, not both")
    if not bounds:
        return FINITE
    lower = bounds.get("min", bounds.get("above"))
    upper = bounds.get("max", bounds.get("below"))
    return Rule(lower=None if lower is None else float(lower), lower_strict="above" in bounds,
                upper=None if upper is None else float(upper), upper_strict="below" in bounds,
                reason=str(entry.get("reason", "")))  # fmt: skip


def parse_parameters(table: object, where: str) -> ParameterTable:
    """Read a ``[parameters]`` table of a layout file.

    Raises
    ------
    LayoutError
        Unknown keys, a missing value, a value that is neither a number nor an expression,
        an expression naming an unknown parameter, a cycle of expressions.
    """
    if not isinstance(table, dict):
        raise LayoutError(f"{where}: [parameters] must be a table")
    specs: dict[str, ParameterSpec] = {}
    sources: dict[str, str] = {}
    exprs: dict[str, Expression] = {}
    rules: list[ConsistencyRule] = []
    for name, entry in table.items():
        if not name.isidentifier():
            raise LayoutError(f"{where}: parameter name {name!r} is not a name "
                              "(letters, digits, _)")  # fmt: skip
        if isinstance(entry, dict):
            check_keys(entry, PARAMETER_KEYS, f"{where}: [parameters.{name}]")
            if "value" not in entry:
                raise LayoutError(f"{where}: [parameters.{name}]: missing 'value'")
            value = entry["value"]
            unit, meaning = str(entry.get("unit", "")), str(entry.get("meaning", ""))
            sources[name] = str(entry.get("source", ""))
            rule = _rule(name, entry, where)
            default = entry.get("default")
            rule_c = consistency_rule(name, entry, where)
            if rule_c is not None:
                rules.append(rule_c)
        else:
            value, unit, meaning, rule, default = entry, "", "", FINITE, None
            sources[name] = ""
        try:
            exprs[name] = Expression(value)
        except ExpressionError as exc:
            raise LayoutError(f"{where}: parameter {name!r}: {exc}") from None
        specs[name] = ParameterSpec(name, unit, meaning, rule,
                                    None if default is None else float(default))  # fmt: skip
    try:
        values = evaluate_parameters(exprs)
    except ExpressionError as exc:
        raise LayoutError(f"{where}: {exc}") from None
    return ParameterTable(specs, sources, values, tuple(rules))
