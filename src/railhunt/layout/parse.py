"""Reading a layout file's ``[[body]]``, ``[[element]]`` and ``[wheel_rail]`` tables.

:func:`parse_layout` checks everything a layout can get wrong before any computation and
raises one :class:`~railhunt.layout.spec.LayoutError` naming the body, element or key and
what to do: unknown kinds or axes, duplicate names, unknown bodies, an element joining a
body to itself, a law with missing values, a wheelset without wheel/rail data, values
that are neither numbers nor expressions. Names of parameters and free modes are checked
with the values (:func:`railhunt.layout.assembly.check_layout`).
"""

from __future__ import annotations

from typing import Any

from railhunt.layout.expressions import Expression, ExpressionError
from railhunt.layout.spec import (
    AXES,
    BODY_KINDS,
    COORDINATES,
    LAWS,
    TRACK,
    BodySpec,
    ConsistencyRule,
    ElementSpec,
    LayoutError,
    LayoutSpec,
    check_keys,
)

__all__ = ["BODY_KEYS", "CONTACT_MECHANICS", "ELEMENT_KEYS", "WHEEL_RAIL_KEYS", "parse_layout"]

BODY_KEYS = frozenset({"name", "kind", "x", "height", "mass", "yaw_inertia", "roll_inertia",
                       "coordinates", "tag", "wheel_rail"})  # fmt: skip
ELEMENT_KEYS = frozenset({"name", "kind", "bodies", "axis", "at", "at_b", "mirror",
                          "stiffness", "damping", "damping2", "blowoff_force", "gap",
                          "stiffness3"})  # fmt: skip
#: Keys of ``[wheel_rail]`` (and of a wheelset's ``wheel_rail``): strings, then numbers.
WHEEL_RAIL_TEXT = ("contact", "creep_law", "contact_mechanics")
WHEEL_RAIL_NUMBERS = ("half_gauge", "radius", "f11", "f22", "f23", "f33", "mu", "load",
                      "axle_load", "lambda1", "lambda2", "lambda3", "lambda4", "lambda5",
                      "d0", "d1", "d4", "d5", "delta_max", "conicity",
                      "contact_angle", "shear_modulus", "poisson")  # fmt: skip
#: Contact mechanics: the vehicle's coefficients at the centred contact (scaled by the
#: load in curves), or each contact point's own ellipse, coefficients and normal force, or
#: up to two patches per wheel with their own (two-point contact, over y and yaw).
CONTACT_MECHANICS = ("centred", "per-point", "two-point")
WHEEL_RAIL_KEYS = frozenset(WHEEL_RAIL_TEXT + WHEEL_RAIL_NUMBERS)
#: Contact descriptions and the keys each needs.
CONTACTS: dict[str, tuple[str, ...]] = {
    "polynomial": ("lambda1",),
    "conical": ("conicity",),
    "profiles": (),
}
#: Keys every wheelset needs (after the common table and its own are merged).
WHEEL_RAIL_REQUIRED = ("half_gauge", "radius", "f11", "f22", "f23", "f33", "mu")
_TAG_PREFIX = {"car": "c", "frame": "t", "wheelset": "w"}
_COORDINATE_OF = {"mass": "y", "yaw_inertia": "psi", "roll_inertia": "phi"}


def _expr(value: object, where: str) -> Expression:
    try:
        return Expression(value)  # type: ignore[arg-type]
    except ExpressionError as exc:
        raise LayoutError(f"{where}: {exc}") from None


