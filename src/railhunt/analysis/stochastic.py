"""Instability criterion of the acceptance test (EN 14363 style) on irregular track.

The paper's excitation type (c): run at constant speed over a stochastic (or measured)
track irregularity and apply the criteria of the vehicle acceptance test. Two criteria,
as in EN 14363:2005 (Sec. 5.5.2.2 / Annex on the stability assessment) and UIC 518
(the "normal" and the "simplified" measuring method):

* **Sum of guiding forces** ΣY of each wheelset (the lateral force it exerts on the track,
  channel ``SY_wj`` of :mod:`railhunt.channels`), band-pass filtered ``f0 ± 2 Hz`` around
  the instability frequency ``f0``, sliding rms over 100 m of track in steps of 10 m,
  against ``(ΣY)_lim,rms = (10 kN + 2*Q0/3) / 2`` with ``Q0`` the static wheel load:
  half the Prud'homme limit (``α = 1``, passenger vehicles).
* **Bogie frame lateral acceleration** ÿ+ above each wheelset (``ddy_t ± l1*ddpsi_t``),
  band-pass filtered ``f0 ± 2 Hz``, sliding rms over 100 m in steps of 10 m, against
  ``ÿ+_lim,rms = (12 - M_b/5) / 2`` m/s² with ``M_b`` the bogie mass in t (here bogie
  frame plus its two wheelsets, ``M_t + 2*M_w``).

Sources: EN 14363:2005 *Railway applications - Testing for the acceptance of running
characteristics of railway vehicles*, stability criteria (ΣY filtered f0 ± 2 Hz, sliding
rms; limits half the peak limits ``10 + P0/3`` kN, ``P0 = 2*Q0`` the axle load, and
``12 - M+/5`` m/s²); the same table is reproduced in the GENSYS course notes "Acceptance
test according to UIC 518 and EN 14363" (gensys.se/course/UIC518_tests.html). The filter
is a Butterworth band-pass (4th-order prototype, i.e. 8th-order band-pass) applied
forwards and backwards (zero phase); the standard fixes the pass band, not the order.

The instability frequency ``f0`` is, unless given, the frequency of the largest peak of
the Welch PSD of the leading wheelset's ΣY between 0.5 Hz and 15 Hz (the hunting mode of
a bogie vehicle lies in 1-10 Hz); the pass band's lower edge is kept at 0.3 Hz or above.

:func:`stochastic_critical_speed` then searches the lowest speed at which either rms
exceeds its limit, stepping and bisecting like :func:`railhunt.critical_speed`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy import signal

from railhunt.analysis.search import bracket_and_bisect, check_search
from railhunt.irregularity import TrackIrregularity, track_irregularity
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.simulation import SimulationResult, simulate
from railhunt.track import SampledTrack
from railhunt.units import kmh_to_ms
from railhunt.vehicle import Vehicle

#: Length of the sliding rms window and its step (m), EN 14363.
WINDOW_LENGTH = 100.0
WINDOW_STEP = 10.0
#: Half width of the band-pass around the instability frequency (Hz), EN 14363.
HALF_BAND = 2.0
#: Where f0 is looked for (Hz).
F0_SEARCH = (0.5, 15.0)

STABLE, UNSTABLE = "stable", "unstable"


def sum_y_limit(vehicle: Vehicle) -> float:
    """``(ΣY)_lim,rms = (10 kN + 2*Q0/3) / 2`` in N, ``Q0 = vehicle.N`` the static wheel load."""
    return 0.5 * (10e3 + 2.0 * vehicle.N / 3.0)


def running_gear(vehicle: Vehicle) -> list[tuple[str, float, list[tuple[str, float]]]]:
    """The bogies of a layout: for each bogie frame (a ``frame`` body) its coordinate tag,
    its mass with the wheelsets an element joins to it (kg), and those wheelsets' tags
    with their distance ahead of the frame's centre (m). Empty for a layout without
    frames (a two-axle wagon): EN 14363's bogie-frame acceleration does not exist there
    and the criterion is judged on ΣY alone."""
    from railhunt.layout.expressions import difference

    layout, values = vehicle.layout, vehicle.values
    out = []
    for frame in (b for b in layout.bodies if b.kind == "frame" and b.coordinates):
        joined = {el.body_b if el.body_a == frame.name else el.body_a for el in layout.elements
                  if frame.name in (el.body_a, el.body_b)}  # fmt: skip
        wheelsets = [w for w in layout.wheelsets if w.name in joined]
        mass = frame.mass(values) + sum(w.mass(values) for w in wheelsets)
        out.append((frame.tag, mass,
                    [(w.tag, difference(w.x, frame.x, values)) for w in wheelsets]))
    return out


def bogie_mass(vehicle: Vehicle) -> float:
    """Bogie mass (kg): the first bogie frame and its wheelsets (``M_t + 2*M_w`` for the
    paper's vehicle); NaN without a bogie frame."""
    gear = running_gear(vehicle)
    return gear[0][1] if gear else math.nan


def acceleration_limit(vehicle: Vehicle) -> float:
    """``ÿ+_lim,rms = (12 - M_b/5) / 2`` in m/s², ``M_b`` the bogie mass in t (NaN for a
    layout without bogie frames)."""
    return 0.5 * (12.0 - bogie_mass(vehicle) / 1000.0 / 5.0)


@dataclass(repr=False)
class Assessment(ResultDisplay):
    """The instability criterion evaluated on one run.

    Attributes
    ----------
    speed_kmh : float
        Speed of the run (km/h).
    f0_hz : float
        Instability frequency used for the band-pass (Hz).
    distance : numpy.ndarray
        Track position of the leading wheelset at the centre of each 100 m window (m).
    sum_y_rms : numpy.ndarray
        Sliding rms of the band-passed ΣY (N), shape (windows, 4 wheelsets).
    acceleration_rms : numpy.ndarray
        Sliding rms of the band-passed bogie frame lateral acceleration above each
        wheelset (m/s²), shape (windows, 4).
    sum_y_limit, acceleration_limit : float
        The limits (N, m/s²).
    status : str
        Integrator status of the run (``"derailed"`` counts as unstable).
    limits : list of Limit
        The limits of the validity envelope the run reaches (:mod:`railhunt.validity`:
        Y/Q, ΣY, unloading, flange clearance, ...), as its :class:`SimulationResult` has them.
    """

    speed_kmh: float
    f0_hz: float
    distance: np.ndarray
    sum_y_rms: np.ndarray
    acceleration_rms: np.ndarray
    sum_y_limit: float
    acceleration_limit: float
    status: str = "ok"
    limits: list = field(default_factory=list)

    @property
    def warnings(self) -> list[str]:
        """The limits the run reached, in words, each with the run's speed (they change no
        verdict: the criterion is about the run's ΣY and frame accelerations)."""
        return [f"{self.speed_kmh:g} km/h: {lim.text}" for lim in self.limits]

    @property
    def sum_y_ratio(self) -> float:
        """Largest sliding rms of ΣY over its limit (> 1: criterion exceeded)."""
        return _max_ratio(self.sum_y_rms, self.sum_y_limit)

    @property
    def acceleration_ratio(self) -> float:
        """Largest sliding rms of the bogie acceleration over its limit."""
        return _max_ratio(self.acceleration_rms, self.acceleration_limit)

    @property
    def unstable(self) -> bool:
        """True when either rms exceeds its limit, or the run derailed or diverged."""
        if self.status != "ok":
            return True
        if not self.evaluated:
            raise ValueError("the criterion was not evaluated: the run is shorter than one "
                             f"{WINDOW_LENGTH:g} m window")  # fmt: skip
        return self.sum_y_ratio > 1.0 or self.acceleration_ratio > 1.0

    @property
    def evaluated(self) -> bool:
        """True when the run covered at least one sliding window (the criterion has values)."""
        no_frames = self.acceleration_rms.ndim == 2 and self.acceleration_rms.shape[1] == 0
        return bool(self.sum_y_rms.size and (self.acceleration_rms.size or no_frames))

    @property
    def verdict(self) -> str:
        """``"unstable"``, ``"stable"`` or ``"not evaluated"`` (run shorter than a window)."""
        if self.status == "ok" and not self.evaluated:
            return "not evaluated"
        return UNSTABLE if self.unstable else STABLE

    def _summary(self) -> list[Row]:
        return [("speed", self.speed_kmh, "km/h"), ("verdict", self.verdict, ""),
                ("instability frequency f0", self.f0_hz, "Hz"),
                ("largest ΣY rms / limit", self.sum_y_ratio, ""),
                ("ΣY limit", self.sum_y_limit, "N"),
                ("largest bogie acceleration rms / limit", self.acceleration_ratio, ""),
                ("acceleration limit", self.acceleration_limit, "m/s^2"),
                ("windows", self.distance.size, ""), ("run status", self.status, "")]

    def _columns(self) -> Columns:
        """One row per 100 m window: its centre and the rms of each wheelset's channels."""
        cols: Columns = {"distance": (self.distance, "m")}
        for j in range(self.sum_y_rms.shape[1] if self.sum_y_rms.ndim == 2 else 0):
            cols[f"sum_y_rms_w{j + 1}"] = (self.sum_y_rms[:, j], "N")
        for j in range(self.acceleration_rms.shape[1] if self.acceleration_rms.ndim == 2 else 0):
            cols[f"acceleration_rms_w{j + 1}"] = (self.acceleration_rms[:, j], "m/s^2")
        return cols


def _max_ratio(values: np.ndarray, limit: float) -> float:
    return float(np.max(values) / limit) if values.size else math.nan


def dominant_frequency(
    t: np.ndarray, y: np.ndarray, band: tuple[float, float] = F0_SEARCH
) -> float:
    """Frequency (Hz) of the largest Welch PSD peak of ``y(t)`` within ``band``."""
    fs = 1.0 / float(np.median(np.diff(t)))
    nperseg = min(y.size, int(round(8.0 * fs)))  # 0.125 Hz resolution where possible
    f, p = signal.welch(y - np.mean(y), fs=fs, nperseg=nperseg)
    m = (f >= band[0]) & (f <= band[1])
    if not np.any(m) or not np.any(p[m] > 0):
        return math.nan
    return float(f[m][np.argmax(p[m])])


def band_pass(y: np.ndarray, fs: float, f0: float, half_band: float = HALF_BAND) -> np.ndarray:
    """Zero-phase Butterworth band-pass ``f0 ± half_band`` (Hz) of samples at ``fs``.

    ``scipy.signal.butter(4, ..., btype="bandpass")``: a 4th-order prototype, 8th-order
    band-pass; applied forwards and backwards (``sosfiltfilt``), so the magnitude response
    is squared and the phase is zero.
    """
    lo = max(f0 - half_band, 0.3)
    hi = min(f0 + half_band, 0.45 * fs)
    if not lo < hi:
        raise ValueError(f"f0 = {f0!r} Hz is invalid: the pass band is empty at {fs:g} Hz")
    sos = signal.butter(4, [lo, hi], btype="bandpass", fs=fs, output="sos")
    return signal.sosfiltfilt(sos, y, axis=0)


def sliding_rms(
    s: np.ndarray, y: np.ndarray, window: float = WINDOW_LENGTH, step: float = WINDOW_STEP
) -> tuple[np.ndarray, np.ndarray]:
    """Rms of ``y`` over windows of ``window`` metres of ``s`` every ``step`` metres.

    Parameters
    ----------
    s : numpy.ndarray
        Increasing track positions (m) of the samples.
    y : numpy.ndarray
        Samples, shape (n,) or (n, channels).

    Returns
    -------
    centres : numpy.ndarray
        Window centres (m).
    rms : numpy.ndarray
        Rms per window (and channel).
    """
    y2 = np.asarray(y, dtype=np.float64)
    flat = y2.ndim == 1
    if flat:
        y2 = y2[:, None]
    n_win = int(math.floor((s[-1] - s[0] - window) / step + 1e-9)) + 1 if s.size else 0
    if n_win <= 0:
        empty = np.empty((0,) + y2.shape[1:])
        return np.empty(0), empty[:, 0] if flat else empty
    cum = np.vstack([np.zeros((1, y2.shape[1])), np.cumsum(y2**2, axis=0)])
    starts = s[0] + step * np.arange(n_win)
    i0 = np.searchsorted(s, starts, side="left")
    i1 = np.searchsorted(s, starts + window, side="right")
    count = np.maximum(i1 - i0, 1)[:, None]
    rms = np.sqrt((cum[i1] - cum[i0]) / count)
    return starts + 0.5 * window, rms[:, 0] if flat else rms


def assess(
    result: SimulationResult, vehicle: Vehicle, f0_hz: float | None = None,
    window: float = WINDOW_LENGTH, step: float = WINDOW_STEP,
) -> Assessment:  # fmt: skip
    """Evaluate the instability criterion on a simulated run.

    Parameters
    ----------
    result : SimulationResult
        A run with the derived channels ``SY_w1..4``, ``ddy_t1/2``, ``ddpsi_t1/2``
        (every run of :func:`railhunt.simulate` has them), sampled uniformly in time.
    vehicle : Vehicle
        The vehicle (static wheel load, bogie mass, ``l1``).
    f0_hz : float, optional
        Instability frequency (Hz); default the dominant frequency of ``SY_w1``.
    window, step : float
        Sliding window length and step (m); EN 14363: 100 m and 10 m.

    Returns
    -------
    Assessment
    """
    t = result.t
    fs = 1.0 / float(np.median(np.diff(t)))
    sum_y = np.column_stack([result[f"SY_{b.tag}"] for b in result.layout.bodies
                             if b.is_wheelset])  # fmt: skip
    # The bogie frame's lateral acceleration above each of its wheelsets (l1 ahead and
    # behind for the paper's vehicle); a layout without frames has none (ΣY alone).
    columns = [result[f"ddy_{tag}"] + arm * result[f"ddpsi_{tag}"]
               for tag, _, wheelsets in running_gear(vehicle) for _, arm in wheelsets]
    acc = np.column_stack(columns) if columns else np.empty((t.size, 0))
    f0 = dominant_frequency(t, sum_y[:, 0]) if f0_hz is None else float(f0_hz)
    s = result.speed * t
    if not math.isfinite(f0) or t.size < 32:
        centres = np.empty(0)
        rms_y, rms_a = np.empty((0, sum_y.shape[1])), np.empty((0, acc.shape[1]))
    else:
        centres, rms_y = sliding_rms(s, band_pass(sum_y, fs, f0), window, step)
        if acc.shape[1]:
            _, rms_a = sliding_rms(s, band_pass(acc, fs, f0), window, step)
        else:
            rms_a = np.empty((centres.size, 0))
    return Assessment(
        speed_kmh=result.speed_kmh, f0_hz=f0, distance=centres, sum_y_rms=rms_y,
        acceleration_rms=rms_a, sum_y_limit=sum_y_limit(vehicle),
        acceleration_limit=acceleration_limit(vehicle), status=result.status,
        limits=list(getattr(result, "limits", [])),
    )  # fmt: skip


#: Public name of :func:`assess` in the ``railhunt`` namespace.
assess_stability = assess


def check_track_length(track: SampledTrack, model: Model) -> None:
    """Raise ``ValueError`` when a run over ``track`` is shorter than one rms window.

    The run lasts until the last wheelset leaves the section, so it covers
    ``track.end() + wheelbase`` metres; with less than one 100 m window the criterion
    cannot be evaluated, and no verdict (least of all "stable") can be given.
    """
    covered = track.end() + float(model.wheelset_offsets()[-1])
    if covered < WINDOW_LENGTH:
        raise ValueError(
            f"irregularity length = {track.end():.1f} m is invalid: a run over it covers "
            f"{covered:.1f} m, less than one {WINDOW_LENGTH:g} m window of the criterion; give at "
            f"least {WINDOW_LENGTH - float(model.wheelset_offsets()[-1]):.1f} m of track"
        )


def run_on_track(
    vehicle: Vehicle, speed_kmh: float, track: SampledTrack, model: Model | None = None,
    dt: float | None = None, output_dt: float = 2e-3, f0_hz: float | None = None,
) -> tuple[SimulationResult, Assessment]:  # fmt: skip
    """Run over the whole irregular section and assess the criterion.

    The run lasts until the last wheelset leaves the section; output every ``output_dt``
    seconds (2 ms: 250 Hz, far above the pass band).
    """
    model = model or Model(vehicle)
    speed = kmh_to_ms(speed_kmh)
    check_track_length(track, model)
    duration = (track.end() + model.wheelset_offsets()[-1]) / speed
    res = simulate(
        vehicle, speed_kmh, duration=duration, excitation=track, dt=dt,
        output_dt=output_dt, model=model,
    )  # fmt: skip
    return res, assess(res, vehicle, f0_hz=f0_hz)


@dataclass(repr=False)
class StochasticCriticalSpeedResult(ResultDisplay):
    """Outcome of :func:`stochastic_critical_speed`.

    Attributes
    ----------
    speed_kmh : float
        Stochastic critical speed: the lowest speed (km/h) at which the criterion is
        exceeded, within ``tol_kmh``; NaN when the search did not bracket a change.
    highest_stable_kmh : float
        Highest speed below it at which the criterion is met (km/h).
    trials : list of Assessment
        Every speed tried, in order.
    bracketed : bool
        True when a stable and an unstable speed were found.
    irregularity : SampledTrack
        The track run over at every speed.
    """

    speed_kmh: float
    highest_stable_kmh: float
    trials: list[Assessment] = field(default_factory=list)
    bracketed: bool = True
    irregularity: SampledTrack | None = None

    @property
    def limits(self) -> list:
        """Every limit of the validity envelope a run reached
        (:class:`railhunt.validity.Limit`, its place naming the run's speed)."""
        from dataclasses import replace

        return [replace(lim, place=f"{lim.place}, {a.speed_kmh:g} km/h")
                for a in self.trials for lim in a.limits]  # fmt: skip

    @property
    def limit_summary(self) -> list:
        """One summary per kind of limit the runs reached (the largest value, where, at
        which speeds; :class:`railhunt.validity.LimitSummary`); they change no verdict."""
        from railhunt.validity import summarize_limits

        return summarize_limits(((a.speed_kmh, lim) for a in self.trials for lim in a.limits),
                                decided=False)  # fmt: skip

    @property
    def details(self) -> list[str]:
        """Every limit every run reached, one line each (what :attr:`warnings` summarises)."""
        return [w for a in self.trials for w in a.warnings]

    @property
    def warnings(self) -> list[str]:
        """What the answer must be read with: one line per kind of limit the runs reached
        (:attr:`limit_summary`); :attr:`details` has them run by run."""
        return [s.text for s in self.limit_summary]

    def _summary(self) -> list[Row]:
        track = getattr(self.irregularity, "spectrum", None)
        return [("stochastic critical speed", self.speed_kmh, "km/h"),
                ("highest speed meeting the criterion", self.highest_stable_kmh, "km/h"),
                ("bracketed", self.bracketed, ""), ("trials", len(self.trials), ""),
                ("track", track if track is not None else "-", "")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row per trial speed, in the order tried."""
        t = self.trials
        return {"speed_kmh": ([a.speed_kmh for a in t], "km/h"),
                "verdict": ([a.verdict for a in t], ""), "f0_hz": ([a.f0_hz for a in t], "Hz"),
                "sum_y_ratio": ([a.sum_y_ratio for a in t], "1"),
                "acceleration_ratio": ([a.acceleration_ratio for a in t], "1"),
                "status": ([a.status for a in t], "")}  # fmt: skip


def stochastic_critical_speed(
    vehicle: Vehicle,
    irregularity: SampledTrack | None = None,
    start_kmh: float = 300.0,
    step_kmh: float = 10.0,
    tol_kmh: float = 1.0,
    min_kmh: float = 20.0,
    max_kmh: float = 800.0,
    dt: float | None = None,
    creep_law: str | None = None,
    f0_hz: float | None = None,
    progress: Callable[[Assessment], None] | None = None,
) -> StochasticCriticalSpeedResult:
    """Lowest speed at which the acceptance-test instability criterion is exceeded.

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    irregularity : SampledTrack, optional
        Track run over at every trial speed (the same track each time). Default:
        ``track_irregularity("german-high", length=2000, dx=0.25, seed=1)``.
    start_kmh, step_kmh, tol_kmh : float
        First speed, bracketing step and final resolution (km/h).
    min_kmh, max_kmh : float
        Search limits (km/h).
    dt : float, optional
        RK4 step (s); default :func:`railhunt.simulation.auto_step`.
    creep_law : str
        See :class:`railhunt.model.Model`.
    f0_hz : float, optional
        Fixed instability frequency (Hz); default estimated from each run.
    progress : callable, optional
        Called with each :class:`Assessment` as it finishes.

    Returns
    -------
    StochasticCriticalSpeedResult
    """
    if irregularity is None:
        irregularity = track_irregularity("german-high", length=2000.0, dx=0.25, seed=1)
    if not isinstance(irregularity, SampledTrack):
        from railhunt.arguments import ArgumentTypeError

        raise ArgumentTypeError(
            f"irregularity = {irregularity!r:.60} is a {type(irregularity).__name__}, not a "
            "SampledTrack: give railhunt.track_irregularity(...) (a published spectrum) or "
            "railhunt.load_irregularity(PATH) (a measured track)"
        )
    check_search(start_kmh, step_kmh, tol_kmh, min_kmh, max_kmh)
    if f0_hz is not None and not (math.isfinite(f0_hz) and 0.5 <= f0_hz <= 50.0):
        raise ValueError(f"f0_hz = {f0_hz!r} Hz is invalid: must be finite and in [0.5, 50] Hz")
    model = Model(vehicle, creep_law=creep_law)
    check_track_length(irregularity, model)
    trials: list[Assessment] = []

    def unstable(speed_kmh: float) -> bool:
        _, a = run_on_track(vehicle, speed_kmh, irregularity, model=model, dt=dt, f0_hz=f0_hz)
        trials.append(a)
        if progress is not None:
            progress(a)
        return a.unstable

    lo, hi, bracketed = bracket_and_bisect(unstable, start_kmh, step_kmh, tol_kmh, min_kmh,
                                           max_kmh)  # fmt: skip
    if not bracketed:
        return StochasticCriticalSpeedResult(math.nan, lo, trials, False, irregularity)
    return StochasticCriticalSpeedResult(hi, lo, trials, True, irregularity)


__all__ = [
    "Assessment",
    "StochasticCriticalSpeedResult",
    "TrackIrregularity",
    "acceleration_limit",
    "assess",
    "assess_stability",
    "band_pass",
    "dominant_frequency",
    "sliding_rms",
    "stochastic_critical_speed",
    "sum_y_limit",
]
