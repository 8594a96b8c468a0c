"""Vehicle TOML files: reading (:func:`load_vehicle`, ``base =``), writing, shipped vehicles.

A vehicle file has a ``[vehicle]`` table (name, description, optional ``base`` naming a
shipped vehicle), a ``[parameters]`` table (short form ``C_d1 = 600000.0`` or table form
with ``value`` and optional ``unit``, ``meaning``, ``source``) and an optional
``[contact]`` table (:class:`~railhunt.vehicle.ContactSpec`). The shipped vehicles are
the files of ``railhunt/data/vehicles``; they cannot themselves have a base.
"""

import dataclasses
import functools
import math
import os
import tomllib
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

from railhunt.quantities.units import UnitError, parse_unit, same_dimension, to_si
from railhunt.vehicle.contact import ContactSpec
from railhunt.vehicle.core import Vehicle, set_file_readers
from railhunt.vehicle.errors import (
    MissingParametersError,
    ParameterError,
    UnknownParameterError,
    VehicleFileError,
)
from railhunt.vehicle.formatting import toml_string, with_unit
from railhunt.vehicle.parameters import (
    DERIVED,
    PARAMETERS,
    as_float,
    derived_values,
    missing_parameters,
    validate_all,
    validate_value,
)

if TYPE_CHECKING:
    from railhunt.layout.spec import LayoutSpec

__all__ = ["paper_layout", "load_shipped", "load_vehicle", "shipped_vehicles", "vehicle_toml"]

_DATA_PACKAGE = "railhunt"
_VEHICLE_DIR = ("data", "vehicles")
_TABLE_KEYS = frozenset({"value", "unit", "meaning", "source"})
# A layout file's parameter tables also state the rule (read by railhunt.layout.params;
# a file of the paper's parameters may carry them: the paper's own rules apply).
_RULE_KEYS = frozenset({"rule", "min", "max", "above", "below", "reason", "default",
                        "greater_than", "allow"})  # fmt: skip
_VEHICLE_KEYS = frozenset({"name", "description", "base", "gravity", "source"})
_LAYOUT_SECTIONS = frozenset({"body", "element", "wheel_rail"})
_CONTACT_KEYS = frozenset({"wheel", "rail", "rail_inclination", "gauge", "back_to_back",
                           "wheel_radius", "y_max", "y_step", "smooth"})  # fmt: skip


# --------------------------------------------------------------------------- shipped data


def _shipped_dir() -> Any:
    folder = resources.files(_DATA_PACKAGE)
    for part in _VEHICLE_DIR:
        folder = folder / part
    return folder


def shipped_path(name: str) -> Any:
    """The shipped vehicle file of ``name`` (an importlib resource; may not exist)."""
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


@functools.cache
def paper_layout() -> "LayoutSpec":
    """The layout of the paper's vehicle (``paper2019.toml``), read once."""
    path = shipped_path("paper2019")
    data = _parse_toml(path.read_text(encoding="utf-8"), str(path))
    return _layout_from_data(data, str(path))[0]


def _layout_from_data(data: dict[str, Any], where: str) -> tuple["LayoutSpec", dict[str, float]]:
    """The layout (with its parameter table) and the parameter values of a layout file."""
    from railhunt.layout.params import parse_parameters
    from railhunt.layout.parse import parse_layout
    from railhunt.layout.spec import LayoutError

    table = parse_parameters(data.get("parameters", {}), where)
    layout = parse_layout(data, where)
    unknown = sorted(layout.names() - set(table.specs))
    if unknown:
        raise LayoutError(f"{where}: unknown parameter(s) {', '.join(map(repr, unknown))} in "
                          "the layout's values: add them to [parameters] or correct the "
                          "name")  # fmt: skip
    reserved = sorted(set(table.specs) & _RESERVED)
    if reserved:
        raise LayoutError(f"{where}: parameter name(s) {', '.join(map(repr, reserved))} are "
                          "taken by the vehicle's own attributes: rename them")  # fmt: skip
    layout = dataclasses.replace(layout, consistency=table.consistency,
                                 parameters=tuple(table.specs.values()),
                                 sources=tuple(table.sources.items()),
                                 formulas=table.formulas, allowed=table.allowed)  # fmt: skip
    # Each parameter gets the rule and unit of its use (unless its file states its rule).
    from railhunt.layout.checks import infer_parameters

    layout = infer_parameters(layout, table.stated)
    return layout, table.values


_RESERVED = frozenset({"name", "description", "contact", "layout", "values", "v_u",
                       "gravity", "blowoff_force", "length",
                       "assembly", "parameters", "source", "replace", "derived", "as_dict",
                       "to_toml", "shipped", "load", "from_toml", "paper2019",
                       "parameter_table", "allowing"})  # fmt: skip


