"""Vehicle parameters: the validated, immutable parameter set of the 17-DOF vehicle model.

A :class:`Vehicle` holds one SI float per model parameter (53 of them, listed in
:data:`PARAMETERS`) plus a name and a description.  Every way of building a vehicle
(the constructor, :meth:`Vehicle.replace`, :func:`load_vehicle`) goes through the same
checks (:func:`validate_value`, :func:`validate_all`), so an invalid vehicle cannot exist.

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

import dataclasses
import difflib
import functools
import math
import numbers
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from types import MappingProxyType
from typing import Any, NamedTuple, Self

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
]

_DATA_PACKAGE = "railhunt"
_VEHICLE_DIR = ("data", "vehicles")
_DIMENSIONLESS = "1"
_TABLE_KEYS = frozenset({"value", "unit", "meaning", "source"})
_VEHICLE_KEYS = frozenset({"name", "description", "base"})
_CONTACT_KEYS = frozenset({"wheel", "rail", "rail_inclination", "gauge", "back_to_back",
                           "wheel_radius", "y_max", "y_step"})  # fmt: skip


# --------------------------------------------------------------------------- formatting


def _fmt(value: object) -> str:
    """Format a value for an error message: integral floats without ``.0``, others by repr."""
    if isinstance(value, bool):
        return str(value)
    if isinstance(value, float):
        if math.isfinite(value) and value.is_integer() and abs(value) < 1e15:
            return str(int(value))
        return repr(value)
    if isinstance(value, int):
        return str(value)
    return repr(value)


def _with_unit(value: object, unit: str | None) -> str:
    """``"-5 N*s/m"``; dimensionless (unit ``"1"``) and unit-less values print bare."""
    text = _fmt(value)
    if unit and unit != _DIMENSIONLESS:
        return f"{text} {unit}"
    return text


# --------------------------------------------------------------------------- errors


def _rebuild_error(cls: type, args: tuple, state: dict) -> Exception:
    err = cls.__new__(cls)
    Exception.__init__(err, *args)
    err.__dict__.update(state)
    return err


class ParameterError(ValueError):
    """An invalid vehicle parameter value.

    Parameters
    ----------
    parameter : str or None
        Name of the offending parameter (``None`` when the error is about a set of names).
    value : object
        The rejected value, as given.
    rule : str
        The rule that was broken, e.g. ``"finite and > 0"``.
    unit : str or None
        Expected SI unit of the parameter.
    meaning : str, optional
        Physical meaning, appended to the default message.
    message : str, optional
        Full message, replacing the default
        ``"<name> = <value> <unit> is invalid: must be <rule> (<meaning>)"``.

    Attributes
    ----------
    parameter, value, rule, unit : see Parameters
    path : str or None
        Vehicle file the value came from, if any (prefixed to the message by ``str()``).
    """

    def __init__(
        self,
        parameter: str | None,
        value: object,
        rule: str,
        unit: str | None,
        *,
        meaning: str | None = None,
        message: str | None = None,
    ) -> None:
        if message is None:
            message = f"{parameter} = {_with_unit(value, unit)} is invalid: must be {rule}"
            if meaning:
                message += f" ({meaning})"
        super().__init__(message)
        self.parameter = parameter
        self.value = value
        self.rule = rule
        self.unit = unit
        self.message = message
        self.path: str | None = None

    def __str__(self) -> str:
        return f"{self.path}: {self.message}" if self.path else self.message

    def __reduce__(self) -> tuple:
        return (_rebuild_error, (type(self), self.args, dict(self.__dict__)))


class UnknownParameterError(ParameterError):
    """A parameter name that the model does not know.

    Attributes
    ----------
    suggestions : tuple of str
        Close known names (``difflib``), best first; may be empty.
    """

    def __init__(self, parameter: str, value: object = None) -> None:
        suggestions = _suggest(parameter)
        if suggestions:
            quoted = [repr(s) for s in suggestions]
            options = quoted[0] if len(quoted) == 1 else f"{', '.join(quoted[:-1])} or {quoted[-1]}"
            hint = f"did you mean {options}?"
        else:
            hint = f"see railhunt.vehicle.PARAMETERS for the {len(PARAMETERS)} known names"
        super().__init__(
            parameter,
            value,
            "a known parameter name",
            None,
            message=f"unknown vehicle parameter {parameter!r}; {hint}",
        )
        self.suggestions = suggestions


class MissingParametersError(ParameterError):
    """Parameters absent from a complete parameter set.

    Attributes
    ----------
    missing : tuple of str
        The missing names, in :data:`PARAMETERS` order.
    """

    def __init__(self, missing: tuple[str, ...], *, hint: str = "") -> None:
        message = f"{len(missing)} vehicle parameter(s) missing: {', '.join(missing)}"
        if hint:
            message += f" ({hint})"
        super().__init__(None, None, "every parameter must be given", None, message=message)
        self.missing = missing


class DerivedParameterError(ParameterError):
    """An attempt to set a derived quantity (``v_u`` or ``N``) directly."""

    def __init__(self, parameter: str, value: object = None) -> None:
        spec = DERIVED[parameter]
        message = (
            f"{parameter} is derived, not a parameter: {parameter} = {spec.formula} "
            f"({spec.meaning}, {spec.unit}); change {spec.change_instead} instead"
        )
        super().__init__(
            parameter, value, f"not set (derived: {spec.formula})", spec.unit, message=message
        )


class VehicleFileError(ValueError):
    """A vehicle file that is not valid TOML or has the wrong structure."""


# --------------------------------------------------------------------------- rules


@dataclass(frozen=True)
class Rule:
    """Admissible range of a parameter: always finite, optionally bounded.

    Parameters
    ----------
    lower, upper : float or None
        Bounds (``None``: unbounded on that side).
    lower_strict, upper_strict : bool
        Whether the bound itself is excluded.
    reason : str
        Why the range is what it is (shown in error messages).
    upper_label : str or None
        Text for the upper bound in messages (e.g. ``"pi/2"``).
    """

    lower: float | None = None
    lower_strict: bool = False
    upper: float | None = None
    upper_strict: bool = False
    reason: str = ""
    upper_label: str | None = None

    def accepts(self, value: float) -> bool:
        """Return whether the float ``value`` satisfies the rule."""
        if not math.isfinite(value):
            return False
        if self.lower is not None:
            if value < self.lower or (self.lower_strict and value == self.lower):
                return False
        if self.upper is not None:
            if value > self.upper or (self.upper_strict and value == self.upper):
                return False
        return True

    def __str__(self) -> str:
        lo, hi = self.lower, self.upper
        hi_text = self.upper_label or (_fmt(hi) if hi is not None else "")
        if lo is None and hi is None:
            text = "finite"
        elif hi is None:
            text = f"finite and {'>' if self.lower_strict else '>='} {_fmt(lo)}"
        elif lo is None:
            text = f"finite and {'<' if self.upper_strict else '<='} {hi_text}"
        else:
            left = "(" if self.lower_strict else "["
            right = ")" if self.upper_strict else "]"
            text = f"finite and in {left}{_fmt(lo)}, {hi_text}{right}"
        return f"{text}; {self.reason}" if self.reason else text


FINITE = Rule()
POSITIVE = Rule(lower=0.0, lower_strict=True)
NONNEGATIVE = Rule(lower=0.0)

# The rule table.  Order defines the order of PARAMETERS and of the Vehicle fields;
# units and meanings come from the shipped vehicle file.
_RULES: dict[str, Rule] = {
    "M_c": POSITIVE,
    "M_t": POSITIVE,
    "M_w": POSITIVE,
    "J_cx": POSITIVE,
    "J_cz": POSITIVE,
    "J_tx": POSITIVE,
    "J_tz": POSITIVE,
    "J_wz": POSITIVE,
    "K_px": POSITIVE,
    "K_py": POSITIVE,
    "K_pz": POSITIVE,
    "K_sx": POSITIVE,
    "K_sy": POSITIVE,
    "K_sz": POSITIVE,
    "C_px": NONNEGATIVE,
    "C_py": NONNEGATIVE,
    "C_pz": NONNEGATIVE,
    "C_sy": NONNEGATIVE,
    "C_sz": NONNEGATIVE,
    "K_d": POSITIVE,
    "C_d1": POSITIVE,
    "C_d2": POSITIVE,
    "F_u": POSITIVE,
    "a": Rule(
        lower=0.5,
        lower_strict=True,
        upper=1.0,
        reason="half the contact-point distance in m (0.7465 for standard gauge)",
    ),
    "b1": POSITIVE,
    "b2": POSITIVE,
    "b3": POSITIVE,
    "b4": POSITIVE,
    "h1": NONNEGATIVE,
    "h2": NONNEGATIVE,
    "h3": NONNEGATIVE,
    "h4": POSITIVE,
    "h5": NONNEGATIVE,
    "l": POSITIVE,
    "l1": POSITIVE,
    "f11": POSITIVE,
    "f22": POSITIVE,
    "f23": NONNEGATIVE,
    "f33": NONNEGATIVE,
    "mu": Rule(
        lower=0.0,
        lower_strict=True,
        upper=1.5,
        reason="a friction coefficient above 1.5 is not physical",
    ),
    "W": POSITIVE,
    "g": POSITIVE,
    "r0": Rule(
        lower=0.2,
        lower_strict=True,
        upper=0.7,
        reason="rolling radius in m (a value in mm is a common mistake)",
    ),
    "lambda1": FINITE,
    "lambda2": FINITE,
    "lambda3": FINITE,
    "lambda4": FINITE,
    "lambda5": FINITE,
    "d0": FINITE,
    "d1": FINITE,
    "d4": FINITE,
    "d5": FINITE,
    "delta_max": Rule(
        lower=0.0,
        lower_strict=True,
        upper=math.pi / 2,
        upper_strict=True,
        upper_label="pi/2",
        reason="a contact angle in rad",
    ),
}


class ParameterSpec(NamedTuple):
    """Description of one vehicle parameter.

    Attributes
    ----------
    name : str
        Attribute name on :class:`Vehicle` and key in vehicle files.
    unit : str
        SI unit (``"1"`` for dimensionless).
    meaning : str
        Physical meaning.
    rule : Rule
        Admissible range; ``str(rule)`` gives the text used in error messages.
    """

    name: str
    unit: str
    meaning: str
    rule: Rule


class DerivedSpec(NamedTuple):
    """Description of a derived quantity (computed from parameters, never set).

    Attributes
    ----------
    name, unit, meaning : str
        As for :class:`ParameterSpec`.
    formula : str
        How it is computed, e.g. ``"F_u / C_d1"``.
    change_instead : str
        Which parameter(s) to change to change it.
    rel_tol : float
        Relative tolerance when a vehicle file states the value as a cross-check.
    """

    name: str
    unit: str
    meaning: str
    formula: str
    change_instead: str
    rel_tol: float


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


def _derived_values(params: Mapping[str, float]) -> dict[str, float]:
    return {
        "v_u": params["F_u"] / params["C_d1"],
        "N": params["W"] * params["g"] / 2.0,
    }


# Consistency rules between parameters: (parameter, other, predicate, rule text).
_CONSISTENCY = (
    ("l", "l1", lambda p: p["l"] > p["l1"], "> l1 = {l1} m (bogie centres outside the wheelbase)"),
)


# --------------------------------------------------------------------------- shipped data


def _shipped_dir() -> Any:
    folder = resources.files(_DATA_PACKAGE)
    for part in _VEHICLE_DIR:
        folder = folder / part
    return folder


def _shipped_path(name: str) -> Any:
    return _shipped_dir() / f"{name}.toml"


def shipped_vehicles() -> tuple[str, ...]:
    """Names of the vehicles shipped with railhunt (usable as ``[vehicle] base``).

    Returns
    -------
    tuple of str
        Sorted names, e.g. ``("paper2019",)``.
    """
    suffix = ".toml"
    files = (p.name for p in _shipped_dir().iterdir())
    return tuple(sorted(f[: -len(suffix)] for f in files if f.endswith(suffix)))


def _build_parameters() -> Mapping[str, ParameterSpec]:
    data = tomllib.loads(_shipped_path("paper2019").read_text(encoding="utf-8"))
    tables = data.get("parameters", {})
    if set(tables) != set(_RULES):
        raise RuntimeError(
            "railhunt installation error: paper2019.toml and the rule table disagree "
            f"(file only: {sorted(set(tables) - set(_RULES))}, "
            f"rules only: {sorted(set(_RULES) - set(tables))})"
        )
    return MappingProxyType(
        {
            name: ParameterSpec(name, tables[name]["unit"], tables[name]["meaning"], rule)
            for name, rule in _RULES.items()
        }
    )


#: Ordered mapping name -> :class:`ParameterSpec` of every vehicle parameter.
PARAMETERS: Mapping[str, ParameterSpec] = _build_parameters()


def _suggest(name: str) -> tuple[str, ...]:
    known = [*PARAMETERS, *DERIVED]
    exact_case = [k for k in known if k.lower() == name.lower()]
    close = difflib.get_close_matches(name, known, n=3, cutoff=0.6)
    return tuple(dict.fromkeys([*exact_case, *close]))


# --------------------------------------------------------------------------- validation


def _as_float(name: str, value: object, unit: str | None, meaning: str) -> float:
    """Convert a real number (not bool) to float, or raise ParameterError."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ParameterError(
            name, value, f"a real number, not {type(value).__name__}", unit, meaning=meaning
        )
    try:
        return float(value)
    except (OverflowError, ValueError, TypeError):
        raise ParameterError(name, value, "finite", unit, meaning=meaning) from None


