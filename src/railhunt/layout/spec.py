"""The parsed description of a vehicle layout: bodies, force elements, wheel/rail data.

A :class:`LayoutSpec` is what a layout file says, with every numeric value kept as an
:class:`~railhunt.layout.expressions.Expression` of the vehicle's parameters: it is read
and checked once (:mod:`railhunt.layout.parse`) and turned into the kernel's arrays for
each set of parameter values (:mod:`railhunt.layout.assembly`), so a sweep re-evaluates
numbers, never the file. Everything here is immutable and hashable.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING

from railhunt.layout.expressions import Expression

if TYPE_CHECKING:
    from railhunt.quantities.rules import ParameterSpec

__all__ = [
    "AXES", "BODY_KINDS", "COORDINATES", "ELEMENT_KINDS", "LAWS", "TRACK", "BodySpec",
    "ConsistencyRule", "ElementSpec", "LayoutError", "LayoutSpec",
]  # fmt: skip

#: The body kinds and the coordinates each has unless ``coordinates`` says otherwise.
BODY_KINDS: dict[str, tuple[str, ...]] = {
    "car": ("y", "psi", "phi"),
    "frame": ("y", "psi", "phi"),
    "wheelset": ("y", "psi"),
    "fixed": (),
}
#: Coordinates a body may have: lateral (m), yaw and roll (rad).
COORDINATES = ("y", "psi", "phi")
#: The element kinds and the law values each needs (required, optional with default).
LAWS: dict[str, tuple[tuple[str, ...], dict[str, float]]] = {
    "spring": (("stiffness",), {}),
    "damper": (("damping",), {}),
    "maxwell": (("stiffness", "damping", "damping2", "blowoff_force"), {}),
    "stop": (("gap", "stiffness"), {"stiffness3": 0.0}),
    "torsion-spring": (("stiffness",), {}),
    "torsion-damper": (("damping",), {}),
}
ELEMENT_KINDS = tuple(LAWS)
#: Axes of each element kind.
AXES: dict[str, tuple[str, ...]] = {
    "spring": ("x", "y", "z"), "damper": ("x", "y", "z"), "maxwell": ("x", "y", "z"),
    "stop": ("x", "y", "z"), "torsion-spring": ("yaw", "roll"),
    "torsion-damper": ("yaw", "roll"),
}  # fmt: skip
#: The name of the rails as an element's second body.
TRACK = "track"


class LayoutError(ValueError):
    """A layout that cannot be a vehicle: names the body, element or parameter, and what
    to do. Raised before any computation."""


def check_keys(table: dict, allowed: frozenset[str] | set[str], label: str) -> None:
    """Refuse keys of a file's ``table`` outside ``allowed``, naming them and ``label``."""
    bad = set(table) - allowed
    if bad:
        raise LayoutError(f"{label}: unknown key(s) {sorted(bad)}; allowed: "
                          f"{', '.join(sorted(allowed))}")  # fmt: skip


@dataclass(frozen=True)
class BodySpec:
    """One rigid body of the layout.

    Attributes
    ----------
    name : str
        Unique name (``"car"``, ``"bogie1"``, ``"wheelset3"``).
    kind : {"car", "frame", "wheelset", "fixed"}
    tag : str
        Suffix of its coordinate names (``"c"``, ``"t1"``, ``"w3"``).
    x, height : Expression
        Longitudinal position of the centre of gravity (m, + forward) and its height above
        the top of rail (m).
    mass, yaw_inertia, roll_inertia : Expression or None
        kg and kg*m^2 (None where the body has no such coordinate).
    coordinates : tuple of str
        Its coordinates in state order.
    wheel_rail : tuple of (str, object)
        A wheelset's own wheel/rail values, overriding the ``[wheel_rail]`` table.
    """

    name: str
    kind: str
    tag: str
    x: Expression
    height: Expression
    mass: Expression | None
    yaw_inertia: Expression | None
    roll_inertia: Expression | None
    coordinates: tuple[str, ...]
    wheel_rail: tuple[tuple[str, object], ...] = ()


@dataclass(frozen=True)
class ElementSpec:
    """One force element (after ``mirror`` has been expanded).

    Attributes
    ----------
    name : str
        Label (given, or made from kind, bodies and axis).
    kind : str
        A key of :data:`LAWS`.
    body_a, body_b : str
        The bodies joined; ``body_b`` may be ``"track"``.
    axis : str
        ``"x"``, ``"y"``, ``"z"``, or ``"yaw"``, ``"roll"`` for torsion.
    at, at_b : tuple of Expression
        Attachment point on ``body_a`` and on ``body_b`` (m, vehicle coordinates at rest,
        z above the top of rail); the same point unless ``at_b`` was given.
    law : tuple of (str, Expression)
        The law's values (``stiffness``, ``damping``, ...).
    mirrored : bool
        One of a pair made by ``mirror = true`` (its points' y must not be 0).
    """

    name: str
    kind: str
    body_a: str
    body_b: str
    axis: str
    at: tuple[Expression, Expression, Expression]
    at_b: tuple[Expression, Expression, Expression]
    law: tuple[tuple[str, Expression], ...]
    mirrored: bool = field(default=False, compare=False)

    def value(self, key: str) -> Expression:
        """The law's value ``key``."""
        return dict(self.law)[key]