@functools.cache
def load_shipped(name: str) -> Vehicle:
    """The shipped vehicle ``name``, read once (see :meth:`Vehicle.shipped`).

    Raises
    ------
    VehicleFileError
        No shipped vehicle has that name.
    """
    available = shipped_vehicles()
    if name not in available:
        raise VehicleFileError(
            f"no shipped vehicle named {name!r}; available: {', '.join(available)}"
        )
    path = shipped_path(name)
    return _vehicle_from_data(
        _parse_toml(path.read_text(encoding="utf-8"), str(path)),
        str(path),
        default_name=name,
        depth=1,
    )


# --------------------------------------------------------------------------- writing


def vehicle_toml(vehicle: Vehicle) -> str:
    """The complete vehicle file of ``vehicle`` (see :meth:`Vehicle.to_toml`).

    Parameters
    ----------
    vehicle : Vehicle

    Returns
    -------
    str
        TOML text: every parameter in table form with value, unit and meaning.
    """
    lines = [
        "# railhunt vehicle file (written by railhunt.vehicle.Vehicle.to_toml).",
        "# SI units throughout. Each parameter: value (SI), unit, meaning.",
        f"# Derived, not inputs: v_u = F_u / C_d1 = {vehicle.v_u!r} m/s,"
        f" N = W * g / 2 = {vehicle.N!r} N.",
        "",
        "[vehicle]",
        f"name = {toml_string(vehicle.name)}",
        f"description = {toml_string(vehicle.description)}",
    ]
    for spec in PARAMETERS.values():
        lines += [
            "",
            f"[parameters.{spec.name}]",
            f"value = {float(getattr(vehicle, spec.name))!r}",
            f"unit = {toml_string(spec.unit)}",
            f"meaning = {toml_string(spec.meaning)}",
        ]
    if vehicle.contact is not None:
        lines += vehicle.contact.toml_lines()
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- reading


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
    and overrides only the parameters it lists; otherwise every parameter is required
    (except one with a default in the table, which takes its default).
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
    return _load_file(Path(path), ())


def _load_file(path: Path, chain: tuple[Path, ...]) -> Vehicle:
    """:func:`load_vehicle` of a file reached through the ``base`` files of ``chain``."""
    try:
        text = path.read_text(encoding="utf-8-sig")  # a byte-order mark is skipped
    except UnicodeDecodeError as exc:
        raise VehicleFileError(f"{path}: not a UTF-8 text file") from exc
    return _vehicle_from_data(_parse_toml(text, str(path)), str(path), default_name=path.stem,
                              chain=(*chain, path.resolve()))  # fmt: skip


def _vehicle_from_data(
    data: dict[str, Any], where: str, *, default_name: str, depth: int = 0,
    chain: tuple[Path, ...] = (),
) -> Vehicle:
    try:
        vehicle = _build_vehicle(data, where, default_name, depth, chain)
        vehicle.assembly  # noqa: B018  (a file's layout is checked when it is read)
        return vehicle
    except ParameterError as exc:
        if exc.path is None:
            exc.path = where
        raise


