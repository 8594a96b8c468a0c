"""The rule a value gets from what it is: a mass, a stiffness, a wheel radius, a position.

Every numeric value of a layout file has a meaning (:class:`Meaning`): its SI unit, the
rule of sign it must obey for the model to mean anything (a mass is positive, a damping
is not negative, a friction coefficient is positive) and, for many, the range real rail
vehicles fall in (:attr:`Meaning.plausible`). A value outside that range is almost always
a unit slip (a mass in t, a radius in mm, a stiffness in kN/m): it is refused naming the
range, unless the parameter it comes from says ``allow = true`` (a scale model, a roller
rig, a study on purpose outside the usual). The rule of sign is never waived.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from railhunt.quantities.rules import (
    CONTACT_ANGLE,
    FINITE,
    FRICTION,
    NONNEGATIVE,
    POSITIVE,
    ROLLING_RADIUS,
    Rule,
)

__all__ = ["GRAVITY", "INERTIA_RADIUS", "Meaning", "POINT", "WHEEL_RAIL", "body_meaning",
           "element_meaning"]  # fmt: skip


class Meaning(NamedTuple):
    """What a value of a layout is, and the rules that follow from it.

    Attributes
    ----------
    what : str
        In words, for messages (``"a car body's mass"``).
    unit : str
        Its SI unit.
    rule : Rule
        The rule of sign or physics it must obey (never waived).
    plausible : Rule or None
        The range of real rail vehicles (waived by ``allow = true``); None: any value the
        rule accepts.
    """

    what: str
    unit: str
    rule: Rule
    plausible: Rule | None = None


def _range(lo: float | None, hi: float | None, reason: str, *, lo_strict: bool = False,
           hi_strict: bool = False) -> Rule:  # fmt: skip
    return Rule(lower=lo, lower_strict=lo_strict, upper=hi, upper_strict=hi_strict,
                reason=reason)  # fmt: skip


_ABOVE_RAIL = Rule(lower=0.0, lower_strict=True,
                   reason="a centre of gravity above the top of rail")  # fmt: skip
_POSITIVE_MASS = Rule(lower=0.0, lower_strict=True, reason="a mass or inertia is positive")
_MASS = {
    "car": _range(1e3, 5e5, "a car body of 1 to 500 t (a value in t is a common mistake)"),
    "frame": _range(50.0, 5e4, "a bogie frame of 50 kg to 50 t (a value in t is a common "
                    "mistake)"),  # fmt: skip
    "wheelset": _range(50.0, 1e4, "a wheelset of 50 kg to 10 t (a value in t is a common "
                       "mistake)"),  # fmt: skip
}
#: Radius of gyration sqrt(J / m) (m) of each kind of body: a yaw or roll inertia outside
#: it is implausible for the body's mass (an inertia in t*m^2 is the usual slip).
INERTIA_RADIUS = {
    "car": _range(0.3, 40.0, "a car body's radius of gyration sqrt(J/m) of 0.3 to 40 m"),
    "frame": _range(0.1, 10.0, "a bogie frame's radius of gyration sqrt(J/m) of 0.1 to 10 m"),
    "wheelset": _range(0.1, 3.0, "a wheelset's radius of gyration sqrt(J/m) of 0.1 to 3 m"),
}
_POSITION = _range(-200.0, 200.0, "a position within 200 m of the vehicle centre (a value in "
                   "mm is a common mistake)")  # fmt: skip
_HEIGHT = _range(None, 6.0, "a height above the top of rail below 6 m (a value in mm is a "
                 "common mistake)")  # fmt: skip


def body_meaning(kind: str, key: str) -> Meaning:
    """The meaning of a ``[[body]]`` value (``x``, ``height``, ``mass``, ``yaw_inertia``,
    ``roll_inertia``) of a body of ``kind``."""
    body = {"car": "a car body", "frame": "a bogie frame", "wheelset": "a wheelset",
            "fixed": "a fixed body"}.get(kind, "a body")  # fmt: skip
    if key == "x":
        return Meaning(f"{body}'s longitudinal position", "m", FINITE, _POSITION)
    if key == "height":
        return Meaning(f"{body}'s centre of gravity above the top of rail", "m", _ABOVE_RAIL,
                       _HEIGHT)  # fmt: skip
    if key == "mass":
        return Meaning(f"{body}'s mass", "kg", _POSITIVE_MASS, _MASS.get(kind))
    what = "yaw" if key == "yaw_inertia" else "roll"
    return Meaning(f"{body}'s {what} moment of inertia", "kg*m^2", _POSITIVE_MASS)


#: An attachment point ``[x, y, z]`` (m, vehicle coordinates, z above the top of rail).
POINT = (
    Meaning("an attachment point's x", "m", FINITE, _POSITION),
    Meaning("an attachment point's y", "m", FINITE,
            _range(-3.0, 3.0, "a point within 3 m of the track centre line (a value in mm "
                   "is a common mistake)")),  # fmt: skip
    Meaning("an attachment point's height z", "m", FINITE,
            _range(-1.0, 6.0, "a point from 1 m below to 6 m above the top of rail (a value "
                   "in mm is a common mistake)")),  # fmt: skip
)

_NOT_NEGATIVE = Rule(lower=0.0, reason="a passive element's coefficient is not negative")
_MAXWELL = Rule(lower=0.0, lower_strict=True, reason="the Maxwell element's values are "
                "positive")  # fmt: skip


def element_meaning(kind: str, axis: str, key: str) -> Meaning:
    """The meaning of a law value of an ``[[element]]`` of ``kind`` along ``axis``."""
    torsion = axis in ("yaw", "roll")
    if key == "stiffness" and kind != "maxwell":
        unit = "N*m/rad" if torsion else "N/m"
        return Meaning(f"a {kind}'s stiffness", unit, _NOT_NEGATIVE)
    if key == "damping" and kind != "maxwell":
        unit = "N*m*s/rad" if torsion else "N*s/m"
        return Meaning(f"a {kind}'s damping", unit, _NOT_NEGATIVE)
    if kind == "maxwell":
        what, unit = {"stiffness": ("series stiffness", "N/m"),
                      "damping": ("first-stage damping", "N*s/m"),
                      "damping2": ("second-stage damping", "N*s/m"),
                      "blowoff_force": ("blow-off force", "N")}[key]  # fmt: skip
        return Meaning(f"a Maxwell element's {what}", unit, _MAXWELL)
    if key == "gap":
        return Meaning("a stop's free play", "m", Rule(lower=0.0, reason="a free play is not "
                       "negative"), _range(None, 0.2, "a free play below 0.2 m (a value in mm "
                       "is a common mistake)"))  # fmt: skip
    if key == "stiffness3":
        return Meaning("a stop's cubic stiffness", "N/m^3", _NOT_NEGATIVE)
    raise KeyError(f"{kind} {key}")


#: The meaning of each ``[wheel_rail]`` value.
WHEEL_RAIL: dict[str, Meaning] = {
    "half_gauge": Meaning("half the distance between the contact points", "m",
                          Rule(lower=0.0, lower_strict=True, reason="a distance is positive"),
                          _range(0.3, 1.0, "half the contact-point distance in m, 0.3 to 1.0 "
                                 "(0.7465 for standard gauge; a value in mm is a common "
                                 "mistake)")),  # fmt: skip
    "radius": Meaning("the centred rolling radius", "m",
                      Rule(lower=0.0, lower_strict=True, reason="a radius is positive"),
                      ROLLING_RADIUS),  # fmt: skip
    "f11": Meaning("Kalker's longitudinal creep coefficient", "N", POSITIVE),
    "f22": Meaning("Kalker's lateral creep coefficient", "N", POSITIVE),
    "f23": Meaning("Kalker's lateral/spin creep coefficient", "N*m", NONNEGATIVE),
    "f33": Meaning("Kalker's spin creep coefficient", "N*m^2", NONNEGATIVE),
    "mu": Meaning("the friction coefficient", "1", FRICTION),
    "load": Meaning("the static wheel load", "N",
                    Rule(lower=0.0, lower_strict=True, reason="a wheel load is positive"),
                    _range(1e3, 3e5, "a wheel load of 1 to 300 kN (a value in kN is a "
                           "common mistake)")),  # fmt: skip
    "axle_load": Meaning("the mass carried by the wheelset", "kg",
                         Rule(lower=0.0, lower_strict=True, reason="a mass is positive"),
                         _range(100.0, 1e5, "an axle load of 0.1 to 100 t (a value in t is a "
                                "common mistake)")),  # fmt: skip
    "conicity": Meaning("the conicity", "1", NONNEGATIVE,
                        _range(None, 1.0, "a conicity below 1")),  # fmt: skip
    "contact_angle": Meaning("the contact angle", "rad",
                             Rule(lower=0.0, upper=math.pi / 2, upper_strict=True,
                                  upper_label="pi/2", reason="a contact angle in rad")),
    "delta_max": Meaning("the flange angle", "rad", CONTACT_ANGLE),
    "lambda1": Meaning("the rolling-radius polynomial's linear coefficient", "1", FINITE),
    "lambda2": Meaning("the rolling-radius polynomial's quadratic coefficient", "1/m", FINITE),
    "lambda3": Meaning("the rolling-radius polynomial's cubic coefficient", "1/m^2", FINITE),
    "lambda4": Meaning("the rolling-radius polynomial's quartic coefficient", "1/m^3", FINITE),
    "lambda5": Meaning("the rolling-radius polynomial's quintic coefficient", "1/m^4", FINITE),
    "d0": Meaning("the contact-angle polynomial's constant term", "rad", FINITE),
    "d1": Meaning("the contact-angle polynomial's linear term", "rad/m", FINITE),
    "d4": Meaning("the contact-angle polynomial's quartic term", "rad/m^4", FINITE),
    "d5": Meaning("the contact-angle polynomial's quintic term", "rad/m^5", FINITE),
    "shear_modulus": Meaning("the shear modulus of wheel and rail steel", "Pa",
                             Rule(lower=0.0, lower_strict=True,
                                  reason="a shear modulus is positive"),
                             _range(1e10, 1e12, "a shear modulus of 10 to 1000 GPa (8.2e10 Pa "
                                    "for wheel and rail steel; a value in GPa is a common "
                                    "mistake)")),  # fmt: skip
    "poisson": Meaning("Poisson's ratio of wheel and rail steel", "1",
                       Rule(lower=0.0, upper=0.5, upper_strict=True,
                            reason="Poisson's ratio of an elastic solid is in [0, 0.5)")),
}

#: The acceleration of gravity (``[vehicle] gravity``).
GRAVITY = Meaning("the acceleration of gravity", "m/s^2",
                  Rule(lower=0.0, lower_strict=True, reason="gravity pulls down"),
                  _range(9.7, 9.9, "the acceleration of gravity on Earth, 9.7 to 9.9 m/s^2"))
