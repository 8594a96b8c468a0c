"""The :class:`Vehicle`: a validated, immutable parameter set of the 17-DOF vehicle model."""

import dataclasses
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Self

from railhunt.vehicle.contact import ContactSpec
from railhunt.vehicle.errors import DerivedParameterError, UnknownParameterError
from railhunt.vehicle.parameters import DERIVED, PARAMETERS, VehicleFields, validate_all

__all__ = ["Vehicle"]


@dataclass(frozen=True, kw_only=True, repr=False)
class Vehicle(VehicleFields):
    """Validated, immutable parameter set of the 17-DOF vehicle (SI units).

    Construct with every parameter as a keyword (see :data:`PARAMETERS` for names, units
    and meanings), or use :meth:`paper2019`, :func:`load_vehicle` or :meth:`replace`.
    The constructor validates every value; a :class:`ParameterError` is raised otherwise.
    The fields (one per parameter, in :data:`PARAMETERS` order, after ``name``,
    ``description`` and ``contact``) are declared in the parameter table,
    :class:`railhunt.vehicle.parameters.VehicleFields`.

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
    M_c, C_d1 : float
        Every parameter of :data:`PARAMETERS` is one keyword, in its SI unit (``M_c``, the
        car body mass in kg; ``C_d1``, the yaw damper's first-stage damping in N*s/m; ...).
    """

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
        from railhunt.vehicle.files import load_shipped

        vehicle = load_shipped(name)
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

    def to_toml(self, path: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
        """Write the vehicle as a complete TOML vehicle file (read back by :func:`load_vehicle`).

        Parameters
        ----------
        path : str or os.PathLike
            Destination file.
        overwrite : bool
            Replace ``path`` if it exists; without it an existing file is an error (the
            command line's overwrite policy).

        Returns
        -------
        pathlib.Path
            The path written.

        Raises
        ------
        FileExistsError
            ``path`` exists and ``overwrite`` is False.
        """
        path = Path(path)
        if path.exists() and not overwrite:
            raise FileExistsError(f"{path} exists: give overwrite=True to replace it, or "
                                  "choose another file")  # fmt: skip
        path.write_text(self._toml_text(), encoding="utf-8")
        return path

    def _toml_text(self) -> str:
        from railhunt.vehicle.files import vehicle_toml

        return vehicle_toml(self)
