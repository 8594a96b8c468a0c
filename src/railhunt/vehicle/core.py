"""The :class:`Vehicle`: a layout (bodies, force elements, wheel/rail data) and the
validated values of its named parameters."""

import dataclasses
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Self

from railhunt.vehicle.contact import ContactSpec
from railhunt.vehicle.errors import (
    DerivedOverrideWarning,
    DerivedParameterError,
    UnknownParameterError,
)
from railhunt.vehicle.parameters import DERIVED, validate_with

if TYPE_CHECKING:
    from railhunt.layout.assembly import Assembly
    from railhunt.layout.spec import LayoutSpec

__all__ = ["Vehicle", "set_file_readers"]

_IDENTITY = ("name", "description", "contact", "layout", "values")

#: How vehicle files are read: :mod:`railhunt.vehicle.files` builds vehicles from files, so
#: it sits above this module, and hands its readers over when it is imported (the package
#: imports it): ``paper_layout`` (the default layout of ``Vehicle()``), ``load_shipped``
#: (:meth:`Vehicle.shipped`) and ``load_vehicle`` (:meth:`Vehicle.from_toml`).
_READERS: dict[str, Any] = {}


def set_file_readers(**readers: Any) -> None:
    """Hand this module the readers of vehicle files (``paper_layout``, ``load_shipped``,
    ``load_vehicle``): called once, by :mod:`railhunt.vehicle.files`."""
    _READERS.update(readers)


