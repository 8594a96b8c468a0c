"""Reproduction steps for the paper's Figs. 6-8: critical speed, bifurcation, frequency jump.

- Fig. 6: the nonlinear critical speed by the paper's bisection, and the runs at V_cr and
  V_cr + 1 km/h (time history and phase plane);
- Fig. 7: (a) the bifurcation diagram (Hopf point, its type, the lowest limit cycle,
  point P), (b) the hunting frequency versus speed from a 3 mm release, its jump bisected;
- Fig. 8: the wheelset displacement and yaw damper velocity of the two releases that
  bracket the jump, and their periods.

Each step returns a :class:`~railhunt.studies.records.Step` whose headline rows compare
railhunt's numbers with the paper's (:data:`railhunt.paper2019.EXPECTED`).
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

import railhunt.paper2019 as paper2019
from railhunt.studies.records import Context, Step, claim, compare, compare_within

__all__ = ["fig6", "fig7", "fig8", "peak_period"]


def peak_period(t: np.ndarray, y: np.ndarray) -> float:
    """Mean spacing of the positive maxima of ``y`` larger than 10 % of its largest (s).

    NaN when ``y`` has fewer than two such maxima.
    """
    t, y = np.asarray(t), np.asarray(y)
    if y.size < 3:
        return math.nan
    inner = (y[1:-1] >= y[:-2]) & (y[1:-1] > y[2:]) & (y[1:-1] > 0.1 * np.max(np.abs(y)))
    peaks = t[1:-1][inner]
    return float(np.mean(np.diff(peaks))) if peaks.size >= 2 else math.nan


# --------------------------------------------------------------------------- Fig. 6


def fig6(ctx: Context) -> Step:
    """Fig. 6: the nonlinear critical speed by bisection, runs at V_cr and V_cr + 1 km/h."""
    from railhunt.analysis.critical import HUNTING, critical_speed
    from railhunt.plots import plot_time_histories
    from railhunt.simulation import simulate
    from railhunt.track import SingleDefect

    step = Step("fig6", "Fig. 6: time history and phase plane at V_cr and V_cr + 1 km/h",
                paper2019.CAPTIONS["fig6"])
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
    paper = paper2019.EXPECTED
    step.headline = [compare(paper["nonlinear_critical_speed_kmh"], v_cr),
                     compare(paper["first_hunting_speed_kmh"], first_hunting)]  # fmt: skip
    if verdict.get(v_cr + 1.0) != HUNTING:
        step.message = f"{v_cr + 1:g} km/h was not among the trials judged hunting"
    return step


# --------------------------------------------------------------------------- Fig. 7



def fig7(ctx: Context) -> Step:
    """Fig. 7: (a) the bifurcation diagram, (b) the hunting frequency and its jump."""
    from railhunt.analysis.continuation import bifurcation_diagram
    from railhunt.analysis.frequency import frequency_jump, frequency_kind, hunting_frequency
    from railhunt.model import Model
    from railhunt.plots import plot_bifurcation, plot_hunting_frequency

    s = ctx.settings
    step = Step("fig7", "Fig. 7: (a) bifurcation diagram, (b) hunting frequency versus speed",
                paper2019.CAPTIONS["fig7"])
    # (a) Bifurcation diagram.
    t0 = time.perf_counter()
    diagram = bifurcation_diagram(ctx.vehicle, s.diagram_range_kmh)
    t_diagram = time.perf_counter() - t0
    ctx.shared["diagram"] = diagram
    # The largest wheelset's amplitude: on the Hopf branch mainly the rear bogie hunts, and
    # the leading wheelset's fraction of a millimetre would hide how large that cycle is.
    step.figures.append(plot_bifurcation(diagram, ctx.out_dir / "fig7a.png", s.initial_amplitude,
                                         wheelset="largest"))  # fmt: skip
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
    sources = [frequency_kind(points[v].source) for v in speeds]
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
                f"{sum(b.speed_kmh.size for b in diagram.branches)} orbits, {t_diagram:.1f} s), "
                "drawn with the largest of the four wheelsets' amplitudes (point P on the "
                "leading wheelset's, as in the paper). "
                f"(b) railhunt.hunting_frequency from a {s.initial_amplitude * 1e3:g} mm release "
                f"at {lo:g}–{hi:g} km/h every {dv:g} km/h, the jump bisected to "
                f"{s.jump_tol_kmh:g} km/h ({len(points)} releases).")  # fmt: skip
    paper = paper2019.EXPECTED
    hopf_type = paper["hopf_type"]
    rows = [
        compare(paper["linear_critical_speed_kmh"], diagram.hopf_speed_kmh),
        compare(paper["bifurcation_nonlinear_critical_speed_kmh"], diagram.fold_speed_kmh),
        claim(hopf_type, diagram.hopf_type, diagram.hopf_type in hopf_type.hopf_types),
        compare(paper["point_p_kmh"], p_kmh),
    ]
    jump_row = paper["frequency_jump_speed_kmh"]
    if below is not None:
        v_jump = 0.5 * (below.speed_kmh + above.speed_kmh)
        judged = (compare(jump_row, v_jump) if not s.coarse else compare_within(
            jump_row, v_jump, below.speed_kmh, above.speed_kmh,
            f"a coarse run (--quick): the jump lies between {below.speed_kmh:.4g} and "
            f"{above.speed_kmh:.4g} km/h, partly inside the paper's tolerance"))
        rows += [judged,
                 compare(paper["frequency_q1_hz"], below.frequency_hz),
                 compare(paper["frequency_q2_hz"], above.frequency_hz)]  # fmt: skip
    else:
        no_jump = dataclasses.replace(jump_row, quantity="speed of the frequency jump",
                                      paper=f"{jump_row.paper:g}", note="widen the speed range")
        rows.append(claim(no_jump, "no jump found", False))
    step.headline = rows
    return step


# --------------------------------------------------------------------------- Fig. 8


def fig8(ctx: Context) -> Step:
    """Fig. 8: displacement and damper velocity of the releases that bracket the jump."""
    from railhunt.plots import plot_damper_histories

    step = Step("fig8", "Fig. 8: wheelset displacement and yaw damper velocity below and above "
                "the jump", paper2019.CAPTIONS["fig8"])  # fmt: skip
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
        period = peak_period(t[measured], y[measured])
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
    paper = paper2019.EXPECTED
    step.headline = [compare(paper["period_below_blowoff_s"], periods[0]),
                     compare(paper["period_above_blowoff_s"], periods[1])]  # fmt: skip
    return step

