"""Linear stability of the centred equilibrium: eigenvalues, hunting mode, Hopf speed.

(In a curve: of the steady-curving equilibrium, :mod:`railhunt.analysis.curving`.)

The Jacobian of the one compiled right-hand side (:func:`railhunt.model.jacobian`, central
differences) at the centred state on ideal track is the linearised system. Its eigenvalues
versus speed give the root locus; the *hunting mode* is the least-damped oscillatory mode
whose eigenvector is dominated by a wheelset's lateral/yaw motion; the *linear critical
speed* is where the least-damped eigenvalue's real part crosses zero.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from railhunt.analysis.curving import EquilibriumPath
from railhunt.analysis.curving_limit import capped_at_curving_limit
from railhunt.analysis.modes import (
    eigenvalues,
    hunting_mode_index,
    mac,
    moves_the_wheelsets,
    sorted_eig,
)
from railhunt.curve import Curve
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.units import kmh_to_ms
from railhunt.vehicle import Vehicle


@dataclass(repr=False)
class EigenResult(ResultDisplay):
    """Eigenvalues of the linearised model at a set of speeds.

    Attributes
    ----------
    speeds_kmh : numpy.ndarray
        Speeds (km/h).
    eigenvalues : numpy.ndarray, shape (n_speeds, 38)
        Eigenvalues (1/s), complex, sorted by decreasing real part.
    hunting : numpy.ndarray, shape (n_speeds,)
        Hunting-mode eigenvalue at each speed (upper half plane), complex (1/s).
    """

    speeds_kmh: np.ndarray
    eigenvalues: np.ndarray
    hunting: np.ndarray

    @property
    def hunting_frequency_hz(self) -> np.ndarray:
        """Hunting-mode frequency ``Im(lambda) / 2 pi`` (Hz)."""
        return self.hunting.imag / (2 * math.pi)

    @property
    def hunting_damping_ratio(self) -> np.ndarray:
        """Hunting-mode damping ratio ``-Re(lambda) / |lambda|`` (dimensionless)."""
        return -self.hunting.real / np.abs(self.hunting)

    def _summary(self) -> list[Row]:
        zeta = self.hunting_damping_ratio
        i = int(np.argmin(zeta))
        return [("speeds", f"{self.speeds_kmh.min():.4g} to {self.speeds_kmh.max():.4g}", "km/h"),
                ("number of speeds", self.speeds_kmh.size, ""),
                ("eigenvalues per speed", self.eigenvalues.shape[1], ""),
                ("least hunting damping ratio", zeta[i], ""),
                ("at speed", self.speeds_kmh[i], "km/h"),
                ("hunting frequency there", self.hunting_frequency_hz[i], "Hz")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row per speed: the hunting mode (all eigenvalues: ``eigenvalues``)."""
        return {"speed_kmh": (self.speeds_kmh, "km/h"),
                "hunting_real": (self.hunting.real, "1/s"),
                "hunting_imag": (self.hunting.imag, "1/s"),
                "hunting_frequency_hz": (self.hunting_frequency_hz, "Hz"),
                "hunting_damping_ratio": (self.hunting_damping_ratio, "1")}  # fmt: skip


