"""Every value of a layout checked by its meaning: rules of sign, plausible ranges, units.

Each numeric value of a layout file (a body's mass, an element's stiffness, a point's
height, a wheel radius) is a *slot* with a :class:`~railhunt.quantities.meanings.Meaning`.
When the file is read, :func:`infer_parameters` gives each parameter that a slot uses
directly (``stiffness = "k1"``) the rule of that use, unless the file states the
parameter's own rule, and checks the units: a parameter's unit, and the unit an expression
of parameters comes out in, must be the slot's. :func:`check_values` checks the values a
vehicle is built with (from the file, ``--set``, ``replace``, a sweep's point) before any
model is assembled: every slot against its rule of sign and its plausible range (waived for
values computed from a parameter with ``allow = true``), each body's inertia against its
mass, and the wheelsets' spacing against their wheels.
"""

from __future__ import annotations

import ast
import dataclasses
import math
from collections.abc import Mapping
from functools import lru_cache
from typing import NamedTuple

from railhunt.layout.expressions import Expression, ExpressionError, _parse
from railhunt.layout.spec import LayoutError, LayoutSpec
from railhunt.quantities.formatting import fmt_value, with_unit
from railhunt.quantities.meanings import (
    GRAVITY,
    INERTIA_RADIUS,
    POINT,
    WHEEL_RAIL,
    Meaning,
    body_meaning,
    element_meaning,
)
from railhunt.quantities.rules import FINITE, ParameterSpec, Rule, contains, narrower
from railhunt.quantities.units import Dimension, UnitError, dimension_text, parse_unit

__all__ = ["Slot", "allow", "check_values", "infer_parameters", "slots"]


class Slot(NamedTuple):
    """One numeric value of a layout: whose it is, its key, its expression, its meaning."""

    owner: str
    key: str
    expr: Expression
    meaning: Meaning

    @property
    def label(self) -> str:
        """``"body 'car' mass"``, ``"[wheel_rail] f11"``."""
        return f"{self.owner} {self.key}"

    @property
    def parameter(self) -> str | None:
        """The parameter the slot is, when its value is a parameter's bare name."""
        src = self.expr.source
        if isinstance(src, str) and len(self.expr.names) == 1:
            (name,) = self.expr.names
            if src.strip() == name:
                return name
        return None


@lru_cache(maxsize=64)
def slots(spec: LayoutSpec) -> tuple[Slot, ...]:
    """Every numeric value of the layout with its meaning, in the file's order."""
    out = [Slot("[vehicle]", "gravity", spec.gravity, GRAVITY)]
    for b in spec.bodies:
        owner = f"body {b.name!r}"
        for key in ("x", "height", "mass", "yaw_inertia", "roll_inertia"):
            expr = getattr(b, key)
            if expr is not None:
                out.append(Slot(owner, key, expr, body_meaning(b.kind, key)))
    for el in spec.elements:
        owner = f"element {el.name!r}"
        points = [("at", el.at)] + ([("at_b", el.at_b)] if el.at_b != el.at else [])
        for key, point in points:
            for coord, expr, meaning in zip("xyz", point, POINT, strict=True):
                out.append(Slot(owner, f"{key} {coord}", expr, meaning))
        for key, expr in el.law:
            out.append(Slot(owner, key, expr, element_meaning(el.kind, el.axis, key)))
    common = dict(spec.wheel_rail)
    for key, value in spec.wheel_rail:
        if isinstance(value, Expression):
            out.append(Slot("[wheel_rail]", key, value, WHEEL_RAIL[key]))
    for w in spec.wheelsets:
        for key, value in w.wheel_rail:
            if isinstance(value, Expression) and common.get(key) != value:
                out.append(Slot(f"wheelset {w.name!r} wheel_rail", key, value,
                                WHEEL_RAIL[key]))  # fmt: skip
    return tuple(out)


# --------------------------------------------------------------------------- units


def _dimension(spec: ParameterSpec) -> Dimension | None:
    if not spec.unit:
        return None
    try:
        return parse_unit(spec.unit).dimension
    except UnitError:
        return None


def _same(a: Dimension, b: Dimension) -> bool:
    return all(abs(x - y) < 1e-9 for x, y in zip(a, b, strict=True))


class _UnitConflict(Exception):
    pass