@dataclass(frozen=True, init=False, repr=False, eq=False)
class Vehicle:
    """A vehicle: its layout and the validated, immutable values of its parameters (SI).

    Construct with :meth:`paper2019`, :meth:`shipped`, :func:`load_vehicle` or
    :meth:`replace`; or with every parameter as a keyword (``Vehicle(name="x", M_c=...,
    ...)``: the paper's layout, see :data:`PARAMETERS`). Every value is checked against its
    rule and the layout against its parameters; a :class:`ParameterError` (or a
    :class:`~railhunt.layout.spec.LayoutError`) is raised otherwise. ``vehicle.NAME`` is
    the value of parameter ``NAME``.

    Two vehicles are equal (and hash equal) when their names, layouts, contact and all
    parameters are equal; the description is ignored.

    Parameters
    ----------
    name : str
        Short identifier (non-empty).
    description : str
        Free text.
    contact : ContactSpec, optional
        Contact geometry from profiles (tabulated in the model); None: the layout's.
    layout : LayoutSpec, optional
        Bodies, elements and wheel/rail data; default: the paper's vehicle
        (``paper2019.toml``).
    values : Mapping[str, float], optional
        The parameters by name (SI); more may be given as keywords.
    **parameters : float
        Parameter values by name (``M_c``, the car body mass in kg; ...).
    """

    name: str
    description: str
    contact: ContactSpec | None
    layout: "LayoutSpec"
    values: Mapping[str, float]

    def __init__(self, *, name: str = "custom", description: str = "",
                 contact: ContactSpec | None = None, layout: "LayoutSpec | None" = None,
                 values: Mapping[str, float] | None = None, **parameters: Any) -> None:  # fmt: skip
        if not isinstance(name, str) or not name.strip():
            raise ValueError(f"vehicle name must be a non-empty string, got {name!r}")
        if not isinstance(description, str):
            raise ValueError(f"vehicle description must be a string, got {description!r}")
        if contact is not None and not isinstance(contact, ContactSpec):
            raise ValueError(f"vehicle contact must be a ContactSpec or None, got "
                             f"{contact!r}")  # fmt: skip
        if layout is None:
            layout = _READERS["paper_layout"]()
        given = {**(values or {}), **parameters}
        specs = layout.specs
        if layout.formulas:
            layout, given = _follow(layout, given)
            specs = layout.specs
        if values is None:
            missing = [n for n, s in specs.items() if n not in given and s.default is None]
            if missing:
                raise TypeError(f"Vehicle() missing {len(missing)} required parameter(s): "
                                f"{', '.join(missing)}")  # fmt: skip
        checked = validate_with(given, specs, layout.consistency)
        from railhunt.layout.checks import check_values

        check_values(layout, checked)
        for key, value in (("name", name), ("description", description), ("contact", contact),
                           ("layout", layout), ("values", checked)):  # fmt: skip
            object.__setattr__(self, key, value)

    # -- parameters as attributes ---------------------------------------------------------

    def __getattr__(self, key: str) -> float:
        if key.startswith("__"):
            raise AttributeError(key)
        values = self.__dict__.get("values")
        if values is not None and key in values:
            return values[key]
        raise AttributeError(f"vehicle {self.__dict__.get('name')!r} has no parameter or "
                             f"attribute {key!r}")  # fmt: skip

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Vehicle):
            return NotImplemented
        return (self.name == other.name and self.contact == other.contact
                and self.layout == other.layout and dict(self.values) == dict(other.values))

    def __hash__(self) -> int:
        return hash((self.name, self.contact, self.layout, tuple(sorted(self.values.items()))))

    def __reduce__(self) -> tuple:
        return (_rebuild, (self.name, self.description, self.contact, self.layout,
                           dict(self.values)))  # fmt: skip

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
        vehicle = _READERS["load_shipped"](name)
        if type(vehicle) is not cls:  # subclass: rebuild as that class
            return cls(name=vehicle.name, description=vehicle.description,
                       contact=vehicle.contact, layout=vehicle.layout,
                       values=vehicle.as_dict())  # fmt: skip
        return vehicle  # type: ignore[return-value]

    @classmethod
    def from_toml(cls, path: str | os.PathLike[str]) -> "Vehicle":
        """Read a vehicle or layout file (:func:`railhunt.vehicle.load_vehicle`)."""
        return _READERS["load_vehicle"](path)

    load = from_toml

    def allowing(self, *names: str) -> Self:
        """This vehicle, with the parameters ``names`` allowed outside the ranges their uses
        in the layout make plausible (as ``allow = true`` in a file: a scale model, a study
        on purpose; the rules of sign still hold): ``vehicle.allowing("W").replace(W=100)``.

        Raises
        ------
        UnknownParameterError
            A name is not a parameter of the vehicle.
        """
        for name in names:
            if name not in self.values:
                raise UnknownParameterError(name, None, known=tuple(self.values))
        from railhunt.layout.checks import allow

        return self.replace(layout=allow(self.layout, set(names)))

    def replace(self, **changes: Any) -> Self:
        """Return a validated copy with some parameters (or name/description) changed.

        Parameters
        ----------
        **changes
            New SI values by parameter name; ``name``, ``description``, ``contact`` and
            ``layout`` are accepted too.

        Returns
        -------
        Vehicle
            A new vehicle; ``self`` is unchanged. A derived parameter (given in its file as
            an expression of others, ``f11 = "GPIAB / phi_vj"``) follows its inputs; set
            directly, it no longer does (a :class:`DerivedOverrideWarning` says so).

        Raises
        ------
        DerivedParameterError
            For ``v_u`` or ``N`` (derived: change ``F_u``/``C_d1`` or ``W`` instead).
        UnknownParameterError
            For any other unknown name (with a "did you mean" suggestion).
        ParameterError
            If a new value, or the resulting set, breaks a rule.
        """
        ident = {k: changes.pop(k) for k in list(changes) if k in _IDENTITY}
        for key, value in changes.items():
            if key in self.values:
                continue
            if key in DERIVED:
                raise DerivedParameterError(key, value)
            raise UnknownParameterError(key, value, known=tuple(self.values))
        layout = ident.get("layout", self.layout)
        values = ident.get("values")
        if values is None:
            # A derived parameter (a formula of others) follows its inputs: its old value is
            # not carried over, unless it is changed itself (an override, said so).
            derived = dict(layout.formulas)
            values = {k: v for k, v in self.values.items() if k not in derived}
        return type(self)(name=ident.get("name", self.name),
                          description=ident.get("description", self.description),
                          contact=ident.get("contact", self.contact), layout=layout,
                          values=values, **changes)  # fmt: skip

    # -- derived quantities -------------------------------------------------------------

    @property
    def v_u(self) -> float:
        """Blow-off velocity of the yaw damper, ``F_u / C_d1``, in m/s."""
        try:
            return self.values["F_u"] / self.values["C_d1"]
        except KeyError:
            raise AttributeError(f"vehicle {self.name!r} has no F_u and C_d1 (v_u)") from None

    @property
    def N(self) -> float:
        """Wheel normal load (N): ``W * g / 2`` for a vehicle with parameters ``W`` and
        ``g``, else the leading wheelset's static load."""
        if "W" in self.values and "g" in self.values:
            return self.values["W"] * self.values["g"] / 2.0
        from railhunt.kernel.layout import WR

        return float(self.assembly.wheel_rail[0, WR.N])

    @property
    def gravity(self) -> float:
        """Acceleration of gravity of the layout (m/s^2; ``g`` for the paper's vehicle)."""
        from railhunt.kernel.layout import WR

        return float(self.assembly.wheel_rail[0, WR.G])

    @property
    def blowoff_force(self) -> float:
        """Blow-off force of the first Maxwell element (N; ``F_u`` for the paper's
        vehicle); NaN for a layout without one."""
        from railhunt.kernel.layout import DamperParam

        d = self.assembly.damper
        return float(d[0, DamperParam.F_U]) if d.shape[0] else float("nan")

    @property
    def length(self) -> float:
        """Distance from the leading to the last wheelset (m)."""
        return float(self.assembly.wheelset_delay.max())

    @property
    def assembly(self) -> "Assembly":
        """The layout's matrices and rows for these values, built on first use (a model,
        a file read) and kept: about a millisecond for the paper's vehicle.

        Raises
        ------
        LayoutError
            What the values make of the layout cannot be assembled (a non-positive mass
            or inertia, a free mode; see :mod:`railhunt.layout.assembly`).
        """
        asm = self.__dict__.get("_assembly")
        if asm is None:
            from railhunt.layout.assembly import assemble_layout

            asm = assemble_layout(self.layout, self.values)
            object.__setattr__(self, "_assembly", asm)
        return asm

    # -- views ---------------------------------------------------------------------------

    @property
    def parameters(self) -> dict[str, Any]:
        """The vehicle's parameters: name -> :class:`ParameterSpec` (unit, meaning, rule)."""
        return self.layout.specs

    def source(self, name: str) -> str:
        """Where parameter ``name``'s value comes from (as its file says)."""
        return dict(self.layout.sources).get(name, "")

    def as_dict(self) -> dict[str, float]:
        """Parameters as a new dict name -> SI float, in the layout's order."""
        return dict(self.values)

    def derived(self) -> dict[str, float]:
        """Derived quantities ``{"v_u": m/s, "N": N}`` (those the vehicle has)."""
        out = {}
        for key in ("v_u", "N"):
            try:
                out[key] = getattr(self, key)
            except AttributeError:
                pass
        return out

    def parameter_table(self, include_derived: bool = False) -> list[tuple[str, float, str, str]]:
        """Rows ``(name, value, unit, meaning)`` for reports, in the layout's order; a
        derived parameter's meaning ends with its formula (``(= GPIAB / 0.60252)``).

        Parameters
        ----------
        include_derived : bool
            Append rows for ``v_u`` and ``N``.

        Returns
        -------
        list of tuple (str, float, str, str)
        """
        specs = self.layout.specs
        formulas = dict(self.layout.formulas)
        rows = [(n, v, specs[n].unit, specs[n].meaning if n not in formulas else
                 f"{specs[n].meaning} (= {formulas[n]})".lstrip()) for n, v in self.values.items()]
        if include_derived:
            values = self.derived()
            for spec in DERIVED.values():
                if spec.name in values:
                    meaning = f"{spec.meaning} (derived: {spec.formula})"
                    rows.append((spec.name, values[spec.name], spec.unit, meaning))
        return rows

    def __repr__(self) -> str:
        return f"Vehicle({self.name!r}, {len(self.values)} parameters)"

    # -- output -------------------------------------------------------------------------

    def to_toml(self, path: str | os.PathLike[str], overwrite: bool = False) -> Path:
        """Write the vehicle as a complete layout file (read back by :func:`load_vehicle`):
        its parameters with unit, meaning, source and rule, its bodies, elements and
        wheel/rail data.

        Parameters
        ----------
        path : str or os.PathLike
            Destination file.
        overwrite : bool
            Replace an existing file (refused otherwise).

        Returns
        -------
        pathlib.Path
            The path written.

        Raises
        ------
        FileExistsError
            The file exists and ``overwrite`` is False.
        """
        path = Path(path)
        if path.exists() and not overwrite:
            raise FileExistsError(f"{path} exists: pass overwrite=True to replace it")
        path.write_text(self._toml_text(), encoding="utf-8")
        return path

    def _toml_text(self) -> str:
        from railhunt.layout.writer import layout_toml

        return layout_toml(self)


