"""Recompute the paper's results figures (Figs. 6, 7, 8, 10–13) and compare its numbers.

:func:`reproduce` runs one independent step per figure for the default vehicle
(``paper2019``), writes each figure as ``DIR/figN.png``, a machine-readable
``DIR/headline.json`` and a self-contained ``DIR/report.html``
(:mod:`railhunt.studies.report`), and returns a :class:`Report`. Every step returns its
figure files, its rows of the headline table (the paper's number beside railhunt's, with
the difference) and its run time; a step that raises is recorded as failed and the others
still run.

Where railhunt differs from the paper the table says so; the reasons are documented in
``docs/bifurcation.md`` and ``docs/model.md`` and summarised in ``docs/reproduce.md``.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import time
import traceback
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from railhunt.vehicle import Vehicle

__all__ = ["Headline", "Report", "Settings", "Step", "reproduce", "sweep_headline"]

#: Blow-off force (N) that stands for "no blow-off" (a linear yaw damper).
NO_BLOWOFF = 1e12
#: Yaw damper parameters (the paper's Fig. 10) and the others of Fig. 11, in figure order.
FIG10_LINES = ("C_d1", "C_d2", "K_d")
FIG11_LINES = ("mu", "f11", "K_px", "C_sy")
_BIFURCATION_DOC = "docs/bifurcation.md, section 'The default vehicle (measured)'"


# --------------------------------------------------------------------------- records


@dataclass
class Headline:
    """One row of the headline table: a number (or a claim) of the paper beside railhunt's.

    Attributes
    ----------
    key : str
        Machine name, e.g. ``"nonlinear_critical_speed_kmh"`` (the key in headline.json).
    quantity : str
        What is compared.
    where : str
        Where the paper states it (section, figure).
    unit : str
        Unit of both values ("" for a type or a claim).
    paper : float or str
        The paper's value (a number in ``unit``, or text for a type or a claim).
    railhunt : float or str or None
        railhunt's value (None when the step was not available).
    difference : str
        ``railhunt - paper`` with the relative difference, or whether a claim holds.
    agrees : bool or None
        True when within the row's tolerance (or the claim holds), None when not computed.
    quote : str
        The paper's sentence the number is taken from.
    note : str
        Why railhunt differs, with the document that explains it ("" when it agrees).
    """

    key: str
    quantity: str
    where: str
    unit: str
    paper: float | str
    railhunt: float | str | None
    difference: str
    agrees: bool | None
    quote: str
    note: str = ""

    @property
    def paper_text(self) -> str:
        """The paper's value as shown in the table."""
        return _show(self.paper)

    @property
    def railhunt_text(self) -> str:
        """railhunt's value as shown in the table ("not available" when not computed)."""
        return "not available" if self.railhunt is None else _show(self.railhunt)


@dataclass
class Step:
    """One figure (or group of figures) of the reproduction.

    Attributes
    ----------
    name : str
        Short name (``"fig6"``, ``"fig7"``, ``"fig8"``, ``"fig10-12"``, ``"fig13"``).
    title : str
        Heading in the report.
    paper_caption : str
        The paper's caption of the figure(s).
    shows : str
        What railhunt's figure shows, with its main numbers.
    how : str
        How railhunt computed it (functions and settings).
    figures : list of pathlib.Path
        PNG files written.
    headline : list of Headline
        This step's rows of the headline table.
    seconds : float
        Run time of the step (s).
    status : str
        ``"ok"``, ``"not available"`` (a part railhunt does not have yet) or ``"failed"``.
    message : str
        Why the step is not available or failed ("" when ok).
    """

    name: str
    title: str
    paper_caption: str
    shows: str = ""
    how: str = ""
    figures: list[Path] = field(default_factory=list)
    headline: list[Headline] = field(default_factory=list)
    seconds: float = 0.0
    status: str = "ok"
    message: str = ""


