"""A fleet of measured wheels: conicity, two-point bands and critical speeds, wheel by wheel.

The question a maintenance engineer asks before reprofiling: which wheelsets of the fleet,
as measured, run on an equivalent conicity that makes the vehicle hunt? :func:`wheel_fleet`
takes each wheel profile (a MiniProf ``.whl``, SIMPACK ``.prw`` or text file, read and
smoothed by :func:`railhunt.read_profile`), computes its rigid contact geometry against the
rail, its equivalent conicity (EN 15302 Annex B) and its two-point bands
(:func:`railhunt.contact.bands.two_point_bands`) and, on request, the linear and nonlinear
critical speeds of a vehicle running on it (:func:`with_wheel`). Both wheels of a wheelset
are taken as the measured one (the left one mirrored): a symmetric wheelset.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from railhunt.contact.bands import two_point_bands
from railhunt.contact.conicity import equivalent_conicity
from railhunt.contact.fit import transverse_curvature
from railhunt.contact.geometry import contact_geometry
from railhunt.contact.profiles import Profile, ProfileError, read_profile, s1002, uic60
from railhunt.mechanics.hertz import creep_coefficients
from railhunt.vehicle import Vehicle
from railhunt.vehicle.contact import ContactSpec

__all__ = ["FleetWheel", "load_wheel", "wheel_fleet", "with_wheel"]

#: The vehicle the critical speeds are computed on unless another is given.
DEFAULT_VEHICLE = "s1002_uic60_table"


@dataclass
class FleetWheel:
    """One wheelset of the fleet (SI units).

    Attributes
    ----------
    name : str
        The wheel file's name (or ``"S1002"``).
    source : str
        Its path (or the analytic profile's description).
    conicity : float
        Equivalent conicity ``tan(gamma_e)`` at the amplitude asked (EN 15302 Annex B);
        NaN when the table does not reach it.
    bands : list of tuple
        Two-point bands ``(y_from, y_to)`` (m of wheelset displacement).
    centred_radius : float
        Rolling radius of the centred wheelset (m).
    smoothing : float
        Smoothing tolerance applied to the points (m), 0 for none.
    linear_kmh, nonlinear_kmh : float
        Linear and nonlinear critical speeds (km/h) on the vehicle, NaN when not asked.
    frequency_hz : float
        Frequency of the mode that loses stability at ``linear_kmh`` (Hz).
    """

    name: str
    source: str
    conicity: float
    bands: list = field(default_factory=list)
    centred_radius: float = math.nan
    smoothing: float = 0.0
    linear_kmh: float = math.nan
    nonlinear_kmh: float = math.nan
    frequency_hz: float = math.nan


def load_wheel(spec: str, smooth: float | str | None = None, repair: bool = False) -> Profile:
    """A wheel profile from a file path, or ``"S1002"`` for the analytic EN 13715 profile."""
    if spec.upper() == "S1002":
        return s1002(step=1e-5)
    return read_profile(spec, "wheel", smooth=smooth, repair=repair)


def with_wheel(vehicle: Vehicle, wheel: str, *, rail: str | None = None,
               rail_inclination: float | None = None, gauge: float | None = None,
               back_to_back: float | None = None, wheel_radius: float | None = None,
               smooth: float | str | None = None) -> Vehicle:  # fmt: skip
    """The vehicle with its wheel profile replaced (and, if given, its rail and track).

    The vehicle must run on profiles (a ``[contact]`` section; ``wheel`` and ``rail`` are
    what such a section takes: ``"S1002"``/``"UIC60"`` or file paths). Its ``r0`` becomes
    the new centred rolling radius (the model requires them equal). A vehicle whose
    creepage coefficients are those of its centred contact (``contact_mechanics =
    "centred"``, the default) gets ``f11, f22, f23, f33`` again from Hertz and Kalker at
    the new wheel's centred contact point (``N = W g / 2``, E = 210 GPa, nu = 0.3, the
    transverse curvatures of wheel and rail there), as
    :func:`railhunt.contact.fit.s1002_uic60_parameters` makes them for S1002; a
    ``"per-point"`` vehicle computes each contact's own ellipse from the profiles anyway.
    """
    if vehicle.contact is None:
        raise ValueError(f"vehicle {vehicle.name!r} has no contact geometry from profiles "
                         "(no [contact] section), so a wheel profile cannot be put into it; "
                         f"use a profile vehicle such as {DEFAULT_VEHICLE}")  # fmt: skip
    old = vehicle.contact
    spec = dataclasses.replace(
        old, wheel=wheel, rail=old.rail if rail is None else rail,
        rail_inclination=old.rail_inclination if rail_inclination is None else rail_inclination,
        gauge=old.gauge if gauge is None else gauge,
        back_to_back=old.back_to_back if back_to_back is None else back_to_back,
        wheel_radius=old.wheel_radius if wheel_radius is None else wheel_radius,
        smooth=old.smooth if smooth is None else smooth,
    )
    geo = spec.geometry()
    r_centre = float(np.interp(0.0, geo.y, geo.r_left))
    changes: dict = {"r0": r_centre}
    mechanics = set(getattr(vehicle.assembly, "contact_mechanics", ()) or ("centred",))
    if mechanics <= {"centred"} and all(k in vehicle.values for k in ("f11", "f22", "f33")):
        changes.update(_centred_coefficients(spec, geo, vehicle.N))
    return vehicle.replace(contact=spec, name=f"{vehicle.name} on {Path(wheel).name}",
                           **changes)  # fmt: skip


def _centred_coefficients(spec: ContactSpec, geo: object, normal_load: float) -> dict:
    """Kalker's ``f11, f22, f23, f33`` (N) at the centred contact point of ``spec``."""
    wheel = (s1002() if spec.wheel.upper() == "S1002"
             else read_profile(spec.wheel, "wheel", smooth=spec.smooth))  # fmt: skip
    rail = (uic60() if spec.rail.upper() in ("UIC60", "60E1")
            else read_profile(spec.rail, "rail", smooth=spec.smooth))  # fmt: skip
    rail_c = rail.inclined(spec.rail_inclination) if spec.rail_inclination else rail
    i0 = int(np.argmin(np.abs(geo.y)))
    k_wheel = -transverse_curvature(wheel.y, wheel.z, float(geo.wheel_left[i0]))
    k_rail = transverse_curvature(rail_c.y, rail_c.z, float(geo.rail_left[i0]))
    cc = creep_coefficients(
        normal_load, float(geo.r_left[i0]),
        wheel_transverse_radius=1.0 / k_wheel if k_wheel else math.inf,
        rail_transverse_radius=1.0 / k_rail if k_rail else math.inf,
    )
    return {"f11": float(cc.f11), "f22": float(cc.f22), "f23": float(cc.f23),
            "f33": float(cc.f33)}  # fmt: skip