@dataclass(frozen=True)
class ConsistencyRule:
    """``parameter > other`` must hold (e.g. ``l > l1``), with the reason for messages."""

    parameter: str
    other: str
    reason: str = ""


@dataclass(frozen=True)
class LayoutSpec:
    """A vehicle layout: bodies, elements, wheel/rail data (values as expressions).

    Attributes
    ----------
    bodies : tuple of BodySpec
        In state order (the file's order).
    elements : tuple of ElementSpec
        In the file's order, each mirrored element followed by its mirror image.
    wheel_rail : tuple of (str, object)
        The ``[wheel_rail]`` table every wheelset gets (strings for ``contact`` and
        ``creep_law``, expressions for numbers).
    gravity : Expression
        Acceleration of gravity (m/s^2).
    consistency : tuple of ConsistencyRule
        Rules between parameters.
    source : str
        Where the layout was read from (for messages).
    parameters : tuple of ParameterSpec
        The vehicle's parameters (name, unit, meaning, rule, default), in order.
    sources : tuple of (str, str)
        Where each parameter's value comes from.
    citation : str
        Where the vehicle comes from (``[vehicle] source``: one line).
    formulas : tuple of (str, str)
        The derived parameters and their expressions of other parameters, as the file
        writes them (``("f11", "GPIAB / phi_vj")``): each follows its inputs wherever they
        change (``replace``, ``--set``, sweeps, studies).
    allowed : frozenset of str
        The parameters whose file says ``allow = true``: they (and every value computed
        from them) may lie outside the ranges their uses make plausible
        (:mod:`railhunt.quantities.meanings`); the rules of sign still hold.
    inferred : frozenset of str
        The parameters whose rule is the rule of their use in the layout (their file states
        none): a file written from the layout leaves it out, as its source did.
    """

    bodies: tuple[BodySpec, ...]
    elements: tuple[ElementSpec, ...]
    wheel_rail: tuple[tuple[str, object], ...]
    gravity: Expression
    consistency: tuple[ConsistencyRule, ...] = ()
    source: str = field(default="", compare=False)
    parameters: tuple[ParameterSpec, ...] = ()
    sources: tuple[tuple[str, str], ...] = field(default=(), compare=False)
    citation: str = field(default="", compare=False)
    formulas: tuple[tuple[str, str], ...] = ()
    allowed: frozenset[str] = frozenset()
    inferred: frozenset[str] = frozenset()

    def __hash__(self) -> int:
        # Hashed once and kept: the layout is the key of the assembly's and the checks'
        # caches, hashed at every vehicle built from it (a sweep builds one per point).
        h = self.__dict__.get("_hash")
        if h is None:
            h = hash(tuple(getattr(self, f.name) for f in fields(self) if f.compare))
            object.__setattr__(self, "_hash", h)
        return h

    def __getstate__(self) -> dict:
        # What is kept per process (the hash of its strings differs between processes,
        # e.g. Dask workers) is not pickled.
        return {k: v for k, v in self.__dict__.items() if not k.startswith("_")}

    def formula(self, name: str) -> str | None:
        """The expression a derived parameter is computed from (None: an independent one)."""
        for n, text in self.formulas:
            if n == name:
                return text
        return None

    @property
    def specs(self) -> dict[str, ParameterSpec]:
        """The layout's parameters: name -> unit, meaning, rule, default."""
        return {p.name: p for p in self.parameters}

    def body(self, name: str) -> BodySpec:
        """The body named ``name``."""
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    @property
    def wheelsets(self) -> tuple[BodySpec, ...]:
        """The wheelset bodies, in order (the leading one first)."""
        return tuple(b for b in self.bodies if b.kind == "wheelset")

    def wheel_rail_of(self, body: BodySpec) -> dict[str, object]:
        """The wheel/rail values of a wheelset: the common table and its own."""
        return {**dict(self.wheel_rail), **dict(body.wheel_rail)}

    def names(self) -> frozenset[str]:
        """Every parameter name the layout's expressions use."""
        out: set[str] = set(self.gravity.names)
        for b in self.bodies:
            for e in (b.x, b.height, b.mass, b.yaw_inertia, b.roll_inertia):
                if e is not None:
                    out |= e.names
            for _, v in b.wheel_rail:
                if isinstance(v, Expression):
                    out |= v.names
        for el in self.elements:
            for e in (*el.at, *el.at_b, *(v for _, v in el.law)):
                out |= e.names
        for _, v in self.wheel_rail:
            if isinstance(v, Expression):
                out |= v.names
        return frozenset(out)