@dataclass
class Report:
    """Outcome of :func:`reproduce`.

    Attributes
    ----------
    out_dir, html, json : pathlib.Path
        Output folder, ``report.html`` and ``headline.json``.
    steps : list of Step
        One per figure, in report order.
    vehicle : str
        Name of the vehicle.
    version : str
        railhunt version.
    date : str
        UTC time the run started (ISO 8601).
    quick : bool
        True for the coarser ``--quick`` run.
    seconds : float
        Total run time (s).
    workers : int
        Number of Dask workers used (0: none, everything in this process).
    """

    out_dir: Path
    html: Path
    json: Path
    steps: list[Step]
    vehicle: str
    version: str
    date: str
    quick: bool
    seconds: float
    workers: int = 0

    @property
    def headline(self) -> list[Headline]:
        """All rows of the headline table, in step order."""
        return [row for step in self.steps for row in step.headline]

    @property
    def failed(self) -> list[Step]:
        """The steps that raised an error."""
        return [s for s in self.steps if s.status == "failed"]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (the content of headline.json)."""
        rows = []
        for row in self.headline:
            d = asdict(row)
            d["railhunt"] = _json_number(row.railhunt)
            d["paper"] = _json_number(row.paper)
            rows.append(d)
        return {
            "railhunt_version": self.version,
            "vehicle": self.vehicle,
            "date": self.date,
            "quick": self.quick,
            "seconds": round(self.seconds, 2),
            "workers": self.workers,
            "values": {r["key"]: r["railhunt"] for r in rows},
            "headline": rows,
            "steps": [{"name": s.name, "title": s.title, "status": s.status,
                       "message": s.message, "seconds": round(s.seconds, 2),
                       "figures": [p.name for p in s.figures]} for s in self.steps],
        }  # fmt: skip


@dataclass(frozen=True)
class Settings:
    """Resolution of the reproduction (the full run; :meth:`quick` for the coarse one).

    Attributes
    ----------
    fig6_duration : float
        Simulated time of the two Fig. 6 runs (s).
    diagram_range_kmh : (float, float)
        Speed range of the bifurcation diagrams (km/h).
    frequency_speeds_kmh : (float, float, float)
        First, last speed and step of the Fig. 7b frequency scan (km/h).
    jump_tol_kmh : float
        Resolution to which the frequency jump is bisected (km/h).
    initial_amplitude : float
        Initial lateral displacement of every wheelset for the frequency (m); the paper's 3 mm.
    family_kn : tuple of float
        Blow-off forces of the Fig. 13 family (kN; ``inf`` for no blow-off).
    sweep_points_per_section : int
        Points per Table 1 section of the Figs. 10–12 sweep, both ends included (each
        parameter line has ``3 * (n - 1) + 1`` points).
    """

    fig6_duration: float = 20.0
    diagram_range_kmh: tuple[float, float] = (200.0, 500.0)
    frequency_speeds_kmh: tuple[float, float, float] = (250.0, 450.0, 5.0)
    jump_tol_kmh: float = 1.0
    initial_amplitude: float = 3e-3
    family_kn: tuple[float, ...] = (1.0, 2.0, 3.0, 5.0, 8.0, math.inf)
    sweep_points_per_section: int = 6

    @classmethod
    def quick(cls) -> Settings:
        """Coarser settings for a run of under a minute (fewer speeds, a smaller family)."""
        return cls(frequency_speeds_kmh=(300.0, 450.0, 10.0), jump_tol_kmh=2.5,
                   family_kn=(1.0, 3.0, math.inf), sweep_points_per_section=2)  # fmt: skip


@dataclass
class _Context:
    vehicle: Vehicle
    out_dir: Path
    settings: Settings
    client: Any = None
    shared: dict[str, Any] = field(default_factory=dict)


# --------------------------------------------------------------------------- comparisons


def _show(value: float | str | None, fmt: str = ".4g") -> str:
    if value is None:
        return "n/a"
    if isinstance(value, str):
        return value
    if not math.isfinite(value):
        return "none"
    return format(value, fmt)


def _json_number(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _compare(key: str, quantity: str, where: str, unit: str, paper: float, value: float,
             quote: str, note: str = "", rel_tol: float = 0.03,
             digits: int = 1) -> Headline:  # fmt: skip
    """A numeric row: agrees when ``|value - paper| <= rel_tol * |paper|``."""
    value = float(value)
    if not math.isfinite(value):
        return Headline(key, quantity, where, unit, paper, value, "railhunt has none", False,
                        quote, note)  # fmt: skip
    value = round(value, digits + 2)
    diff = value - paper
    rel = f" ({diff / paper * 100:+.1f} %)" if paper else ""
    unit_text = f" {unit}" if unit else ""
    agrees = bool(abs(diff) <= rel_tol * abs(paper))
    return Headline(key, quantity, where, unit, paper, value,
                    f"{diff:+.{digits}f}{unit_text}{rel}", agrees, quote,
                    "" if agrees else note)  # fmt: skip


def _claim(key: str, quantity: str, where: str, unit: str, paper: str, value: float | str,
           holds: bool, quote: str, note: str = "") -> Headline:  # fmt: skip
    """A row for a statement of the paper (an inequality, a type, a sequence)."""
    holds = bool(holds)
    if not isinstance(value, str):
        value = round(float(value), 3)
    return Headline(key, quantity, where, unit, paper, value,
                    "holds" if holds else "does not hold", holds, quote,
                    "" if holds else note)  # fmt: skip


def _period(t: np.ndarray, y: np.ndarray) -> float:
    """Mean spacing of the positive maxima of ``y`` larger than 10 % of its largest (s)."""
    t, y = np.asarray(t), np.asarray(y)
    if y.size < 3:
        return math.nan
    inner = (y[1:-1] >= y[:-2]) & (y[1:-1] > y[2:]) & (y[1:-1] > 0.1 * np.max(np.abs(y)))
    peaks = t[1:-1][inner]
    return float(np.mean(np.diff(peaks))) if peaks.size >= 2 else math.nan


# --------------------------------------------------------------------------- Fig. 6

_Q_VCR = ("Therefore, it can be concluded that the critical hunting speed of this vehicle is "
          "321 km/h.")  # fmt: skip
_Q_322 = ("When the vehicle speed reaches 322 km/h, the lateral displacements of the vehicle "
          "components diverge to a stable limit cycle and a sustained lateral hunting motion "
          "occurs.")  # fmt: skip
_NOTE_VCR = ("railhunt's bisection with the 8 mm defect finds the fold of the Hopf branch "
             "(302.0 km/h); the paper does not print its rolling-radius polynomial and the fold "
             "is set mainly by the yaw damper's blow-off: see docs/model.md and "
             f"{_BIFURCATION_DOC}.")  # fmt: skip


def _fig6(ctx: _Context) -> Step:
    from railhunt.analysis.critical import HUNTING, critical_speed
    from railhunt.plots import plot_time_histories
    from railhunt.simulation import simulate
    from railhunt.track import SingleDefect

    step = Step("fig6", "Fig. 6: time history and phase plane at V_cr and V_cr + 1 km/h",
                "Calculated wheelset lateral movements. (a) Time history at 321 km/h. (b) Shift "
                "velocity versus displacement at 321 km/h. (c) Time history at 322 km/h. (d) "
                "Shift velocity versus displacement at 322 km/h.")  # fmt: skip
    defect = SingleDefect()
    result = critical_speed(ctx.vehicle, defect)
    v_cr = result.speed_kmh
    ctx.shared["critical_speed"] = result
    runs = [simulate(ctx.vehicle, v, ctx.settings.fig6_duration, excitation=defect)
            for v in (v_cr, v_cr + 1.0)]  # fmt: skip
    step.figures.append(plot_time_histories(runs, ctx.out_dir / "fig6.png"))
    first_hunting = result.first_hunting_kmh
    tail = [float(np.max(np.abs(r["y_w1"][r.t >= r.t[-1] - 2.0]))) * 1e3 for r in runs]
    verdict = {t.speed_kmh: t.verdict for t in result.trials}
    step.shows = (f"railhunt's highest stable speed is {v_cr:g} km/h: the leading wheelset "
                  f"returns to the centre ({tail[0]:.3g} mm in the last 2 s); at "
                  f"{v_cr + 1:g} km/h it is judged {verdict.get(v_cr + 1, '?')} and ends on a "
                  f"limit cycle of {tail[1]:.2f} mm (y_w1; on this small cycle mainly the rear "
                  "bogie hunts, see docs/bifurcation.md).")  # fmt: skip
    step.how = (f"railhunt.critical_speed (the paper's dichotomy from 300 km/h in 10 km/h "
                f"steps to 1 km/h, {len(result.trials)} runs, single 8 mm x 20 m lateral bump), "
                f"then railhunt.simulate for {ctx.settings.fig6_duration:g} s at V_cr and "
                "V_cr + 1 km/h; phase plane from t = 3 s (plots.plot_time_histories).")
    step.headline = [
        _compare("nonlinear_critical_speed_kmh", "nonlinear critical speed (bisection)",
                 "Sec. 4, Fig. 6", "km/h", 321.0, v_cr, _Q_VCR, _NOTE_VCR, digits=0),
        _compare("first_hunting_speed_kmh", "lowest speed judged hunting", "Sec. 4, Fig. 6",
                 "km/h", 322.0, first_hunting, _Q_322, _NOTE_VCR, digits=0),
    ]  # fmt: skip
    if verdict.get(v_cr + 1.0) != HUNTING:
        step.message = f"{v_cr + 1:g} km/h was not among the trials judged hunting"
    return step


# --------------------------------------------------------------------------- Fig. 7

_Q_7A = ("It is a typical supercritical Hopf bifurcation of type (a), and the linear critical "
         "speed is 440 km/h while the nonlinear critical speed is 321 km/h.")  # fmt: skip
_Q_P = ("Point P is on the unstable limit cycle with an amplitude of 3 mm, and the "
        "corresponding speed is 375 km/h.")  # fmt: skip
_Q_JUMP = ("However, there is a jump from point Q_1 to point Q_2 at 375 km/h which just "
           "corresponds to point P in Figure 7(a).")  # fmt: skip
_NOTE_TYPE = ("With the heuristic creep saturation every branch starts toward lower speed; the "
              "Hopf branch falls 139 km/h to its fold at 302.0 km/h, so by the tolerance rule "
              f"(2 km/h or 1 %) it is subcritical: see {_BIFURCATION_DOC}.")  # fmt: skip
_NOTE_FOLD = ("railhunt's lowest limit cycle is the fold of a large branch (both bogies "
              "hunting) that no single defect reaches; the ramp of type (a) finds it too "
              f"(292.0 km/h): see {_BIFURCATION_DOC}.")  # fmt: skip
_NOTE_P = ("railhunt's unstable branches lie below 1.4 mm or above 4.3 mm of y_w1, so no "
           "unstable cycle has 3 mm; the 3 mm release still jumps (Fig. 7b): see "
           f"{_BIFURCATION_DOC}.")  # fmt: skip
_NOTE_JUMP = ("railhunt's 3 mm release reaches the large cycle at a lower speed, from a lower "
              "eigenvalue frequency: the same mechanism (blow-off) on a diagram whose "
              f"unstable branch lies elsewhere (see {_BIFURCATION_DOC}).")  # fmt: skip


def _fig7(ctx: _Context) -> Step:
    from railhunt.analysis.continuation import bifurcation_diagram
    from railhunt.analysis.frequency import frequency_jump, hunting_frequency
    from railhunt.model import Model
    from railhunt.plots import plot_bifurcation, plot_hunting_frequency

    s = ctx.settings
    step = Step("fig7", "Fig. 7: (a) bifurcation diagram, (b) hunting frequency versus speed",
                "Calculation results. (a) Bifurcation diagram. (b) Hunting frequency.")
    # (a) Bifurcation diagram.
    t0 = time.perf_counter()
    diagram = bifurcation_diagram(ctx.vehicle, s.diagram_range_kmh)
    t_diagram = time.perf_counter() - t0
    ctx.shared["diagram"] = diagram
    step.figures.append(plot_bifurcation(diagram, ctx.out_dir / "fig7a.png", s.initial_amplitude))
    p_kmh = diagram.point_p_kmh(s.initial_amplitude)
    # (b) Frequency scan, then the jump bisected.
    model = Model(ctx.vehicle)
    lo, hi, dv = s.frequency_speeds_kmh
    n = int(math.floor((hi - lo) / dv + 1e-9)) + 1
    points = {float(v): hunting_frequency(ctx.vehicle, float(v), s.initial_amplitude,
                                          model=model) for v in lo + dv * np.arange(n)}
    speeds = np.array(sorted(points))
    jump = frequency_jump(speeds, np.array([points[v].frequency_hz for v in speeds]),
                          [points[v].source for v in speeds])  # fmt: skip
    below = above = None
    if jump is not None:
        i = int(np.searchsorted(speeds, jump[0]))
        below, above = points[float(speeds[i - 1])], points[float(speeds[i])]
        while above.speed_kmh - below.speed_kmh > s.jump_tol_kmh:
            mid = 0.5 * (below.speed_kmh + above.speed_kmh)
            r = hunting_frequency(ctx.vehicle, mid, s.initial_amplitude, model=model)
            points[mid] = r
            if r.source == "eigenvalue":
                below = r
            else:
                above = r
        speeds = np.array(sorted(points))
    freqs = np.array([points[v].frequency_hz for v in speeds])
    sources = [points[v].source for v in speeds]
    step.figures.append(plot_hunting_frequency(speeds, freqs, sources, ctx.out_dir / "fig7b.png",
                                               s.initial_amplitude))  # fmt: skip
    ctx.shared["jump"] = (below, above)

    step.shows = (f"(a) Hopf point {diagram.hopf_speed_kmh:.1f} km/h at "
                  f"{diagram.hopf_frequency_hz:.2f} Hz, type {diagram.hopf_type}, lowest limit "
                  f"cycle {diagram.fold_speed_kmh:.1f} km/h, folds at "
                  + ", ".join(f"{f.speed_kmh:.1f}" for f in diagram.folds) + " km/h; point P "
                  f"for {s.initial_amplitude * 1e3:g} mm: "
                  + (f"{p_kmh:.1f} km/h" if math.isfinite(p_kmh) else "none") + ". (b) ")
    if below is not None:
        step.shows += (f"the {s.initial_amplitude * 1e3:g} mm release decays up to "
                       f"{below.speed_kmh:.1f} km/h ({below.frequency_hz:.2f} Hz, eigenvalue) "
                       f"and reaches a limit cycle from {above.speed_kmh:.1f} km/h "
                       f"({above.frequency_hz:.2f} Hz): the jump Q1 → Q2.")
    else:
        step.shows += "no frequency jump in the scanned range."
    step.how = (f"(a) railhunt.bifurcation_diagram {s.diagram_range_kmh[0]:g}–"
                f"{s.diagram_range_kmh[1]:g} km/h (shooting + pseudo-arclength continuation, "
                f"{sum(b.speed_kmh.size for b in diagram.branches)} orbits, {t_diagram:.1f} s). "
                f"(b) railhunt.hunting_frequency from a {s.initial_amplitude * 1e3:g} mm release "
                f"at {lo:g}–{hi:g} km/h every {dv:g} km/h, the jump bisected to "
                f"{s.jump_tol_kmh:g} km/h ({len(points)} releases).")  # fmt: skip
    rows = [
        _compare("linear_critical_speed_kmh", "linear critical speed (Hopf point)",
                 "Sec. 4, Fig. 7a", "km/h", 440.0, diagram.hopf_speed_kmh, _Q_7A),
        _compare("bifurcation_nonlinear_critical_speed_kmh",
                 "nonlinear critical speed (lowest limit cycle)", "Sec. 4, Fig. 7a", "km/h",
                 321.0, diagram.fold_speed_kmh, _Q_7A, _NOTE_FOLD),
        _claim("hopf_type", "type of the Hopf bifurcation", "Sec. 4, Fig. 7a", "",
               "supercritical (a)", diagram.hopf_type, diagram.hopf_type == "supercritical-a",
               _Q_7A, _NOTE_TYPE),
        _compare("point_p_kmh", "point P: 3 mm on the unstable branch", "Sec. 4, Fig. 7a",
                 "km/h", 375.0, p_kmh, _Q_P, _NOTE_P),
    ]  # fmt: skip
    if below is not None:
        v_jump = 0.5 * (below.speed_kmh + above.speed_kmh)
        rows += [
            _compare("frequency_jump_speed_kmh", "speed of the frequency jump (3 mm release)",
                     "Sec. 4, Fig. 7b", "km/h", 375.0, v_jump, _Q_JUMP, _NOTE_JUMP),
            _compare("frequency_q1_hz", "frequency before the jump (Q1)", "Sec. 4, Fig. 7b/8",
                     "Hz", 4.0, below.frequency_hz, _Q_FIG8, _NOTE_JUMP, digits=2),
            _compare("frequency_q2_hz", "frequency after the jump (Q2)", "Sec. 4, Fig. 7b/8",
                     "Hz", 5.3, above.frequency_hz, _Q_FIG8, _NOTE_JUMP, digits=2),
        ]  # fmt: skip
    else:
        rows.append(_claim("frequency_jump_speed_kmh", "speed of the frequency jump",
                           "Sec. 4, Fig. 7b", "km/h", "375", "no jump found", False, _Q_JUMP,
                           "widen the speed range"))  # fmt: skip
    step.headline = rows
    return step


# --------------------------------------------------------------------------- Fig. 8

_Q_FIG8 = ("It can be seen that, when v_d is lower than the blow-off velocity, the cycle of "
           "the wheelset displacement is 0.25 s, namely, a frequency of 4 Hz. When v_d is "
           "greater than the blow-off velocity, the cycle of the wheelset displacement is "
           "0.19 s, namely, a frequency of 5.3 Hz.")  # fmt: skip


def _fig8(ctx: _Context) -> Step:
    from railhunt.plots import plot_damper_histories

    step = Step("fig8", "Fig. 8: wheelset displacement and yaw damper velocity below and above "
                "the jump", "Time histories of (a) wheelset lateral displacement and (b) yaw "
                "damper velocity.")  # fmt: skip
    below, above = ctx.shared.get("jump", (None, None))
    if below is None:
        step.status = "failed"
        step.message = "Fig. 7b found no frequency jump, so there is no speed on either side"
        return step
    window = 3.0
    cases, periods, ratios = [], [], []
    for r, part in ((below, "below"), (above, "above")):
        mask = r.t <= window if part == "below" else r.t >= r.t[-1] - window
        t, y, vd = r.t[mask], r.y[mask], r.damper_velocity[mask]
        front = np.max(np.abs(vd[:, :2]), axis=1)
        measured = np.ones(t.size, dtype=bool)
        if part == "below":  # the decay, once the front dampers stay below v_u
            over = np.flatnonzero(front > r.blowoff_velocity)
            measured = t > (t[over[-1]] if over.size else -1.0)
        period = _period(t[measured], y[measured])
        ratio = float(np.max(front[measured])) / r.blowoff_velocity
        periods.append(period)
        ratios.append(ratio)
        when = f"from t = {t[measured][0]:.2f} s" if part == "below" else "last 3 s"
        cases.append((f"{r.speed_kmh:.1f} km/h, {part} the jump ({r.verdict})\n{when}: period "
                      f"{period:.3f} s, max |v_d| = {ratio:.2f} v_u", t, y, vd,
                      r.blowoff_velocity))  # fmt: skip
    step.figures.append(plot_damper_histories(cases, ctx.out_dir / "fig8.png"))
    step.shows = (f"At {below.speed_kmh:.1f} km/h the 3 mm release blows the dampers off only "
                  "in the first oscillations, then decays with the front dampers below v_u "
                  f"(at most {ratios[0]:.2f} v_u) and a period of {periods[0]:.3f} s; at "
                  f"{above.speed_kmh:.1f} km/h it settles on a limit cycle of "
                  f"period {periods[1]:.3f} s with the front dampers at {ratios[1]:.2f} v_u "
                  "(blown off).")  # fmt: skip
    step.how = (f"The two releases that bracket the jump of Fig. 7b; period = mean spacing of "
                f"the maxima of y_w1 within the first {window:g} s once both front dampers stay "
                f"below v_u (decay), or over the last {window:g} s (limit cycle); "
                "v_u = F_u / C_d1.")  # fmt: skip
    step.headline = [
        _compare("period_below_blowoff_s", "period with v_d below v_u", "Sec. 4, Fig. 8", "s",
                 0.25, periods[0], _Q_FIG8, _NOTE_JUMP, digits=3),
        _compare("period_above_blowoff_s", "period with v_d above v_u", "Sec. 4, Fig. 8", "s",
                 0.19, periods[1], _Q_FIG8, _NOTE_JUMP, digits=3),
    ]  # fmt: skip
    return step


# --------------------------------------------------------------------------- Fig. 13

_Q_13 = ("With the increase in F_u, the type of Hopf bifurcation transforms from subcritical "
         "to supercritical Hopf bifurcation of type (a), and, when F_u tends to infinity, "
         "namely, with a linear damping coefficient, the bifurcation type transforms to "
         "supercritical Hopf bifurcation of type (b).")  # fmt: skip
_Q_13_HOPF = ("Furthermore, F_u does not affect the linear critical speed, which is decided by "
              "C_d1, and increasing F_u can increase V_cr until the system reaches the linear "
              "critical speed.")  # fmt: skip
_NOTE_13 = ("Without blow-off the wheel/rail nonlinearity alone still leaves a fold pair "
            "(456–484 km/h), so the type stays (a); with Kalker's linear creep law it is (b): "
            "see docs/bifurcation.md, section 'Blow-off force and bifurcation type'.")


def _diagram_task(vehicle: Vehicle, speed_range_kmh: tuple[float, float]) -> Any:
    """One family member (a top-level function, so that Dask can ship it to a worker)."""
    from railhunt.analysis.continuation import bifurcation_diagram

    return bifurcation_diagram(vehicle, speed_range_kmh)


def _fig13(ctx: _Context) -> Step:
    from railhunt.plots import plot_bifurcation_family

    s = ctx.settings
    step = Step("fig13", "Fig. 13: bifurcation type versus blow-off force F_u",
                "Variation of bifurcation type with increase in F_u.")
    forces = [NO_BLOWOFF if math.isinf(kn) else kn * 1e3 for kn in s.family_kn]
    known = ctx.shared.get("diagram")
    done: dict[float, Any] = {}
    if known is not None and known.speed_range_kmh == tuple(s.diagram_range_kmh):
        done[ctx.vehicle.F_u] = known  # the Fig. 7a diagram is this member: reuse it
    todo = [f for f in forces if f not in done]
    members = [ctx.vehicle.replace(F_u=f) for f in todo]
    if ctx.client is not None and todo:
        futures = [ctx.client.submit(_diagram_task, m, s.diagram_range_kmh, pure=False)
                   for m in members]  # fmt: skip
        done.update(zip(todo, ctx.client.gather(futures), strict=True))
        where = f"as {len(todo)} Dask tasks"
    else:
        done.update((f, _diagram_task(m, s.diagram_range_kmh))
                    for f, m in zip(todo, members, strict=True))  # fmt: skip
        where = "one after another in this process"
    family = [(f, done[f]) for f in forces]
    step.figures.append(plot_bifurcation_family(family, ctx.out_dir / "fig13.png"))
    types = [d.hopf_type for _, d in family]
    sequence = [t for i, t in enumerate(types) if i == 0 or t != types[i - 1]]
    hopf = np.array([d.hopf_speed_kmh for _, d in family])
    folds = np.array([d.fold_speed_kmh for _, d in family])
    label = [("no blow-off" if f >= NO_BLOWOFF else f"{f * 1e-3:g} kN") for f in forces]
    step.shows = "; ".join(f"F_u = {lab}: {t}, lowest limit cycle {v:.1f} km/h"
                           for lab, t, v in zip(label, types, folds, strict=True))
    step.shows += f". Hopf point {hopf.min():.1f}–{hopf.max():.1f} km/h for every member."
    step.how = (f"railhunt.bifurcation_diagram {s.diagram_range_kmh[0]:g}–"
                f"{s.diagram_range_kmh[1]:g} km/h for each F_u ({len(todo)} computed {where}"
                + (", the 3 kN member reused from Fig. 7a" if len(todo) < len(forces) else "")
                + "); type by classify_hopf (tolerance max(2 km/h, 1 %)).")
    paper_seq = ["subcritical", "supercritical-a", "supercritical-b"]
    rising = bool(np.all(np.diff(folds) >= -0.5))
    step.headline = [
        _claim("fu_type_sequence", "type sequence as F_u grows", "Sec. 4, Fig. 13", "",
               "subcritical → supercritical (a) → supercritical (b)", " → ".join(sequence),
               sequence == paper_seq, _Q_13, _NOTE_13),
        _claim("fu_hopf_spread_kmh", "spread of the Hopf speed over the F_u family",
               "Sec. 4, Fig. 13", "km/h", "independent of F_u",
               float(hopf.max() - hopf.min()), float(hopf.max() - hopf.min()) < 0.5, _Q_13_HOPF),
        _claim("fu_vcr_rises", "lowest limit cycle rises with F_u up to the Hopf point",
               "Sec. 4, Fig. 13", "km/h", "rises to V_lim",
               " → ".join(f"{v:.1f}" for v in folds),
               rising and abs(folds[-1] - hopf[-1]) < 0.01 * hopf[-1], _Q_13_HOPF),
    ]  # fmt: skip
    return step


# --------------------------------------------------------------------------- Figs. 10-12
# The Table 1 study (railhunt.studies.sections.table1_study) run by railhunt.sweep; its
# figures (plots.plot_sweep, plots.plot_sections) and headline rows.

_Q_10A = ("It can be seen that V_cr increases logarithmically with the increase in C_d1 and "
          "finally stabilizes at 330 km/h. The f exhibits a sudden change at the value of 140 "
          "kN·s/m where V_cr reaches 300 km/h.")  # fmt: skip
_Q_10B = ("Similar to C_d1, f also exhibits a sudden change at the value of 15 kN·s/m where "
          "V_cr reaches 300 km/h.")  # fmt: skip
_Q_11C = ("The results show that V_cr increases logarithmically with the increase in K_px and "
          "finally stabilizes at 322 km/h. The f decreases gradually with the increase in K_px "
          "and finally stabilizes at 4.9 Hz.")  # fmt: skip
_Q_12A = ("Within the range of these parameters, ΔV_cr all exceed 100 km/h. The parameters of "
          "K_px and C_sy, by contrast, have less influence on the critical speed, and ΔV_cr "
          "are within 50 km/h.")  # fmt: skip
_Q_12B = ("The parameters of K_px and C_sy, by contrast, have less influence on the hunting "
          "frequency, and Δf are within 0.8 Hz.")  # fmt: skip
_NOTE_SWEEP = ("railhunt's nonlinear critical speed of the default vehicle is 20 km/h below "
               "the paper's (Fig. 6 row), which shifts the levels and jump positions: see "
               "docs/reproduce.md.")  # fmt: skip
_Q_10A_TREND = "It can be seen that V_cr increases logarithmically with the increase in C_d1"
_Q_11A = "The V_cr decreases with the increase in u, as shown in Figure 11(a)."
_Q_11B = ("Figure 11(b) shows the results of f_11 (f_22), and it can be seen that, with the "
          "increasing of f_11 (f_22), V_cr decreases gradually, f increases overall")  # fmt: skip
_Q_11D = ("As for C_sy, the influences on both V_cr and f are coincident with the results of "
          "K_px in the trend")  # fmt: skip
_NOTE_TRENDS = ("railhunt's Hopf speed peaks near K_px = 12 MN/m (the kinematic/bogie trade-"
                "off) and near C_sy = 27 kN·s/m, so much of Table 1's ranges lies on the "
                "falling sides (docs/studies.md, 'The paper's study, measured').")  # fmt: skip
#: Trends of the paper's Figs. 10-11: (key, line, quantity, where, "v" (V_cr) or "f",
#: rises?, quote). Judged on the line's first and last points.
_TRENDS: list[tuple[str, str, str, str, str, bool, str]] = [
    ("fig10a_trend_vcr_cd1", "C_d1", "V_cr as C_d1 grows", "Fig. 10a", "v", True, _Q_10A_TREND),
    ("fig11a_trend_vcr_mu", "mu", "V_cr as mu grows", "Fig. 11a", "v", False, _Q_11A),
    ("fig11b_trend_vcr_f11", "f11", "V_cr as f11 = f22 grows", "Fig. 11b", "v", False, _Q_11B),
    ("fig11b_trend_f_f11", "f11", "f as f11 = f22 grows", "Fig. 11b", "f", True, _Q_11B),
    ("fig11c_trend_vcr_kpx", "K_px", "V_cr as K_px grows", "Fig. 11c", "v", True, _Q_11C),
    ("fig11c_trend_f_kpx", "K_px", "f as K_px grows", "Fig. 11c", "f", False, _Q_11C),
    ("fig11d_trend_vcr_csy", "C_sy", "V_cr as C_sy grows (like K_px)", "Fig. 11d", "v", True,
     _Q_11D),
    ("fig11d_trend_f_csy", "C_sy", "f as C_sy grows (like K_px)", "Fig. 11d", "f", False,
     _Q_11D),
]  # fmt: skip
_SWEEP_ROWS: list[tuple[str, str, str, str, float | str, str]] = [
    ("fig10a_vcr_large_cd1_kmh", "V_cr for large C_d1", "Fig. 10a", "km/h", 330.0, _Q_10A),
    ("fig10a_jump_cd1", "C_d1 of the frequency jump (300 km/h)", "Fig. 10a", "kN·s/m", 140.0,
     _Q_10A),
    ("fig10b_jump_cd2", "C_d2 of the frequency jump (300 km/h)", "Fig. 10b", "kN·s/m", 15.0,
     _Q_10B),
    ("fig11c_vcr_large_kpx_kmh", "V_cr for large K_px", "Fig. 11c", "km/h", 322.0, _Q_11C),
    ("fig11c_f_large_kpx_hz", "f (350 km/h) for large K_px", "Fig. 11c", "Hz", 4.9, _Q_11C),
    *[(f"fig12a_dvcr_{p}_kmh", f"ΔV_cr over Table 1, {p}", "Fig. 12a", "km/h", "> 100", _Q_12A)
      for p in ("mu", "C_d2", "K_d", "f11", "C_d1")],
    *[(f"fig12a_dvcr_{p}_kmh", f"ΔV_cr over Table 1, {p}", "Fig. 12a", "km/h", "< 50", _Q_12A)
      for p in ("K_px", "C_sy")],
    *[(f"fig12b_df_{p}_hz", f"Δf over Table 1 (jump removed), {p}", "Fig. 12b", "Hz", "< 0.8",
       _Q_12B) for p in ("K_px", "C_sy")],
]  # fmt: skip


def sweep_headline(results: Any) -> list[Headline]:
    """Headline rows of Figs. 10–12 from the results of a one-parameter-at-a-time sweep.

    Parameters
    ----------
    results : railhunt.studies.store.SweepResults
        A ``design="lines"`` sweep over the paper's seven parameters (``C_d1``, ``C_d2``,
        ``K_d``, ``mu``, ``f11`` with ``f22`` tied, ``K_px``, ``C_sy``), with the outputs
        ``critical_speed`` and ``hunting_frequency``. Only ``.lines``, ``.line(name)`` and
        ``.column(name)`` are used.

    Returns
    -------
    list of Headline
        Rows for the lines present: V_cr at the largest C_d1 and K_px (km/h), f at the
        largest K_px (Hz), the C_d1 and C_d2 of the frequency jump (kN·s/m: midpoint of the
        first neighbours whose ``frequency_source`` differs), ΔV_cr over each line
        (total variation over the Table 1 sections, km/h), Δf over the K_px and C_sy
        lines with the jumps left out (Hz; both from
        :func:`railhunt.studies.sections.section_changes`), and the paper's trends of
        Figs. 10-11 judged on each line's first and last points.
    """
    from railhunt.studies.sections import load_table1, section_changes, sweep_lines

    table = load_table1()
    lines = sweep_lines(results)
    sections = section_changes(results)
    spec = {row[0]: row for row in _SWEEP_ROWS}
    rows: list[Headline] = []

    def numeric(key: str, value: float, digits: int = 1) -> None:
        _, quantity, where, unit, paper, quote = spec[key]
        rows.append(_compare(key, quantity, where, unit, float(paper), value, quote,
                             _NOTE_SWEEP, rel_tol=0.05, digits=digits))  # fmt: skip

    def jump_at(name: str) -> float:
        """Display value midway between the first neighbours whose frequency source differs."""
        line = lines[name]
        jumps = line.jumps()
        if not jumps:
            return math.nan
        i = jumps[0]
        idx = np.flatnonzero(np.isfinite(line.frequency_hz))
        j = int(idx[np.searchsorted(idx, i) + 1])
        return 0.5 * (line.values[i] + line.values[j]) / table[name].scale

    if "C_d1" in lines:
        numeric("fig10a_vcr_large_cd1_kmh", lines["C_d1"].critical_speed_kmh[-1], 0)
        numeric("fig10a_jump_cd1", jump_at("C_d1"))
    if "C_d2" in lines:
        numeric("fig10b_jump_cd2", jump_at("C_d2"))
    if "K_px" in lines:
        numeric("fig11c_vcr_large_kpx_kmh", lines["K_px"].critical_speed_kmh[-1], 0)
        numeric("fig11c_f_large_kpx_hz", lines["K_px"].frequency_hz[-1], 2)
    for key, name, quantity, where, column, rises, quote in _TRENDS:
        if name not in lines:
            continue
        line = lines[name]
        y = line.critical_speed_kmh if column == "v" else line.frequency_hz
        ok = np.isfinite(y)
        if np.count_nonzero(ok) < 2:
            continue
        first, last = float(y[ok][0]), float(y[ok][-1])
        holds = last > first if rises else last < first
        unit = "km/h" if column == "v" else "Hz"
        rows.append(_claim(key, quantity, where, unit, "rises" if rises else "falls",
                           f"{first:.3g} → {last:.3g}", holds, quote, _NOTE_TRENDS))  # fmt: skip
    for key, quantity, where, unit, paper, quote in _SWEEP_ROWS:
        name = key.split("_", 2)[2].rsplit("_", 1)[0]
        if not key.startswith("fig12") or name not in lines:
            continue
        part = sections[name]
        value = part.speed_change_kmh if key.startswith("fig12a") else part.frequency_change_hz
        bound = float(str(paper)[2:])
        holds = value > bound if str(paper).startswith(">") else value < bound
        rows.append(_claim(key, quantity, where, unit, str(paper), value, holds, quote,
                           _NOTE_SWEEP))  # fmt: skip
    return rows


def _sweep_shows(results: Any) -> str:
    """One sentence per line of the study: V_cr and f at its ends, and where f jumps."""
    from railhunt.studies.sections import load_table1, sweep_lines

    table = load_table1()
    parts = []
    for name, line in sweep_lines(results).items():
        entry = table[name]
        ok = np.isfinite(line.critical_speed_kmh)
        v = line.critical_speed_kmh[ok]
        x = line.values / entry.scale
        text = (f"{entry.label}: V_cr {v[0]:.0f} → {v[-1]:.0f} km/h" if v.size else
                f"{entry.label}: no critical speed")  # fmt: skip
        f = line.frequency_hz[np.isfinite(line.frequency_hz)]
        if f.size:
            text += f", f {f[0]:.2f} → {f[-1]:.2f} Hz at {line.frequency_speed_kmh:g} km/h"
        jumps = line.jumps()
        if jumps:
            i = jumps[0]
            text += f" (jump after {x[i]:.3g} {entry.unit})"
        parts.append(text)
    return "; ".join(parts) + "."


def _fig10_12(ctx: _Context) -> Step:
    step = Step("fig10-12", "Figs. 10–12: parameter lines over Table 1 and their sections",
                "Fig. 10: Change in critical speed and hunting frequency with (a) increase of "
                "C_d1, (b) increase of C_d2, and (c) increase of K_d. Fig. 11: Change in "
                "critical speed and hunting frequency with (a) increase of u, (b) increase of "
                "f_11, (c) increase of K_px, and (d) increase of C_sy. Fig. 12: Comparison of "
                "the influences of different parameters and different sections on (a) critical "
                "speed and (b) hunting frequency.")  # fmt: skip
    from railhunt.plots import plot_sections, plot_sweep
    from railhunt.studies.sections import section_changes, table1_study
    from railhunt.studies.sweep import sweep

    n = ctx.settings.sweep_points_per_section
    params, ties = table1_study(n, FIG10_LINES + FIG11_LINES)
    # Without a client reproduce runs in this one process, and so does the sweep.
    results = sweep(ctx.vehicle, params, ties=ties, out=ctx.out_dir / "sweep.csv",
                    overwrite=True, client=ctx.client,
                    workers=1 if ctx.client is None else None)  # fmt: skip
    step.figures += [plot_sweep(results, ctx.out_dir / "fig10.png", parameters=FIG10_LINES),
                     plot_sweep(results, ctx.out_dir / "fig11.png", parameters=FIG11_LINES),
                     plot_sections(section_changes(results), ctx.out_dir / "fig12.png")]
    step.headline = sweep_headline(results)
    step.shows = _sweep_shows(results)
    step.how = (f"railhunt.sweep over Table 1 ({n} points per section, f22 tied to f11; "
                "frequency after an 8 mm release at 300 km/h for the yaw-damper lines and "
                "350 km/h otherwise), results in sweep.csv; ΔV_cr and Δf (jump removed) by "
                "railhunt.studies.sections.section_changes.")
    return step


# --------------------------------------------------------------------------- driver

STEPS: tuple[Callable[[_Context], Step], ...] = (_fig6, _fig7, _fig8, _fig10_12, _fig13)
_TITLES = {"_fig6": "Fig. 6", "_fig7": "Fig. 7", "_fig8": "Fig. 8", "_fig10_12": "Figs. 10–12",
           "_fig13": "Fig. 13"}  # fmt: skip


def reproduce(
    out_dir: str | Path,
    quick: bool = False,
    client: Any = None,
    progress: Callable[[str, str], None] | None = None,
    vehicle: Vehicle | None = None,
    settings: Settings | None = None,
) -> Report:
    """Recompute the paper's Figs. 6, 7, 8, 10–13 and write a self-contained HTML report.

    Parameters
    ----------
    out_dir : str or pathlib.Path
        Output folder (created if missing): ``report.html``, ``headline.json``, ``figN.png``
        (``fig7a.png``, ``fig7b.png`` for Fig. 7) and, with the sweep, ``sweep.csv``.
    quick : bool
        Coarser settings (:meth:`Settings.quick`): a run of under a minute.
    client : dask.distributed.Client, optional
        Runs the Fig. 13 family members (and the sweep) as Dask tasks; otherwise everything
        runs in this process.
    progress : callable, optional
        Called as ``progress(title, state)`` with ``state`` ``"start"`` when a step starts
        and its status (``"ok"``, ``"not available"``, ``"failed"``) when it ends.
    vehicle : Vehicle, optional
        Default: the paper's vehicle (``Vehicle.paper2019()``). The paper's numbers are of
        that vehicle; for another one the table compares against them all the same.
    settings : Settings, optional
        Overrides ``quick``.

    Returns
    -------
    Report
    """
    import railhunt
    from railhunt.studies.report import write_html

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    settings = settings or (Settings.quick() if quick else Settings())
    vehicle = vehicle or Vehicle.paper2019()
    ctx = _Context(vehicle, out, settings, client)
    started = _dt.datetime.now(_dt.UTC).replace(microsecond=0).isoformat()
    t_start = time.perf_counter()
    steps = []
    for func in STEPS:
        title = _TITLES[func.__name__]
        if progress is not None:
            progress(title, "start")
        t0 = time.perf_counter()
        try:
            step = func(ctx)
        except Exception as exc:  # noqa: BLE001 - one failed figure must not lose the others
            step = Step(func.__name__.lstrip("_").replace("_", "-"), title, "", status="failed",
                        message=f"{type(exc).__name__}: {exc}\n{traceback.format_exc(limit=4)}")
        step.seconds = time.perf_counter() - t0
        steps.append(step)
        if progress is not None:
            progress(title, step.status)
    workers = 0
    if client is not None:
        try:
            workers = len(client.scheduler_info().get("workers", {}))
        except Exception:  # noqa: BLE001 - only for the report's header
            workers = 0
    report = Report(out, out / "report.html", out / "headline.json", steps, vehicle.name,
                    railhunt.__version__, started, settings != Settings(),
                    time.perf_counter() - t_start, workers)  # fmt: skip
    report.json.write_text(json.dumps(report.to_dict(), indent=2, ensure_ascii=False) + "\n",
                           encoding="utf-8")  # fmt: skip
    write_html(report, report.html)
    return report
