"""A layout file's ``[parameters]``: named values with unit, meaning, source and rule.

Short form ``K_py = 1.5e7`` (or an expression of other parameters, ``W_half = "W / 2"``),
or a table with ``value``, ``unit``, ``meaning``, ``source`` and optionally the admissible
range: ``rule`` (one of :data:`NAMED_RULES`), or ``min`` / ``max`` (inclusive) and
``above`` / ``below`` (strict), ``reason`` (shown in messages), ``default`` (taken when a
file that starts from this vehicle leaves the parameter out), ``greater_than`` (another
parameter this one must exceed, e.g. ``l > l1``) and ``allow = true`` (the value may lie
outside the range its use makes plausible: :mod:`railhunt.quantities.meanings`). Without a
rule a value gets the rule of its use in the layout (:mod:`railhunt.layout.checks`).

A ``unit`` is read (:func:`railhunt.quantities.units.parse_unit`): a number given in
another unit than SI (``unit = "kN/m"``) is converted to SI and the parameter's unit is
the SI one; an unknown unit is refused. A value given as an expression of other
parameters is *derived*: its formula is kept (:attr:`ParameterSpec.formula`) and it follows
its inputs wherever they change.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from typing import Any

from railhunt.layout.expressions import Expression, ExpressionError, evaluate_parameters
from railhunt.layout.parse import consistency_rule
from railhunt.layout.spec import ConsistencyRule, LayoutError, check_keys
from railhunt.quantities.rules import (
    FINITE,
    NAMED_RULES,
    ParameterSpec,
    Rule,
    rule_name,
)
from railhunt.quantities.units import UnitError, parse_unit, to_si

__all__ = ["NAMED_RULES", "PARAMETER_KEYS", "ParameterTable", "follow_formulas", "formula",
           "parse_parameters", "rule_name"]  # fmt: skip

PARAMETER_KEYS = frozenset({"value", "unit", "meaning", "source", "rule", "min", "max",
                            "above", "below", "reason", "default", "greater_than",
                            "allow"})  # fmt: skip


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
    stated, allowed : frozenset of str
    formulas : tuple of (str, str)
    """

    def __init__(self, specs: dict[str, ParameterSpec], sources: dict[str, str],
                 values: dict[str, float], consistency: tuple[ConsistencyRule, ...],
                 stated: frozenset[str] = frozenset(),
                 formulas: tuple[tuple[str, str], ...] = (),
                 allowed: frozenset[str] = frozenset()) -> None:  # fmt: skip
        self.specs, self.sources, self.values = specs, sources, values
        self.consistency = consistency
        #: The parameters whose file states their rule (``rule``, ``min``, ``max``, ...).
        self.stated = stated
        #: The derived parameters and their expressions (``LayoutSpec.formulas``).
        self.formulas = formulas
        #: The parameters with ``allow = true`` (``LayoutSpec.allowed``).
        self.allowed = allowed


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
    stated: set[str] = set()
    allowed: set[str] = set()
    formulas: list[tuple[str, str]] = []
    for name, entry in table.items():
        if not name.isidentifier():
            raise LayoutError(f"{where}: parameter name {name!r} is not a name "
                              "(letters, digits, _)")  # fmt: skip
        allow = False
        if isinstance(entry, dict):
            label = f"{where}: [parameters.{name}]"
            check_keys(entry, PARAMETER_KEYS, label)
            if "value" not in entry:
                raise LayoutError(f"{label}: missing 'value'")
            value = entry["value"]
            unit, meaning = str(entry.get("unit", "")), str(entry.get("meaning", ""))
            sources[name] = str(entry.get("source", ""))
            rule = _rule(name, entry, where)
            if {"rule", "min", "max", "above", "below"} & set(entry):
                stated.add(name)
            default = entry.get("default")
            allow = entry.get("allow", False)
            if not isinstance(allow, bool):
                raise LayoutError(f"{label}: allow must be true or false")
            rule_c = consistency_rule(name, entry, where)
            if rule_c is not None:
                rules.append(rule_c)
            if "unit" in entry:
                value, unit, default = _in_si(name, entry, value, default, label)
        else:
            value, unit, meaning, rule, default = entry, "", "", FINITE, None
            sources[name] = ""
        try:
            exprs[name] = Expression(value)
        except ExpressionError as exc:
            raise LayoutError(f"{where}: parameter {name!r}: {exc}") from None
        if exprs[name].names:
            formulas.append((name, str(exprs[name].source)))
        if allow:
            allowed.add(name)
        specs[name] = ParameterSpec(name, unit, meaning, rule,
                                    None if default is None else float(default))  # fmt: skip
    try:
        values = evaluate_parameters(exprs)
    except ExpressionError as exc:
        raise LayoutError(f"{where}: {exc}") from None
    return ParameterTable(specs, sources, values, tuple(rules), frozenset(stated),
                          tuple(formulas), frozenset(allowed))  # fmt: skip