def validate_value(name: str, value: object) -> float:
    """Check one parameter value against its rule.

    Parameters
    ----------
    name : str
        Parameter name (a key of :data:`PARAMETERS`).
    value : object
        Candidate value in the parameter's SI unit: an int or float (not a bool).

    Returns
    -------
    float
        The value as a float.

    Raises
    ------
    UnknownParameterError
        ``name`` is not a parameter.
    DerivedParameterError
        ``name`` is a derived quantity (``v_u`` or ``N``).
    ParameterError
        The value is not a real number, not finite, or out of range.
    """
    if name in DERIVED:
        raise DerivedParameterError(name, value)
    spec = PARAMETERS.get(name)
    if spec is None:
        raise UnknownParameterError(name, value)
    x = _as_float(name, value, spec.unit, spec.meaning)
    if not spec.rule.accepts(x):
        raise ParameterError(name, value, str(spec.rule), spec.unit, meaning=spec.meaning)
    return x


def validate_all(params: Mapping[str, object]) -> dict[str, float]:
    """Check a complete parameter set: names, every value, and consistency rules.

    Parameters
    ----------
    params : Mapping[str, object]
        Every name of :data:`PARAMETERS` mapped to its SI value.

    Returns
    -------
    dict[str, float]
        The values as floats, in :data:`PARAMETERS` order.

    Raises
    ------
    UnknownParameterError, DerivedParameterError
        A name is not a parameter.
    MissingParametersError
        Some parameters are absent (all of them are listed).
    ParameterError
        A value breaks its rule, or a consistency rule (``l > l1``) is broken.
    """
    for name in params:
        if name not in PARAMETERS:
            if name in DERIVED:
                raise DerivedParameterError(name, params[name])
            raise UnknownParameterError(name, params[name])
    missing = tuple(name for name in PARAMETERS if name not in params)
    if missing:
        raise MissingParametersError(missing)
    out = {name: validate_value(name, params[name]) for name in PARAMETERS}
    for name, other, predicate, text in _CONSISTENCY:
        if not predicate(out):
            spec = PARAMETERS[name]
            rule = text.format(**{other: _fmt(out[other])})
            raise ParameterError(name, params[name], rule, spec.unit, meaning=spec.meaning)
    return out