@dataclass(repr=False)
class LinearCriticalSpeed(ResultDisplay):
    """Outcome of :func:`linear_critical_speed`.

    Attributes
    ----------
    speed_kmh : float
        Speed where the least-damped eigenvalue crosses into the right half plane (km/h);
        NaN when none does in the searched range.
    frequency_hz : float
        Frequency of the crossing eigenvalue there (Hz).
    eigenvalue : complex
        The crossing eigenvalue (1/s), real part ~0.
    is_hunting_mode : bool
        True when the crossing mode is the wheelset hunting mode.
    crossing : str
        What crosses: ``"hopf"`` (a complex pair: a Hopf point), ``"divergence"`` (a real
        eigenvalue, verdict word of :mod:`railhunt.verdicts`) or ``""`` (none).
    unstable_from_kmh : float
        When the equilibrium is already unstable at the lowest speed searched: that speed
        (km/h; ``speed_kmh`` is then NaN, there is no crossing); else NaN.
    limit : CurvingLimit or None
        In a curve, the first limit of the validity envelope the steady-curving state
        reaches (:func:`railhunt.analysis.curving_limit.curving_limit`); the search stops
        below it. None on straight track.
    """

    speed_kmh: float
    frequency_hz: float
    eigenvalue: complex
    is_hunting_mode: bool
    crossing: str = ""
    unstable_from_kmh: float = math.nan
    limit: object = None

    @property
    def limit_reached(self) -> bool:
        """True when the search stopped at a limit of the validity envelope."""
        return bool(self.limit is not None and self.limit.reached)

    @property
    def limits(self) -> list:
        """The limits reached where the search stopped (:class:`railhunt.validity.Limit`)."""
        return list(self.limit.limits) if self.limit_reached else []

    @property
    def warnings(self) -> list[str]:
        """What the answer must be read with: the curving limit the search stopped at."""
        return [f"limit reached: {self.limit.text}"] if self.limit_reached else []

    @property
    def text(self) -> str:
        """The answer in words, e.g. ``"441.3 km/h (Hopf point; hunting mode at 3.98 Hz)"``."""
        if math.isfinite(self.unstable_from_kmh):
            kind = ("real eigenvalue: divergence" if self.crossing == "divergence"
                    else f"complex pair at {self.frequency_hz:.2f} Hz")  # fmt: skip
            return f"unstable at every speed from {self.unstable_from_kmh:g} km/h ({kind})"
        if not math.isfinite(self.speed_kmh) and self.limit_reached:
            return (f"not found (stable up to {self.limit.last_valid_kmh:g} km/h, where the "
                    f"search stopped: limit reached, {self.limit.text})")  # fmt: skip
        if not math.isfinite(self.speed_kmh):
            return "not found (stable at every speed searched)"
        if self.crossing == "divergence":
            return f"{self.speed_kmh:.1f} km/h (real eigenvalue: divergence, not a Hopf point)"
        mode = "hunting mode" if self.is_hunting_mode else "not the hunting mode"
        return f"{self.speed_kmh:.1f} km/h (Hopf point; {mode} at {self.frequency_hz:.2f} Hz)"

    def _summary(self) -> list[Row]:
        return [("linear critical speed", self.speed_kmh, "km/h"),
                ("frequency", self.frequency_hz, "Hz"),
                ("eigenvalue", self.eigenvalue, "1/s"),
                ("hunting mode", self.is_hunting_mode, "")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row."""
        lam = complex(self.eigenvalue)
        return {"speed_kmh": (self.speed_kmh, "km/h"), "frequency_hz": (self.frequency_hz, "Hz"),
                "eigenvalue_real": (lam.real, "1/s"), "eigenvalue_imag": (lam.imag, "1/s"),
                "is_hunting_mode": (self.is_hunting_mode, "")}  # fmt: skip


def crossing_index(w: np.ndarray, above: np.ndarray) -> int:
    """Index into ``w`` (the eigenvalues at the crossing) of the one that crosses: the
    eigenvalue nearest to the one with the largest real part just ``above`` the crossing
    (a real eigenvalue that merely sits near zero, e.g. a weak yaw damper's relaxation,
    does not grow across it and is not chosen)."""
    top = above[int(np.argmax(above.real))]
    return int(np.argmin(np.abs(w - top)))


def eigen_analysis(
    vehicle: Vehicle, speeds_kmh: np.ndarray | list[float], creep_law: str | None = None
) -> EigenResult:
    """Eigenvalues of the linearised model and the hunting mode at each speed.

    The hunting mode is identified at the speed where it is least damped (the highest of
    the per-speed picks of :func:`hunting_mode_index`) and followed from there to the other
    speeds by continuity of its mode shape (largest modal assurance criterion among the
    oscillatory modes), so that at low speed, where several wheelset modes have similar
    damping, the branch does not jump to another mode.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    speeds_kmh : array_like
        Speeds (km/h), each > 0, in increasing order for mode tracking.
    creep_law : str
        See :class:`railhunt.model.Model`.
    """
    speeds = np.asarray(speeds_kmh, dtype=float)
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds) & (speeds > 0)):
        raise ValueError("speeds_kmh must be a non-empty 1-D list of finite speeds > 0 km/h")
    model = Model(vehicle, creep_law=creep_law)
    n_state, n_dof = model.layout.n_state, model.layout.n_dof
    eig = np.empty((speeds.size, n_state), dtype=complex)
    shapes = []
    first_pick = np.empty(speeds.size, dtype=int)
    for i, s in enumerate(speeds):
        w, vecs = eigenvalues(model, kmh_to_ms(s))
        eig[i] = w
        shapes.append(vecs[:n_dof])
        first_pick[i] = hunting_mode_index(w, vecs, model.half_gauge, model.layout)
    # Seed: the speed at which the per-speed pick is least damped (ratio).
    picked = eig[np.arange(speeds.size), first_pick]
    zeta = -picked.real / np.maximum(np.abs(picked), 1e-12)
    seed = int(np.argmin(zeta))
    index = first_pick.copy()
    for direction in (-1, 1):
        i = seed
        while 0 <= i + direction < speeds.size:
            prev = shapes[i][:, index[i]]
            j = i + direction
            best, best_mac = index[j], -1.0
            for k in range(n_state):
                if eig[j, k].imag <= 1e-6:
                    continue
                m = mac(prev, shapes[j][:, k])
                if m > best_mac:
                    best, best_mac = k, m
            index[j] = best
            i = j
    hunt = eig[np.arange(speeds.size), index]
    return EigenResult(speeds, eig, hunt)


def linear_critical_speed(
    vehicle: Vehicle,
    min_kmh: float = 20.0,
    max_kmh: float = 1000.0,
    tol_kmh: float = 0.01,
    scan_step_kmh: float = 20.0,
    creep_law: str | None = None,
    contact: object = None,
    curve: Curve | Callable[[float], Curve] | None = None,
    *,
    model: Model | None = None,
) -> LinearCriticalSpeed:
    """Lowest speed at which the centred (or steady-curving) equilibrium loses stability.

    The largest real part over all eigenvalues, ``g(v)``, is scanned on a grid of
    ``scan_step_kmh`` from ``min_kmh`` to ``max_kmh``. A sign change is refined by Brent's
    method to ``tol_kmh``. So that a narrow window of instability between two grid points
    is not missed, every local maximum of ``g`` on the grid that comes within 1 s^-1 of zero
    is searched for its true maximum first.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    min_kmh, max_kmh : float
        Search range (km/h).
    tol_kmh : float
        Resolution (km/h).
    scan_step_kmh : float
        Grid step of the scan (km/h).
    creep_law : str
        See :class:`railhunt.model.Model`.
    contact : ContactGeometry, optional
        Tabulated contact geometry instead of the polynomials (see ``Model``).
    curve : Curve or callable, optional
        Stability about the steady-curving equilibrium in this curve's constant part
        (:func:`railhunt.curving`) instead of the centred state on straight track. The
        equilibrium moves with speed as the cant deficiency changes; it is followed from
        each speed to the next. A callable gives the curve at each speed in m/s (a fixed
        cant deficiency, :func:`railhunt.curve.fixed_deficiency`). The search stops at the
        first limit of the validity envelope the steady-curving state reaches, as
        :func:`railhunt.critical_speed` does (``.limit``, ``.warnings``); it raises
        :class:`~railhunt.analysis.curving.CurvingError` when the state is beyond it
        already at ``min_kmh``.
    model : Model, optional
        The model of ``vehicle`` to use as it is (its creep law, contact table and each
        wheelset's contact mechanics, e.g. ``Model(vehicle, contact_mechanics=...)``)
        instead of building one from ``creep_law`` and ``contact``, which must then be
        None.

    Returns
    -------
    LinearCriticalSpeed
        ``.speed_kmh`` and ``.frequency_hz`` of the crossing mode.
    """
    for name, value in (("min_kmh", min_kmh), ("max_kmh", max_kmh), ("tol_kmh", tol_kmh),
                        ("scan_step_kmh", scan_step_kmh)):  # fmt: skip
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r} km/h is invalid: must be finite and > 0")
    if min_kmh >= max_kmh:
        raise ValueError(
            f"min_kmh = {min_kmh} km/h is invalid: must be below max_kmh = {max_kmh} km/h"
        )
    if model is None:
        model = Model(vehicle, creep_law=creep_law, contact=contact)
    elif creep_law is not None or contact is not None or model.vehicle is not vehicle:
        raise ValueError("model= is invalid together with creep_law= or contact=, or with "
                         "another vehicle: the model already holds them")  # fmt: skip
    limit = None
    if curve is None:
        def jacobian_at(kmh: float) -> np.ndarray:
            return model.jacobian(kmh_to_ms(kmh))
    else:
        path = EquilibriumPath(model, curve)
        jacobian_at = path.jacobian_kmh
        limit, max_kmh = capped_at_curving_limit(path, curve, min_kmh, max_kmh)

    def growth(kmh: float) -> float:
        return float(np.max(np.linalg.eigvals(jacobian_at(kmh)).real))

    grid = np.unique(np.append(np.arange(min_kmh, max_kmh, scan_step_kmh), max_kmh))
    values = [growth(grid[0])]
    bracket = None
    if values[0] > 0:
        w, vecs = sorted_eig(jacobian_at(float(grid[0])))
        k = int(np.argmax(w.real))
        real = abs(w[k].imag) < 1e-9
        return LinearCriticalSpeed(math.nan, abs(w[k].imag) / (2 * math.pi), complex(w[k]),
                                   False, "divergence" if real else "hopf",
                                   float(grid[0]), limit=limit)  # fmt: skip
    else:
        for i in range(1, grid.size):
            values.append(growth(grid[i]))
            if values[i] > 0:
                bracket = (grid[i - 1], grid[i])
                break
            if i >= 2 and values[i - 2] < values[i - 1] > values[i] and values[i - 1] > -1.0:
                peak = minimize_scalar(lambda k: -growth(k), bounds=(grid[i - 2], grid[i]),
                                       method="bounded", options={"xatol": tol_kmh})  # fmt: skip
                if -peak.fun > 0:
                    bracket = (grid[i - 2], float(peak.x))
                    break
        if bracket is None:
            return LinearCriticalSpeed(math.nan, math.nan, complex(math.nan), False,
                                       limit=limit)  # fmt: skip
        speed = brentq(growth, *bracket, xtol=tol_kmh)
    w, vecs = sorted_eig(jacobian_at(speed))
    k = crossing_index(w, sorted_eig(jacobian_at(speed + max(tol_kmh, 0.05)))[0])
    if abs(w[k].imag) < 1e-9:
        is_hunting = False
    else:
        kk = k if w[k].imag > 0 else int(np.argmin(np.abs(w - np.conj(w[k]))))
        is_hunting = (kk == hunting_mode_index(w, vecs, model.half_gauge, model.layout)
                      or moves_the_wheelsets(vecs[:model.layout.n_dof, kk], model.half_gauge,
                                             model.layout))  # fmt: skip
    return LinearCriticalSpeed(float(speed), abs(w[k].imag) / (2 * math.pi), complex(w[k]),
                               is_hunting, "divergence" if abs(w[k].imag) < 1e-9 else "hopf",
                               limit=limit)  # fmt: skip
