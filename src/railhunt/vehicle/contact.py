"""The ``[contact]`` section of a vehicle: wheel/rail profiles and their contact geometry."""

import functools
import math
import numbers
from dataclasses import dataclass
from typing import Any

from railhunt.vehicle.formatting import toml_string

__all__ = ["ContactSpec"]


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
    smooth : float, "auto" or None
        Smoothing of measured (MiniProf) profile files as :func:`railhunt.read_profile`
        takes it: the RMS residual (m, in [0, 2e-4]; 0 keeps the points), ``"auto"`` (the
        points' own noise) or None (each format's default: ``"auto"`` for MiniProf, none
        for SIMPACK and text files). Only profile files read it.
    """

    wheel: str = "S1002"
    rail: str = "UIC60"
    rail_inclination: float = 0.025
    gauge: float = 1.435
    back_to_back: float = 1.36
    wheel_radius: float = 0.43
    y_max: float = 0.012
    y_step: float = 1e-4
    smooth: float | str | None = None

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
        smooth = self.smooth
        if isinstance(smooth, str) and smooth.strip().lower() == "auto":
            object.__setattr__(self, "smooth", "auto")
        elif smooth is not None:
            if isinstance(smooth, bool) or not isinstance(smooth, numbers.Real) or not (
                math.isfinite(smooth) and 0.0 <= smooth <= 2e-4
            ):
                raise ValueError(f"contact smooth = {smooth!r} is invalid: must be \"auto\" "
                                 "or a tolerance in [0, 0.0002] m")  # fmt: skip
            object.__setattr__(self, "smooth", float(smooth))

    def geometry(self) -> Any:
        """The rigid contact geometry of these profiles (computed once, then cached)."""
        return _contact_geometry(self)

    def toml_lines(self) -> list[str]:
        """The ``[contact]`` section of a vehicle file."""
        lines = ["", "[contact]", f"wheel = {toml_string(self.wheel)}",
                 f"rail = {toml_string(self.rail)}"]  # fmt: skip
        for key in self._RANGES:
            lines.append(f"{key} = {getattr(self, key)!r}")
        if self.smooth is not None:
            value = self.smooth
            text = toml_string(value) if isinstance(value, str) else repr(value)
            lines.append(f"smooth = {text}")
        return lines


@functools.lru_cache(maxsize=16)
def _contact_geometry(spec: ContactSpec) -> Any:
    from railhunt.contact.geometry import contact_geometry
    from railhunt.contact.profiles import read_profile, s1002, uic60

    wheel = (s1002() if spec.wheel.upper() == "S1002"
             else read_profile(spec.wheel, "wheel", smooth=spec.smooth))  # fmt: skip
    rail = (uic60() if spec.rail.upper() in ("UIC60", "60E1")
            else read_profile(spec.rail, "rail", smooth=spec.smooth))  # fmt: skip
    return contact_geometry(wheel, rail, rail_inclination=spec.rail_inclination,
                            gauge=spec.gauge, back_to_back=spec.back_to_back,
                            r0=spec.wheel_radius, y_max=spec.y_max,
                            y_step=spec.y_step)  # fmt: skip
