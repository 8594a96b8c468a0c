"""A complete layout file from a vehicle (:meth:`railhunt.vehicle.Vehicle.to_toml`).

Every parameter in table form (value, unit, meaning, source, rule; a derived parameter's
value is its formula, and ``allow = true`` is kept), the ``[wheel_rail]``
table, every body and every element (mirrored elements written out as two), so that the
file loads back to the same numbers, bit for bit: values are written with ``repr`` and
expressions as they were read.
"""

from __future__ import annotations

from typing import Any

from railhunt.layout.expressions import Expression
from railhunt.layout.params import rule_name
from railhunt.quantities.formatting import toml_string

__all__ = ["layout_toml"]


def _value(v: object) -> str:
    if isinstance(v, Expression):
        v = v.source
    if isinstance(v, str):
        return toml_string(v)
    return repr(float(v))  # type: ignore[arg-type]


def _point(p: tuple[Expression, ...]) -> str:
    return "[" + ", ".join(_value(e) for e in p) + "]"


def layout_toml(vehicle: Any) -> str:
    """The text of a complete layout file for ``vehicle``."""
    layout = vehicle.layout
    sources = dict(layout.sources)
    above = {r.parameter: r for r in layout.consistency}
    lines = [
        "# railhunt layout file (written by railhunt.vehicle.Vehicle.to_toml).",
        "# SI units throughout. Each parameter: value (SI), unit, meaning, source, rule.",
        "",
        "[vehicle]",
        f"name = {toml_string(vehicle.name)}",
        f"description = {toml_string(vehicle.description)}",
        f"gravity = {_value(layout.gravity)}",
    ]
    if layout.citation:
        lines.append(f"source = {toml_string(layout.citation)}")
    formulas = dict(layout.formulas)
    for spec in layout.parameters:
        value = (toml_string(formulas[spec.name]) if spec.name in formulas
                 else repr(float(vehicle.values[spec.name])))  # fmt: skip
        lines += ["", f"[parameters.{spec.name}]", f"value = {value}"]
        if spec.name in layout.allowed:
            lines.append("allow = true")
        if spec.unit:
            lines.append(f"unit = {toml_string(spec.unit)}")
        if spec.meaning:
            lines.append(f"meaning = {toml_string(spec.meaning)}")
        if sources.get(spec.name):
            lines.append(f"source = {toml_string(sources[spec.name])}")
        name = "finite" if spec.name in layout.inferred else rule_name(spec.rule)
        if name is not None:
            if name != "finite":
                lines.append(f"rule = {toml_string(name)}")
        else:
            r = spec.rule
            if r.lower is not None:
                lines.append(f"{'above' if r.lower_strict else 'min'} = {r.lower!r}")
            if r.upper is not None:
                lines.append(f"{'below' if r.upper_strict else 'max'} = {r.upper!r}")
            if r.reason:
                lines.append(f"reason = {toml_string(r.reason)}")
        if spec.default is not None:
            lines.append(f"default = {spec.default!r}")
        if spec.name in above:
            lines.append(f"greater_than = {toml_string(above[spec.name].other)}")
            if above[spec.name].reason:
                lines.append(f"reason = {toml_string(above[spec.name].reason)}")
    lines += ["", "[wheel_rail]"]
    lines += [f"{k} = {_value(v)}" for k, v in layout.wheel_rail]
    for b in layout.bodies:
        lines += ["", "[[body]]", f"name = {toml_string(b.name)}",
                  f"kind = {toml_string(b.kind)}", f"tag = {toml_string(b.tag)}",
                  f"x = {_value(b.x)}", f"height = {_value(b.height)}"]  # fmt: skip
        for key in ("mass", "yaw_inertia", "roll_inertia"):
            expr = getattr(b, key)
            if expr is not None:
                lines.append(f"{key} = {_value(expr)}")
        lines.append("coordinates = [" + ", ".join(toml_string(c) for c in b.coordinates) + "]")
        if b.wheel_rail:
            inner = ", ".join(f"{k} = {_value(v)}" for k, v in b.wheel_rail)
            lines.append(f"wheel_rail = {{{inner}}}")
    for el in layout.elements:
        lines += ["", "[[element]]", f"name = {toml_string(el.name)}",
                  f"kind = {toml_string(el.kind)}",
                  f"bodies = [{toml_string(el.body_a)}, {toml_string(el.body_b)}]",
                  f"axis = {toml_string(el.axis)}", f"at = {_point(el.at)}"]  # fmt: skip
        if el.at_b != el.at:
            lines.append(f"at_b = {_point(el.at_b)}")
        lines += [f"{k} = {_value(v)}" for k, v in el.law]
    if vehicle.contact is not None:
        lines += vehicle.contact.toml_lines()
    return "\n".join(lines) + "\n"