def _dim_of(node: ast.AST, dims: Mapping[str, Dimension | None]) -> tuple[str, Dimension]:
    """``(kind, dimension)`` of an expression node: kind ``"known"``, ``"number"`` (a pure
    number: dimensionless in a product, of its neighbour's unit in a sum) or
    ``"unknown"`` (it names a parameter without a unit)."""
    none: Dimension = (0.0, 0.0, 0.0)
    if isinstance(node, ast.Constant):
        return "number", none
    if isinstance(node, ast.Name):
        if node.id == "pi":
            return "number", none
        d = dims.get(node.id)
        return ("unknown", none) if d is None else ("known", d)
    if isinstance(node, ast.UnaryOp):
        return _dim_of(node.operand, dims)
    if isinstance(node, ast.Call):
        name = node.func.id  # type: ignore[attr-defined]
        args = [_dim_of(a, dims) for a in node.args]
        if name == "sqrt":
            kind, d = args[0]
            return kind, (d[0] / 2, d[1] / 2, d[2] / 2)
        if name == "abs":
            return args[0]
        return _sum(args)
    assert isinstance(node, ast.BinOp)
    left, right = _dim_of(node.left, dims), _dim_of(node.right, dims)
    if isinstance(node.op, (ast.Add, ast.Sub)):
        return _sum([left, right])
    if isinstance(node.op, (ast.Mult, ast.Div)):
        if "unknown" in (left[0], right[0]):
            return "unknown", none
        if left[0] == right[0] == "number":
            return "number", none
        sign = 1.0 if isinstance(node.op, ast.Mult) else -1.0
        return "known", tuple(a + sign * b for a, b in zip(left[1], right[1], strict=True))  # type: ignore[return-value]
    # a power: a number exponent scales the dimension
    if left[0] == "number":
        return right if right[0] == "unknown" else ("number", none)
    if left[0] == "unknown" or right[0] != "number" or _same(left[1], none):
        return ("unknown", none) if left[0] == "unknown" or right[0] != "number" else left
    try:
        p = float(Expression(ast.unparse(node.right))({}))
    except ExpressionError:
        return "unknown", none
    return "known", (left[1][0] * p, left[1][1] * p, left[1][2] * p)


def _sum(terms: list[tuple[str, Dimension]]) -> tuple[str, Dimension]:
    known = [d for kind, d in terms if kind == "known"]
    for d in known[1:]:
        if not _same(d, known[0]):
            raise _UnitConflict(f"adds {dimension_text(known[0])} to {dimension_text(d)}")
    if any(kind == "unknown" for kind, _ in terms):
        return "unknown", (0.0, 0.0, 0.0)
    return ("known", known[0]) if known else ("number", (0.0, 0.0, 0.0))


def _check_unit(where: str, label: str, expr: Expression, unit: str,
                dims: Mapping[str, Dimension | None], what: str) -> None:  # fmt: skip
    if not isinstance(expr.source, str):
        return
    try:
        kind, dim = _dim_of(_parse(expr.source), dims)
    except _UnitConflict as exc:
        raise LayoutError(f"{where}: {label} = {expr.source!r} {exc}: check the units of "
                          f"its parameters") from None  # fmt: skip
    want = parse_unit(unit).dimension
    if kind == "known" and not _same(dim, want):
        names = ", ".join(f"{n} ({dimension_text(dims[n])})" for n in sorted(expr.names)
                          if dims.get(n) is not None)  # fmt: skip
        raise LayoutError(f"{where}: {label} = {expr.source!r} is in {dimension_text(dim)}, but "
                          f"is {what} ({unit}): check the units of {names}")  # fmt: skip


# --------------------------------------------------------------------------- file


def infer_parameters(spec: LayoutSpec, stated: frozenset[str] = frozenset()) -> LayoutSpec:
    """The layout with its parameters' rules and units as their uses imply them.

    A parameter that a slot uses by its bare name gets, unless it is in ``stated`` (its
    file gives its own rule), the slot's rule of sign and, unless it says ``allow = true``,
    its plausible range; a parameter without a unit gets the slot's. The units of every
    parameter used by name, of every expression and of every formula are checked against
    their slots.

    Raises
    ------
    LayoutError
        A parameter's unit, or the unit an expression comes out in, is not its slot's.
    """
    where = spec.source or "layout"
    specs = {p.name: p for p in spec.parameters}
    dims = {n: _dimension(p) for n, p in specs.items()}
    uses: dict[str, list[Slot]] = {}
    for slot in slots(spec):
        name = slot.parameter
        if name is not None and name in specs:
            uses.setdefault(name, []).append(slot)
            d = dims[name]
            want = parse_unit(slot.meaning.unit).dimension
            if d is not None and not _same(d, want):
                raise LayoutError(f"{where}: parameter {name!r} is given in "
                                  f"{specs[name].unit}, but is {slot.meaning.what} "
                                  f"({slot.meaning.unit}) at {slot.label}: give it in "
                                  f"{slot.meaning.unit}")  # fmt: skip
        else:
            _check_unit(where, slot.label, slot.expr, slot.meaning.unit, dims, slot.meaning.what)
    out = []
    formulas = dict(spec.formulas)
    for name, p in specs.items():
        if name in formulas and p.unit:
            try:
                _check_unit(where, f"parameter {name!r}", Expression(formulas[name]), p.unit,
                            dims, f"given in {p.unit}")  # fmt: skip
            except UnitError:
                pass
        used = uses.get(name, [])
        unit = p.unit or (used[0].meaning.unit if used else "")
        rule = p.rule
        if name not in stated:
            for slot in used:
                rule = narrower(rule, _reasoned(slot.meaning.rule, slot, name))
                if slot.meaning.plausible is not None and name not in spec.allowed:
                    rule = narrower(rule, _reasoned(slot.meaning.plausible, slot, name, True))
        out.append(p._replace(unit=unit, rule=rule))
    inferred = frozenset(n for n, p in zip(specs, out, strict=True) if p.rule != specs[n].rule)
    return dataclasses.replace(spec, parameters=tuple(out), inferred=inferred)


