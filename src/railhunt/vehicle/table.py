"""The parameter table of the paper's vehicle and its derived quantities.

Each vehicle parameter is written once, as a field of :class:`VehicleFields` (the fields
of :class:`~railhunt.vehicle.Vehicle`): name, SI unit, rule and meaning on one line,
``M_c: float = parameter("kg", POSITIVE, "Car body mass")``. :data:`PARAMETERS` (and so
the order of parameters everywhere) and :data:`DERIVED` follow from it;
:mod:`railhunt.vehicle.parameters` checks values against it and
:mod:`railhunt.vehicle.errors` names its parameters in messages (:func:`suggest`), so the
table sits below both.
"""

import difflib
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from railhunt.quantities.rules import (
    CONTACT_ANGLE,
    CONTACT_HALF_DISTANCE,
    FINITE,
    FRICTION,
    NONNEGATIVE,
    POSITIVE,
    ROLLING_RADIUS,
    DerivedSpec,
    ParameterSpec,
    parameter,
    parameter_specs,
)
from railhunt.vehicle.contact import ContactSpec

__all__ = ["DERIVED", "PARAMETERS", "VehicleFields", "derived_values", "suggest"]


# --------------------------------------------------------------------------- the table


@dataclass(frozen=True, kw_only=True)
class VehicleFields:
    """The fields of :class:`~railhunt.vehicle.Vehicle`: its identity, then the parameter table.

    One line per parameter: ``name: float = parameter(unit, rule, meaning)``, in SI units.
    The order of the lines is the order of :data:`PARAMETERS`, of ``Vehicle.as_dict()``, of
    vehicle files written by ``Vehicle.to_toml`` and of every table.  Not instantiated
    itself: build a :class:`~railhunt.vehicle.Vehicle`, which validates.

    Attributes
    ----------
    name : str
        Short identifier (non-empty).
    description : str
        Free text (not compared).
    contact : ContactSpec or None
        Contact geometry from profiles; None: the paper's polynomials.
    """

    name: str = "custom"
    description: str = field(default="", compare=False)
    contact: ContactSpec | None = None

    # fmt: off
    M_c: float = parameter("kg", POSITIVE, "Car body mass")
    M_t: float = parameter("kg", POSITIVE, "Bogie frame mass")
    M_w: float = parameter("kg", POSITIVE, "Wheelset mass")
    J_cx: float = parameter("kg*m^2", POSITIVE, "Roll moment of inertia of car body")
    J_cz: float = parameter("kg*m^2", POSITIVE, "Yaw moment of inertia of car body")
    J_tx: float = parameter("kg*m^2", POSITIVE, "Roll moment of inertia of bogie frame")
    J_tz: float = parameter("kg*m^2", POSITIVE, "Yaw moment of inertia of bogie frame")
    J_wz: float = parameter("kg*m^2", POSITIVE, "Yaw moment of inertia of wheelset")
    K_px: float = parameter("N/m", POSITIVE,
                            "Longitudinal stiffness of primary suspension, per axle box")
    K_py: float = parameter("N/m", POSITIVE,
                            "Lateral stiffness of primary suspension, per axle box")
    K_pz: float = parameter("N/m", POSITIVE,
                            "Vertical stiffness of primary suspension, per axle box")
    K_sx: float = parameter("N/m", POSITIVE,
                            "Longitudinal stiffness of secondary suspension, per air spring")
    K_sy: float = parameter("N/m", POSITIVE,
                            "Lateral stiffness of secondary suspension, per air spring")
    K_sz: float = parameter("N/m", POSITIVE,
                            "Vertical stiffness of secondary suspension, per air spring")
    C_px: float = parameter("N*s/m", NONNEGATIVE,
                            "Longitudinal damping of primary suspension, per axle box "
                            "(not in Table 2: chosen so that 2*C_px*b1^2 equals "
                            "the yaw damping 2*C_py*l1^2 printed in Eq. 18)")
    C_py: float = parameter("N*s/m", NONNEGATIVE,
                            "Lateral damping of primary suspension, per axle box")
    C_pz: float = parameter("N*s/m", NONNEGATIVE,
                            "Vertical damping of primary suspension, per axle box")
    C_sy: float = parameter("N*s/m", NONNEGATIVE,
                            "Lateral damping of secondary suspension, per damper (two per bogie)")
    C_sz: float = parameter("N*s/m", NONNEGATIVE,
                            "Vertical damping of secondary suspension, per damper (two per bogie)")
    y_bs: float = parameter("m", NONNEGATIVE,
                            "Free play of the secondary lateral bump stop (car body to bogie, "
                            "one per bogie)", default=0.030)
    K_bs: float = parameter("N/m", NONNEGATIVE,
                            "Stiffness of the secondary lateral bump stop once in contact "
                            "(0 with K_bs3 = 0: no bump stop)", default=1.0e6)
    K_bs3: float = parameter("N/m^3", NONNEGATIVE,
                             "Cubic (progressive) stiffness of the secondary lateral bump stop",
                             default=5.0e9)
    K_d: float = parameter("N/m", POSITIVE, "Series stiffness of yaw damper (Maxwell spring)")
    C_d1: float = parameter("N*s/m", POSITIVE, "First stage damping of yaw damper (below blow-off)")
    C_d2: float = parameter("N*s/m", POSITIVE,
                            "Second stage damping of yaw damper (after blow-off)")
    F_u: float = parameter("N", POSITIVE,
                           "Blow-off force of yaw damper; "
                           "blow-off velocity v_u = F_u / C_d1 is derived")
    a: float = parameter("m", CONTACT_HALF_DISTANCE,
                         "Half of the lateral distance between the wheel/rail contact points")
    b1: float = parameter("m", POSITIVE, "Half of primary spring arm (lateral)")
    b2: float = parameter("m", POSITIVE, "Half of secondary spring arm (lateral)")
    b3: float = parameter("m", POSITIVE, "Half of secondary vertical damping arm (lateral)")
    b4: float = parameter("m", POSITIVE, "Half of yaw damper arm (lateral)")
    h1: float = parameter("m", NONNEGATIVE,
                          "Vertical distance from car body centre of gravity down to the "
                          "secondary suspension")
    h2: float = parameter("m", NONNEGATIVE,
                          "Vertical distance from car body centre of gravity down to the "
                          "secondary lateral damper")
    h3: float = parameter("m", NONNEGATIVE,
                          "Vertical distance from bogie frame centre of gravity up to the "
                          "secondary suspension")
    h4: float = parameter("m", POSITIVE,
                          "Vertical distance from bogie frame centre of gravity down to the "
                          "wheelset centre")
    h5: float = parameter("m", NONNEGATIVE,
                          "Vertical distance from bogie frame centre of gravity up to the "
                          "secondary lateral damper")
    l: float = parameter("m", POSITIVE,  # noqa: E741 (the paper's symbol)
                         "Longitudinal distance from bogie centre to car body centre "
                         "(front bogie at +l, rear at -l)")
    l1: float = parameter("m", POSITIVE, "Half of bogie wheelbase")
    f11: float = parameter("N", POSITIVE, "Longitudinal creep coefficient")
    f22: float = parameter("N", POSITIVE, "Lateral creep coefficient")
    f23: float = parameter("N*m", NONNEGATIVE,
                           "Lateral/spin creep coefficient "
                           "(Table 2 prints N*m^2: the unit is N*m)")
    f33: float = parameter("N*m^2", NONNEGATIVE,
                           "Spin creep coefficient (Table 2 prints N: the unit is N*m^2)")
    mu: float = parameter("1", FRICTION, "Wheel/rail coefficient of friction")
    W: float = parameter("kg", POSITIVE,
                         "Axle load (mass per wheelset); "
                         "the wheel normal load N = W*g/2 is derived")
    g: float = parameter("m/s^2", POSITIVE, "Acceleration of gravity")
    r0: float = parameter("m", ROLLING_RADIUS,
                          "Nominal rolling radius (860 mm wheels of a high-speed trailer/EMU car)")
    lambda1: float = parameter("1", FINITE,
                               "Rolling-radius polynomial, linear coefficient (Eq. 32)")
    lambda2: float = parameter("1/m", FINITE,
                               "Rolling-radius polynomial, quadratic coefficient (Eq. 32)")
    lambda3: float = parameter("1/m^2", FINITE,
                               "Rolling-radius polynomial, cubic coefficient (Eq. 32)")
    lambda4: float = parameter("1/m^3", FINITE,
                               "Rolling-radius polynomial, quartic coefficient (Eq. 32)")
    lambda5: float = parameter("1/m^4", FINITE,
                               "Rolling-radius polynomial, quintic coefficient (Eq. 32)")
    d0: float = parameter("rad", FINITE, "Contact-angle polynomial, constant term (Eq. 33)")
    d1: float = parameter("rad/m", FINITE,
                          "Contact-angle polynomial, linear term (Eq. 33, paper's sign of y)")
    d4: float = parameter("rad/m^4", FINITE,
                          "Contact-angle polynomial, quartic term (Eq. 33, paper's sign of y)")
    d5: float = parameter("rad/m^5", FINITE,
                          "Contact-angle polynomial, quintic term (Eq. 33, paper's sign of y)")
    delta_max: float = parameter("rad", CONTACT_ANGLE,
                                 "Largest contact angle (S1002 flange angle, 70 deg): caps the "
                                 "contact-angle polynomial")
    # fmt: on

    def __post_init__(self) -> None:
        raise TypeError("VehicleFields is the parameter table of Vehicle: build a Vehicle")