# --------------------------------------------------------------------------- contact


@dataclass(frozen=True)
class ContactSpec:
    """Wheel/rail contact geometry to compute from profiles (a vehicle file's ``[contact]``).

    A vehicle with a ``ContactSpec`` runs on the tabulated rigid contact geometry of these
    profiles (``r_L, r_R, delta_L, delta_R`` versus ``y``, interpolated in the compiled
    right-hand side) instead of the paper's polynomials; see ``docs/contact.md``.

    Parameters
    ----------
    wheel : str
        ``"S1002"`` (analytic EN 13715 profile) or the path of a wheel profile file
        (SIMPACK ``.prw`` or two columns ``y z`` in mm).
    rail : str
        ``"UIC60"`` (analytic 60E1 head, upright) or the path of an *upright* rail profile.
    rail_inclination : float
        Rail cant as a tangent, in [0, 0.1] (0.025 = 1:40, 0.05 = 1:20).
    gauge : float
        Track gauge (m), in [1.3, 1.8].
    back_to_back : float
        Distance between the wheels' inner faces (m), in [1.2, 1.75].
    wheel_radius : float
        Wheel radius at the tape circle (m), in [0.2, 0.8].
    y_max, y_step : float
        Half-range (m, in [0.005, 0.02]) and step (m, in [1e-5, 5e-4]) of the table.
    """

    wheel: str = "S1002"
    rail: str = "UIC60"
    rail_inclination: float = 0.025
    gauge: float = 1.435
    back_to_back: float = 1.36
    wheel_radius: float = 0.43
    y_max: float = 0.012
    y_step: float = 1e-4

    _RANGES = {"rail_inclination": (0.0, 0.1, ""), "gauge": (1.3, 1.8, "m"),
               "back_to_back": (1.2, 1.75, "m"), "wheel_radius": (0.2, 0.8, "m"),
               "y_max": (0.005, 0.02, "m"), "y_step": (1e-5, 5e-4, "m")}  # fmt: skip

    def __post_init__(self) -> None:
        for key in ("wheel", "rail"):
            value = getattr(self, key)
            if not isinstance(value, str) or not value.strip():
                raise ValueError(f"contact {key} = {value!r} is invalid: must be a profile "
                                 "name or a file path")  # fmt: skip
        for key, (low, high, unit) in self._RANGES.items():
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, numbers.Real) or not (
                math.isfinite(value) and low <= value <= high
            ):
                raise ValueError(f"contact {key} = {value!r} {unit} is invalid: must be in "
                                 f"[{low:g}, {high:g}] {unit}".replace("  ", " "))  # fmt: skip
            object.__setattr__(self, key, float(value))
        if self.gauge <= self.back_to_back:
            raise ValueError(f"contact gauge = {self.gauge} m is invalid: must exceed "
                             f"back_to_back = {self.back_to_back} m")  # fmt: skip

    def geometry(self) -> Any:
        """The rigid contact geometry of these profiles (computed once, then cached)."""
        return _contact_geometry(self)

    def toml_lines(self) -> list[str]:
        """The ``[contact]`` section of a vehicle file."""
        lines = ["", "[contact]", f"wheel = {_toml_string(self.wheel)}",
                 f"rail = {_toml_string(self.rail)}"]  # fmt: skip
        for key in self._RANGES:
            lines.append(f"{key} = {getattr(self, key)!r}")
        return lines


