"""Outputs that studies need beyond the critical speeds and the hunting frequency.

Each output is named by its group (what ``sweep(outputs=...)`` takes) and gives the
results columns listed in :data:`NEW_OUTPUT_COLUMNS`:

``fold_speed`` -> ``fold_speed_kmh``
    The lowest speed of a limit cycle on the hunting (Hopf) branch, by a short continuation
    (:func:`railhunt.analysis.fold.fold_speed`): smooth in the parameters, unlike a
    bisection's 1 km/h steps.
``least_damping_ratio`` -> ``least_damping_ratio``
    The least damping ratio ``-Re(lambda) / |lambda|`` over every eigenvalue of the centred
    running, at ``damping_points`` speeds evenly spread over ``damping_range_kmh``: the
    stability margin at service speeds (negative once a mode is unstable there).
``curving`` -> ``max_YQ``, ``sum_Y_leading``, ``wear_number``
    Steady curving (:func:`railhunt.curving`) in the curve of ``curve_radius``,
    ``curve_cant`` at ``curve_speed_kmh``: the largest derailment quotient Y/Q of any wheel,
    the magnitude of the leading wheelset's track-shifting force |ΣY| (N) and the leading
    wheelset's wear number ``T gamma`` (N): the sum over its two wheels of
    ``|F_x xi_x| + |F_y xi_y|`` (:mod:`railhunt.analysis.wear`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from railhunt.vehicle import Vehicle

#: Output group -> its columns, in file order (added to the study store's outputs).
NEW_OUTPUT_COLUMNS: dict[str, tuple[str, ...]] = {
    "fold_speed": ("fold_speed_kmh",),
    "least_damping_ratio": ("least_damping_ratio",),
    "curving": ("max_YQ", "sum_Y_leading", "wear_number"),
}


@dataclass(frozen=True)
class OutputOptions:
    """Settings of the outputs of :data:`NEW_OUTPUT_COLUMNS`.

    Attributes
    ----------
    curve_radius : float, optional
        Radius of the curve of the ``curving`` output (m), in [100, 100000]; required by it.
    curve_cant : float
        Its cant (m), in [0, 0.2].
    curve_speed_kmh : float, optional
        Speed in the curve (km/h), in (0, 500]; required by ``curving``.
    damping_range_kmh : (float, float)
        Speed range of ``least_damping_ratio`` (km/h).
    damping_points : int
        Speeds evaluated over that range (evenly spread, both ends included), >= 2.
    """

    curve_radius: float | None = None
    curve_cant: float = 0.0
    curve_speed_kmh: float | None = None
    damping_range_kmh: tuple[float, float] = (50.0, 300.0)
    damping_points: int = 11

    def __post_init__(self) -> None:
        if self.curve_radius is not None and not (math.isfinite(self.curve_radius)
                                                  and 100 <= self.curve_radius <= 1e5):  # fmt: skip
            raise ValueError(f"curve_radius = {self.curve_radius!r} m is invalid: must be in "
                             "[100, 100000] m")  # fmt: skip
        if not (math.isfinite(self.curve_cant) and 0 <= self.curve_cant <= 0.2):
            raise ValueError(f"curve_cant = {self.curve_cant!r} m is invalid: must be in "
                             "[0, 0.2] m")  # fmt: skip
        speed = self.curve_speed_kmh
        if speed is not None and not (math.isfinite(speed) and 0 < speed <= 500):
            raise ValueError(f"curve_speed_kmh = {self.curve_speed_kmh!r} km/h is invalid: must "
                             "be in (0, 500] km/h")  # fmt: skip
        lo, hi = (float(s) for s in self.damping_range_kmh)
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi <= 1000):
            raise ValueError(f"damping_range_kmh = {self.damping_range_kmh!r} is invalid: need "
                             "0 < low < high <= 1000 km/h")  # fmt: skip
        if isinstance(self.damping_points, bool) or int(self.damping_points) != \
                self.damping_points or not 2 <= self.damping_points <= 200:  # fmt: skip
            raise ValueError(f"damping_points = {self.damping_points!r} is invalid: must be an "
                             "integer in [2, 200]")  # fmt: skip

    def check_for(self, outputs: tuple[str, ...]) -> None:
        """Refuse ``curving`` without its curve and speed."""
        if "curving" in outputs and (self.curve_radius is None or self.curve_speed_kmh is None):
            raise ValueError("the curving outputs (max_YQ, sum_Y_leading, wear_number) need a "
                             "curve: give curve_radius and curve_speed_kmh (--curve-radius, "
                             "--curve-speed)")  # fmt: skip

    def describe(self, outputs: tuple[str, ...]) -> dict[str, Any]:
        """The settings the chosen outputs use (JSON; part of a study's fingerprint)."""
        out: dict[str, Any] = {}
        if "curving" in outputs:
            out.update(curve_radius=self.curve_radius, curve_cant=self.curve_cant,
                       curve_speed_kmh=self.curve_speed_kmh)  # fmt: skip
        if "least_damping_ratio" in outputs:
            out.update(damping_range_kmh=list(map(float, self.damping_range_kmh)),
                       damping_points=int(self.damping_points))  # fmt: skip
        return out


def empty_columns(name: str) -> dict[str, float]:
    """The columns of output ``name``, all NaN (a point that has not given them)."""
    return {col: math.nan for col in NEW_OUTPUT_COLUMNS[name]}


def least_damping_ratio(vehicle: Vehicle, speeds_kmh: np.ndarray,
                        creep_law: str | None = None) -> float:  # fmt: skip
    """Least ``-Re(lambda)/|lambda|`` over all eigenvalues of the centred running at the
    given speeds (km/h)."""
    from railhunt.analysis.modes import eigenvalues
    from railhunt.model import Model
    from railhunt.units import kmh_to_ms

    model = Model(vehicle, creep_law=creep_law)
    least = math.inf
    for kmh in speeds_kmh:
        w, _ = eigenvalues(model, kmh_to_ms(float(kmh)))
        mod = np.abs(w)
        zeta = -w.real[mod > 0] / mod[mod > 0]
        least = min(least, float(np.min(zeta)))
    return least


def curving_outputs(vehicle: Vehicle, options: OutputOptions,
                    creep_law: str | None = None) -> dict[str, float]:  # fmt: skip
    """``max_YQ``, ``sum_Y_leading`` (N) and ``wear_number`` (N) in the options' curve."""
    from railhunt.analysis.curving import curving
    from railhunt.analysis.wear import wheel_wear_numbers
    from railhunt.curve import Curve
    from railhunt.model import Model
    from railhunt.units import kmh_to_ms

    curve = Curve(radius=float(options.curve_radius), cant=float(options.curve_cant))
    res = curving(vehicle, float(options.curve_speed_kmh), curve, creep_law=creep_law)
    model = Model(vehicle, creep_law=creep_law)
    wear = wheel_wear_numbers(model, kmh_to_ms(res.speed_kmh), res.state, 0, curve.steady_route())
    return {"max_YQ": float(np.max(res.derailment_quotient)),
            "sum_Y_leading": float(abs(res.sum_Y[0])), "wear_number": float(np.sum(wear))}


def evaluate_output(name: str, vehicle: Vehicle, options: OutputOptions | None,
                    creep_law: str | None = None) -> dict[str, float]:  # fmt: skip
    """The columns of one output of :data:`NEW_OUTPUT_COLUMNS` for one vehicle."""
    options = options or OutputOptions()
    if name == "fold_speed":
        from railhunt.analysis.fold import fold_speed

        return {"fold_speed_kmh": float(fold_speed(vehicle, creep_law=creep_law).speed_kmh)}
    if name == "least_damping_ratio":
        lo, hi = options.damping_range_kmh
        speeds = np.linspace(float(lo), float(hi), int(options.damping_points))
        return {"least_damping_ratio": least_damping_ratio(vehicle, speeds, creep_law)}
    if name == "curving":
        return curving_outputs(vehicle, options, creep_law)
    raise ValueError(f"unknown output {name!r}: choose one of {', '.join(NEW_OUTPUT_COLUMNS)}")


def options_from(mapping: Mapping[str, Any] | OutputOptions | None) -> OutputOptions:
    """An :class:`OutputOptions` from itself, a mapping of its fields, or None (defaults)."""
    if mapping is None:
        return OutputOptions()
    if isinstance(mapping, OutputOptions):
        return mapping
    return OutputOptions(**dict(mapping))