def parse_layout(data: dict[str, Any], where: str) -> LayoutSpec:
    """The layout of a parsed layout file.

    Parameters
    ----------
    data : dict
        The TOML document (``body``, ``element``, ``wheel_rail``, ``vehicle`` tables).
    where : str
        The file, for messages.

    Returns
    -------
    LayoutSpec

    Raises
    ------
    LayoutError
        The first problem found, naming the body, element or key.
    """
    bodies = _bodies(data.get("body"), where)
    names = {b.name for b in bodies}
    elements = _elements(data.get("element", []), names, where)
    common = _wheel_rail(data.get("wheel_rail", {}), f"{where}: [wheel_rail]")
    wheelsets = [b for b in bodies if b.kind == "wheelset"]
    if not wheelsets:
        raise LayoutError(f"{where}: the layout has no wheelset: add a [[body]] with "
                          'kind = "wheelset" (a vehicle runs on wheelsets)')  # fmt: skip
    for ws in wheelsets:
        merged = {**dict(common), **dict(ws.wheel_rail)}
        missing = [k for k in WHEEL_RAIL_REQUIRED if k not in merged]
        contact = merged.get("contact", "polynomial")
        if contact not in CONTACTS:
            raise LayoutError(f"{where}: wheelset {ws.name!r}: contact = {contact!r} is "
                              f"unknown; use one of {', '.join(CONTACTS)}")  # fmt: skip
        missing += [k for k in CONTACTS[contact] if k not in merged]
        mechanics = merged.get("contact_mechanics", "centred")
        if mechanics not in CONTACT_MECHANICS:
            raise LayoutError(f"{where}: wheelset {ws.name!r}: contact_mechanics = "
                              f"{mechanics!r} is unknown; use one of "
                              f"{', '.join(CONTACT_MECHANICS)}")  # fmt: skip
        if mechanics in ("per-point", "two-point") and contact != "profiles":
            raise LayoutError(f"{where}: wheelset {ws.name!r}: contact_mechanics = "
                              f"{mechanics!r} needs contact = 'profiles' (the ellipses come "
                              f"from the profiles' curvatures), not {contact!r}")  # fmt: skip
        if merged.get("creep_law") == "exact-table" and mechanics == "centred":
            raise LayoutError(f"{where}: wheelset {ws.name!r}: creep_law = 'exact-table' "
                              "needs contact_mechanics = 'per-point' or 'two-point' (it "
                              "reads each contact's own ellipse)")  # fmt: skip
        if missing:
            raise LayoutError(
                f"{where}: wheelset {ws.name!r} has no wheel/rail data for "
                f"{', '.join(missing)}: give them in [wheel_rail] or in its own "
                f"wheel_rail = {{...}}"
            )
    meta = data.get("vehicle", {})
    gravity = _expr(meta.get("gravity", 9.81), f"{where}: [vehicle] gravity")
    return LayoutSpec(bodies=tuple(bodies), elements=tuple(elements), wheel_rail=common,
                      gravity=gravity, consistency=(), source=where,
                      citation=str(meta.get("source", "")))  # fmt: skip


