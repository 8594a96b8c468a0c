"""The validity envelope: the safety and plausibility limits every answer is checked against.

A result of the equations still means what its label says only inside the limits the
field uses to judge running safety and inside the range the model is built for. Each
check gives a :class:`Limit` (the limit, the value, the place); a result carries them as
``limits`` and, in words, as ``warnings``.

| limit | value | source |
|---|---|---|
| derailment quotient | ``Y/Q <= 0.8`` on every wheel (Nadal) | EN 14363 |
| wheel unloading | ``dQ/Q0 <= 0.6`` (``Q0``: the axle's mean wheel load) | EN 14363 |
| wheel lift | ``Q`` at the model's 1 % floor of ``Q0`` (a lifted wheel) | railhunt |
| track shifting | ``abs(sum Y) <= 10 kN + 2 Q0 / 3`` (Prud'homme, alpha = 1) | EN 14363 |
| cant deficiency | ``abs(I) <= 0.165 m`` (the model's range; I < 0: a cant excess) | railhunt |
| bump stop | car body to bogie beyond the free play plus 40 mm of rubber | railhunt |
| flange clearance | a wheelset past its flange (see below) | railhunt |

The cant deficiency limit is the range railhunt's curving model (small car body roll,
quasi-static load transfer) is meant for, that of non-tilting trains. The flange clearance
is the lateral displacement at which the contact angle reaches the flange angle: beyond it
the wheel climbs its flange (in a curve, a derailment). A lifted wheel's contact forces
are no longer modelled.

``Q0`` is the static wheel load ``N = W g / 2``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from railhunt.kernel.contact import wheel_geometry
from railhunt.kernel.track import rail_offsets

#: Nadal's limit of the derailment quotient (EN 14363, curves of R >= 250 m).
YQ_LIMIT = 0.8
#: Limit of the wheel unloading dQ/Q0 (EN 14363).
UNLOADING_LIMIT = 0.6
#: The kernel keeps a wheel load at this share of the static load or more (a lifted wheel).
Q_FLOOR = 0.01
#: Prud'homme: sum Y <= PRUDHOMME_A + PRUDHOMME_B * Q0 (N; EN 14363 with alpha = 1).
PRUDHOMME_A, PRUDHOMME_B = 10e3, 2.0 / 3.0
#: Length of track over which EN 14363 takes the sliding means of Y/Q and ΣY in a run (m).
SLIDING_MEAN_M = 2.0
#: Largest cant deficiency railhunt's curving model is meant for (m).
CANT_DEFICIENCY_LIMIT = 0.165
#: Travel of the bump stop's rubber beyond its free play taken as the end of travel (m).
BUMP_STOP_TRAVEL = 0.040

#: The names of the limits, as :attr:`Limit.name` gives them.
LIMIT_NAMES = ("Y/Q", "wheel unloading", "wheel lift", "ΣY", "cant deficiency", "cant excess",
               "bump stop", "flange clearance")  # fmt: skip


def _wheel_names(n_wheelsets: int) -> tuple[str, ...]:
    return tuple(f"wheelset {j + 1} {side}" for j in range(n_wheelsets)
                 for side in ("left", "right"))  # fmt: skip


#: How a limit's SI unit is shown in words: (unit shown, factor).
_SHOWN = {"N": ("kN", 1e-3), "m": ("mm", 1e3), "1": ("", 1.0), "": ("", 1.0)}


def shown(value: float, unit: str) -> str:
    """``value`` (SI, ``unit``) as a limit's words show it: forces in kN, lengths in mm,
    three significant digits (``shown(48827.5, "N")`` is ``"48.8 kN"``)."""
    name, factor = _SHOWN.get(unit, (unit, 1.0))
    return f"{value * factor:.3g}" + (f" {name}" if name else "")


@dataclass(frozen=True)
class Limit:
    """One limit of the validity envelope that a result reaches.

    Attributes
    ----------
    name : str
        One of :data:`LIMIT_NAMES`.
    limit : float
        The limit (SI units, ``unit``).
    value : float
        The value reached (same unit).
    unit : str
        Unit of both.
    place : str
        Where: the wheel, wheelset or bogie, and the time or speed.
    source : str
        Where the limit comes from (``"EN 14363"`` or ``"railhunt"``: the model's range).
    """

    name: str
    limit: float
    value: float
    unit: str
    place: str
    source: str

    @property
    def text(self) -> str:
        """The limit in words, e.g. ``"Y/Q 0.93 beyond 0.8 (EN 14363) at wheelset 1
        right, t = 0.308 s"`` (forces in kN and lengths in mm, :func:`shown`)."""
        if math.isnan(self.value):  # no state to measure (e.g. no steady-curving equilibrium)
            return f"{self.name} ({self.source}): {self.place}"
        if self.name == "wheel lift":
            return (f"wheel lift: Q at the model's floor of {shown(self.limit, self.unit)} "
                    f"({self.source}) at {self.place}")  # fmt: skip
        return (f"{self.name} {shown(self.value, self.unit)} beyond "
                f"{shown(self.limit, self.unit)} ({self.source}) at {self.place}")  # fmt: skip

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: name, limit, value, unit, place, source."""
        return {"name": self.name, "limit": self.limit, "value": self.value,
                "unit": self.unit, "place": self.place, "source": self.source}  # fmt: skip


def flange_clearance(model: Any) -> float:
    """Lateral displacement (m) at which the wheel nearer its flange reaches the flange
    angle: the first displacement, scanning 0 to 25 mm in 0.1 mm, where its contact angle
    is within 1 % of its largest value (both directions; the smaller); ``inf`` when the
    contact angle does not grow (conical wheels: no flange in the geometry)."""
    return _flange_clearance(model.wheel_rail_vector().tobytes())


@lru_cache(maxsize=256)
def _flange_clearance(wr_bytes: bytes) -> float:
    """:func:`flange_clearance` of a wheel/rail vector (its raw bytes: the same wheels and
    rails give the same clearance, computed once per process for every trial of a search)."""
    wr = np.frombuffer(wr_bytes, dtype=np.float64)
    ys = np.arange(0.0, 0.0251, 1e-4)
    out = math.inf
    for sign, side in ((1.0, 2), (-1.0, 3)):
        delta = np.array([wheel_geometry(sign * y, wr)[side] for y in ys])
        top = float(np.max(delta))
        if top <= 1.01 * abs(float(delta[0])) + 1e-9:
            continue  # the contact angle does not grow (a conical wheel): no flange modelled
        out = min(out, float(ys[np.argmax(delta >= 0.99 * top)]))
    return out


def _worst(values: np.ndarray, names: tuple[str, ...]) -> tuple[float, str, int]:
    """Largest entry of a (rows, columns) array: its value, its column's name, its row."""
    row, col = np.unravel_index(int(np.nanargmax(values)), values.shape)
    return float(values[row, col]), names[col], int(row)


def sliding_mean(a: np.ndarray, window: int) -> np.ndarray:
    """Mean of ``window`` consecutive rows of ``a`` (axis 0), row ``i`` ending at ``i``;
    the first ``window - 1`` rows average what there is so far."""
    a = np.asarray(a, dtype=float)
    if window <= 1 or a.shape[0] == 0:
        return a
    c = np.cumsum(np.nan_to_num(a), axis=0)
    out = c.copy()
    out[window:] = c[window:] - c[:-window]
    counts = np.minimum(np.arange(1, a.shape[0] + 1), window).astype(float)
    return out / counts.reshape((-1,) + (1,) * (a.ndim - 1))


def check_wheels(Y: np.ndarray, Q: np.ndarray, sum_Y: np.ndarray, q0: float,
                 where: list[str] | None = None, window: int = 1) -> list[Limit]:  # fmt: skip
    """Limits on the wheel/rail forces: Y/Q, unloading, lift and ΣY.

    Parameters
    ----------
    Y, Q : numpy.ndarray, shape (n, 2 * n_wheelsets)
        Guiding forces and wheel loads (N), one row per time or state, the wheels in the
        order wheelset 1 left, wheelset 1 right, ...
    sum_Y : numpy.ndarray, shape (n, n_wheelsets)
        Sum of the guiding forces of each wheelset (N).
    q0 : float
        Static wheel load (N).
    where : list of str, optional
        What each row is (e.g. ``"t = 3.2 s"``); default ``"row i"``.
    window : int
        For the rows of a run in time: Y/Q and ΣY are judged on their sliding means over
        this many rows, as EN 14363 judges them on 2 m sliding means (an impact's
        instantaneous peak is not the standard's quantity); 1: each row alone (a steady
        state).
    """
    Y, Q, sum_Y = (np.atleast_2d(np.asarray(a, dtype=float)) for a in (Y, Q, sum_Y))
    where = where or [f"row {i}" for i in range(Y.shape[0])]
    out: list[Limit] = []
    _WHEELS = _wheel_names(sum_Y.shape[1])  # noqa: N806 (a table of names)
    yq = sliding_mean(Y / Q, window)
    sum_Y = sliding_mean(sum_Y, window)
    if np.nanmax(yq) > YQ_LIMIT:
        value, wheel, row = _worst(yq, _WHEELS)
        out.append(Limit("Y/Q", YQ_LIMIT, value, "1", f"{wheel}, {where[row]}", "EN 14363"))
    # Unloading against each axle's mean wheel load (its quasi-static load without the
    # transfer between its wheels; the static load on straight track).
    mean = 0.5 * (Q[:, 0::2] + Q[:, 1::2])
    unloading = (np.repeat(mean, 2, axis=1) - Q) / np.repeat(mean, 2, axis=1)
    if np.nanmax(unloading) > UNLOADING_LIMIT:
        value, wheel, row = _worst(unloading, _WHEELS)
        out.append(Limit("wheel unloading", UNLOADING_LIMIT, value, "1",
                         f"{wheel}, {where[row]}", "EN 14363"))  # fmt: skip
    if np.nanmin(Q) <= Q_FLOOR * q0 * (1.0 + 1e-9):
        value, wheel, row = _worst(-Q, _WHEELS)
        out.append(Limit("wheel lift", Q_FLOOR * q0, -value, "N",
                         f"{wheel}, {where[row]} (Q clipped at 1 % of Q0: the wheel has "
                         "lifted)", "railhunt"))  # fmt: skip
    limit = PRUDHOMME_A + PRUDHOMME_B * q0
    names = tuple(f"wheelset {j + 1}" for j in range(sum_Y.shape[1]))
    if np.nanmax(np.abs(sum_Y)) > limit:
        value, ws, row = _worst(np.abs(sum_Y), names)
        out.append(Limit("ΣY", limit, value, "N", f"{ws}, {where[row]}", "EN 14363"))
    return out


def check_motion(x: np.ndarray, model: Any, where: list[str] | None = None,
                 track_y: np.ndarray | None = None,
                 geometry: np.ndarray | None = None) -> list[Limit]:  # fmt: skip
    """Limits on the motion: bump stop travel and flange clearance.

    Parameters
    ----------
    x : numpy.ndarray, shape (n, n_state) or (n_state,)
        States (coordinates relative to the track).
    model : Model
        The model (its bump stop rows and contact geometry).
    where : list of str, optional
        What each row is.
    track_y : numpy.ndarray, shape (n, n_wheelsets), optional
        Lateral alignment of the rails under each wheelset (m), subtracted from its
        displacement (a run over a track defect); default 0.
    geometry : numpy.ndarray, shape (n, n_dof), optional
        The curve's offsets of the coordinates (:func:`railhunt.kernel.rhs.curve_geometry`),
        added before the bump stop deformation is taken; default 0 (straight track).
    """
    x = np.atleast_2d(np.asarray(x, dtype=float))
    where = where or [f"row {i}" for i in range(x.shape[0])]
    out: list[Limit] = []
    system = model.system()
    n_dof = system.linear.shape[0]  # the model's own layout: coordinates first
    # Bump stops between two bodies (a stop to the track is a flange: its force is in the
    # wheels' guiding forces, and the flange clearance below is its limit).
    track = np.zeros(system.stop.shape[0], dtype=bool)
    track[:system.stop_wheelset.shape[0]] = system.stop_wheelset >= 0
    between = np.flatnonzero(~track)
    if between.size:
        gap = system.stop[between, 0]
        q = x[:, :n_dof] if geometry is None else x[:, :n_dof] + geometry[:, :n_dof]
        travel = np.abs(q @ system.stop_rows[between].T)
        limit = gap + BUMP_STOP_TRAVEL
        over = travel - limit[None, :]
        if np.max(over) > 0:
            row, k = np.unravel_index(np.argmax(over), over.shape)
            out.append(Limit("bump stop", float(limit[k]), float(travel[row, k]), "m",
                             f"{_stop_name(model, int(between[k]))}, {where[row]}",
                             "railhunt"))  # fmt: skip
    ys = x[:, system.wheelsets[:, 0]]
    if track_y is not None:
        ys = ys - track_y
    clearance = flange_clearance(model)
    if np.max(np.abs(ys)) > clearance + 1e-4:
        row, k = np.unravel_index(np.argmax(np.abs(ys)), ys.shape)
        out.append(Limit("flange clearance", clearance, float(abs(ys[row, k])), "m",
                         f"wheelset {k + 1}, {where[row]}", "railhunt"))  # fmt: skip
    return out


def _stop_name(model: Any, k: int) -> str:
    """The name of the model's ``k``-th stop element (its layout's), e.g. ``"secondary
    lateral bump stop, front bogie"``."""
    vehicle = getattr(model, "vehicle", None)
    layout = getattr(vehicle, "layout", None)
    stops = [el.name for el in getattr(layout, "elements", ()) if el.kind == "stop"]
    if k < len(stops):
        return stops[k]
    return f"{'front' if k == 0 else 'rear'} bogie to car body"


def curve_offsets_along(model: Any, speed: float, t: np.ndarray, route: np.ndarray) -> np.ndarray:
    """The curve's offsets of the coordinates at each time of a run through ``route``
    (:func:`railhunt.kernel.rhs.curve_geometry`, one row per time, ``n_dof`` columns)."""
    from railhunt.kernel.rhs import curve_geometry

    v, system = model.args(speed, route=route)
    n = system.linear.shape[0]
    out = np.empty((t.size, n))
    for i, ti in enumerate(t):
        out[i] = curve_geometry(float(ti), v, system)[:n]
    return out


def static_wheel_load(model: Any) -> float:
    """The static wheel load ``Q0`` (N) of the model's wheel/rail forces (``N`` of the
    kernel's wheel/rail vector: ``W g / 2`` for the paper's vehicle)."""
    from railhunt.kernel.layout import WR

    return float(model.wheel_rail_vector()[WR.N])


def check_cant_deficiency(cant_deficiency: float, where: str) -> list[Limit]:
    """The cant deficiency (m; negative: a cant excess) against
    :data:`CANT_DEFICIENCY_LIMIT`: a negative one beyond it is named a cant excess."""
    if abs(cant_deficiency) > CANT_DEFICIENCY_LIMIT:
        name = "cant deficiency" if cant_deficiency > 0 else "cant excess"
        return [Limit(name, CANT_DEFICIENCY_LIMIT, abs(cant_deficiency), "m", where,
                      "railhunt")]  # fmt: skip
    return []


def curving_limits(result: Any, model: Any) -> list[Limit]:
    """Every limit a steady-curving state (:class:`~railhunt.analysis.curving.CurvingResult`)
    reaches."""
    where = f"{result.speed_kmh:g} km/h in the {result.curve.radius:g} m curve"
    q0 = static_wheel_load(model)
    out = check_wheels(result.Y.ravel()[None, :], result.Q.ravel()[None, :],
                       result.sum_Y[None, :], q0, [where])  # fmt: skip
    out += check_cant_deficiency(result.cant_deficiency, where)
    from railhunt.kernel.rhs import curve_geometry
    from railhunt.units import kmh_to_ms

    v, system = model.args(kmh_to_ms(result.speed_kmh), route=result.curve.steady_route())
    geo = curve_geometry(0.0, v, system)[None, :system.linear.shape[0]]
    out += check_motion(result.state, model, [where], geometry=geo)
    return out


def run_limits(result: Any, model: Any, excitation: object = None,
               route: np.ndarray | None = None) -> list[Limit]:  # fmt: skip
    """Every limit a simulated run (:class:`~railhunt.simulation.SimulationResult`) reaches
    (wheel forces from its derived channels, bump stops, flange clearance); ``route``: the
    curve the run went through (its offsets enter the bump stops' travel)."""
    t = np.asarray(result.t)
    if t.size == 0:
        return []
    where = _Times(t)
    nw = model.system().wheelsets.shape[0]
    ws = [f"w{j + 1}" for j in range(nw)]
    q0 = static_wheel_load(model)
    out: list[Limit] = []
    names = set(result.derived)
    if {f"Y_{w}{s}" for w in ws for s in "LR"} <= names:
        Y = np.column_stack([result[f"Y_{w}{s}"] for w in ws for s in "LR"])
        Q = np.column_stack([result[f"Q_{w}{s}"] for w in ws for s in "LR"])
        sum_y = np.column_stack([result[f"SY_{w}"] for w in ws])
        # EN 14363's 2 m sliding means, in samples of the run's output step
        step = float(np.median(np.diff(t))) if t.size > 1 else 0.0
        window = max(1, round(SLIDING_MEAN_M / (float(result.speed) * step))) if step > 0 else 1
        out += check_wheels(Y, Q, sum_y, q0, where, window=window)
    trk = model.system(excitation)
    track_y = rail_offsets(t, float(result.speed), trk.wheelset_delay, trk.track,
                           trk.track_samples)  # fmt: skip
    geometry = None if route is None else curve_offsets_along(model, float(result.speed), t,
                                                              route)  # fmt: skip
    out += check_motion(result.x, model, where, track_y, geometry)
    return out


def record_limits(model: Any, speed: float, t: np.ndarray, x: np.ndarray,
                  excitation: object = None) -> list[Limit]:  # fmt: skip
    """Every limit a run on straight track reaches, from its bare record: times ``t`` (s)
    and states ``x`` at ``speed`` (m/s) over ``excitation``, its wheel forces derived
    as :func:`railhunt.simulate` derives them (:func:`run_limits`)."""
    from railhunt.channels import derived_channels

    derived = derived_channels(t, x, *model.args(speed, excitation), model.layout,
                               accelerations=False)  # fmt: skip
    return run_limits(_Record(t, x, speed, derived), model, excitation)


@dataclass(frozen=True)
class _Record:
    """The part of a simulated run :func:`run_limits` reads."""

    t: np.ndarray
    x: np.ndarray
    speed: float
    derived: dict

    def __getitem__(self, name: str) -> np.ndarray:
        return self.derived[name]


class _Times:
    """``where[i]`` of a run: ``"t = 1.234 s"``, formatted only for the row reported."""

    def __init__(self, t: np.ndarray) -> None:
        self.t = t

    def __getitem__(self, i: int) -> str:
        return f"t = {float(self.t[i]):.3f} s"


def warnings_of(limits: list[Limit]) -> list[str]:
    """The limits in words, one warning each (:attr:`Limit.text`). These are facts about a
    result, not a verdict: the verdict word *limit reached* is kept for an answer that
    stops at a limit (a search in a curve, :mod:`railhunt.analysis.curving_limit`)."""
    return [lim.text for lim in limits]


def _location(place: str) -> str:
    """A limit's place without its time and speed: ``"wheelset 2, t = 0.240 s, 310 km/h"``
    gives ``"wheelset 2"``."""
    return place.split(", t = ")[0].split(", row ")[0]


def _speeds(speeds: tuple[float, ...]) -> str:
    """Speeds in words: ``"310 km/h"``, ``"305 and 310 km/h"``, ``"301, 302, 305 and 310
    km/h"``, or for more than four ``"100-300 km/h (21 speeds)"``."""
    words = [f"{s:g}" for s in speeds]
    if len(words) > 4:
        return f"{words[0]}–{words[-1]} km/h ({len(words)} speeds)"
    if len(words) > 1:
        return f"{', '.join(words[:-1])} and {words[-1]} km/h"
    return f"{words[0]} km/h"


@dataclass(frozen=True)
class LimitSummary:
    """One kind of limit over the results of a search: the largest value, where, and at
    which speeds it was reached (:func:`summarize_limits`).

    Attributes
    ----------
    name, limit, unit, source : str, float, str, str
        As :class:`Limit` has them.
    value : float
        The largest value reached (SI, ``unit``).
    place : str
        Where the largest value was reached (wheel or wheelset, time).
    speed_kmh : float
        The speed at which it was reached (km/h).
    speeds_kmh : tuple of float
        Every speed at which this limit was reached, ascending (km/h).
    decided : bool
        Whether the limit decided the answer (a search that stopped there); False for
        the limits of a straight-track search's trials, which change no verdict.
    """

    name: str
    limit: float
    unit: str
    source: str
    value: float
    place: str
    speed_kmh: float
    speeds_kmh: tuple[float, ...]
    decided: bool = False

    @property
    def effect(self) -> str:
        """Whether it decided anything, in words."""
        return "the answer stops there" if self.decided else "changes no verdict"

    @property
    def text(self) -> str:
        """The summary in words, e.g. ``"ΣY beyond 45.6 kN (EN 14363) at 301, 302, 305
        and 310 km/h; largest 48.8 kN at wheelset 2, t = 0.240 s, 310 km/h; changes no
        verdict"``."""
        return (f"{self.name} beyond {shown(self.limit, self.unit)} ({self.source}) at "
                f"{_speeds(self.speeds_kmh)}; largest {shown(self.value, self.unit)} at "
                f"{self.place}, {self.speed_kmh:g} km/h; {self.effect}")  # fmt: skip

    @property
    def line(self) -> str:
        """The summary in one line of at most about 80 characters, for a terminal:
        ``"ΣY 48.8 kN > 45.6 kN (EN 14363) at 301-310 km/h, wheelset 2: changes no
        verdict"``."""
        lo, hi = self.speeds_kmh[0], self.speeds_kmh[-1]
        at = f"{lo:g} km/h" if lo == hi else f"{lo:g}–{hi:g} km/h"
        return (f"{self.name} {shown(self.value, self.unit)} > {shown(self.limit, self.unit)} "
                f"({self.source}) at {at}, {_location(self.place)}: {self.effect}")  # fmt: skip

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: name, limit, value (the largest), unit, source, place and speed_kmh
        of the largest, speeds_kmh, decided, text."""
        return {"name": self.name, "limit": self.limit, "value": self.value,
                "unit": self.unit, "source": self.source, "place": self.place,
                "speed_kmh": self.speed_kmh, "speeds_kmh": list(self.speeds_kmh),
                "decided": self.decided, "text": self.text}  # fmt: skip


def summarize_limits(reached: Iterable[tuple[float, Limit]],
                     decided: bool = False) -> list[LimitSummary]:  # fmt: skip
    """One :class:`LimitSummary` per kind of limit (in the order of :data:`LIMIT_NAMES`)
    from ``(speed_kmh, limit)`` pairs: the limits the runs of a search reached, each with
    its run's speed. ``decided``: whether these limits decided the answer."""
    by_name: dict[str, list[tuple[float, Limit]]] = {}
    for speed, lim in reached:
        by_name.setdefault(lim.name, []).append((float(speed), lim))
    order = {name: i for i, name in enumerate(LIMIT_NAMES)}
    out = []
    for name in sorted(by_name, key=lambda n: order.get(n, len(order))):
        items = by_name[name]
        speed, top = max(items, key=lambda item: (item[1].value, item[0]))
        out.append(LimitSummary(name, top.limit, top.unit, top.source, top.value, top.place,
                                speed, tuple(sorted({s for s, _ in items})), decided))  # fmt: skip
    return out


__all__ = ["Limit", "LimitSummary", "check_wheels", "check_motion", "check_cant_deficiency",
           "curving_limits", "run_limits", "record_limits", "flange_clearance", "shown",
           "summarize_limits", "warnings_of"]  # fmt: skip
