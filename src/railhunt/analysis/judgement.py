"""How one run is judged: the envelopes of the bodies' lateral displacements, the verdict
words, the early verdict of decay, and running a speed until its verdict.

Every body that can hunt is watched (:func:`watched_bodies`): every wheelset, the leading
one first, then every bogie frame. Each is judged alone and the worst verdict decides
(hunting before undecided before stable; among equals the first watched): a rear
wheelset that hunts while the leading one runs quietly makes the run hunt, and the
result says which body decided.

The critical-speed search (:func:`railhunt.analysis.critical.critical_speed`), the hunting
frequency (:func:`railhunt.analysis.frequency.hunting_frequency`) and ``railhunt
simulate`` judge runs with these. A run is extended chunk by chunk until its envelope is
clearly decayed or clearly stationary (:class:`Judgement`), so that a slowly decaying or
slowly growing run is not misjudged at the end of a fixed window; between the regular
checks it is looked at for an early verdict of decay (:func:`early_decay`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from railhunt.analysis.linearity import LINEAR_MODEL, is_linear
from railhunt.analysis.modes import least_damped_rate
from railhunt.kernel.integrators import OK, STATUS_NAMES
from railhunt.kernel.layout import LAYOUT, StateLayout
from railhunt.model import Model
from railhunt.simulation import Y_LIMIT, excitation_end_time, integrate_model
from railhunt.track import SampledTrack, SingleDefect
from railhunt.units import kmh_to_ms
from railhunt.verdicts import BLOW_UP, DERAILED, HUNTING, STABLE, UNDECIDED, ending

#: Near the Hopf point the linear motion itself is nearly stationary: when the least
#: damped oscillatory eigenvalue's real part is within ``settle_rate`` of zero, an envelope
#: below this size (m) is not taken for a steady cycle (it must grow or decay first).
LINEAR_RANGE = 1e-3

#: A run counts as decayed only below this share of its excitation's size (and below
#: :attr:`Judgement.decay_amplitude`): a verdict is never taken on a motion that is still
#: as large as what set it off (a 0.01 mm defect is not "decayed" at 0.02 mm).
DECAY_SHARE = 0.1

#: Early verdict of decay (:func:`early_decay`): between two regular checks a run is looked
#: at every ``EARLY_CHECK`` s; it is judged stable as soon as its envelope over the last
#: second is below ``EARLY_DECAY`` (m, and below half the excitation's size) and below
#: ``EARLY_FALL`` times the envelope of the second before, at a speed whose equilibrium is
#: linearly stable: a motion that small and falling that fast is inside the linear range
#: of a stable equilibrium (well below the small unstable cycle, ~1.1 mm for the paper's
#: car near its critical speed, where a run lingers without falling) and dies out.
EARLY_CHECK, EARLY_DECAY, EARLY_FALL = 0.5, 3e-4, 0.5



@dataclass(frozen=True)
class Judgement:
    """How a run is judged (all thresholds in SI units).

    Parameters
    ----------
    decay_amplitude : float
        Envelope below which the motion counts as decayed to equilibrium (m).
    settle_window : float
        Length of the window over which a limit cycle must be stationary (s).
    settle_rate : float
        Largest |d ln(amplitude)/dt| of a stationary envelope (1/s).
    chunk : float
        Simulated time added each time the verdict is still open (s).
    max_duration : float
        Longest simulated time after the excitation (s); a run still open then is judged
        by the sign of its envelope trend and marked undecided.
    """

    decay_amplitude: float = 2e-5
    settle_window: float = 3.0
    settle_rate: float = 0.01
    chunk: float = 3.0
    max_duration: float = 60.0

    def __post_init__(self) -> None:
        for name in ("decay_amplitude", "settle_window", "settle_rate", "chunk", "max_duration"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{name} = {value!r} is invalid: must be finite and > 0")



def envelope_peaks(t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Times and values of the local maxima of ``|y|`` (one per half cycle)."""
    a = np.abs(y)
    if a.size < 3:
        return t[:0], a[:0]
    idx = np.nonzero((a[1:-1] >= a[:-2]) & (a[1:-1] > a[2:]))[0] + 1
    return t[idx], a[idx]