def wheel_fleet(
    wheels: list[str], rail: str = "UIC60", *, rail_inclination: float = 1.0 / 40.0,
    gauge: float = 1.435, back_to_back: float = 1.360, r0: float = 0.43,
    amplitude: float = 3e-3, penetration: float = 1e-4, smooth: float | str | None = None,
    repair: bool = False, critical_speeds: bool = False,
    vehicle: Vehicle | None = None, progress: object = None,
) -> list[FleetWheel]:  # fmt: skip
    """Equivalent conicity, two-point bands and (optionally) critical speeds of each wheel.

    Parameters
    ----------
    wheels : list of str
        Wheel profile files (any format :func:`railhunt.read_profile` reads), or
        ``"S1002"`` for the new analytic profile.
    rail : str
        Upright rail profile file, or ``"UIC60"`` (analytic 60E1).
    rail_inclination, gauge, back_to_back, r0 : float
        Track and wheelset: rail cant (tangent), gauge (m), distance between the wheels'
        inner faces (m), wheel radius at the tape circle (m).
    amplitude : float
        Amplitude (m) of the equivalent conicity (EN 15302: 3 mm).
    penetration : float
        Depth (m) within which a second valley of the gap function is a second patch.
    smooth : float or "auto", optional
        Smoothing of the wheel files (see :func:`railhunt.read_profile`).
    repair : bool
        Drop the points of a MiniProf file that fold back instead of refusing it.
    critical_speeds : bool
        Also the linear and nonlinear critical speeds on ``vehicle``.
    vehicle : Vehicle, optional
        Default the shipped ``s1002_uic60_table``.
    progress : callable, optional
        Called with each :class:`FleetWheel` when it is done.

    Returns
    -------
    list of FleetWheel
        In the order of ``wheels``.
    """
    from railhunt.analysis.critical import critical_speed
    from railhunt.analysis.linear import linear_critical_speed

    if not wheels:
        raise ValueError("wheels is empty: give at least one wheel profile")
    rail_profile = (uic60(0.0, step=1e-5) if rail.upper() in ("UIC60", "60E1")
                    else read_profile(rail, "rail"))  # fmt: skip
    if critical_speeds and vehicle is None:
        vehicle = Vehicle.shipped(DEFAULT_VEHICLE)
    rows = []
    for spec in wheels:
        wheel = load_wheel(spec, smooth, repair)
        try:
            geo = contact_geometry(wheel, rail_profile, rail_inclination=rail_inclination,
                                   gauge=gauge, back_to_back=back_to_back, r0=r0)
        except ProfileError as exc:
            raise ProfileError(f"wheel {spec!r}: {exc}") from None
        try:
            tan_ge = equivalent_conicity(geo.y, geo.delta_r, amplitude)
        except ValueError:
            tan_ge = math.nan
        row = FleetWheel(
            name=wheel.name, source=wheel.source, conicity=float(tan_ge),
            bands=two_point_bands(geo, wheel, rail_profile, penetration=penetration),
            centred_radius=float(np.interp(0.0, geo.y, geo.r_left)),
            smoothing=float(wheel.meta.get("smoothing", 0.0)),
        )
        if critical_speeds:
            path = "S1002" if spec.upper() == "S1002" else str(Path(spec).resolve())
            rail_spec = "UIC60" if rail.upper() in ("UIC60", "60E1") else str(Path(rail).resolve())
            on = with_wheel(vehicle, path, rail=rail_spec, rail_inclination=rail_inclination,
                            gauge=gauge, back_to_back=back_to_back, wheel_radius=r0,
                            smooth=smooth)  # fmt: skip
            lin = linear_critical_speed(on)
            row.linear_kmh = float(lin.speed_kmh)
            row.frequency_hz = float(lin.frequency_hz)
            row.nonlinear_kmh = float(critical_speed(on).speed_kmh)
        rows.append(row)
        if progress is not None:
            progress(row)
    return rows