def _rebuild(name: str, description: str, contact: ContactSpec | None, layout: Any,
             values: dict[str, float]) -> Vehicle:  # fmt: skip
    return Vehicle(name=name, description=description, contact=contact, layout=layout,
                   values=values)



def _follow(layout: "LayoutSpec", given: dict[str, Any]) -> tuple["LayoutSpec", dict[str, Any]]:
    """The derived parameters of ``layout`` computed from ``given``; those given another
    value are overridden: they lose their formula (in the returned layout), and a
    :class:`DerivedOverrideWarning` names them."""
    import warnings

    from railhunt.layout.params import follow_formulas

    values, overridden = follow_formulas(layout.formulas, layout.specs, given)
    if not overridden:
        return layout, values
    texts = dict(layout.formulas)
    for name in overridden:
        inputs = ", ".join(sorted(_inputs(texts[name])))
        warnings.warn(f"{name} is derived in the layout ({name} = {texts[name]!r}): set "
                      f"directly, it no longer follows {inputs}; change {inputs} instead to "
                      "keep the formula", DerivedOverrideWarning, stacklevel=4)  # fmt: skip
    formulas = tuple((n, t) for n, t in layout.formulas if n not in overridden)
    return dataclasses.replace(layout, formulas=formulas), values


def _inputs(text: str) -> frozenset[str]:
    from railhunt.layout.params import formula

    return formula(text).names
