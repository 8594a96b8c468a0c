"""Curves: a route of tangent, transition, constant curve, transition, tangent.

A :class:`Curve` describes one curve of the track: its radius, direction, cant (the
height of the outer rail over the inner one) and the lengths of its transitions (clothoids:
curvature and cant change linearly with the distance along the track). It turns into the
route table the compiled right-hand side reads (:meth:`Curve.route`), or into a constant
curve everywhere (:meth:`Curve.steady_route`) for steady curving and stability in the
curve. SI units: m, m/s, rad.

Sign conventions (docs/curves.md): a curve to the ``"left"`` turns toward +y and has
positive curvature; its outer rail is the right one, raised by the cant, so the track
plane rolls by a positive angle (a point above the track moves toward +y, the inside).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from railhunt.kernel.layout import N_ROUTE
from railhunt.kernel.layout import RouteColumn as C

#: Distance between the rail centres over which the cant is measured (m): standard gauge
#: 1435 mm plus a rail head width of about 65 mm, the usual 1500 mm reference.
RAIL_CENTRE_DISTANCE = 1.5
#: Where the route's rows end when a segment runs on for ever (m).
_FOREVER = 1e9
_DIRECTIONS = {"left": 1.0, "right": -1.0}


def _check(name: str, value: object, low: float, high: float, unit: str,
           low_open: bool = False, high_open: bool = False) -> float:  # fmt: skip
    try:
        x = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} is invalid: must be a number in {unit}") from None
    ok = math.isfinite(x) and (low < x if low_open else low <= x) and (
        x < high if high_open else x <= high
    )
    if not ok:
        lo = "(" if low_open else "["
        hi = ")" if high_open else "]"
        interval = f"{lo}{low:g}, {high:g}{hi}"
        raise ValueError(
            f"{name} = {value!r} {unit} is invalid: must be finite and in {interval} {unit}"
        )
    return x


@dataclass(frozen=True)
class Curve:
    """One curve of the track (SI units).

    Parameters
    ----------
    radius : float
        Radius of the constant curve (m): finite and at least 50 m (straight track has no
        Curve; a very large radius approaches it).
    cant : float
        Height of the outer rail over the inner one (m), measured over the rail-centre
        distance ``rail_distance``: 0 to 0.5 m (real track: up to 0.18-0.2 m; more only
        in studies at a fixed cant deficiency).
    transition : float
        Length of each transition curve (m), 0 to 2000 m: curvature and cant rise
        linearly from the tangent to the constant curve (a clothoid with a linear cant
        ramp); 0 gives a curve that starts abruptly.
    direction : {"left", "right"}
        Which way the track turns (left: toward +y).
    length : float, optional
        Length of the constant curve (m); None: the curve runs on for ever (no exit).
    start : float
        Track position where the entry transition begins (m), measured from where the
        leading wheelset stands at ``t = 0``; >= 0.
    rail_distance : float
        Rail-centre distance over which the cant is given (m), 1 to 2 m (1.5 m for
        standard gauge).
    """

    radius: float
    cant: float = 0.0
    transition: float = 0.0
    direction: str = "left"
    length: float | None = None
    start: float = 0.0
    rail_distance: float = RAIL_CENTRE_DISTANCE

    def __post_init__(self) -> None:
        setter = object.__setattr__
        setter(self, "radius", _check("radius", self.radius, 50.0, math.inf, "m",
                                      high_open=True))
        setter(self, "cant", _check("cant", self.cant, 0.0, 0.5, "m"))
        setter(self, "transition", _check("transition", self.transition, 0.0, 2000.0, "m"))
        if self.direction not in _DIRECTIONS:
            raise ValueError(
                f"direction = {self.direction!r} is invalid: must be 'left' or 'right'"
            )
        if self.length is not None:
            setter(self, "length", _check("length", self.length, 0.0, 1e6, "m"))
        setter(self, "start", _check("start", self.start, 0.0, 1e6, "m"))
        setter(self, "rail_distance",
               _check("rail_distance", self.rail_distance, 1.0, 2.0, "m"))  # fmt: skip

    # -- geometry -----------------------------------------------------------------
    @property
    def curvature(self) -> float:
        """Signed curvature of the constant curve (1/m): + to the left."""
        return _DIRECTIONS[self.direction] / self.radius

    @property
    def cant_angle(self) -> float:
        """Signed roll angle of the track plane in the constant curve (rad)."""
        return _DIRECTIONS[self.direction] * math.asin(self.cant / self.rail_distance)

    def unbalanced_acceleration(self, speed: float, g: float = 9.81) -> float:
        """Unbalanced lateral acceleration in the track plane (m/s^2) at ``speed`` (m/s).

        ``v^2 / R cos(phi) - g sin(phi)`` toward the outside of the curve: positive with
        a cant deficiency, negative with a cant excess (``g`` in m/s^2: pass the
        vehicle's).
        """
        phi = math.asin(self.cant / self.rail_distance)
        return speed * speed / self.radius * math.cos(phi) - g * math.sin(phi)

    def cant_deficiency(self, speed: float, g: float = 9.81) -> float:
        """Cant deficiency (m) at ``speed`` (m/s): the extra cant that would balance it,
        ``rail_distance * a / g`` (negative: cant excess)."""
        return self.rail_distance * self.unbalanced_acceleration(speed, g) / g

    def balance_speed(self, g: float = 9.81) -> float:
        """Speed (m/s) at which the cant balances the curve (no unbalanced acceleration)."""
        phi = math.asin(self.cant / self.rail_distance)
        return math.sqrt(g * math.tan(phi) * self.radius)

    def scaled(self, fraction: float) -> Curve:
        """The same curve with its curvature and cant times ``fraction`` (0 < f <= 1): a
        gentler curve, the first steps of a homotopy toward this one."""
        return replace(self, radius=self.radius / fraction, cant=self.cant * fraction)

    def end(self) -> float:
        """Track position where the exit transition ends (m); inf without an exit."""
        if self.length is None:
            return math.inf
        return self.start + 2 * self.transition + self.length

    def curve_start(self) -> float:
        """Track position where the constant curve begins (m)."""
        return self.start + self.transition

    # -- the kernel's table -------------------------------------------------------
    def route(self) -> np.ndarray:
        """The route table: entry transition, constant curve, exit transition, tangent.

        Returns
        -------
        numpy.ndarray, shape (n, N_ROUTE)
            Rows of :class:`railhunt.kernel.layout.RouteColumn`.
        """
        kappa, cant = self.curvature, self.cant_angle
        lt = self.transition
        # (length, kappa at start, kappa at end, cant at start, cant at end)
        pieces: list[tuple[float, float, float, float, float]] = []
        if lt > 0:
            pieces.append((lt, 0.0, kappa, 0.0, cant))
        if self.length is None:
            pieces.append((_FOREVER, kappa, kappa, cant, cant))
        else:
            pieces.append((self.length, kappa, kappa, cant, cant))
            if lt > 0:
                pieces.append((lt, kappa, 0.0, cant, 0.0))
            pieces.append((_FOREVER, 0.0, 0.0, 0.0, 0.0))
        return _segments(self.start, pieces)

    def steady_route(self, behind: float = 100.0) -> np.ndarray:
        """A constant curve everywhere from ``-behind`` m on: steady curving.

        Every body of a vehicle standing at track positions above ``-behind`` (at
        ``t >= 0``) is in the constant curve, so the right-hand side does not depend on
        time (for the curving equilibrium, its Jacobian, and runs over a defect inside
        the curve).
        """
        k, c = self.curvature, self.cant_angle
        return _segments(-float(behind), [(_FOREVER, k, k, c, c)])


def _segments(s0: float, pieces: list[tuple[float, float, float, float, float]]) -> np.ndarray:
    """Route rows for consecutive pieces from ``s0``.

    Each piece is ``(length, kappa_start, kappa_end, cant_start, cant_end)``; curvature and
    cant vary linearly along it (a transition when start and end differ). Heading and its
    integral are carried on exactly from piece to piece, starting at 0.
    """
    pieces = [p for p in pieces if p[0] > 0.0]  # a curve of zero length has no row
    rows = np.zeros((len(pieces), N_ROUTE))
    th0, ph0 = 0.0, 0.0
    s = s0
    for i, (length, k0, k1, c0, c1) in enumerate(pieces):
        dk = (k1 - k0) / length
        dc = (c1 - c0) / length
        rows[i, C.S0], rows[i, C.S1] = s, s + length
        rows[i, C.KAPPA0], rows[i, C.DKAPPA] = k0, dk
        rows[i, C.THETA0], rows[i, C.PHI0] = th0, ph0
        rows[i, C.CANT0], rows[i, C.DCANT] = c0, dc
        u = length
        ph0 = ph0 + u * (th0 + u * (0.5 * k0 + dk * u / 6.0))
        th0 = th0 + u * (k0 + 0.5 * dk * u)
        s += length
    return rows


def cant_for_deficiency(radius: float, cant_deficiency: float, speed: float, g: float = 9.81,
                        rail_distance: float = RAIL_CENTRE_DISTANCE) -> float:  # fmt: skip
    """The cant (m) that leaves ``cant_deficiency`` (m) at ``speed`` (m/s) in a curve.

    Solves ``v^2/R cos(phi) - g sin(phi) = g h_d / s`` for the cant angle ``phi`` and
    returns ``s sin(phi)``, at least 0 (a cant excess larger than the requested deficiency
    would need a negative cant) and at most 0.5 m (the range of :class:`Curve`).
    """
    a = speed * speed / radius
    target = g * cant_deficiency / rail_distance
    r = math.hypot(a, g)
    phi = math.acos(max(-1.0, min(1.0, target / r))) - math.atan2(g, a)
    return min(max(rail_distance * math.sin(phi), 0.0), 0.5)


def fixed_deficiency(radius: float, cant_deficiency: float, direction: str = "left",
                     g: float = 9.81) -> Callable[[float], Curve]:  # fmt: skip
    """Curves of one radius whose cant keeps a fixed cant deficiency at every speed.

    Parameters
    ----------
    radius : float
        Radius (m).
    cant_deficiency : float
        Cant deficiency to keep (m), e.g. 0.1.
    direction : {"left", "right"}
        Which way the curves turn.
    g : float
        Acceleration of gravity (m/s^2): pass the vehicle's.

    Returns
    -------
    callable
        ``curve(speed) -> Curve`` for a speed in m/s (for ``curve=`` of the critical-speed
        analyses). Where the cant would leave [0, 0.5] m it is held at the limit and the
        deficiency differs from the one asked for.
    """
    Curve(radius, direction=direction)  # validate
    if not (math.isfinite(cant_deficiency) and -0.5 <= cant_deficiency <= 0.5):
        raise ValueError(f"cant_deficiency = {cant_deficiency!r} m is invalid: must be finite "
                         "and in [-0.5, 0.5] m")  # fmt: skip

    def curve_at(speed: float) -> Curve:
        return Curve(radius, cant_for_deficiency(radius, cant_deficiency, speed, g),
                     direction=direction)  # fmt: skip

    return curve_at
