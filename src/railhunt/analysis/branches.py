"""Branches of limit cycles and the bifurcation diagram: results and their reading.

The data a continuation produces (:class:`Branch`, its :class:`Fold` points, the whole
:class:`BifurcationDiagram`), how a branch is built from its orbits (folds located by a
parabola through the turn), and how the type of the Hopf bifurcation is read from the
branch's shape (:func:`classify_hopf`, the paper's Fig. 5). The continuation itself is
:mod:`railhunt.analysis.continuation`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from railhunt.analysis.periodic import PeriodicOrbit
from railhunt.results import Columns, ResultDisplay, Row

HOPF_TYPES = ("subcritical", "supercritical-a", "supercritical-b", "linear")


@dataclass
class Fold:
    """A turning point of the branch in the speed."""

    speed_kmh: float
    amplitude: float  # m
    index: int  # index of the nearest computed point


@dataclass(repr=False)
class Branch(ResultDisplay):
    """One branch of limit cycles, in continuation order.

    Attributes
    ----------
    speed_kmh, amplitude, period, stable : numpy.ndarray
        Speed (km/h), amplitude of the leading wheelset's lateral displacement (m), period
        (s) and stability (bool) of each orbit. A branch born at the Hopf point starts with
        the Hopf point itself (amplitude 0, period from the eigenvalue).
    max_multiplier : numpy.ndarray
        Largest non-trivial Floquet multiplier modulus (NaN at the Hopf point).
    wheelset_amplitudes : numpy.ndarray, shape (n, 4)
        Amplitude of every wheelset (m).
    origin : str
        ``"hopf"`` (born at the Hopf point), ``"simulation"`` (found from a simulated
        large-amplitude cycle and followed both ways) or ``"linear"`` (a linear model's
        neutral oscillations at its Hopf speed: :func:`linear_branch`).
    folds : list of Fold
        Turning points in the speed.
    """

    speed_kmh: np.ndarray
    amplitude: np.ndarray
    period: np.ndarray
    stable: np.ndarray
    max_multiplier: np.ndarray
    wheelset_amplitudes: np.ndarray
    origin: str
    folds: list[Fold]
    orbits: list[PeriodicOrbit] = field(default_factory=list, repr=False)

    @property
    def frequency_hz(self) -> np.ndarray:
        """Orbit frequencies ``1 / period`` (Hz)."""
        return 1.0 / self.period

    def segments(self) -> list[tuple[int, int, bool]]:
        """Runs of equal stability as ``(first, last, stable)`` (inclusive, overlapping by one)."""
        out = []
        start = 0
        st = self.stable
        for i in range(1, st.size + 1):
            if i == st.size or st[i] != st[start]:
                out.append((start, min(i, st.size - 1), bool(st[start])))
                start = i
        return out

    def speeds_at_amplitude(self, amplitude: float, stable: bool | None = False) -> list[float]:
        """Speeds (km/h) where the branch crosses ``amplitude`` (m), linearly interpolated.

        ``stable=False`` keeps crossings between two unstable orbits, ``True`` between two
        stable ones, ``None`` all.
        """
        a, s, st = self.amplitude, self.speed_kmh, self.stable
        out = []
        for i in range(a.size - 1):
            if (a[i] - amplitude) * (a[i + 1] - amplitude) > 0 or a[i] == a[i + 1]:
                continue
            if stable is not None and not (st[i] == stable and st[i + 1] == stable):
                continue
            w = (amplitude - a[i]) / (a[i + 1] - a[i])
            out.append(float(s[i] + w * (s[i + 1] - s[i])))
        return out

    def _summary(self) -> list[Row]:
        return [("origin", self.origin, ""),
                ("orbits", self.speed_kmh.size, ""),
                ("speeds", f"{self.speed_kmh.min():.4g} to {self.speed_kmh.max():.4g}", "km/h"),
                ("largest amplitude", float(self.amplitude.max()), "m"),
                ("stable orbits", int(np.count_nonzero(self.stable)), ""),
                ("folds", ", ".join(f"{f.speed_kmh:.1f}" for f in self.folds) or "-", "km/h")]

    def _columns(self) -> Columns:
        """One row per orbit, in continuation order."""
        return {"speed_kmh": (self.speed_kmh, "km/h"), "amplitude": (self.amplitude, "m"),
                "period": (self.period, "s"), "frequency_hz": (self.frequency_hz, "Hz"),
                "stable": (self.stable, ""), "max_multiplier": (self.max_multiplier, "1")}

    def to_dict(self) -> dict:
        """JSON-ready arrays (km/h, m, s)."""
        return {
            "origin": self.origin,
            "speed_kmh": self.speed_kmh.tolist(),
            "amplitude": self.amplitude.tolist(),
            "period": self.period.tolist(),
            "stable": self.stable.tolist(),
            "max_multiplier": [None if math.isnan(m) else m for m in self.max_multiplier],
            "wheelset_amplitudes": self.wheelset_amplitudes.tolist(),
            "folds": [{"speed_kmh": f.speed_kmh, "amplitude": f.amplitude} for f in self.folds],
        }


@dataclass(repr=False)
class BifurcationDiagram(ResultDisplay):
    """Limit-cycle branches of the vehicle versus speed, with the Hopf point and type.

    Attributes
    ----------
    branches : list of Branch
        ``branches[0]`` is born at the Hopf point; further branches were found from
        simulated large-amplitude cycles that do not lie on an earlier branch.
    hopf_speed_kmh : float
        Linear critical speed (the Hopf point, from the eigenvalues).
    hopf_speed_from_orbits_kmh : float
        The Hopf speed found independently, by extrapolating the three smallest orbits of
        the Hopf branch to zero amplitude (checks the continuation against the eigenvalues).
    hopf_frequency_hz : float
        Frequency of the hunting eigenvalue at the Hopf point (Hz).
    fold_speed_kmh : float
        Lowest speed with a limit cycle on any branch: the nonlinear critical speed. Equal
        to the Hopf speed when no branch reaches below it; NaN when a branch leaves the
        range downward (``fold_below_range``: the lowest cycle lies below the range).
    hopf_type : str
        One of ``"subcritical"``, ``"supercritical-a"``, ``"supercritical-b"`` (module
        docstring), or ``"linear"``: a linear model, whose only periodic orbits are its
        neutral oscillations at the Hopf speed, of any amplitude (no limit cycle, no fold;
        :mod:`railhunt.analysis.linearity`).
    speed_range_kmh : tuple of float
        The range the continuation was confined to.
    complete : bool
        False when a branch stopped early (Newton failure at the smallest step, or the
        point budget ran out).
    message : str
        Why each branch stopped.
    fold_below_range : bool
        True when a branch leaves the speed range downward.
    """

    branches: list[Branch]
    hopf_speed_kmh: float
    hopf_speed_from_orbits_kmh: float
    hopf_frequency_hz: float
    fold_speed_kmh: float
    hopf_type: str
    speed_range_kmh: tuple[float, float]
    complete: bool
    message: str
    fold_below_range: bool = False

    @property
    def warnings(self) -> list[str]:
        """What the diagram may miss, in words: cycles a release settled on that lie on no
        branch, releases that left the track, branches that stopped early."""
        parts = self.message.split("; ") if self.message else []
        return [p for p in parts if p.startswith(("not found", "releases that left"))
                or "Newton failed" in p or "used all its" in p]  # fmt: skip

    @property
    def folds(self) -> list[Fold]:
        """Every fold of every branch."""
        return [f for b in self.branches for f in b.folds]

    def speeds_at_amplitude(self, amplitude: float, stable: bool | None = False) -> list[float]:
        """Crossings of ``amplitude`` (m) on all branches (km/h), sorted."""
        return sorted(v for b in self.branches for v in b.speeds_at_amplitude(amplitude, stable))

    def point_p_kmh(self, amplitude: float = 3e-3) -> float:
        """The paper's point P: lowest speed where ``amplitude`` (m) meets an unstable branch.

        Above it a disturbance of that amplitude of the leading wheelset grows to a large
        limit cycle, below it decays (Fig. 7a). NaN when no unstable branch reaches it.
        """
        speeds = self.speeds_at_amplitude(amplitude, stable=False)
        return speeds[0] if speeds else math.nan

    def _summary(self) -> list[Row]:
        return [("Hopf speed (linear critical speed)", self.hopf_speed_kmh, "km/h"),
                ("Hopf speed from the orbits", self.hopf_speed_from_orbits_kmh, "km/h"),
                ("Hopf frequency", self.hopf_frequency_hz, "Hz"),
                ("lowest limit cycle (fold)", self.fold_speed_kmh, "km/h"),
                ("Hopf type", self.hopf_type, ""),
                ("point P (3 mm)", self.point_p_kmh(3e-3), "km/h"),
                ("branches", len(self.branches), ""),
                ("orbits", sum(b.speed_kmh.size for b in self.branches), ""),
                ("complete", self.complete, "")]  # fmt: skip

    def _columns(self) -> Columns:
        """One row per orbit: ``branch`` (0: born at the Hopf point), its origin, the orbit."""
        cols: Columns = {"branch": ([], ""), "origin": ([], "")}
        for i, b in enumerate(self.branches):
            cols["branch"][0].extend([i] * b.speed_kmh.size)
            cols["origin"][0].extend([b.origin] * b.speed_kmh.size)
            for name, (values, unit) in b._columns().items():
                cols.setdefault(name, ([], unit))[0].extend(np.asarray(values).tolist())
        return cols

    def to_dict(self, point_p_amplitude: float = 3e-3) -> dict:
        """JSON-ready summary (speeds in km/h, amplitudes in m, periods in s)."""
        return {
            "hopf_speed_kmh": self.hopf_speed_kmh,
            "hopf_speed_from_orbits_kmh": self.hopf_speed_from_orbits_kmh,
            "hopf_frequency_hz": self.hopf_frequency_hz,
            "fold_speed_kmh": self.fold_speed_kmh,
            "hopf_type": self.hopf_type,
            "point_p": {"amplitude": point_p_amplitude,
                        "speed_kmh": _none_if_nan(self.point_p_kmh(point_p_amplitude))},
            "folds": [{"speed_kmh": f.speed_kmh, "amplitude": f.amplitude} for f in self.folds],
            "speed_range_kmh": list(self.speed_range_kmh),
            "fold_below_range": self.fold_below_range,
            "complete": self.complete,
            "message": self.message,
            "warnings": self.warnings,
            "branches": [b.to_dict() for b in self.branches],
        }


def _none_if_nan(x: float) -> float | None:
    return None if math.isnan(x) else x


#: A turn of a branch in speed counts as a fold once the branch has moved back this far
#: from it (km/h), or its amplitude has changed by more than FOLD_AMPLITUDE (m): a branch
#: that jitters in speed along a plateau of amplitude (a wheel against its flange) makes
#: no folds of its jitter.
FOLD_RETREAT_KMH = 0.5
FOLD_AMPLITUDE = 5e-5


def _turns(speed: np.ndarray, amplitude: np.ndarray | None = None,
           retreat: float = FOLD_RETREAT_KMH) -> list[int]:  # fmt: skip
    """Indices of the points where the branch turns back in speed, each confirmed by a
    retreat of more than ``retreat`` km/h from it or a change of amplitude of more than
    :data:`FOLD_AMPLITUDE` (on a clean branch: every sign change of the speed step)."""
    amp = np.zeros(speed.size) if amplitude is None else amplitude
    turns: list[int] = []
    direction = 0.0
    extreme = 0
    for k in range(1, speed.size):
        step = speed[k] - speed[extreme]
        if direction == 0.0:
            if step != 0.0:
                direction, extreme = math.copysign(1.0, step), k
            continue
        if step * direction > 0:
            extreme = k
        elif abs(step) > retreat or abs(amp[k] - amp[extreme]) > FOLD_AMPLITUDE:
            if 1 <= extreme <= speed.size - 2:
                turns.append(extreme)
            direction, extreme = -direction, k
    if direction != 0.0 and 1 <= extreme <= speed.size - 2:
        turns.append(extreme)  # the branch ends on its way back: a turn, as it always was
    return turns


def make_branch(orbits: list[PeriodicOrbit], origin: str,
                 hopf: tuple[float, float] | None = None) -> Branch:  # fmt: skip
    """Arrays and folds of a branch; ``hopf = (speed_kmh, period)`` prepends the Hopf point."""
    speed = [o.speed_kmh for o in orbits]
    amp = [o.amplitude for o in orbits]
    period = [o.period for o in orbits]
    stable = [o.stable for o in orbits]
    mmax = [o.max_multiplier for o in orbits]
    wamp = [o.wheelset_amplitudes for o in orbits]
    if hopf is not None:
        speed.insert(0, hopf[0])
        amp.insert(0, 0.0)
        period.insert(0, hopf[1])
        stable.insert(0, stable[0])
        mmax.insert(0, math.nan)
        wamp.insert(0, np.zeros(len(wamp[0]) if wamp else 4))
    speed_a = np.array(speed)
    amp_a = np.array(amp)
    folds = []
    dv = np.diff(speed_a)
    for i in _turns(speed_a, amp_a):
            # Parabola of speed against the distance along the branch in the (speed / 10
            # km/h, amplitude / 1 mm) plane, through the three points around the turn.
            seg = np.hypot(dv[i - 1:i + 1] / 10.0, np.diff(amp_a[i - 1:i + 2]) / 1e-3)
            dist = np.array([-seg[0], 0.0, seg[1]])
            c = np.polyfit(dist, speed_a[i - 1:i + 2], 2)
            s_turn = float(np.clip(-c[1] / (2 * c[0]), dist[0], dist[2])) if c[0] != 0 else 0.0
            v_turn = float(np.polyval(c, s_turn))
            a_turn = float(np.interp(s_turn, dist, amp_a[i - 1:i + 2]))
            folds.append(Fold(v_turn, a_turn, i))
    return Branch(speed_a, amp_a, np.array(period), np.array(stable, dtype=bool),
                  np.array(mmax), np.array(wamp), origin, folds, list(orbits))  # fmt: skip


def classify_hopf(branch: Branch, hopf_kmh: float, tol_kmh: float | None = None) -> str:
    """Type of the Hopf bifurcation from the shape of its branch (the paper's Fig. 5).

    ``"subcritical"`` when the branch falls more than ``tol_kmh`` below the Hopf speed
    before it rises more than ``tol_kmh`` above it; otherwise ``"supercritical-a"`` when it
    later turns back toward lower speeds by more than ``tol_kmh`` (a fold pair: small and
    large cycles coexist), else ``"supercritical-b"``.

    The tolerance (default ``max(2 km/h, 1 % of the Hopf speed)``) is needed because the
    heuristic creep saturation (Eq. 28) reduces the creep forces in proportion to the
    amplitude itself (``alpha = 1 - beta/3 + ...``), so the branch always starts toward
    lower speeds, by ``O(amplitude)``: a dip of a km/h or two at sub-millimetre amplitude
    that no excitation of engineering size can tell from a supercritical start.
    """
    tol = max(2.0, 0.01 * hopf_kmh) if tol_kmh is None else float(tol_kmh)
    speed = branch.speed_kmh
    below = np.flatnonzero(speed < hopf_kmh - tol)
    above = np.flatnonzero(speed > hopf_kmh + tol)
    if below.size and (not above.size or below[0] < above[0]):
        return "subcritical"
    if above.size:
        running_max = np.maximum.accumulate(speed[above[0]:])
        if np.any(running_max - speed[above[0]:] > tol):
            return "supercritical-a"
        return "supercritical-b"
    # The branch never left the tolerance band (cut short): judge by where it ended.
    return "subcritical" if speed[-1] < hopf_kmh else "supercritical-b"


def on_branch(branch: Branch, orbit: PeriodicOrbit, rel: float = 0.02) -> bool:
    """True when ``orbit`` lies on ``branch`` (amplitude and period at its speed within ``rel``)."""
    s, a, p = branch.speed_kmh, branch.amplitude, branch.period
    for i in range(s.size - 1):
        lo_s, hi_s = sorted((s[i], s[i + 1]))
        if not lo_s <= orbit.speed_kmh <= hi_s or hi_s == lo_s:
            continue
        w = (orbit.speed_kmh - s[i]) / (s[i + 1] - s[i])
        ai = a[i] + w * (a[i + 1] - a[i])
        pi = p[i] + w * (p[i + 1] - p[i])
        if abs(ai - orbit.amplitude) <= rel * orbit.amplitude and abs(pi - orbit.period) <= (
            rel * orbit.period
        ):
            return True
    return False


def linear_branch(hopf_kmh: float, period: float, shape: np.ndarray, wheelset_y: np.ndarray,
                  max_amplitude: float, n: int = 16) -> Branch:  # fmt: skip
    """The periodic orbits of a linear model (:mod:`railhunt.analysis.linearity`): at its
    Hopf speed, of every amplitude from 0 to ``max_amplitude`` (m), with the period and
    shape of the crossing eigenvector (``shape``, real, 1 at the measured coordinate;
    ``wheelset_y`` its wheelsets' lateral displacements). A vertical line, no fold; the
    orbits are neutral (multiplier 1: not stable)."""
    amp = np.linspace(0.0, max_amplitude, n)
    ws = np.abs(shape[wheelset_y])
    lead = ws[0] if ws[0] > 0 else 1.0
    return Branch(np.full(n, float(hopf_kmh)), amp, np.full(n, float(period)),
                  np.zeros(n, dtype=bool), np.r_[math.nan, np.ones(n - 1)],
                  np.outer(amp, ws / lead), "linear", [])  # fmt: skip
