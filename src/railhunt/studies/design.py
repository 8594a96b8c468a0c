"""Sweep designs: which parameter values each point of a study runs with.

A design is an ordered list of :class:`Point`; the order is the point's identity in a
results file (column ``point``), so a design must be reproducible from its description
alone: lines and grids are, and random and Latin-hypercube samples are through their seed.

Four designs are offered:

``lines``
    One parameter at a time (the paper's Figs. 10 and 11): every parameter runs over its
    own values while the others stay at the vehicle's nominal values.
``grid``
    The full factorial product of all values.
``random``
    ``samples`` points drawn uniformly and independently in the ranges ``(low, high)``.
``lhs``
    A Latin-hypercube sample of ``samples`` points in the ranges (each range is cut into
    ``samples`` strata and every stratum is used once per parameter).

Tied parameters follow a leader: ``ties={"f22": "f11"}`` sets f22 equal to f11 at every
point, ``ties={"f22": ("f11", 0.9)}`` to 0.9 f11. A tie holds at every point of the study,
including the points of other lines (where the leader has its nominal value), so that one
study describes one family of vehicles; its leader must be varied.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from railhunt.vehicle import (
    DERIVED,
    PARAMETERS,
    DerivedParameterError,
    ParameterError,
    ParameterSpec,
    UnknownParameterError,
    Vehicle,
    validate_value,
)
from railhunt.vehicle.parameters import as_float

DESIGNS = ("lines", "grid", "random", "lhs")
#: Yaw-damper parameters: the paper computes their hunting frequency at 300 km/h.
YAW_DAMPER_PARAMETERS = frozenset({"C_d1", "C_d2", "K_d", "F_u"})
#: Hunting-frequency speeds of the paper's Sec. 4 (km/h).
YAW_DAMPER_FREQUENCY_SPEED_KMH = 300.0
OTHER_FREQUENCY_SPEED_KMH = 350.0


@dataclass(frozen=True)
class Point:
    """One point of a study.

    Attributes
    ----------
    index : int
        Position in the design (0-based); the ``point`` column of a results file.
    line : str
        For a ``lines`` design the parameter this point varies, otherwise the design name.
    values : dict
        Parameter name -> SI value for every parameter of the study, tied ones included.
    """

    index: int
    line: str
    values: dict[str, float]


def _validate(specs: Mapping[str, ParameterSpec], name: str, value: float) -> float:
    """``validate_value`` against a vehicle's own parameter table."""
    if specs is PARAMETERS:
        return validate_value(name, value)
    if name not in specs:
        if name in DERIVED:
            raise DerivedParameterError(name, value)
        raise UnknownParameterError(name, value, known=tuple(specs))
    spec = specs[name]
    x = as_float(name, value, spec.unit or None, spec.meaning)
    if not spec.rule.accepts(x):
        raise ParameterError(name, value, str(spec.rule), spec.unit or None,
                             meaning=spec.meaning)  # fmt: skip
    return x


def _specs(vehicle: Vehicle | None) -> Mapping[str, ParameterSpec]:
    """The parameter table of ``vehicle`` (the paper's :data:`PARAMETERS` for its layout)."""
    if vehicle is None or dict(vehicle.parameters) == dict(PARAMETERS):
        return PARAMETERS
    return vehicle.parameters


def parse_ties(
    ties: Mapping[str, object] | None, specs: Mapping[str, ParameterSpec] = PARAMETERS
) -> dict[str, tuple[str, float]]:
    """Normalise ties to ``{follower: (leader, factor)}`` and check the names.

    Parameters
    ----------
    ties : Mapping, optional
        ``{follower: leader}`` or ``{follower: (leader, factor)}``.

    Returns
    -------
    dict
    """
    out: dict[str, tuple[str, float]] = {}
    for follower, spec in (ties or {}).items():
        leader, factor = (spec, 1.0) if isinstance(spec, str) else spec  # type: ignore[misc]
        for name in (follower, leader):
            if name not in specs:
                raise UnknownParameterError(name, spec, known=tuple(specs))
        factor = float(factor)
        if not (math.isfinite(factor) and factor > 0):
            raise ValueError(f"tie {follower} = {factor!r} * {leader}: the factor must be > 0")
        if follower == leader:
            raise ValueError(f"tie {follower} = {leader}: a parameter cannot follow itself")
        out[follower] = (leader, factor)
    for follower, (leader, _) in out.items():
        if leader in out:
            raise ValueError(f"tie {follower} -> {leader} -> {out[leader][0]}: a leader cannot "
                             "itself follow another parameter")  # fmt: skip
    return out


def _check_values(name: str, values: object,
                  specs: Mapping[str, ParameterSpec] = PARAMETERS) -> np.ndarray:  # fmt: skip
    if name not in specs:
        raise UnknownParameterError(name, values, known=tuple(specs))
    try:
        arr = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        unit = f" in {specs[name].unit}" if specs[name].unit else ""
        raise ValueError(f"{name} = {values!r} is invalid: the values of a sweep are numbers"
                         f"{unit} (SI), e.g. {name} = [1.5e5, 3e5]") from None  # fmt: skip
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name}: the values must be a non-empty 1-D sequence, got {values!r}")
    for v in arr:
        _validate(specs, name, float(v))
    return arr


