"""Vehicles: a layout (bodies, force elements, wheel/rail data) and its validated parameters.
Rooms: parameters (the table, validation), rules, errors, contact, core (Vehicle), files, docs.

Every vehicle is a layout file (:mod:`railhunt.layout`; the format is in docs/model.md,
"Vehicle layouts"): its ``[parameters]`` are the vehicle's named values, each with unit,
meaning, source and rule, and ``vehicle.NAME``, :meth:`Vehicle.replace`, ``--set`` and the
studies act on them. The paper's vehicle is ``data/vehicles/paper2019.toml``; its
parameter table is :data:`PARAMETERS`, described below.

A :class:`Vehicle` of the paper's layout holds one SI float per model parameter (56 of
them, listed in :data:`PARAMETERS`) plus a name and a description.  Every way of building a vehicle
(the constructor, :meth:`Vehicle.replace`, :func:`load_vehicle`) goes through the same
checks (:func:`validate_value`, :func:`validate_all`), so an invalid vehicle cannot exist.
Each parameter is declared once, as a line of the table in
:mod:`railhunt.vehicle.parameters` (name, SI unit, rule, meaning); the ``Vehicle``
attribute, :data:`PARAMETERS`, validation and :func:`parameter_markdown` follow from it.

Two quantities of the paper are *derived*, not parameters (see :data:`DERIVED`):

* ``v_u = F_u / C_d1``, the blow-off velocity of the yaw damper, in m/s;
* ``N = W * g / 2``, the wheel normal load, in N.

They are available as properties and may appear in a vehicle file as a cross-check, but
they cannot be set: change the parameters they are computed from.

Vehicle files are TOML::

    [vehicle]
    name = "stiff-yaw-damper"
    base = "paper2019"          # optional: start from a shipped vehicle

    [parameters]
    C_d1 = 600000.0             # short form, SI value

    [parameters.K_d]            # table form; unit is optional but checked when given
    value = 2.0e7
    unit = "N/m"

    [contact]                   # optional: tabulated contact geometry from profiles
    wheel = "S1002"             # "S1002" (EN 13715) or a profile file (.prw, y z in mm)
    rail = "UIC60"              # "UIC60" (60E1, upright) or an upright rail profile file
    rail_inclination = 0.025    # 1:40
    gauge = 1.435               # m
    back_to_back = 1.36         # m
    wheel_radius = 0.43         # m, at the tape circle

Without ``[contact]`` the wheel/rail geometry is the paper's polynomials (Eqs. 32-33,
parameters ``lambda1..5``, ``d0..d5``); with it, the compiled right-hand side interpolates
the rigid contact geometry computed from the profiles (:class:`ContactSpec`).
"""

from railhunt.vehicle.contact import ContactSpec
from railhunt.vehicle.core import Vehicle
from railhunt.vehicle.docs import parameter_markdown
from railhunt.vehicle.errors import (
    DerivedParameterError,
    MissingParametersError,
    ParameterError,
    UnknownParameterError,
    VehicleFileError,
)
from railhunt.vehicle.files import load_vehicle, shipped_vehicles
from railhunt.vehicle.parameters import DERIVED, PARAMETERS, validate_all, validate_value
from railhunt.vehicle.rules import FINITE as FINITE  # also importable from here, as before
from railhunt.vehicle.rules import NONNEGATIVE as NONNEGATIVE
from railhunt.vehicle.rules import POSITIVE as POSITIVE
from railhunt.vehicle.rules import DerivedSpec, ParameterSpec, Rule
from railhunt.vehicle.rules import parameter as parameter

__all__ = [
    "DERIVED",
    "PARAMETERS",
    "DerivedParameterError",
    "DerivedSpec",
    "MissingParametersError",
    "ParameterError",
    "ParameterSpec",
    "Rule",
    "UnknownParameterError",
    "Vehicle",
    "VehicleFileError",
    "ContactSpec",
    "load_vehicle",
    "shipped_vehicles",
    "validate_all",
    "validate_value",
    "parameter_markdown",
]