def _build_vehicle(data: dict[str, Any], where: str, default_name: str, depth: int,
                   chain: tuple[Path, ...] = ()) -> Vehicle:  # fmt: skip
    extra = set(data) - {"vehicle", "parameters", "contact"} - _LAYOUT_SECTIONS
    if extra:
        raise VehicleFileError(
            f"{where}: unknown top-level key(s) {sorted(extra)}; "
            "expected only [vehicle], [parameters], [contact], [[body]], [[element]] and "
            "[wheel_rail]"
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
    for key in ("name", "description", "base", "source"):
        if key in meta and not isinstance(meta[key], str):
            raise VehicleFileError(f"{where}: [vehicle] {key} must be a string")

    table = data.get("parameters", {})
    if not isinstance(table, dict):
        raise VehicleFileError(f"{where}: 'parameters' must be a table")
    if _LAYOUT_SECTIONS & set(data):
        if "base" in meta:
            raise VehicleFileError(f"{where}: a file with [[body]], [[element]] or "
                                   "[wheel_rail] describes its own layout: remove "
                                   "[vehicle] base (base is for changing the parameters of "
                                   "another vehicle)")  # fmt: skip
        layout, values = _layout_from_data(data, where)
        return Vehicle(name=meta.get("name", default_name),
                       description=meta.get("description", ""), contact=contact,
                       layout=layout, values=values)  # fmt: skip
    base_name = meta.get("base")
    if base_name is not None and depth == 0 and not (
            base_name in shipped_vehicles() and load_shipped(base_name).layout == paper_layout()):
        # Another layout (or a file): its own parameter table. A vehicle of the paper's
        # layout takes the path below, as before (derived cross-checks included).
        return _from_base(data, meta, table, contact, where, default_name, chain)

    if base_name is None and not table and contact is None:
        what = "is empty" if not data else "has no vehicle in it"
        raise VehicleFileError(
            f"{where}: the file {what}: a vehicle file either describes a layout "
            "([parameters], [[body]], [[element]], [wheel_rail]: 'Your own vehicle layout' in "
            "the documentation) or "
            "changes another vehicle ([vehicle] base = one of "
            f"{', '.join(shipped_vehicles())}, or a file, and the [parameters] to change)")
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
        base = load_shipped(base_name)
        params: dict[str, float] = {**base.as_dict(), **given}
        if contact is None:
            contact = base.contact
    else:
        missing = missing_parameters(given)
        if missing:
            raise MissingParametersError(
                missing,
                hint='give them, or set [vehicle] base = "paper2019" to start from '
                "a shipped vehicle",
            )
        params = given
    values = validate_all(params)

    actual = derived_values(values)
    for name, value in stated.items():
        spec = DERIVED[name]
        if not math.isclose(value, actual[name], rel_tol=spec.rel_tol):
            raise ParameterError(
                name,
                value,
                f"equal to {spec.formula} = {with_unit(actual[name], spec.unit)} "
                f"(to relative {spec.rel_tol:g}); {name} is derived: change "
                f"{spec.change_instead} instead, or remove it",
                spec.unit,
                meaning=spec.meaning,
            )

    layout = paper_layout()
    allowed = _allowed(table, where)
    if allowed:
        from railhunt.layout.checks import allow

        layout = allow(layout, allowed)
    return Vehicle(
        name=meta.get("name", default_name),
        description=meta.get("description", ""),
        contact=contact,
        layout=layout,
        values=values,
    )


def _allowed(table: dict[str, Any], where: str) -> frozenset[str]:
    """The parameters a file's tables give ``allow = true``."""
    out = set()
    for name, entry in table.items():
        if isinstance(entry, dict) and "allow" in entry:
            if not isinstance(entry["allow"], bool):
                raise VehicleFileError(f"{where}: [parameters.{name}] allow must be true or "
                                       "false")  # fmt: skip
            if entry["allow"]:
                out.add(name)
    return frozenset(out)


def _from_base(data: dict[str, Any], meta: dict[str, Any], table: dict[str, Any],
               contact: ContactSpec | None, where: str, default_name: str,
               chain: tuple[Path, ...] = ()) -> Vehicle:  # fmt: skip
    """A file that changes the parameters of a shipped vehicle or of another file."""
    base_name = meta["base"]
    if base_name in shipped_vehicles():
        base = load_shipped(base_name)
    else:
        path = Path(base_name)
        if not path.is_absolute():
            path = Path(where).parent / path
        if not path.is_file():
            raise VehicleFileError(f"{where}: base = {base_name!r} is neither a shipped vehicle "
                                   f"({', '.join(shipped_vehicles())}) nor an existing "
                                   "file")  # fmt: skip
        if path.resolve() in chain:
            names = " -> ".join(str(p) for p in (*chain[chain.index(path.resolve()):],
                                                 path.resolve()))  # fmt: skip
            raise VehicleFileError(f"{where}: base = {base_name!r} starts a circle of base files "
                                   f"({names}): a file cannot start from itself; start one of "
                                   "them from a shipped vehicle or a complete layout")  # fmt: skip
        base = _load_file(path, chain)
    specs = base.layout.specs
    changes: dict[str, float] = {}
    for name, entry in table.items():
        if name not in specs:
            raise UnknownParameterError(name, entry, known=tuple(specs))
        spec = specs[name]
        changes[name] = _read_entry(name, entry, spec.unit, spec.meaning)
    allowed = _allowed(table, where)
    if allowed:
        base = base.allowing(*allowed)
    return base.replace(name=meta.get("name", default_name),
                        description=meta.get("description", base.description),
                        contact=contact if contact is not None else base.contact,
                        **changes)  # fmt: skip


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
        bad = set(entry) - _TABLE_KEYS - _RULE_KEYS
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
        scale = 1.0
        if given_unit is not None and given_unit != unit:
            scale = _unit_scale(name, entry["value"], given_unit, unit)
        entry = entry["value"]
        if scale != 1.0:
            return to_si(as_float(name, entry, given_unit, meaning), scale)
    return as_float(name, entry, unit, meaning)


def _unit_scale(name: str, value: object, given: object, unit: str) -> float:
    """The factor from a stated unit to the parameter's SI ``unit`` (``"kN*s/m"`` for
    N*s/m: 1e3); a unit of another dimension, or one railhunt does not know, is refused."""
    message = (f"{name}: unit {given!r} does not match the expected unit {unit!r}; give the "
               f"value in {unit}, or in a unit of the same dimension (such as kN/m for "
               "N/m: it is converted)")  # fmt: skip
    if not isinstance(given, str):
        raise ParameterError(name, value, f"given in {unit}", unit, message=message)
    try:
        stated, expected = parse_unit(given), parse_unit(unit)
    except UnitError as exc:
        raise ParameterError(name, value, f"given in {unit}", unit,
                             message=f"{name}: {exc}") from None  # fmt: skip
    if not same_dimension(stated.dimension, expected.dimension):
        raise ParameterError(name, value, f"given in {unit}", unit, message=message)
    return stated.scale / expected.scale


# The readers Vehicle() and its constructors use (railhunt.vehicle.core imports nothing
# from this module, which builds on it).
set_file_readers(paper_layout=paper_layout, load_shipped=load_shipped, load_vehicle=load_vehicle)