@functools.lru_cache(maxsize=16)
def _contact_geometry(spec: ContactSpec) -> Any:
    from railhunt.contact.geometry import contact_geometry
    from railhunt.contact.profiles import read_profile, s1002, uic60

    wheel = s1002() if spec.wheel.upper() == "S1002" else read_profile(spec.wheel, "wheel")
    rail = uic60() if spec.rail.upper() in ("UIC60", "60E1") else read_profile(spec.rail, "rail")
    return contact_geometry(wheel, rail, rail_inclination=spec.rail_inclination,
                            gauge=spec.gauge, back_to_back=spec.back_to_back,
                            r0=spec.wheel_radius, y_max=spec.y_max,
                            y_step=spec.y_step)  # fmt: skip


# --------------------------------------------------------------------------- Vehicle


@dataclass(frozen=True, kw_only=True, repr=False)
class Vehicle:
    """Validated, immutable parameter set of the 17-DOF vehicle (SI units).

    Construct with every parameter as a keyword (see :data:`PARAMETERS` for names, units
    and meanings), or use :meth:`paper2019`, :func:`load_vehicle` or :meth:`replace`.
    The constructor validates every value; a :class:`ParameterError` is raised otherwise.

    Two vehicles are equal (and hash equal) when their names and all parameters are
    equal; the description is ignored.

    Parameters
    ----------
    name : str
        Short identifier (non-empty).
    description : str
        Free text.
    contact : ContactSpec, optional
        Contact geometry from profiles (tabulated in the model); None: the polynomials.
    **parameters : float
        One keyword per parameter of :data:`PARAMETERS` (e.g. ``M_c`` in kg).
    """

    name: str = "custom"
    description: str = field(default="", compare=False)
    contact: ContactSpec | None = None

    M_c: float
    M_t: float
    M_w: float
    J_cx: float
    J_cz: float
    J_tx: float
    J_tz: float
    J_wz: float
    K_px: float
    K_py: float
    K_pz: float
    K_sx: float
    K_sy: float
    K_sz: float
    C_px: float
    C_py: float
    C_pz: float
    C_sy: float
    C_sz: float
    K_d: float
    C_d1: float
    C_d2: float
    F_u: float
    a: float
    b1: float
    b2: float
    b3: float
    b4: float
    h1: float
    h2: float
    h3: float
    h4: float
    h5: float
    l: float  # noqa: E741  (the paper's symbol)
    l1: float
    f11: float
    f22: float
    f23: float
    f33: float
    mu: float
    W: float
    g: float
    r0: float
    lambda1: float
    lambda2: float
    lambda3: float
    lambda4: float
    lambda5: float
    d0: float
    d1: float
    d4: float
    d5: float
    delta_max: float

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise ValueError(f"vehicle name must be a non-empty string, got {self.name!r}")
        if not isinstance(self.description, str):
            raise ValueError(f"vehicle description must be a string, got {self.description!r}")
        if self.contact is not None and not isinstance(self.contact, ContactSpec):
            raise ValueError(f"vehicle contact must be a ContactSpec or None, got "
                             f"{self.contact!r}")  # fmt: skip
        values = validate_all({name: getattr(self, name) for name in PARAMETERS})
        for name, value in values.items():
            object.__setattr__(self, name, value)

    # -- constructors -------------------------------------------------------------------

    @classmethod
    def paper2019(cls) -> Self:
        """The high-speed vehicle of Table 2 of the 2019 hunting paper (shipped file).

        Returns
        -------
        Vehicle
            The ``paper2019`` vehicle.
        """
        return cls.shipped("paper2019")

    @classmethod
    def shipped(cls, name: str) -> Self:
        """Load a vehicle shipped with railhunt by name (see :func:`shipped_vehicles`).

        Parameters
        ----------
        name : str
            Shipped vehicle name, e.g. ``"paper2019"``.

        Returns
        -------
        Vehicle
        """
        vehicle = _load_shipped(name)
        if type(vehicle) is not cls:  # subclass: rebuild as that class
            return cls(name=vehicle.name, description=vehicle.description,
                       contact=vehicle.contact, **vehicle.as_dict())  # fmt: skip
        return vehicle  # type: ignore[return-value]

    def replace(self, **changes: Any) -> Self:
        """Return a validated copy with some parameters (or name/description) changed.

        Parameters
        ----------
        **changes
            New SI values by parameter name; ``name`` and ``description`` are accepted too.

        Returns
        -------
        Vehicle
            A new vehicle; ``self`` is unchanged.

        Raises
        ------
        DerivedParameterError
            For ``v_u`` or ``N`` (derived: change ``F_u``/``C_d1`` or ``W`` instead).
        UnknownParameterError
            For any other unknown name (with a "did you mean" suggestion).
        ParameterError
            If a new value, or the resulting set, breaks a rule.
        """
        for key, value in changes.items():
            if key in ("name", "description", "contact"):
                continue
            if key in DERIVED:
                raise DerivedParameterError(key, value)
            if key not in PARAMETERS:
                raise UnknownParameterError(key, value)
        return dataclasses.replace(self, **changes)

    # -- derived quantities -------------------------------------------------------------

    @property
    def v_u(self) -> float:
        """Blow-off velocity of the yaw damper, ``F_u / C_d1``, in m/s."""
        return self.F_u / self.C_d1

    @property
    def N(self) -> float:
        """Wheel normal load, ``W * g / 2``, in N."""
        return self.W * self.g / 2.0

    # -- views ---------------------------------------------------------------------------

    def as_dict(self) -> dict[str, float]:
        """Parameters as a new dict name -> SI float, in :data:`PARAMETERS` order."""
        return {name: getattr(self, name) for name in PARAMETERS}

    def derived(self) -> dict[str, float]:
        """Derived quantities ``{"v_u": m/s, "N": N}``."""
        return {"v_u": self.v_u, "N": self.N}

    def parameter_table(self, include_derived: bool = False) -> list[tuple[str, float, str, str]]:
        """Rows ``(name, value, unit, meaning)`` for reports, in :data:`PARAMETERS` order.

        Parameters
        ----------
        include_derived : bool
            Append rows for ``v_u`` and ``N``.

        Returns
        -------
        list of tuple (str, float, str, str)
        """
        rows = [(s.name, getattr(self, s.name), s.unit, s.meaning) for s in PARAMETERS.values()]
        if include_derived:
            for spec in DERIVED.values():
                meaning = f"{spec.meaning} (derived: {spec.formula})"
                rows.append((spec.name, getattr(self, spec.name), spec.unit, meaning))
        return rows

    def __repr__(self) -> str:
        return f"Vehicle({self.name!r}, {len(PARAMETERS)} parameters)"

    # -- output -------------------------------------------------------------------------

    def to_toml(self, path: str | os.PathLike[str]) -> Path:
        """Write the vehicle as a complete TOML vehicle file (read back by :func:`load_vehicle`).

        Parameters
        ----------
        path : str or os.PathLike
            Destination file (overwritten).

        Returns
        -------
        pathlib.Path
            The path written.
        """
        path = Path(path)
        path.write_text(self._toml_text(), encoding="utf-8")
        return path

    def _toml_text(self) -> str:
        lines = [
            "# railhunt vehicle file (written by railhunt.vehicle.Vehicle.to_toml).",
            "# SI units throughout. Each parameter: value (SI), unit, meaning.",
            f"# Derived, not inputs: v_u = F_u / C_d1 = {self.v_u!r} m/s,"
            f" N = W * g / 2 = {self.N!r} N.",
            "",
            "[vehicle]",
            f"name = {_toml_string(self.name)}",
            f"description = {_toml_string(self.description)}",
        ]
        for spec in PARAMETERS.values():
            lines += [
                "",
                f"[parameters.{spec.name}]",
                f"value = {float(getattr(self, spec.name))!r}",
                f"unit = {_toml_string(spec.unit)}",
                f"meaning = {_toml_string(spec.meaning)}",
            ]
        if self.contact is not None:
            lines += self.contact.toml_lines()
        return "\n".join(lines) + "\n"


