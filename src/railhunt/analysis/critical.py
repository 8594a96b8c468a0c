"""Nonlinear critical speed by the paper's dichotomy (excitation type (b)).

Each trial speed is simulated with a single lateral track defect followed by ideal track,
and judged from the envelopes of the lateral displacements of every body that can hunt
after the defect (every wheelset, then the bogie frames; the worst decides, and the
trial says which body that was): *stable* (the motion died out) or not
(*hunting*, *undecided*, *derailed* or *blow-up*; the words are defined in
:mod:`railhunt.verdicts`), as :mod:`railhunt.analysis.judgement` judges a run. The
search starts at 300 km/h, steps by 10 km/h until the verdict changes, then bisects to
1 km/h; the critical speed is the highest stable speed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from railhunt.analysis.curving import EquilibriumPath
from railhunt.analysis.curving_limit import capped_at_curving_limit

# How a run is judged lives in railhunt.analysis.judgement; its names are importable
# from here as before.
from railhunt.analysis.judgement import (  # noqa: F401
    DECAY_SHARE,
    EARLY_CHECK,
    EARLY_DECAY,
    EARLY_FALL,
    LINEAR_RANGE,
    Judgement,
    RunVerdict,
    early_decay,
    envelope_peaks,
    excitation_size,
    judge,
    judge_run,
    run_until_verdict,
    run_verdict,
    swing_peaks,
    watched_bodies,
)
from railhunt.analysis.search import bracket_and_bisect, check_search
from railhunt.curve import Curve
from railhunt.kernel.integrators import STATUS_NAMES
from railhunt.model import Model
from railhunt.results import Columns, ResultDisplay, Row
from railhunt.simulation import auto_step
from railhunt.stepsize import check_step
from railhunt.track import SampledTrack, SingleDefect, check_excitation
from railhunt.units import kmh_to_ms
from railhunt.validity import LimitSummary, record_limits, summarize_limits
from railhunt.vehicle import Vehicle
from railhunt.verdicts import (  # noqa: F401
    BLOW_UP,
    DERAILED,
    HUNTING,
    STABLE,
    UNDECIDED,
    trial_reason,
    trial_summaries,
)


class _Deferred:
    """A data field whose value is a list, or a zero-argument callable that gives the list
    when the field is first read (then kept): what is costly and seldom read is computed
    only for those who read it."""

    def __set_name__(self, owner: type, name: str) -> None:
        self.slot = f"_{name}"

    def __get__(self, obj: object, objtype: type | None = None) -> Any:
        if obj is None:
            return ()  # the dataclass's default: no limits
        value = obj.__dict__[self.slot]
        if callable(value):
            value = obj.__dict__[self.slot] = list(value())
        return value

    def __set__(self, obj: object, value: Any) -> None:
        obj.__dict__[self.slot] = value if callable(value) else list(value)


@dataclass(frozen=True)
class _Replay:
    """A straight-track trial, to run again: :func:`run_until_verdict` is deterministic (the
    same record, bit for bit), so its validity limits (:func:`railhunt.validity.
    record_limits`) are computed from the record run again when first read, and a search
    whose limits nobody reads (a study's point) neither computes nor keeps them."""

    model: Model
    speed_kmh: float
    excitation: object
    judgement: Judgement
    method: str
    dt: float
    output_dt: float

    def __call__(self) -> list:
        _, t, x, *_ = run_until_verdict(self.model, self.speed_kmh, self.judgement,
                                        self.excitation, method=self.method, dt=self.dt,
                                        output_dt=self.output_dt)  # fmt: skip
        return record_limits(self.model, kmh_to_ms(self.speed_kmh), t, x, self.excitation)


@dataclass
class Trial:
    """One simulated speed and its verdict.

    Every body that can hunt is judged; the worst verdict decides and ``body`` names the
    body it came from (the first watched, the leading wheelset, among equals); ``amplitude``
    is that body's envelope. ``limits`` are the validity limits the run reached on straight track
    (:class:`railhunt.validity.Limit`); a search computes them when they are first read,
    from the trial run again (the same record).
    """

    speed_kmh: float
    verdict: str
    amplitude: float  # final envelope of the deciding body's lateral displacement (m)
    growth_rate: float  # d ln(envelope)/dt over the last window (1/s)
    duration: float  # simulated time (s)
    decided: bool  # False when max_duration ran out and the trend decided
    status: str  # integrator status ("ok", "derailed", ...)
    reason: str = ""  # why an undecided, derailed or blow-up trial is so, in words
    limits: list = _Deferred()  # validity limits the run reached (straight track)
    body: str = ""  # the body whose verdict decided (the worst of the watched bodies)


@dataclass(repr=False)
class CriticalSpeedResult(ResultDisplay):
    """Outcome of :func:`critical_speed`.

    Attributes
    ----------
    speed_kmh : float
        Nonlinear critical speed: the highest speed judged stable below the lowest speed
        judged hunting (km/h); NaN when the search did not bracket a change.
    trials : list of Trial
        Every speed tried, in order, with its verdict.
    bracketed : bool
        True when a stable and a hunting speed were found within ``tol_kmh``.
    excitation : object
        The defect run over at each trial.
    curve : Curve or None
        The curve the search ran in (None: straight track).
    """

    speed_kmh: float
    trials: list[Trial] = field(default_factory=list)
    bracketed: bool = True
    excitation: object = None
    curve: Curve | None = None
    limit: object = None  # CurvingLimit of a search in a curve (railhunt.validity)

    @property
    def limit_reached(self) -> bool:
        """True when the search stopped at a limit of the validity envelope."""
        return bool(self.limit is not None and self.limit.reached)

    @property
    def limits(self) -> list:
        """Every limit reached (:class:`railhunt.validity.Limit`): the curving limit's,
        then each trial's, its place naming the trial's speed."""
        return (list(self.limit.limits) if self.limit_reached else []) + [
            replace(lim, place=f"{lim.place}, {t.speed_kmh:g} km/h") for t in self.trials
            for lim in t.limits]  # fmt: skip

    @property
    def deciding_body(self) -> str:
        """The body whose hunting (or undecided, derailed) verdict at the lowest speed not
        stable set the critical speed; empty when no trial was not stable."""
        hunting = [t for t in self.trials if t.verdict != STABLE]
        return min(hunting, key=lambda t: t.speed_kmh).body if hunting else ""

    @property
    def first_hunting_kmh(self) -> float:
        """Lowest speed judged not stable (hunting, undecided, derailed or blow-up; km/h)."""
        hunting = [t.speed_kmh for t in self.trials if t.verdict != STABLE]
        return min(hunting) if hunting else math.nan

    @property
    def undecided(self) -> list[Trial]:
        """The trials whose motion neither died out nor settled (counted as not stable)."""
        return [t for t in self.trials if t.verdict == UNDECIDED]

    @property
    def limit_summary(self) -> list[LimitSummary]:
        """One summary per kind of limit the trials' runs reached (the largest value, where,
        at which speeds; :class:`railhunt.validity.LimitSummary`). On straight track these
        change no verdict: the verdict is about the motion."""
        return summarize_limits(((t.speed_kmh, lim) for t in self.trials
                                 for lim in t.limits), decided=False)  # fmt: skip

    @property
    def details(self) -> list[str]:
        """What :attr:`warnings` summarises, one line each: every undecided, derailed or
        blown-up trial with its reason, and every limit each trial's run reached."""
        out = []
        for t in self.trials:
            if t.verdict in (UNDECIDED, DERAILED, BLOW_UP):
                out.append(f"{t.speed_kmh:g} km/h: {t.verdict}"
                           + (f" ({t.reason})" if t.reason else ""))  # fmt: skip
            out += [f"{t.speed_kmh:g} km/h: {lim.text}" for lim in t.limits]
        return out

    @property
    def warnings(self) -> list[str]:
        """What the answer must be read with, one line per kind: the limit the search
        stopped at, the undecided, derailed and blown-up trials (:func:`railhunt.verdicts.
        trial_summaries`), and each kind of limit the trials reached
        (:attr:`limit_summary`); :attr:`details` has every one."""
        out = [f"limit reached: {self.limit.text}"] if self.limit_reached else []
        out += trial_summaries(self.trials)
        out += [s.text for s in self.limit_summary]
        return out

    def _summary(self) -> list[Row]:
        rows: list[Row] = [("nonlinear critical speed", self.speed_kmh, "km/h"),
                           ("lowest speed hunting", self.first_hunting_kmh, "km/h"),
                           ("deciding body", self.deciding_body, ""),
                           ("bracketed", self.bracketed, ""),
                           ("trials", len(self.trials), "")]  # fmt: skip
        if self.curve is not None:
            rows.append(("curve radius", self.curve.radius, "m"))
        return rows

    def _columns(self) -> Columns:
        """One row per trial speed, in the order tried."""
        t = self.trials
        return {"speed_kmh": ([x.speed_kmh for x in t], "km/h"),
                "verdict": ([x.verdict for x in t], ""),
                "amplitude": ([x.amplitude for x in t], "m"),
                "growth_rate": ([x.growth_rate for x in t], "1/s"),
                "duration": ([x.duration for x in t], "s"),
                "decided": ([x.decided for x in t], ""),
                "status": ([x.status for x in t], ""),
                "body": ([x.body for x in t], "")}  # fmt: skip




def run_trial(
    model: Model,
    speed_kmh: float,
    excitation: object,
    judgement: Judgement,
    method: str = "rk4",
    dt: float = 1e-3,
    output_dt: float = 2e-3,
    route: np.ndarray | None = None,
    reference: np.ndarray | None = None,
) -> Trial:
    """Simulate one speed over ``excitation`` until the verdict is clear (one bisection step).

    ``route`` and ``reference``: a curve's steady route and its equilibrium (see
    :func:`run_until_verdict`).
    """
    verdict, t, x, code, amp, rate, decided, body = run_verdict(
        model, speed_kmh, judgement, excitation, method=method, dt=dt, output_dt=output_dt,
        route=route, reference=reference,
    )  # fmt: skip
    status = STATUS_NAMES[code]
    # The dynamic limits reached on straight track (a curve's search stops at its steady
    # state's); they inform and change no verdict, and are computed when first read.
    limits = (_Replay(model, speed_kmh, excitation, judgement, method, dt, output_dt)
              if route is None else [])  # fmt: skip
    return Trial(speed_kmh, verdict, amp, rate, float(t[-1]), decided, status,
                 trial_reason(verdict, amp, rate, decided, float(t[-1]), status), limits, body)


def critical_speed(
    vehicle: Vehicle,
    excitation: object = None,
    start_kmh: float = 300.0,
    step_kmh: float = 10.0,
    tol_kmh: float = 1.0,
    min_kmh: float = 20.0,
    max_kmh: float = 800.0,
    judgement: Judgement | None = None,
    method: str = "rk4",
    dt: float | None = None,
    creep_law: str | None = None,
    progress: Callable[[Trial], None] | None = None,
    contact: object = None,
    curve: Curve | Callable[[float], Curve] | None = None,
) -> CriticalSpeedResult:
    """Nonlinear critical speed by bisection (the paper's Sec. 4, excitation type (b)).

    Parameters
    ----------
    vehicle : Vehicle
        Vehicle description.
    excitation : SingleDefect, optional
        Track defect run over at every trial speed. Default: a 8 mm, 20 m lateral
        alignment bump, large enough to throw the default vehicle onto its large limit
        cycle wherever one exists (so the result is the fold of the bifurcation diagram).
    start_kmh, step_kmh, tol_kmh : float
        First speed, bracketing step and final resolution (km/h).
    min_kmh, max_kmh : float
        Search limits (km/h).
    judgement : Judgement, optional
        Thresholds for judging a run (see :class:`Judgement`).
    method : {"rk4", "dopri5"}
        Integrator.
    dt : float, optional
        RK4 step (s); default :func:`railhunt.simulation.auto_step` at each speed.
    creep_law : str
        See :class:`railhunt.model.Model`.
    progress : callable, optional
        Called with each :class:`Trial` as it finishes.
    contact : ContactGeometry, optional
        Tabulated contact geometry instead of the polynomials (see :class:`Model`).
    curve : Curve or callable, optional
        Search in the constant part of this curve: each trial starts on the steady-curving
        equilibrium at its speed (:func:`railhunt.curving`), runs over the defect inside
        the curve and is judged by the leading wheelset's distance from that equilibrium.
        A callable gives the curve at each trial speed in m/s (a fixed cant deficiency,
        :func:`railhunt.curve.fixed_deficiency`).

    Returns
    -------
    CriticalSpeedResult
    """
    if excitation is None:
        excitation = SingleDefect()
    check_excitation(excitation, (SingleDefect, SampledTrack))
    if excitation_size(excitation) == 0.0:
        raise ValueError(f"excitation = {excitation!r} has zero size: it excites nothing, so "
                         "every speed would look stable; give a defect of nonzero "
                         "amplitude")  # fmt: skip
    judgement = judgement or Judgement()
    check_search(start_kmh, step_kmh, tol_kmh, min_kmh, max_kmh)
    model = Model(vehicle, creep_law=creep_law, contact=contact)
    trials: list[Trial] = []

    if dt is not None and not (math.isfinite(dt) and 0 < dt <= 0.01):
        raise ValueError(f"dt = {dt!r} s is invalid: must be finite and in (0, 0.01] s")
    if dt is not None and method == "rk4":
        check_step(model, kmh_to_ms(start_kmh), dt)

    path, limit = (None, None) if curve is None else (EquilibriumPath(model, curve), None)
    if path is not None:  # the search stops at the first limit of the steady state
        limit, max_kmh = capped_at_curving_limit(path, curve, min_kmh, max_kmh, step_kmh, tol_kmh)
        if limit.reached:
            start_kmh = min(start_kmh, max_kmh)
            step_kmh = min(step_kmh, max(max_kmh - min_kmh, tol_kmh))

    def verdict(speed_kmh: float) -> str:
        if dt is not None and method == "rk4":
            check_step(model, kmh_to_ms(speed_kmh), dt)
        step = dt if dt is not None else auto_step(model, kmh_to_ms(speed_kmh))
        if path is None:
            trial = run_trial(model, speed_kmh, excitation, judgement, method=method, dt=step)
        else:
            speed = kmh_to_ms(speed_kmh)
            trial = run_trial(model, speed_kmh, excitation, judgement, method=method, dt=step,
                              route=path.route_at(speed), reference=path.state(speed))
        trials.append(trial)
        if progress is not None:
            progress(trial)
        return trial.verdict

    lo, _, bracketed = bracket_and_bisect(lambda kmh: verdict(kmh) != STABLE, start_kmh,
                                          step_kmh, tol_kmh, min_kmh, max_kmh)  # fmt: skip
    return CriticalSpeedResult(lo if bracketed else math.nan, trials, bracketed=bracketed,
                               excitation=excitation, curve=curve, limit=limit)
