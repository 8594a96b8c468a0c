"""The verdict words: what railhunt means when it calls a run, a trial or a search one thing.

Each word is defined once, here (:data:`VERDICTS`); the documentation
(docs/critical-speeds.md, "Verdicts") and the ``--help`` of the commands that judge
runs print these definitions (:func:`verdict_help`), and the code uses each word only in
that sense.

This module also tells a numerical blow-up from a derailment (:func:`ending`): a run
that stops early either left the track (a wheelset beyond the derailment limit, physics)
or the integration blew up (the state grew by orders of magnitude within a few steps, or
became non-finite: numerics, a smaller step is needed).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

STABLE = "stable"
HUNTING = "hunting"
STEADY_CYCLE = "steady cycle"
UNDECIDED = "undecided"
DERAILED = "derailed"
BLOW_UP = "blow-up"
DIVERGENCE = "divergence"
LIMIT_REACHED = "limit reached"

#: Every verdict word and its one meaning.
VERDICTS: dict[str, str] = {
    STABLE: "the motion died out: the envelope of the lateral displacement of every "
            "wheelset and bogie frame fell below the decay threshold (0.02 mm, or a tenth "
            "of the excitation when that is smaller); or, about an equilibrium whose "
            "eigenvalues all decay, it fell below 0.3 mm (and half the excitation) while "
            "halving within a second (decided early), or was still decaying below 1 mm "
            "(the linear range) when the longest duration ran out. Nothing else is called "
            "stable.",
    HUNTING: "the motion did not die out and kept oscillating: it settled on a limit "
             "cycle (a steady cycle) or kept growing, without leaving the track. Every "
             "wheelset and bogie frame is judged; the worst decides, and the result names "
             "it.",
    STEADY_CYCLE: "hunting on a limit cycle: the envelope is stationary (within ±0.01 1/s "
                  "over 3 s, peaks within 5 %; a small negative growth is still a cycle), "
                  "outside the range where the linear motion "
                  "itself is that slow (near the Hopf point a small oscillation must grow "
                  "or decay first).",
    UNDECIDED: "the run ended (its longest duration, or a too short run) neither died "
               "out nor settled on a cycle; the reason is given. A search counts it as "
               "not stable and says so.",
    DERAILED: "a wheelset moved beyond the derailment limit (25 mm from the track centre "
              "line), or in a curve climbed its flange: physics, the vehicle left the "
              "track.",
    BLOW_UP: "the numerical integration blew up (the state grew by orders of magnitude "
             "within a few steps, or became non-finite): numerics, not physics; the step "
             "is too large for the model's fastest dynamics.",
    DIVERGENCE: "a real eigenvalue of the linearised model is in the right half plane: "
                "the equilibrium drifts away without oscillating (no Hopf point).",
    LIMIT_REACHED: "a limit of the validity envelope was reached (Y/Q against Nadal, wheel "
                   "unloading, ΣY against Prud'homme, cant deficiency, bump stop, flange "
                   "clearance): the answer stops there and names the limit. A limit that "
                   "stops nothing (a run's peak forces beyond EN 14363 while its verdict is "
                   "about the motion) is reported by its value and 'changes no verdict', "
                   "never with this word.",
}  # fmt: skip

#: A run that stops early blew up when its largest state grew by more than this factor
#: over its last :data:`BLOW_UP_STEPS` stored samples.
BLOW_UP_GROWTH = 100.0
#: Samples over which :data:`BLOW_UP_GROWTH` is measured.
BLOW_UP_STEPS = 10
#: ... or when, over the last :data:`BLOW_UP_WINDOW` samples, the increments of a state
#: change sign at more than this share of them (an oscillation at the step's own scale).
BLOW_UP_WINDOW, BLOW_UP_FLIPS = 30, 0.4


def verdict_help(words: Sequence[str] = tuple(VERDICTS)) -> str:
    """The definitions of ``words`` as one paragraph per word (for ``--help`` epilogs)."""
    return "Verdicts (docs: Critical speeds, Verdicts):\n\n" + "\n\n".join(
        f"{w}: {VERDICTS[w]}" for w in words)


def ending(status: str, x: Any, scale: Any = None) -> str:
    """How a run that ended with solver ``status`` ended, in verdict words.

    Parameters
    ----------
    status : str
        The integrator's status name (``"ok"``, ``"derailed"``, ``"diverged"``,
        ``"step-failed"``).
    x : numpy.ndarray
        The stored states, one row per sample.
    scale : numpy.ndarray, optional
        Indices of the states that measure the motion (default: all).

    Returns
    -------
    str
        ``"ok"`` for a run that reached its end; :data:`BLOW_UP` for a non-finite state,
        a step failure or a derailment reached by growth of more than
        :data:`BLOW_UP_GROWTH` times within the last :data:`BLOW_UP_STEPS` samples or by an
        oscillation at the step's own scale (:data:`BLOW_UP_FLIPS`); :data:`DERAILED`
        otherwise.
    """
    import numpy as np  # here, so that ``--help`` (which prints VERDICTS) loads no numerics

    if status == "ok":
        return "ok"
    if status != "derailed":
        return BLOW_UP
    xx = np.asarray(x, dtype=float)
    if scale is not None:
        xx = xx[:, scale]
    if xx.shape[0] < 2:
        return DERAILED
    size = np.max(np.abs(xx), axis=1)
    if not np.all(np.isfinite(size)):
        return BLOW_UP
    before = size[max(0, size.size - 1 - BLOW_UP_STEPS)]
    if size[-1] > BLOW_UP_GROWTH * max(before, 1e-12):
        return BLOW_UP
    # A step just above the stable one grows slowly, but at the step's own scale: the
    # increments of some state change sign at most samples (motion of railway dynamics,
    # below ~100 Hz, changes direction a few times in hundreds of samples).
    tail = np.diff(xx[-(BLOW_UP_WINDOW + 2):], axis=0)
    flips = np.count_nonzero(np.diff(np.sign(tail), axis=0) != 0, axis=0)
    if tail.shape[0] >= 8 and np.max(flips) > BLOW_UP_FLIPS * (tail.shape[0] - 1):
        return BLOW_UP
    return DERAILED


#: What the trials of one verdict have in common, for :func:`trial_summaries`.
_IN_COMMON = {
    UNDECIDED: "each run neither died out nor settled on a cycle",
    DERAILED: "a wheelset left the track",
    BLOW_UP: "the integration blew up: numerics, not physics; give a smaller dt",
}


def trial_summaries(trials: Sequence[Any]) -> list[str]:
    """One line per verdict among *undecided*, *derailed* and *blow-up* over a search's
    ``trials`` (objects with ``speed_kmh``, ``verdict`` and ``reason``): a single trial
    with its reason, several by their number and speeds. The undecided line says how the
    search counts them."""
    out = []
    for word, common in _IN_COMMON.items():
        hit = sorted((t for t in trials if t.verdict == word), key=lambda t: t.speed_kmh)
        if not hit:
            continue
        if len(hit) == 1:
            reason = getattr(hit[0], "reason", "")
            text = f"{hit[0].speed_kmh:g} km/h: {word}" + (f" ({reason})" if reason else "")
        else:
            text = (f"{word} at {len(hit)} trial speeds, {hit[0].speed_kmh:g}–"
                    f"{hit[-1].speed_kmh:g} km/h ({common})")  # fmt: skip
        if word == UNDECIDED:
            text += (": counted as not stable, the critical speed is the highest speed "
                     "whose motion died out")  # fmt: skip
        out.append(text)
    return out


def trial_reason(verdict: str, amplitude: float, rate: float, decided: bool,
                 duration: float, status: str) -> str:  # fmt: skip
    """Why a trial has its verdict, in words (empty for a decided stable or hunting one)."""
    size = f"{amplitude * 1e3:.3g} mm" if math.isfinite(amplitude) else "unknown size"
    if verdict == UNDECIDED:
        trend = (f"{rate:+.3g} 1/s" if math.isfinite(rate) else "no oscillation to measure")
        return (f"after {duration:.0f} s the motion is {size} and neither died out nor "
                f"settled on a cycle (envelope trend {trend})")  # fmt: skip
    if verdict == DERAILED:
        return f"a wheelset left the track (solver status {status})"
    if verdict == BLOW_UP:
        return (f"the integration blew up (solver status {status}): numerics, not physics; "
                "give a smaller dt")  # fmt: skip
    if verdict == HUNTING and not decided:
        return f"still growing at {rate:+.3g} 1/s after {duration:.0f} s ({size})"
    return ""