def _bodies(table: object, where: str) -> list[BodySpec]:
    if not isinstance(table, list) or not table:
        raise LayoutError(f"{where}: no [[body]] tables: a layout needs its bodies")
    out: list[BodySpec] = []
    counts: dict[str, int] = {}
    seen: set[str] = set()
    for k, entry in enumerate(table):
        if not isinstance(entry, dict):
            raise LayoutError(f"{where}: [[body]] number {k + 1} is not a table")
        label = f"{where}: [[body]] {entry.get('name', f'number {k + 1}')!r}"
        check_keys(entry, BODY_KEYS, label)
        name = entry.get("name")
        if not isinstance(name, str) or not name.isidentifier():
            raise LayoutError(f"{label}: needs a name (letters, digits, _)")
        if name in seen or name == TRACK:
            raise LayoutError(f"{label}: the name {name!r} is "
                              f"{'taken' if name in seen else 'reserved for the rails'}: "
                              "give each body its own name")  # fmt: skip
        seen.add(name)
        kind = entry.get("kind")
        if kind not in BODY_KINDS:
            raise LayoutError(f"{label}: kind = {kind!r} is unknown; use one of "
                              f"{', '.join(BODY_KINDS)}")  # fmt: skip
        coords = entry.get("coordinates", BODY_KINDS[kind])
        if (not isinstance(coords, (list, tuple)) or any(c not in COORDINATES for c in coords)
                or len(set(coords)) != len(coords)):  # fmt: skip
            raise LayoutError(f"{label}: coordinates = {coords!r}: each of "
                              f"{', '.join(COORDINATES)} at most once")  # fmt: skip
        if kind == "wheelset" and tuple(coords) != ("y", "psi"):
            raise LayoutError(f"{label}: a wheelset has coordinates y and psi")
        coords = tuple(c for c in COORDINATES if c in coords)
        needs = {"mass": "y" in coords, "yaw_inertia": "psi" in coords,
                 "roll_inertia": "phi" in coords}  # fmt: skip
        values: dict[str, Expression | None] = {}
        for key, needed in needs.items():
            if key in entry:
                values[key] = _expr(entry[key], f"{label}: {key}")
            elif needed:
                raise LayoutError(f"{label}: needs {key} (it has coordinate "
                                  f"{_COORDINATE_OF[key]})")  # fmt: skip
            else:
                values[key] = None
        for key in ("x", "height"):
            if key not in entry:
                raise LayoutError(f"{label}: needs {key} (m)")
        own = entry.get("wheel_rail", {})
        if own and kind != "wheelset":
            raise LayoutError(f"{label}: only a wheelset has wheel_rail data")
        tag = entry.get("tag")
        if tag is None and coords:
            prefix = _TAG_PREFIX.get(kind, "b")
            counts[prefix] = counts.get(prefix, 0) + 1
            tag = f"{prefix}{counts[prefix]}"
        out.append(BodySpec(
            name=name, kind=kind, tag=str(tag or ""), x=_expr(entry["x"], f"{label}: x"),
            height=_expr(entry["height"], f"{label}: height"), mass=values["mass"],
            yaw_inertia=values["yaw_inertia"], roll_inertia=values["roll_inertia"],
            coordinates=coords, wheel_rail=_wheel_rail(own, f"{label}: wheel_rail"),
        ))  # fmt: skip
    # A single car body is "c" (y_c, psi_c, phi_c), as in the paper.
    cars = [b for b in out if b.kind == "car" and b.tag == "c1"]
    if counts.get("c") == 1 and len(cars) == 1:
        out[out.index(cars[0])] = BodySpec(**{**cars[0].__dict__, "tag": "c"})
    tags = [b.tag for b in out if b.coordinates]
    dup = {t for t in tags if tags.count(t) > 1}
    if dup:
        raise LayoutError(f"{where}: two bodies share the coordinate tag(s) {sorted(dup)}: "
                          "give each body its own tag")  # fmt: skip
    return out