def allow(spec: LayoutSpec, names: frozenset[str] | set[str]) -> LayoutSpec:
    """The layout with ``names`` allowed outside their plausible ranges (``allow =
    true``): a parameter whose rule came from its uses keeps only their rules of sign."""
    allowed = spec.allowed | frozenset(names)
    if allowed == spec.allowed:
        return spec
    uses: dict[str, list[Slot]] = {}
    for slot in slots(spec):
        if slot.parameter in names:
            uses.setdefault(slot.parameter, []).append(slot)
    parameters = []
    for p in spec.parameters:
        if p.name in names and p.name in spec.inferred:
            rule = FINITE
            for slot in uses.get(p.name, []):
                rule = narrower(rule, _reasoned(slot.meaning.rule, slot, p.name))
            p = p._replace(rule=rule)
        parameters.append(p)
    return dataclasses.replace(spec, parameters=tuple(parameters), allowed=allowed)


def _reasoned(rule: Rule, slot: Slot, name: str, plausible: bool = False) -> Rule:
    """The rule with the parameter's use in its reason (``...; k1 is the stiffness of
    element 'x'``) and, for a plausible range, how to take another value on purpose."""
    use = f"{name} is the {slot.key} of {slot.owner}"
    if plausible:
        use += f"; allow = true in [parameters.{name}] takes another value on purpose"
    reason = f"{rule.reason} ({use})" if rule.reason else use
    return dataclasses.replace(rule, reason=reason)


# --------------------------------------------------------------------------- values


class _Check(NamedTuple):
    """One distinct expression of a layout's slots, with the range that all its slots'
    rules (and plausible ranges, unless allowed) accept: the fast path of a check."""

    expr: Expression
    rule: Rule
    slots: tuple[Slot, ...]


def _plan(spec: LayoutSpec) -> tuple[_Check, ...]:
    """The checks of a layout's values, made once and kept on the layout: each distinct
    expression once, with the narrowest range its slots accept; a slot that is a bare
    parameter whose own rule already implies the slot's rules (a rule inferred from its
    uses) is left to the parameter's check."""
    plan = spec.__dict__.get("_checks")
    if plan is not None:
        return plan
    specs = spec.specs
    grouped: dict[Expression, list[Slot]] = {}
    for slot in slots(spec):
        name = slot.parameter
        allowed = bool(spec.allowed & slot.expr.names)
        if name is not None and name in specs:
            own = specs[name].rule
            m = slot.meaning
            if contains(m.rule, own) and (m.plausible is None or allowed
                                          or contains(m.plausible, own)):  # fmt: skip
                continue
        grouped.setdefault(slot.expr, []).append(slot)
    out = []
    for expr, group in grouped.items():
        rule = FINITE
        for slot in group:
            rule = narrower(rule, slot.meaning.rule)
            if slot.meaning.plausible is not None and not spec.allowed & expr.names:
                rule = narrower(rule, slot.meaning.plausible)
        out.append(_Check(expr, rule, tuple(group)))
    plan = tuple(out)
    object.__setattr__(spec, "_checks", plan)
    return plan