def swing_peaks(t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Times of the extrema of ``y`` and the half swing into each (half peak-to-peak).

    The envelope of an oscillation that is not symmetric about zero (about a curving
    equilibrium the excursions toward the flange and away from it differ): at each local
    extremum, half its distance from the extremum before it.
    """
    if y.size < 3:
        return t[:0], y[:0]
    d = np.diff(y)
    idx = np.nonzero(((d[:-1] > 0) & (d[1:] <= 0)) | ((d[:-1] < 0) & (d[1:] >= 0)))[0] + 1
    if idx.size < 2:
        return t[:0], y[:0]
    return t[idx[1:]], 0.5 * np.abs(np.diff(y[idx]))


def judge(
    t: np.ndarray, y: np.ndarray, t_start: float, judgement: Judgement, final: bool = False,
    two_sided: bool = False, linear_rate: float | None = None,
    equilibrium_rate: float | None = None, linear_model: bool = False,
) -> tuple[str | None, float, float]:  # fmt: skip
    """Verdict on a displacement history after ``t_start``.

    ``y`` is the distance from the equilibrium the motion should decay to. With
    ``two_sided`` the envelope is the half peak-to-peak swing (:func:`swing_peaks`), for
    oscillations that are not symmetric about that equilibrium (in a curve); otherwise the
    peaks of ``|y|`` (:func:`envelope_peaks`).

    ``linear_rate`` is the real part of the least damped oscillatory eigenvalue at the
    run's speed (1/s): when it lies within ``settle_rate`` of zero (near the Hopf point),
    or of the envelope's own rate, an envelope below :data:`LINEAR_RANGE` is the linear
    motion, not a steady cycle, and the run must go on. ``equilibrium_rate`` is the
    largest real part of all the eigenvalues there: when it is negative, a motion still
    decaying below
    :data:`LINEAR_RANGE` at ``final`` dies out (it is inside the linear range of a stable
    equilibrium) and is judged stable. For a ``linear_model``
    (:func:`railhunt.analysis.linearity.is_linear`) every amplitude is in the linear range:
    it has no limit cycle, and a still envelope near its Hopf point is its neutral motion.

    Returns
    -------
    verdict : {"stable", "hunting", "undecided"} or None
        None while the run is still open (and ``final`` is False). At ``final`` a run
        that has not died out is "hunting" when its envelope grows, else "undecided"
        (verdict words: :mod:`railhunt.verdicts`).
    amplitude : float
        Latest envelope value (m).
    growth_rate : float
        Slope of ``ln(envelope)`` over the last ``settle_window`` (1/s); NaN if unknown.
    """
    linear_range = math.inf if linear_model else LINEAR_RANGE
    mask = t >= t_start
    tt, yy = t[mask], y[mask]
    if tt.size < 3:
        return None, math.nan, math.nan
    pt, pa = swing_peaks(tt, yy) if two_sided else envelope_peaks(tt, yy)
    recent = tt >= tt[-1] - min(1.0, judgement.settle_window)
    amplitude = float(np.max(np.abs(yy[recent])))
    if amplitude < judgement.decay_amplitude:
        return STABLE, amplitude, math.nan
    win = pt >= tt[-1] - judgement.settle_window
    rate = math.nan
    if np.count_nonzero(win) >= 4 and tt[-1] - t_start >= judgement.settle_window:
        rate = float(np.polyfit(pt[win], np.log(pa[win]), 1)[0])
        spread = (pa[win].max() - pa[win].min()) / pa[win].mean()
        # Inside the linear range an envelope that changes at the linear motion's own rate
        # (or, near the Hopf point, at almost none) is that motion, not a steady cycle.
        near_hopf = (linear_rate is not None and math.isfinite(linear_rate)
                     and amplitude < linear_range
                     and (abs(linear_rate) < judgement.settle_rate
                          or abs(rate - linear_rate) < judgement.settle_rate))  # fmt: skip
        # Inside the linear range of a stable equilibrium an envelope that still falls,
        # however slowly (two modes beating on a rear wheelset), is the motion dying out.
        falling = (equilibrium_rate is not None and equilibrium_rate < 0
                   and amplitude < linear_range and rate < 0)  # fmt: skip
        if abs(rate) < judgement.settle_rate and spread < 0.05 and not (near_hopf or falling):
            return HUNTING, float(pa[win][-1]), rate
    if final:
        if math.isfinite(rate) and rate > 0:
            return HUNTING, amplitude, rate
        linear_decay = (equilibrium_rate is not None and equilibrium_rate < 0
                        and amplitude < linear_range)  # fmt: skip
        if not math.isfinite(rate):  # no oscillation to fit: the trend of max |y| instead
            rate = _drift_rate(tt, yy, judgement.settle_window)
        if math.isfinite(rate) and rate < 0 and linear_decay:
            return STABLE, amplitude, rate
        return UNDECIDED, amplitude, rate
    return None, amplitude, rate


def _drift_rate(t: np.ndarray, y: np.ndarray, window: float) -> float:
    """Log slope (1/s) of ``max |y|`` between the last second and the second ``window``
    earlier, for a motion that does not oscillate; NaN when the record is too short."""
    now = t >= t[-1] - 1.0
    before = (t >= t[-1] - window - 1.0) & (t < t[-1] - window)
    if not before.any():
        return math.nan
    a_now, a_before = float(np.max(np.abs(y[now]))), float(np.max(np.abs(y[before])))
    if a_now <= 0 or a_before <= 0:
        return math.nan
    return math.log(a_now / a_before) / window


#: Verdicts from worst to best: the worst of the watched bodies' verdicts decides.
_WORST_FIRST = (HUNTING, UNDECIDED, None, STABLE)


def watched_bodies(layout: StateLayout) -> tuple[tuple[str, int], ...]:
    """The bodies a run is judged on, as ``(name, index of its lateral displacement)``:
    every wheelset (the leading one first), then every bogie frame with a lateral
    coordinate, in the layout's order.

    These are the bodies that hunt: the creep forces that feed a hunting motion act on
    the wheelsets, and a frame hunts with its wheelsets. A car body rides on them; its
    slow sway after a defect (0.4 Hz for the paper's car, still 0.1 mm 10 s after the
    defect at 250 km/h, falling) is given to it and dies out without feeding anything, and
    a car body that hunts with the bogies makes their wheelsets hunt.
    """
    wheelsets = [(name, layout.body_dofs(name)[0]) for name in layout.wheelsets]
    frames = [(b.name, layout.body_dofs(b.name)[0]) for b in layout.bodies
              if _is_frame(b) and "y" in b.coordinates]  # fmt: skip
    return tuple(wheelsets + frames)


def _is_frame(body: object) -> bool:
    kind = getattr(body, "kind", "")
    return kind == "frame" or (not kind and body.name.startswith("bogie"))  # type: ignore[attr-defined]


def judge_bodies(
    t: np.ndarray, y: np.ndarray, t_start: float, judgement: Judgement, final: bool = False,
    two_sided: bool = False, linear_rate: float | None = None,
    equilibrium_rate: float | None = None, linear_model: bool = False,
) -> tuple[str | None, float, float, int]:  # fmt: skip
    """:func:`judge` of each column of ``y`` (one per watched body); the worst verdict
    decides (hunting, then undecided, then still open, then stable; among equals the first
    column, or for stable the body with the largest envelope).

    Returns
    -------
    verdict, amplitude, growth_rate
        As :func:`judge` gives them, of the deciding body.
    body : int
        The column of the deciding body.
    """
    results = [judge(t, y[:, k], t_start, judgement, final=final, two_sided=two_sided,
                     linear_rate=linear_rate, equilibrium_rate=equilibrium_rate,
                     linear_model=linear_model) for k in range(y.shape[1])]  # fmt: skip
    for verdict in _WORST_FIRST:
        ks = [k for k, r in enumerate(results) if r[0] == verdict]
        if ks:
            if verdict == STABLE:
                ks = [max(ks, key=lambda k: results[k][1])]
            return (*results[ks[0]], ks[0])
    raise AssertionError("judge gives a verdict word or None")


def early_decay(t: np.ndarray, y: np.ndarray, t_start: float, size: float,
                equilibrium_rate: float | None) -> tuple[float, float] | None:  # fmt: skip
    """The early verdict of decay (see :data:`EARLY_DECAY`) on a record ``y`` after
    ``t_start`` (s) set off by an excitation of ``size`` (m; 0: unknown). ``y`` may hold
    one column per watched body: the verdict needs every one of them decayed.

    Returns
    -------
    (amplitude, growth_rate) or None
        The envelope of the last second (m) and ``ln`` of its ratio to the second
        before's, per second (1/s), of the body that decays last, when the run has clearly
        decayed; None otherwise (the regular checks of :func:`judge` go on).
    """
    if equilibrium_rate is None or not equilibrium_rate < 0 or t[-1] - 2.0 < t_start:
        return None
    now = t >= t[-1] - 1.0
    before = (t >= t[-1] - 2.0) & (t < t[-1] - 1.0)
    if not before.any():
        return None
    # One column per watched body (a 1-D record is one body): every one must have decayed.
    y2 = y.reshape(y.shape[0], -1)
    a_nows = np.max(np.abs(y2[now]), axis=0)
    a_befores = np.max(np.abs(y2[before]), axis=0)
    limit = EARLY_DECAY if size <= 0 else min(EARLY_DECAY, 0.5 * size)
    if np.all(a_nows < limit) and np.all(a_nows < EARLY_FALL * a_befores):
        k = int(np.argmax(a_nows))  # the body that decays last
        a_now, a_before = float(a_nows[k]), float(a_befores[k])
        return a_now, math.log(a_now / a_before) if a_now > 0 else -math.inf
    return None


def _pieces(duration: float, dt: float, output_dt: float) -> list[float]:
    """Durations (s) of the pieces an RK4 chunk of ``duration`` is integrated in, for the
    early checks: about :data:`EARLY_CHECK` s each, a whole number of output intervals, so
    that the pieces' steps and stored samples are the whole chunk's."""
    n_steps = int(round(duration / dt))
    stride = max(1, int(round(output_dt / dt)))
    m = stride * max(1, int(round(EARLY_CHECK / (dt * stride))))
    counts = [m] * (n_steps // m) + ([n_steps % m] if n_steps % m else [])
    return [c * dt for c in counts]


def _tail_pieces(ts: list[np.ndarray], span: float) -> int:
    """How many of the last record pieces ``ts`` (times, s) cover the last ``span`` s."""
    end, n = ts[-1][-1], 0
    while n < len(ts):
        n += 1
        if ts[-n][0] <= end - span:
            break
    return n


@dataclass(frozen=True)
class RunVerdict:
    """The stability verdict on one finished run (:func:`judge_run`), apart from the
    solver's status, which only says how the integration ended.

    Attributes
    ----------
    verdict : {"stable", "hunting", "undecided", "derailed", "blow-up"}
        The verdict words of :mod:`railhunt.verdicts`: ``"stable"``: the motion died out;
        ``"hunting"``: it settles on a limit cycle or keeps growing; ``"derailed"``: it left
        the track; ``"blow-up"``: the integration blew up (numerics); ``"undecided"``: the
        run cannot tell yet (it ended still decaying, or too short).
    amplitude : float
        Latest envelope of the leading wheelset's lateral displacement (m).
    growth_rate : float
        Slope of the envelope's logarithm over the last window (1/s); NaN if unknown.
    text : str
        The verdict in words, e.g. ``"hunting: limit cycle of 9.63 mm"``.
    body : str
        The body whose motion decided the verdict (the worst of the watched bodies:
        :func:`watched_bodies`), e.g. ``"wheelset3"``.
    """

    verdict: str
    amplitude: float
    growth_rate: float
    text: str
    body: str = ""

    @property
    def short(self) -> str:
        """The verdict with the amplitude when hunting, e.g. ``"hunting, 9.63 mm"``."""
        if self.verdict == "hunting" and math.isfinite(self.amplitude):
            return f"hunting, {self.amplitude * 1e3:.3g} mm"
        return self.verdict


def judge_run(result: object, judgement: Judgement | None = None,
              two_sided: bool = False, linear_model: bool = False) -> RunVerdict:  # fmt: skip
    """Judge a finished run of :func:`railhunt.simulate` by every body that can hunt (every
    wheelset, then the bogie frames: :func:`watched_bodies`; the worst decides),
    after the last wheelset has left the excitation, as the critical-speed search judges a
    trial.

    ``two_sided``: judge the swing about the run's last mean position (a run in a curve,
    whose equilibrium is off the track centre) instead of the distance from the centre.
    ``linear_model``: the run is of a linear model
    (:func:`railhunt.analysis.linearity.is_linear`), which has no limit cycle: a still
    envelope is its neutral motion at its Hopf speed ("undecided", in words "neutral").
    """
    judgement = judgement or Judgement()
    layout = getattr(result, "layout", LAYOUT)
    watched = watched_bodies(layout)
    t, x = np.asarray(result.t), np.asarray(result.x)
    y = x[:, [i for _, i in watched]] if x.size else np.zeros((0, len(watched)))
    if result.status != "ok":
        how = ending(result.status, x)
        k = int(np.argmax(np.max(np.abs(y[-50:]), axis=0))) if y.size else 0
        amp = float(np.max(np.abs(y[-50:, k]))) if y.size else math.nan
        body = watched[k][0]
        if how == DERAILED:
            return RunVerdict(DERAILED, amp, math.nan, f"derailed: left the track "
                              f"({result.message})", body)  # fmt: skip
        return RunVerdict(BLOW_UP, amp, math.nan, f"blow-up: the integration blew up, not "
                          f"physics; give a smaller dt ({result.message})", body)  # fmt: skip
    t_exc = float(result.excitation_end)
    if t[-1] <= t_exc:
        return RunVerdict(UNDECIDED, math.nan, math.nan, "undecided: the run ended before "
                          "the last wheelset left the excitation", watched[0][0])  # fmt: skip
    if two_sided:
        y = y - np.median(y[t >= t[-1] - 1.0], axis=0)
    verdict, amp, rate, k = judge_bodies(t, y, t_exc, judgement, two_sided=two_sided)
    body = watched[k][0]
    where = "" if k == 0 else f" ({body})"
    size = f"{amp * 1e3:.3g} mm"
    if verdict == STABLE:
        return RunVerdict(STABLE, amp, rate, f"stable: the motion died out (below "
                          f"{judgement.decay_amplitude * 1e3:g} mm at the end)", body)  # fmt: skip
    if verdict == HUNTING and linear_model:
        return RunVerdict(UNDECIDED, amp, rate, f"neutral: an oscillation of {size}{where} that "
                          f"neither grows nor decays ({rate:+.2g} 1/s): {LINEAR_MODEL}; this "
                          "is (or is within the run's resolution of) that speed", body)  # fmt: skip
    if verdict == HUNTING:
        return RunVerdict(HUNTING, amp, rate, f"hunting: limit cycle of {size}{where}", body)
    if math.isnan(rate):
        return RunVerdict(UNDECIDED, amp, rate, f"undecided: {size}{where} at the end; give a "
                          "longer duration", body)  # fmt: skip
    if rate < 0:
        return RunVerdict(UNDECIDED, amp, rate, f"undecided: {size}{where} at the end, still "
                          f"decaying ({rate:.3g} 1/s); a longer duration decides",
                          body)  # fmt: skip
    return RunVerdict(HUNTING, amp, rate, f"hunting: {size}{where} at the end, growing "
                      f"({rate:+.3g} 1/s)", body)  # fmt: skip


def excitation_size(excitation: object, x0: np.ndarray | None = None,
                    reference: np.ndarray | None = None,
                    layout: StateLayout = LAYOUT) -> float:  # fmt: skip
    """Size of what sets a run off (m): the largest lateral offset of the track input (a
    defect's amplitude, a sampled track's largest alignment) and of the wheelsets' start
    from the equilibrium ``reference`` (default the centred state); 0 for none."""
    size = 0.0
    if isinstance(excitation, SingleDefect):
        size = abs(excitation.amplitude)
    elif isinstance(excitation, SampledTrack) and len(excitation.alignment):
        size = float(np.max(np.abs(excitation.alignment)))
    if x0 is not None:
        ys = layout.wheelset_y
        start = np.asarray(x0, dtype=float)[ys]
        ref = 0.0 if reference is None else np.asarray(reference, dtype=float)[ys]
        size = max(size, float(np.max(np.abs(start - ref))))
    return size


def run_until_verdict(
    model: Model,
    speed_kmh: float,
    judgement: Judgement,
    excitation: object = None,
    x0: np.ndarray | None = None,
    method: str = "rk4",
    dt: float = 1e-3,
    output_dt: float = 2e-3,
    route: np.ndarray | None = None,
    reference: np.ndarray | None = None,
) -> tuple[str, np.ndarray, np.ndarray, int, float, float, bool]:
    """Simulate one speed, chunk by chunk, until the verdict on every watched body is clear.

    :func:`run_verdict` without the deciding body (the same run, the same verdict).

    Returns
    -------
    verdict, t, x, code, amplitude, growth_rate, decided
        As :class:`RunOutcome`.
    """
    out = run_verdict(model, speed_kmh, judgement, excitation, x0, method, dt, output_dt,
                      route, reference)  # fmt: skip
    return out[:7]  # type: ignore[return-value]


class RunOutcome(NamedTuple):
    """A run until its verdict (:func:`run_verdict`).

    Attributes
    ----------
    verdict : {"stable", "hunting", "undecided", "derailed", "blow-up"}
        The verdict words of :mod:`railhunt.verdicts`; a run that stopped early
        (``code != OK``) is "derailed" or "blow-up" (:func:`~railhunt.verdicts.ending`).
    t, x : numpy.ndarray
        The whole record: times (s) and states.
    code : int
        Integrator status (:data:`railhunt.kernel.integrators.STATUS_NAMES`).
    amplitude, growth_rate : float
        Final envelope of the deciding body's lateral displacement (m) and its log slope
        (1/s), as :func:`judge` gives them.
    decided : bool
        False when ``max_duration`` ran out and the envelope's trend decided.
    body : str
        The deciding body (:func:`judge_bodies`), e.g. ``"wheelset1"``.
    """

    verdict: str
    t: np.ndarray
    x: np.ndarray
    code: int
    amplitude: float
    growth_rate: float
    decided: bool
    body: str


def run_verdict(
    model: Model,
    speed_kmh: float,
    judgement: Judgement,
    excitation: object = None,
    x0: np.ndarray | None = None,
    method: str = "rk4",
    dt: float = 1e-3,
    output_dt: float = 2e-3,
    route: np.ndarray | None = None,
    reference: np.ndarray | None = None,
) -> RunOutcome:
    """Simulate one speed, chunk by chunk, until the verdict on every watched body is clear.

    Every body that can hunt is judged (:func:`watched_bodies`: every wheelset, then the
    bogie frames), each by its lateral displacement from the equilibrium;
    the worst verdict decides (:func:`judge_bodies`).

    Parameters
    ----------
    model : Model
        The assembled model.
    speed_kmh : float
        Speed (km/h).
    judgement : Judgement
        Thresholds and chunk lengths.
    excitation : SingleDefect, optional
        Track input; the verdict is taken on the record after the last wheelset has left it.
    x0 : numpy.ndarray, optional
        Initial state (default: the centred equilibrium).
    method : {"rk4", "dopri5"}
        Integrator.
    dt, output_dt : float
        RK4 step and output interval (s).
    route : numpy.ndarray, optional
        Track geometry (a curve's steady route); straight track by default.
    reference : numpy.ndarray, optional
        The equilibrium the motion decays to (the steady-curving state in a curve): each
        body is judged by its distance from ``reference``, and the run starts there unless
        ``x0`` is given. Default: the centred state.

    Returns
    -------
    RunOutcome
    """
    speed = kmh_to_ms(speed_kmh)
    t_exc = excitation_end_time(model, excitation, speed)
    watched = watched_bodies(model.layout)
    cols = np.array([i for _, i in watched], dtype=np.int64)
    y_ref = 0.0 if reference is None else np.asarray(reference, dtype=float)[cols]
    if x0 is None:
        x0 = np.zeros(model.layout.n_state) if reference is None else reference
    size = excitation_size(excitation, x0, reference, model.layout)
    if 0 < DECAY_SHARE * size < judgement.decay_amplitude:
        judgement = replace(judgement, decay_amplitude=DECAY_SHARE * size)
    t0, x_start = 0.0, np.asarray(x0, dtype=float)
    duration = t_exc + judgement.chunk
    linear_rate, equilibrium_rate = least_damped_rate(model, speed,
                                                      None if reference is None else x0,
                                                      route)  # fmt: skip
    linear = is_linear(model)
    ts: list[np.ndarray] = []
    xs: list[np.ndarray] = []
    ys: list[np.ndarray] = []  # the watched bodies from the reference, piece by piece
    first = True
    while True:
        # After the first chunk (the excitation), an RK4 chunk is integrated in pieces,
        # each looked at for an early verdict of decay; the regular check at the chunk's
        # end is as before (the pieces give the chunk's steps and samples).
        pieces = ([duration] if first or method != "rk4"
                  else _pieces(duration, dt, output_dt))  # fmt: skip
        first = False
        for k, span in enumerate(pieces):
            t, x, code, _ = integrate_model(
                model, speed, span, x_start, t0=t0, excitation=excitation, method=method,
                dt=dt, output_dt=output_dt, y_limit=Y_LIMIT, route=route,
            )  # fmt: skip
            if not ts or t.size > 1:  # a piece shorter than the output step stores nothing
                ts.append(t if not ts else t[1:])
                xs.append(x if not xs else x[1:])
                ys.append(xs[-1][:, cols] - y_ref)
            t0, x_start = float(t[-1]), x[-1].copy()
            if code != OK or k == len(pieces) - 1:
                break
            if np.max(np.abs(ys[-1])) >= EARLY_DECAY:
                continue  # still too large for an early verdict (it reads the last second)
            n = _tail_pieces(ts, 2.0)  # the early verdict reads the last 2 s
            early = early_decay(np.concatenate(ts[-n:]), np.concatenate(ys[-n:]), t_exc,
                                size, equilibrium_rate)  # fmt: skip
            if early is not None:
                return RunOutcome(STABLE, np.concatenate(ts), np.concatenate(xs), code, *early,
                                  True, _last_to_decay(ys, watched))  # fmt: skip
        tt, y = np.concatenate(ts), np.concatenate(ys)
        if code != OK:
            xx = np.concatenate(xs)
            how = ending(STATUS_NAMES[code], xx)
            tail = np.max(np.abs(y[-50:]), axis=0)
            kk = int(np.argmax(tail))
            return RunOutcome(how, tt, xx, code, float(tail[kk]), math.nan, True,
                              watched[kk][0])  # fmt: skip
        final = tt[-1] - t_exc >= judgement.max_duration - 1e-9
        verdict, amp, rate, kk = judge_bodies(tt, y, t_exc, judgement, final=final,
                                              two_sided=reference is not None,
                                              linear_rate=linear_rate,
                                              equilibrium_rate=equilibrium_rate,
                                              linear_model=linear)  # fmt: skip
        if verdict is not None:
            return RunOutcome(verdict, tt, np.concatenate(xs), code, amp, rate, not final,
                              watched[kk][0])  # fmt: skip
        early = early_decay(tt, y, t_exc, size, equilibrium_rate)
        if early is not None:
            return RunOutcome(STABLE, tt, np.concatenate(xs), code, early[0], early[1], True,
                              _last_to_decay(ys, watched))  # fmt: skip
        duration = judgement.chunk


def _last_to_decay(ys: list[np.ndarray], watched: tuple[tuple[str, int], ...]) -> str:
    """The watched body with the largest motion in the last piece of a record."""
    return watched[int(np.argmax(np.max(np.abs(ys[-1]), axis=0)))][0]