def _in_si(name: str, entry: dict[str, Any], value: object, default: object,
           label: str) -> tuple[object, str, object]:  # fmt: skip
    """A table's value and default in SI, and its unit's SI spelling (a number in kN/m
    becomes N/m); an unknown unit, or an expression given in another unit, is refused."""
    text = entry["unit"]
    if not isinstance(text, str):
        raise LayoutError(f"{label}: unit must be a string, e.g. \"N/m\"")
    try:
        unit = parse_unit(text)
    except UnitError as exc:
        raise LayoutError(f"{label}: {exc}") from None
    if unit.scale == 1.0:
        return value, text, default
    if isinstance(value, str):
        raise LayoutError(f"{label}: value = {value!r} is an expression of other parameters, "
                          f"which are in SI units: give it in {unit.si}, not {text}")  # fmt: skip
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return value, unit.si, default  # refused as a value below, naming it
    if default is not None and not isinstance(default, bool) and isinstance(default,
                                                                             (int, float)):
        default = to_si(default, unit.scale)
    return to_si(value, unit.scale), unit.si, default


@lru_cache(maxsize=1024)
def formula(text: str) -> Expression:
    """The compiled expression of a derived parameter's formula (compiled once)."""
    return Expression(text)


@lru_cache(maxsize=64)
def _formula_order(formulas: tuple[tuple[str, str], ...]) -> tuple[str, ...]:
    """Derived parameters in an order in which each comes after the derived ones it uses."""
    names = dict(formulas)
    order: list[str] = []
    seen: set[str] = set()

    def visit(name: str) -> None:
        if name in seen:
            return
        seen.add(name)
        for dep in sorted(formula(names[name]).names):
            if dep in names:
                visit(dep)
        order.append(name)

    for name in names:
        visit(name)
    return tuple(order)


def follow_formulas(formulas: tuple[tuple[str, str], ...], specs: Mapping[str, ParameterSpec],
                    given: Mapping[str, object]) -> tuple[dict[str, object], tuple[str, ...]]:
    """Every derived parameter computed from its inputs (``LayoutSpec.formulas``).

    Parameters
    ----------
    formulas : tuple of (str, str)
        The derived parameters and their expressions.
    specs : Mapping[str, ParameterSpec]
        A layout's parameters.
    given : Mapping[str, object]
        Values by name; the derived ones may be left out (they are computed). A parameter
        left out takes its default.

    Returns
    -------
    values : dict
        ``given`` with each derived parameter's value: its formula's, or the given one
        where that differs (an override).
    overridden : tuple of str
        The derived parameters whose given value is not their formula's: set directly.

    Raises
    ------
    LayoutError
        A formula cannot be evaluated (a division by zero) from valid inputs.
    """
    out = dict(given)
    if not formulas:
        return out, ()
    texts = dict(formulas)
    done: dict[str, object] = {n: (given[n] if n in given else s.default)
                               for n, s in specs.items() if n not in texts}  # fmt: skip
    overridden: list[str] = []
    for name in _formula_order(formulas):
        expr = formula(texts[name])
        inputs = [done.get(n) for n in expr.names]
        if not all(isinstance(x, float) or (isinstance(x, int) and not isinstance(x, bool))
                   for x in inputs):  # fmt: skip
            done[name] = given.get(name)  # a bad input: the parameter checks name it
            continue
        try:
            value = expr(done)  # type: ignore[arg-type]
        except ExpressionError as exc:
            raise LayoutError(f"parameter {name!r} = {texts[name]!r}: {exc}") from None
        if name in given and given[name] != value:
            done[name] = given[name]
            overridden.append(name)
        else:
            done[name] = value
    for name, _ in formulas:
        if done.get(name) is not None:
            out[name] = done[name]
    return out, tuple(overridden)