def check_values(spec: LayoutSpec, values: Mapping[str, float]) -> None:
    """Check the values a vehicle of this layout is built with, before any assembly.

    Raises
    ------
    LayoutError
        A slot's value breaks its rule of sign, or lies outside its plausible range and no
        parameter it is computed from says ``allow = true``; a body's inertia is
        implausible for its mass; two wheelsets are closer than their wheels' radii
        together; an element mirrored at y = 0.
    """
    where = spec.source or "layout"
    for check in _plan(spec):
        try:
            x = check.expr(values)
        except ExpressionError as exc:
            raise LayoutError(f"{where}: {check.slots[0].label}: {exc}") from None
        if not check.rule.accepts(x):
            _refuse(spec, where, check, x)
    for b in spec.bodies:
        radius = INERTIA_RADIUS.get(b.kind)
        if radius is None or b.mass is None:
            continue
        for key in ("yaw_inertia", "roll_inertia"):
            expr = getattr(b, key)
            if expr is None or spec.allowed & (expr.names | b.mass.names):
                continue
            mass, inertia = b.mass(values), expr(values)
            rg = math.sqrt(inertia / mass) if mass > 0 and inertia > 0 else math.nan
            if not radius.accepts(rg):
                raise LayoutError(
                    f"{where}: body {b.name!r}: {key} = {with_unit(inertia, 'kg*m^2')} is "
                    f"implausible for its mass of {with_unit(mass, 'kg')}: its radius of "
                    f"gyration sqrt(J/m) = {rg:.3g} m is outside {_span(radius)} m "
                    f"({radius.reason}; an inertia in t*m^2 is a common mistake); to use it "
                    "on purpose, give it as a parameter with allow = true")  # fmt: skip
    for el in spec.elements:
        if el.mirrored and el.name.endswith(" left") and el.at[1](values) == 0.0 and (
                el.at_b[1](values) == 0.0):  # fmt: skip
            raise LayoutError(f"{where}: element {el.name[:-5]!r}: mirror = true at y = 0 would "
                              "put the element twice in the same place (twice its stiffness "
                              "or damping): give its whole value once without mirror, or its "
                              "points' y (the left one; the mirror is at -y)")  # fmt: skip
    _check_spacing(spec, values, where)


def _refuse(spec: LayoutSpec, where: str, check: _Check, x: float) -> None:
    """The message of the first slot whose rule (or plausible range) ``x`` breaks."""
    for slot in check.slots:
        m = slot.meaning
        if not m.rule.accepts(x):
            raise LayoutError(_message(where, slot, x, m.rule, "is invalid: must be"))
    for slot in check.slots:
        m = slot.meaning
        if m.plausible is not None and not m.plausible.accepts(x):
            raise LayoutError(_message(where, slot, x, m.plausible, "is implausible: must be")
                              + _ALLOW(slot))  # fmt: skip
    raise LayoutError(f"{where}: {check.slots[0].label} = {x!r} is invalid")  # not reached


def _check_spacing(spec: LayoutSpec, values: Mapping[str, float], where: str) -> None:
    ws = spec.wheelsets
    pos = []
    for w in ws:
        data = spec.wheel_rail_of(w)
        r = data.get("radius")
        pos.append((w.name, w.x(values), r(values) if isinstance(r, Expression) else 0.0))
    for i in range(len(pos)):
        for j in range(i + 1, len(pos)):
            (a, xa, ra), (b, xb, rb) = pos[i], pos[j]
            if abs(xa - xb) < ra + rb:
                raise LayoutError(f"{where}: wheelsets {a!r} (x = {fmt_value(xa)} m) and {b!r} "
                                  f"(x = {fmt_value(xb)} m) are {fmt_value(abs(xa - xb))} m "
                                  f"apart, less than their wheels' radii together "
                                  f"({ra + rb:.3g} m): their wheels would overlap; give each "
                                  "wheelset its own x")  # fmt: skip


def _span(rule: Rule) -> str:
    return str(Rule(lower=rule.lower, lower_strict=rule.lower_strict, upper=rule.upper,
                    upper_strict=rule.upper_strict, upper_label=rule.upper_label)
               ).replace("finite and ", "")  # fmt: skip


def _message(where: str, slot: Slot, x: float, rule: Rule, verb: str) -> str:
    """``"file: body 'bogie1': mass = -3000.0 is invalid: must be > 0 kg (mass = '-M_t',
    a bogie frame's mass; a mass or inertia is positive)"``."""
    unit = slot.meaning.unit
    shown = repr(x)
    bound = _span(rule) + ("" if unit in ("1", "") or rule == FINITE else f" {unit}")
    written = slot.expr.source
    how = [f"{slot.key} = {written!r}"] if isinstance(written, str) else []
    how.append(slot.meaning.what)
    reason = f"; {rule.reason}" if rule.reason else ""
    return (f"{where}: {slot.owner}: {slot.key} = {shown} {verb} {bound} "
            f"({', '.join(how)}{reason})")


def _ALLOW(slot: Slot) -> str:  # noqa: N802 (a sentence)
    name = slot.parameter
    if name is not None:
        return (f"; to use it on purpose, allow it: `allow = true` in [parameters.{name}] of "
                f"the file, `--allow {name}` on the command line or "
                f"`Vehicle.allowing({name!r})`")
    return ("; to use it on purpose, compute it from a parameter that is allowed "
            "(`allow = true` in its [parameters] table)")