#: Ordered mapping name -> :class:`ParameterSpec` of every vehicle parameter.
PARAMETERS: Mapping[str, ParameterSpec] = parameter_specs(VehicleFields)

#: The derived quantities: computed from parameters, never set.
DERIVED: Mapping[str, DerivedSpec] = MappingProxyType(
    {
        "v_u": DerivedSpec(
            "v_u",
            "m/s",
            "blow-off velocity of the yaw damper",
            "F_u / C_d1",
            "F_u (blow-off force) or C_d1 (first stage damping)",
            1e-6,
        ),
        "N": DerivedSpec(
            "N", "N", "wheel normal load", "W * g / 2", "W (axle load, kg) or g", 1e-3
        ),
    }
)


def derived_values(params: Mapping[str, float]) -> dict[str, float]:
    """The derived quantities of a complete parameter set.

    Parameters
    ----------
    params : Mapping[str, float]
        SI values by parameter name.

    Returns
    -------
    dict[str, float]
        ``{"v_u": F_u / C_d1 (m/s), "N": W * g / 2 (N)}``.
    """
    return {
        "v_u": params["F_u"] / params["C_d1"],
        "N": params["W"] * params["g"] / 2.0,
    }


# Consistency rules between parameters: (parameter, other, predicate, rule text).
_CONSISTENCY = (
    ("l", "l1", lambda p: p["l"] > p["l1"], "> l1 = {l1} m (bogie centres outside the wheelbase)"),
)


def suggest(name: str, known_names: object = None) -> tuple[str, ...]:
    """Known names close to a misspelt one, best first (same name in other case first).

    Parameters
    ----------
    name : str
        An unknown name.
    known_names : iterable of str, optional
        The names to choose from (default: the paper's parameters and derived names).

    Returns
    -------
    tuple of str
        Up to a few parameter or derived names; may be empty.
    """
    known = [*PARAMETERS, *DERIVED] if known_names is None else list(known_names)
    known = [k for k in known if k != name]
    exact_case = [k for k in known if k.lower() == name.lower()]
    close = difflib.get_close_matches(name, known, n=3, cutoff=0.6)
    return tuple(dict.fromkeys([*exact_case, *close]))