def _elements(table: object, bodies: set[str], where: str) -> list[ElementSpec]:
    if not isinstance(table, list):
        raise LayoutError(f"{where}: [[element]] must be an array of tables")
    out: list[ElementSpec] = []
    seen: set[str] = set()
    for k, entry in enumerate(table):
        if not isinstance(entry, dict):
            raise LayoutError(f"{where}: [[element]] number {k + 1} is not a table")
        label = f"{where}: [[element]] {entry.get('name', f'number {k + 1}')!r}"
        check_keys(entry, ELEMENT_KEYS, label)
        kind = entry.get("kind")
        if kind not in LAWS:
            raise LayoutError(f"{label}: kind = {kind!r} is unknown; use one of "
                              f"{', '.join(LAWS)}")  # fmt: skip
        pair = entry.get("bodies")
        if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(p, str)
                                                                  for p in pair)):
            raise LayoutError(f"{label}: bodies must be two body names, e.g. "
                              '["bogie1", "wheelset1"]')  # fmt: skip
        a, b = pair
        for body in (a, b):
            if body not in bodies and not (body == TRACK and body is b):
                hint = " (the rails are \"track\", as the second body)" if body == TRACK else ""
                raise LayoutError(f"{label}: unknown body {body!r}{hint}; bodies are: "
                                  f"{', '.join(sorted(bodies))}")  # fmt: skip
        if a == b:
            raise LayoutError(f"{label}: joins body {a!r} to itself: name two bodies")
        axis = entry.get("axis")
        if axis not in AXES[kind]:
            raise LayoutError(f"{label}: axis = {axis!r} is invalid for a {kind}; use one "
                              f"of {', '.join(AXES[kind])}")  # fmt: skip
        required, optional = LAWS[kind]
        missing = [key for key in required if key not in entry]
        if missing:
            raise LayoutError(f"{label}: a {kind} needs {', '.join(required)}; missing "
                              f"{', '.join(missing)}")  # fmt: skip
        extra = {"stiffness", "damping", "damping2", "blowoff_force", "gap", "stiffness3"}
        extra -= set(required) | set(optional)
        stray = sorted(extra & set(entry))
        if stray:
            raise LayoutError(f"{label}: a {kind} has no {', '.join(stray)}")
        law = tuple((key, _expr(entry.get(key, optional.get(key)), f"{label}: {key}"))
                    for key in (*required, *optional))  # fmt: skip
        at = _point(entry.get("at", [0.0, 0.0, 0.0]), f"{label}: at")
        at_b = _point(entry["at_b"], f"{label}: at_b") if "at_b" in entry else at
        name = entry.get("name") or f"{kind} {axis} {a}-{b}"
        mirror = entry.get("mirror", False)
        if not isinstance(mirror, bool):
            raise LayoutError(f"{label}: mirror must be true or false")
        if mirror and _on_centre_line(at) and _on_centre_line(at_b):
            raise LayoutError(f"{label}: mirror = true at y = 0 would put the element twice in "
                              "the same place (twice its stiffness or damping): give its "
                              "whole value once without mirror, or its points' y (the left "
                              "one; the mirror is at -y)")  # fmt: skip
        copies = [(name + (" left" if mirror else ""), at, at_b)]
        if mirror:
            copies.append((name + " right", _mirrored(at), _mirrored(at_b)))
        for nm, p, pb in copies:
            if entry.get("name") and nm in seen:
                raise LayoutError(f"{label}: the name {nm!r} is taken: give each element "
                                  "its own name")  # fmt: skip
            seen.add(nm)
            out.append(ElementSpec(name=nm, kind=kind, body_a=a, body_b=b, axis=axis, at=p,
                                   at_b=pb, law=law, mirrored=mirror))  # fmt: skip
    return out


def _point(value: object, where: str) -> tuple[Expression, Expression, Expression]:
    if not isinstance(value, list) or len(value) != 3:
        raise LayoutError(f"{where}: must be [x, y, z] (m, vehicle coordinates)")
    x, y, z = (_expr(v, where) for v in value)
    return (x, y, z)


def _on_centre_line(p: tuple[Expression, Expression, Expression]) -> bool:
    """Whether the point's y is the number 0 (an expression is checked with its values)."""
    return p[1].is_constant and p[1]({}) == 0.0


def _mirrored(p: tuple[Expression, Expression, Expression]) -> tuple[Expression, ...]:
    y = p[1]
    if isinstance(y.source, float):
        return (p[0], Expression(-y.source), p[2])
    return (p[0], Expression(f"-({y.source})"), p[2])


def _wheel_rail(table: object, where: str) -> tuple[tuple[str, object], ...]:
    if not isinstance(table, dict):
        raise LayoutError(f"{where}: must be a table")
    check_keys(table, WHEEL_RAIL_KEYS, where)
    out: list[tuple[str, object]] = []
    for key, value in table.items():
        if key in WHEEL_RAIL_TEXT:
            if not isinstance(value, str):
                raise LayoutError(f"{where}: {key} must be a string")
            out.append((key, value))
        else:
            out.append((key, _expr(value, f"{where}: {key}")))
    return tuple(out)


def consistency_rule(name: str, entry: dict[str, Any], where: str) -> ConsistencyRule | None:
    """The ``greater_than`` rule of a ``[parameters.NAME]`` table, if it has one."""
    other = entry.get("greater_than")
    if other is None:
        return None
    if not isinstance(other, str):
        raise LayoutError(f"{where}: [parameters.{name}] greater_than must be a parameter name")
    return ConsistencyRule(name, other, str(entry.get("reason", "")))