def _check_range(
    name: str, rng: object, specs: Mapping[str, ParameterSpec] = PARAMETERS
) -> tuple[float, float]:
    if name not in specs:
        raise UnknownParameterError(name, rng, known=tuple(specs))
    try:
        lo, hi = (float(v) for v in rng)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {rng!r}: a random or lhs design needs a range "
                         "(low, high) in SI units") from None  # fmt: skip
    _validate(specs, name, lo)
    _validate(specs, name, hi)
    if not lo < hi:
        raise ValueError(f"{name} = ({lo:g}, {hi:g}): low must be below high")
    return lo, hi


def tied_values(values: dict[str, float], ties: dict[str, tuple[str, float]],
                specs: Mapping[str, ParameterSpec] = PARAMETERS) -> dict[str, float]:  # fmt: skip
    """``values`` with each tied parameter set from its leader (``ties``: follower ->
    ``(leader, factor)``, :func:`parse_ties`), checked against its valid range."""
    out = dict(values)
    for follower, (leader, factor) in ties.items():
        if leader in out:
            out[follower] = _validate(specs, follower, factor * out[leader])
    return out


def build_design(
    vehicle: Vehicle,
    parameters: Mapping[str, object],
    design: str = "lines",
    samples: int | None = None,
    seed: int = 0,
    ties: Mapping[str, object] | None = None,
) -> list[Point]:
    """The points of a study.

    Parameters
    ----------
    vehicle : Vehicle
        Nominal vehicle (the values of parameters not varied by a point).
    parameters : Mapping
        Parameter name -> SI values (``lines``, ``grid``) or ``(low, high)`` range
        (``random``, ``lhs``).
    design : {"lines", "grid", "random", "lhs"}
        See the module docstring.
    samples : int, optional
        Number of points of a ``random`` or ``lhs`` design (required there).
    seed : int
        Seed of the random generator (``random``, ``lhs``).
    ties : Mapping, optional
        ``{follower: leader}`` or ``{follower: (leader, factor)}``; a follower may not be
        varied itself.

    Returns
    -------
    list of Point
    """
    if design not in DESIGNS:
        raise ValueError(f"design = {design!r} is invalid: must be one of {', '.join(DESIGNS)}")
    if not parameters:
        raise ValueError("parameters is empty: give at least one parameter to vary")
    specs = _specs(vehicle)
    tie_map = parse_ties(ties, specs)
    for follower in tie_map:
        if follower in parameters:
            raise ValueError(f"{follower} is both varied and tied to {tie_map[follower][0]}: "
                             "drop one of the two")  # fmt: skip
    for follower, (leader, _) in tie_map.items():
        if leader not in parameters:
            raise ValueError(f"tie {follower} = {leader}: {leader} is not varied in this study "
                             f"(set {follower} on the vehicle instead)")  # fmt: skip
    names = list(parameters)
    nominal = vehicle.as_dict()
    points: list[Point] = []

    def add(line: str, values: dict[str, float]) -> None:
        plain = {k: float(v) for k, v in values.items()}  # no numpy scalars in the files
        points.append(Point(len(points), line, tied_values(plain, tie_map, specs)))

    if design in ("lines", "grid"):
        arrays = {name: _check_values(name, parameters[name], specs) for name in names}
        if design == "lines":
            for name in names:
                for v in arrays[name]:
                    values = {n: nominal[n] for n in names}
                    values[name] = float(v)
                    add(name, values)
        else:
            for combo in itertools.product(*(arrays[n] for n in names)):
                add("grid", {n: float(v) for n, v in zip(names, combo, strict=True)})
        return points

    ranges = {name: _check_range(name, parameters[name], specs) for name in names}
    if samples is None or isinstance(samples, bool) or int(samples) != samples or samples < 1:
        raise ValueError(f"samples = {samples!r} is invalid: a {design} design needs an "
                         "integer number of points >= 1")  # fmt: skip
    samples = int(samples)
    rng = np.random.default_rng(seed)
    if design == "random":
        unit = rng.random((samples, len(names)))
    else:
        # Latin hypercube: one point per stratum and parameter, strata shuffled per column.
        unit = np.empty((samples, len(names)))
        for j in range(len(names)):
            unit[:, j] = (rng.permutation(samples) + rng.random(samples)) / samples
    for row in unit:
        add(design, {n: ranges[n][0] + u * (ranges[n][1] - ranges[n][0])
                     for n, u in zip(names, row, strict=True)})  # fmt: skip
    return points


def frequency_speed(point: Point, names: Sequence[str], stated_kmh: float | None) -> float:
    """Speed of a point's hunting-frequency run (km/h).

    Parameters
    ----------
    point : Point
        The point.
    names : sequence of str
        The parameters the study varies.
    stated_kmh : float, optional
        A speed stated by the user (km/h).

    Returns
    -------
    float
        The stated speed if given; otherwise the paper's: 300 km/h when every parameter
        the point varies is a yaw-damper parameter (``C_d1``, ``C_d2``, ``K_d``, ``F_u``),
        else 350 km/h.
    """
    if stated_kmh is not None:
        return float(stated_kmh)
    varied = [point.line] if point.line in names else list(names)
    if all(n in YAW_DAMPER_PARAMETERS for n in varied):
        return YAW_DAMPER_FREQUENCY_SPEED_KMH
    return OTHER_FREQUENCY_SPEED_KMH