def _toml_string(text: str) -> str:
    """Quote ``text`` as a TOML basic string."""
    escapes = {
        '"': '\\"',
        "\\": "\\\\",
        "\b": "\\b",
        "\t": "\\t",
        "\n": "\\n",
        "\f": "\\f",
        "\r": "\\r",
    }
    out = []
    for ch in text:
        if ch in escapes:
            out.append(escapes[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


# --------------------------------------------------------------------------- loading


@functools.cache
def _load_shipped(name: str) -> Vehicle:
    available = shipped_vehicles()
    if name not in available:
        raise VehicleFileError(
            f"no shipped vehicle named {name!r}; available: {', '.join(available)}"
        )
    path = _shipped_path(name)
    return _vehicle_from_data(
        _parse_toml(path.read_text(encoding="utf-8"), str(path)),
        str(path),
        default_name=name,
        depth=1,
    )


def _parse_toml(text: str, where: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise VehicleFileError(f"{where}: not a valid TOML file: {exc}") from exc


def load_vehicle(path: str | os.PathLike[str]) -> Vehicle:
    """Read a vehicle TOML file.

    Each parameter is given under ``[parameters]`` either in short form
    (``M_c = 28000.0``) or in table form (``[parameters.M_c]`` with ``value`` and optional
    ``unit``, ``meaning``, ``source``; a given ``unit`` must equal the expected SI unit).
    With ``[vehicle] base = "<shipped name>"`` the file starts from that shipped vehicle
    and overrides only the parameters it lists; otherwise every parameter is required.
    The derived ``v_u`` (m/s) and ``N`` (N) may be stated as a cross-check: they must
    agree with ``F_u / C_d1`` (relative 1e-6) and ``W * g / 2`` (relative 1e-3).

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file.

    Returns
    -------
    Vehicle
        Named by ``[vehicle] name``, defaulting to the file's stem.

    Raises
    ------
    VehicleFileError
        Invalid TOML, unknown sections or keys, unknown base.
    ParameterError
        (or a subclass) for unknown, missing, non-numeric, mis-united, out-of-range or
        inconsistent parameters; ``str(error)`` starts with the file path.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise VehicleFileError(f"{path}: not a UTF-8 text file") from exc
    return _vehicle_from_data(_parse_toml(text, str(path)), str(path), default_name=path.stem)


def _vehicle_from_data(
    data: dict[str, Any], where: str, *, default_name: str, depth: int = 0
) -> Vehicle:
    try:
        return _build_vehicle(data, where, default_name, depth)
    except ParameterError as exc:
        if exc.path is None:
            exc.path = where
        raise


def _build_vehicle(data: dict[str, Any], where: str, default_name: str, depth: int) -> Vehicle:
    extra = set(data) - {"vehicle", "parameters", "contact"}
    if extra:
        raise VehicleFileError(
            f"{where}: unknown top-level key(s) {sorted(extra)}; "
            "expected only [vehicle], [parameters] and [contact]"
        )
    contact = _read_contact(data.get("contact"), where)
    meta = data.get("vehicle", {})
    if not isinstance(meta, dict):
        raise VehicleFileError(f"{where}: 'vehicle' must be a table")
    bad = set(meta) - _VEHICLE_KEYS
    if bad:
        raise VehicleFileError(
            f"{where}: unknown key(s) {sorted(bad)} in [vehicle]; "
            f"allowed: {', '.join(sorted(_VEHICLE_KEYS))}"
        )
    for key in ("name", "description", "base"):
        if key in meta and not isinstance(meta[key], str):
            raise VehicleFileError(f"{where}: [vehicle] {key} must be a string")

    table = data.get("parameters", {})
    if not isinstance(table, dict):
        raise VehicleFileError(f"{where}: 'parameters' must be a table")

    given: dict[str, float] = {}
    stated: dict[str, float] = {}
    for name, entry in table.items():
        if name in DERIVED:
            spec = DERIVED[name]
            stated[name] = _read_entry(name, entry, spec.unit, spec.meaning)
            continue
        if name not in PARAMETERS:
            raise UnknownParameterError(name, entry)
        spec = PARAMETERS[name]
        given[name] = validate_value(name, _read_entry(name, entry, spec.unit, spec.meaning))

    base_name = meta.get("base")
    if base_name is not None:
        if depth > 0:
            raise VehicleFileError(f"{where}: a shipped vehicle cannot itself have a base")
        base = _load_shipped(base_name)
        params: dict[str, float] = {**base.as_dict(), **given}
        if contact is None:
            contact = base.contact
    else:
        missing = tuple(name for name in PARAMETERS if name not in given)
        if missing:
            raise MissingParametersError(
                missing,
                hint='give them, or set [vehicle] base = "paper2019" to start from '
                "a shipped vehicle",
            )
        params = given
    values = validate_all(params)

    actual = _derived_values(values)
    for name, value in stated.items():
        spec = DERIVED[name]
        if not math.isclose(value, actual[name], rel_tol=spec.rel_tol):
            raise ParameterError(
                name,
                value,
                f"equal to {spec.formula} = {_with_unit(actual[name], spec.unit)} "
                f"(to relative {spec.rel_tol:g}); {name} is derived: change "
                f"{spec.change_instead} instead, or remove it",
                spec.unit,
                meaning=spec.meaning,
            )

    return Vehicle(
        name=meta.get("name", default_name),
        description=meta.get("description", ""),
        contact=contact,
        **values,
    )


def _read_contact(table: object, where: str) -> ContactSpec | None:
    """The ``[contact]`` section; file paths relative to the vehicle file's folder."""
    if table is None:
        return None
    if not isinstance(table, dict):
        raise VehicleFileError(f"{where}: 'contact' must be a table")
    bad = set(table) - _CONTACT_KEYS
    if bad:
        raise VehicleFileError(f"{where}: unknown key(s) {sorted(bad)} in [contact]; "
                               f"allowed: {', '.join(sorted(_CONTACT_KEYS))}")  # fmt: skip
    entries = dict(table)
    folder = Path(where).parent
    for key, names in (("wheel", ("S1002",)), ("rail", ("UIC60", "60E1"))):
        value = entries.get(key)
        if isinstance(value, str) and value.upper() not in names:
            path = Path(value)
            if not path.is_absolute():
                path = folder / path
            if not path.is_file():
                raise VehicleFileError(f"{where}: [contact] {key} = {value!r} is neither "
                                       f"{' nor '.join(names)} nor an existing file")  # fmt: skip
            entries[key] = str(path.resolve())
    try:
        return ContactSpec(**entries)
    except (TypeError, ValueError) as exc:
        raise VehicleFileError(f"{where}: [contact]: {exc}") from None


def _read_entry(name: str, entry: object, unit: str, meaning: str) -> float:
    """Value of a short-form or table-form entry, with the unit check of the table form."""
    if isinstance(entry, dict):
        bad = set(entry) - _TABLE_KEYS
        if bad:
            raise ParameterError(
                name,
                entry,
                "a table with keys value, unit, meaning, source",
                unit,
                message=f"[parameters.{name}]: unknown key(s) {sorted(bad)}; "
                f"allowed: {', '.join(sorted(_TABLE_KEYS))}",
            )
        if "value" not in entry:
            raise ParameterError(
                name,
                None,
                "a table with a 'value' key",
                unit,
                message=f"[parameters.{name}]: missing 'value' (SI value in {unit})",
            )
        given_unit = entry.get("unit")
        if given_unit is not None and given_unit != unit:
            raise ParameterError(
                name,
                entry["value"],
                f"given in {unit}",
                unit,
                message=f"{name}: unit {given_unit!r} does not match the expected unit "
                f"{unit!r}; vehicle files use SI units: give the value in {unit}",
            )
        entry = entry["value"]
    return _as_float(name, entry, unit, meaning)
