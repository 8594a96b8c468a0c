"""Figures: time histories, phase planes, root loci, bifurcation diagrams, contact geometry,
parameter sweeps and their Table 1 sections.

Everything is drawn on :class:`matplotlib.figure.Figure` objects rendered by the Agg
canvas, so no GUI backend (and no global ``pyplot`` state) is ever involved; the functions
are safe to call from scripts, tests and worker processes without a display.

Units on the axes are the engineer's units, not SI: lateral displacements in mm, lateral
velocities in mm/s, times in s, frequencies in Hz, speeds in km/h and swept parameters in
the paper's Table 1 units (kN*s/m, MN/m, MN).
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from railhunt.analysis.continuation import BifurcationDiagram
    from railhunt.analysis.linear import EigenResult, LinearCriticalSpeed
    from railhunt.simulation import SimulationResult
    from railhunt.studies.sections import SectionTable, SweepLine

__all__ = [
    "plot_bifurcation",
    "plot_bifurcation_family",
    "plot_contact_geometry",
    "plot_damper_histories",
    "plot_damper_velocity",
    "plot_hunting_frequency",
    "plot_root_locus",
    "plot_sections",
    "plot_sweep",
    "plot_time_histories",
    "plot_time_history",
]

#: Start of the phase-plane window (s), as in the paper's Fig. 6 (after the transient).
PHASE_FROM = 3.0
_DPI = 120


def _new_figure(width: float, height: float) -> Figure:
    fig = Figure(figsize=(width, height), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _save(fig: Figure, path: str | os.PathLike[str]) -> Path:
    path = Path(path)
    fig.savefig(path, dpi=_DPI)
    return path


def plot_time_history(
    result: SimulationResult,
    path: str | os.PathLike[str],
    channel: str = "y_w1",
    phase_from: float = PHASE_FROM,
) -> Path:
    """Plot a wheelset's lateral displacement history and its phase plane.

    Left: lateral displacement (mm) against time (s), with the time spent on the track
    excitation shaded. Right: lateral velocity (mm/s) against lateral displacement (mm)
    after ``phase_from`` seconds, where a decaying spiral means a stable run and a closed
    orbit means hunting on a limit cycle (the paper's Fig. 6).

    Parameters
    ----------
    result : SimulationResult
        A run of :func:`railhunt.simulate`.
    path : str or os.PathLike
        Output file; the format follows the suffix (``.png``, ``.pdf``, ``.svg``, ...).
    channel : str
        Lateral displacement channel to show, ``"y_w1"`` (leading wheelset) by default;
        its velocity channel ``"d" + channel`` is used for the phase plane.
    phase_from : float
        Start of the phase-plane window (s). When the run is shorter than that, the
        second half of the run is shown instead (and the title says so).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    fig = _new_figure(11.0, 4.2)
    ax_t, ax_p = fig.subplots(1, 2, width_ratios=(1.6, 1.0))
    _draw_time_history(ax_t, ax_p, result, channel, phase_from)
    return _save(fig, path)


def _draw_time_history(ax_t: Axes, ax_p: Axes, result: SimulationResult, channel: str,
                       phase_from: float) -> None:  # fmt: skip
    """Draw one run's displacement history on ``ax_t`` and its phase plane on ``ax_p``."""
    t = np.asarray(result.t)
    y = np.asarray(result[channel]) * 1e3
    dy = np.asarray(result["d" + channel]) * 1e3
    speed = result.speed_kmh
    wheelset = channel.rsplit("_", 1)[-1]

    ax_t.plot(t, y, color="tab:blue", lw=0.9)
    t_exc = float(getattr(result, "excitation_end", 0.0) or 0.0)
    if t_exc > 0.0 and t.size:
        ax_t.axvspan(t[0], min(t_exc, t[-1]), color="0.85", zorder=0, label="on track defect")
        ax_t.legend(loc="upper right", fontsize="small")
    ax_t.axhline(0.0, color="0.5", lw=0.6)
    ax_t.set_xlabel("time t (s)")
    ax_t.set_ylabel(f"lateral displacement {channel} (mm)")
    ax_t.set_title(f"{_wheelset_label(wheelset)} at {speed:.0f} km/h: {result.status}")
    ax_t.grid(True, alpha=0.3)

    start = phase_from
    note = f"t ≥ {phase_from:g} s"
    if t.size == 0 or t[-1] <= phase_from:
        start = float(t[-1]) / 2.0 if t.size else 0.0
        note = f"t ≥ {start:.2g} s\n(run shorter than {phase_from:g} s)"
    mask = t >= start
    ax_p.plot(y[mask], dy[mask], color="tab:red", lw=0.7)
    if np.any(mask):
        ax_p.plot(y[mask][-1], dy[mask][-1], "o", color="k", ms=4, label="end of run")
        ax_p.legend(loc="upper right", fontsize="small")
    ax_p.axhline(0.0, color="0.5", lw=0.6)
    ax_p.axvline(0.0, color="0.5", lw=0.6)
    ax_p.set_xlabel(f"lateral displacement {channel} (mm)")
    ax_p.set_ylabel(f"lateral velocity d{channel} (mm/s)")
    ax_p.set_title(f"phase plane at {speed:.0f} km/h, {note}")
    ax_p.grid(True, alpha=0.3)


def _wheelset_label(index: str) -> str:
    if index == "w1":
        return "leading wheelset"
    return f"wheelset {index[1:]}" if index.startswith("w") else index


def plot_root_locus(
    eigen_result: EigenResult,
    path: str | os.PathLike[str],
    linear: LinearCriticalSpeed | None = None,
) -> Path:
    """Plot the root locus and the hunting-mode damping ratio versus speed.

    Left: every eigenvalue of the linearised model in the upper half plane, real part
    (1/s) against frequency ``Im/2pi`` (Hz), coloured by speed (km/h), with the hunting
    mode drawn as a connected line. The view is zoomed on the hunting mode; the number of
    eigenvalues outside the view is noted. Right: hunting-mode damping ratio (%) against
    speed (km/h); it crosses zero at the linear critical speed.

    Parameters
    ----------
    eigen_result : EigenResult
        Output of :func:`railhunt.eigen_analysis`.
    path : str or os.PathLike
        Output file; the format follows the suffix.
    linear : LinearCriticalSpeed, optional
        Output of :func:`railhunt.linear_critical_speed`; marked on both panels when given.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    speeds = np.asarray(eigen_result.speeds_kmh, dtype=float)
    eig = np.asarray(eigen_result.eigenvalues)
    hunt = np.asarray(eigen_result.hunting)
    freq_h = hunt.imag / (2 * math.pi)
    zeta = np.asarray(eigen_result.hunting_damping_ratio) * 100.0

    fig = _new_figure(12.0, 4.8)
    ax_r, ax_z = fig.subplots(1, 2, width_ratios=(1.4, 1.0))

    s_all = np.repeat(speeds, eig.shape[1])
    lam = eig.ravel()
    upper = lam.imag >= -1e-9
    sc = ax_r.scatter(
        lam.real[upper],
        lam.imag[upper] / (2 * math.pi),
        c=s_all[upper],
        s=9,
        cmap="viridis",
        vmin=speeds.min(),
        vmax=max(speeds.max(), speeds.min() + 1),
        linewidths=0,
    )
    ax_r.plot(hunt.real, freq_h, "-o", color="tab:red", ms=3.5, lw=1.4, label="hunting mode")
    ax_r.axvline(0.0, color="k", lw=0.8)

    x_lo = min(-8.0, 2.0 * float(np.min(hunt.real)))
    x_hi = max(2.0, 1.5 * float(np.max(hunt.real)))
    y_hi = max(10.0, 1.8 * float(np.max(freq_h)))
    ax_r.set_xlim(x_lo, x_hi)
    ax_r.set_ylim(-0.02 * y_hi, y_hi)
    inside = (
        (lam.real[upper] >= x_lo)
        & (lam.real[upper] <= x_hi)
        & (lam.imag[upper] / (2 * math.pi) <= y_hi)
    )
    hidden = int(np.count_nonzero(~inside))
    if hidden:
        ax_r.text(
            0.01,
            0.01,
            f"{hidden} eigenvalues outside this view",
            fontsize="x-small",
            color="0.4",
            transform=ax_r.transAxes,
        )
    if linear is not None and math.isfinite(linear.speed_kmh):
        ax_r.plot(
            0.0,
            linear.frequency_hz,
            "*",
            color="k",
            ms=12,
            label=f"Hopf point {linear.speed_kmh:.0f} km/h, {linear.frequency_hz:.2f} Hz",
        )
    ax_r.set_xlabel("real part Re λ (1/s)   (> 0: unstable)")
    ax_r.set_ylabel("frequency Im λ / 2π (Hz)")
    ax_r.set_title(f"root locus, {speeds.min():.0f} to {speeds.max():.0f} km/h")
    ax_r.legend(loc="upper left", fontsize="small")
    ax_r.grid(True, alpha=0.3)
    fig.colorbar(sc, ax=ax_r, label="speed (km/h)")

    ax_z.plot(speeds, zeta, "-o", color="tab:red", ms=3.5)
    ax_z.axhline(0.0, color="k", lw=0.8)
    if linear is not None and math.isfinite(linear.speed_kmh):
        ax_z.axvline(
            linear.speed_kmh,
            color="k",
            ls="--",
            lw=1.0,
            label=f"linear critical speed {linear.speed_kmh:.0f} km/h",
        )
        ax_z.legend(loc="upper right", fontsize="small")
    ax_z.set_xlabel("speed (km/h)")
    ax_z.set_ylabel("hunting damping ratio (%)")
    ax_z.set_title("hunting mode damping (< 0: hunting grows)")
    ax_z.grid(True, alpha=0.3)
    return _save(fig, path)


def plot_bifurcation(
    diagram: BifurcationDiagram,
    path: str | os.PathLike[str],
    point_p_amplitude: float | None = 3e-3,
) -> Path:
    """Bifurcation diagram like the paper's Fig. 7a.

    Amplitude of the leading wheelset (mm) against speed (km/h): stable limit cycles
    solid, unstable dashed, the centred equilibrium along the axis (stable solid up to
    the Hopf point, dashed above), the Hopf point and the folds marked, and the paper's
    point P where a disturbance of ``point_p_amplitude`` (m) meets an unstable branch.
    """
    fig = _new_figure(7.5, 4.8)
    ax = fig.add_subplot(1, 1, 1)
    lo, hi = diagram.speed_range_kmh
    hopf = diagram.hopf_speed_kmh
    ax.plot([lo, min(hopf, hi)], [0, 0], "k-", lw=2, label="equilibrium, stable")
    if hopf < hi:
        ax.plot([hopf, hi], [0, 0], "k--", lw=1.2, label="equilibrium, unstable")
    colours = ["C0", "C2", "C4", "C5"]
    for n, branch in enumerate(diagram.branches):
        c = colours[n % len(colours)]
        name = "Hopf branch" if branch.origin == "hopf" else f"branch {n + 1}"
        for first, last, stable in branch.segments():
            sl = slice(first, last + 1)
            ax.plot(branch.speed_kmh[sl], branch.amplitude[sl] * 1e3, "-" if stable else "--",
                    color=c, lw=2 if stable else 1.2)  # fmt: skip
        ax.plot([], [], "-", color=c, lw=2, label=f"{name}: stable (solid) / unstable (dashed)")
    ax.plot([hopf], [0], "o", color="C3", ms=8, zorder=5,
            label=f"Hopf point A, V_lim = {hopf:.1f} km/h")  # fmt: skip
    for k, fold in enumerate(diagram.folds):
        ax.plot([fold.speed_kmh], [fold.amplitude * 1e3], "s", color="C1", ms=6, zorder=5,
                label="folds" if k == 0 else None)  # fmt: skip
    v_nl = diagram.fold_speed_kmh
    ax.axvline(v_nl, color="C1", lw=0.8, ls=":")
    ax.text(v_nl, 0.02, f" V_nl = {v_nl:.1f} km/h", transform=ax.get_xaxis_transform(),
            color="C1", va="bottom")  # fmt: skip
    if point_p_amplitude is not None:
        vp = diagram.point_p_kmh(point_p_amplitude)
        ax.axhline(point_p_amplitude * 1e3, color="0.5", lw=0.6, ls=":")
        if math.isfinite(vp):
            ax.plot([vp], [point_p_amplitude * 1e3], "D", color="C3", ms=7, zorder=6,
                    label=f"P: {point_p_amplitude * 1e3:g} mm meets unstable branch, "
                    f"{vp:.1f} km/h")  # fmt: skip
        else:
            ax.text(lo, point_p_amplitude * 1e3, f" {point_p_amplitude * 1e3:g} mm: no unstable "
                    "branch crosses it", va="bottom", fontsize=8, color="0.4")  # fmt: skip
    ax.set_xlim(lo, hi)
    ax.set_ylim(bottom=-0.3)
    ax.set_xlabel("speed (km/h)")
    ax.set_ylabel("amplitude of leading wheelset y_w1 (mm)")
    ax.set_title(f"Bifurcation diagram ({diagram.hopf_type} Hopf bifurcation)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    return _save(fig, path)


def plot_hunting_frequency(
    speeds_kmh: np.ndarray,
    frequency_hz: np.ndarray,
    sources: list[str],
    path: str | os.PathLike[str],
    initial_amplitude: float = 3e-3,
) -> Path:
    """Hunting frequency versus speed like the paper's Fig. 7b, the jump drawn dashed.

    Frequencies from the hunting eigenvalue (disturbance decays) as circles joined by a
    line, from the limit cycle as squares; the jump between them (points Q1, Q2) dashed.
    """
    speeds = np.asarray(speeds_kmh, dtype=float)
    freq = np.asarray(frequency_hz, dtype=float)
    fig = _new_figure(7.0, 4.2)
    ax = fig.add_subplot(1, 1, 1)
    for source, marker, label in (("eigenvalue", "o-", "from the hunting eigenvalue"),
                                  ("limit-cycle", "s-", "from the limit cycle")):  # fmt: skip
        mask = np.array([s == source for s in sources])
        if mask.any():
            ax.plot(speeds[mask], freq[mask], marker, ms=4, label=label)
    for i in range(1, len(sources)):
        if sources[i] != sources[i - 1]:
            ax.plot(speeds[i - 1:i + 1], freq[i - 1:i + 1], "k--", lw=1)
            ax.annotate("Q1", (speeds[i - 1], freq[i - 1]), xytext=(-18, 4),
                        textcoords="offset points")  # fmt: skip
            ax.annotate("Q2", (speeds[i], freq[i]), xytext=(4, 4), textcoords="offset points")
    ax.set_xlabel("speed (km/h)")
    ax.set_ylabel("hunting frequency of leading wheelset (Hz)")
    ax.set_title(f"Hunting frequency, initial wheelset displacement {initial_amplitude * 1e3:g} mm")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


def plot_damper_velocity(
    t: np.ndarray,
    y: np.ndarray,
    damper_velocity: np.ndarray,
    blowoff_velocity: float,
    path: str | os.PathLike[str],
    title: str = "",
) -> Path:
    """Time histories like the paper's Fig. 8: leading wheelset displacement (mm) and the
    front yaw damper's velocity (m/s) against the blow-off velocity (red lines).

    One case of :func:`plot_damper_histories`.
    """
    return plot_damper_histories([(title, t, y, damper_velocity, blowoff_velocity)], path)


def plot_bifurcation_family(
    family: list[tuple[float, BifurcationDiagram]],
    path: str | os.PathLike[str],
    parameter: str = "F_u",
    unit: str = "kN",
    scale: float = 1e-3,
) -> Path:
    """Bifurcation diagrams of a parameter family side by side, like the paper's Fig. 13.

    One panel per member: amplitude of the leading wheelset (mm) against speed, stable
    solid, unstable dashed, the Hopf point and the lowest fold marked, the type in the title.
    """
    n = len(family)
    cols = min(n, 3)
    rows = int(math.ceil(n / cols))
    fig = _new_figure(4.2 * cols, 3.3 * rows)
    for k, (value, d) in enumerate(family):
        ax = fig.add_subplot(rows, cols, k + 1)
        lo, hi = d.speed_range_kmh
        hopf = d.hopf_speed_kmh
        ax.plot([lo, min(hopf, hi)], [0, 0], "k-", lw=1.5)
        if hopf < hi:
            ax.plot([hopf, hi], [0, 0], "k--", lw=1)
        for n_b, branch in enumerate(d.branches):
            c = f"C{[0, 2, 4, 5][n_b % 4]}"
            for first, last, stable in branch.segments():
                sl = slice(first, last + 1)
                ax.plot(branch.speed_kmh[sl], branch.amplitude[sl] * 1e3,
                        "-" if stable else "--", color=c, lw=1.6 if stable else 1)  # fmt: skip
        ax.plot([hopf], [0], "o", color="C3", ms=5)
        ax.axvline(d.fold_speed_kmh, color="C1", lw=0.8, ls=":")
        text = "no blow-off" if value >= 1e8 else f"{value * scale:g} {unit}"
        ax.set_title(f"{parameter} = {text}: {d.hopf_type}", fontsize=9)
        ax.set_xlim(lo, hi)
        ax.set_ylim(bottom=-0.3)
        ax.grid(True, alpha=0.3)
        ax.set_xlabel("speed (km/h)", fontsize=8)
        ax.set_ylabel("y_w1 amplitude (mm)", fontsize=8)
    return _save(fig, path)


def plot_time_histories(
    results: list[SimulationResult],
    path: str | os.PathLike[str],
    channel: str = "y_w1",
    phase_from: float = PHASE_FROM,
) -> Path:
    """Several runs stacked, each as time history and phase plane (the paper's Fig. 6).

    One row per run: lateral displacement (mm) against time (s) on the left, lateral
    velocity (mm/s) against displacement (mm) after ``phase_from`` seconds on the right, as
    drawn by :func:`plot_time_history`. The paper's Fig. 6 is two rows: the highest stable
    speed and 1 km/h above it.

    Parameters
    ----------
    results : list of SimulationResult
        Runs of :func:`railhunt.simulate`, drawn top to bottom.
    path : str or os.PathLike
        Output file; the format follows the suffix.
    channel : str
        Lateral displacement channel, ``"y_w1"`` (leading wheelset) by default.
    phase_from : float
        Start of the phase-plane window (s).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    if not results:
        raise ValueError("results is empty: give at least one simulation result")
    fig = _new_figure(11.0, 3.6 * len(results))
    axes = fig.subplots(len(results), 2, width_ratios=(1.6, 1.0), squeeze=False)
    for (ax_t, ax_p), result in zip(axes, results, strict=True):
        _draw_time_history(ax_t, ax_p, result, channel, phase_from)
    return _save(fig, path)


def plot_damper_histories(
    cases: list[tuple[str, np.ndarray, np.ndarray, np.ndarray, float]],
    path: str | os.PathLike[str],
) -> Path:
    """Side-by-side time histories like the paper's Fig. 8, one column per case.

    Top row: the leading wheelset's lateral displacement (mm); bottom row: the front left
    yaw damper's velocity (m/s) with the blow-off velocity ``±v_u`` as red lines. The
    paper's Fig. 8 contrasts a run whose damper stays below ``v_u`` (period 0.25 s) with
    one whose damper blows off (0.19 s).

    Parameters
    ----------
    cases : list of (title, t, y, damper_velocity, blowoff_velocity)
        Per column: a title, times (s), displacements (m), the damper velocities (m/s, one
        column per damper, as :class:`railhunt.analysis.frequency.HuntingFrequency` holds
        them) and the blow-off velocity (m/s).
    path : str or os.PathLike
        Output file; the format follows the suffix.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    if not cases:
        raise ValueError("cases is empty: give at least one time history")
    fig = _new_figure(5.2 * len(cases), 5.2)
    axes = fig.subplots(2, len(cases), squeeze=False, sharex="col")
    for k, (title, t, y, vd, v_u) in enumerate(cases):
        ax_y, ax_v = axes[0, k], axes[1, k]
        ax_y.plot(t, np.asarray(y) * 1e3, lw=0.8)
        ax_y.set_ylabel("y_w1 (mm)")
        ax_y.set_title(title, fontsize=9)
        ax_y.grid(True, alpha=0.3)
        ax_v.plot(t, np.asarray(vd)[:, 0], lw=0.8, label="front left yaw damper v_d")
        for sign in (1, -1):
            ax_v.axhline(sign * v_u, color="r", lw=1,
                         label="blow-off velocity v_u" if sign > 0 else None)  # fmt: skip
        ax_v.set_xlabel("time (s)")
        ax_v.set_ylabel("damper velocity (m/s)")
        ax_v.grid(True, alpha=0.3)
        ax_v.legend(fontsize=7, loc="upper right")
    return _save(fig, path)


def plot_contact_geometry(geometry: object, path: str | os.PathLike[str]) -> Path:
    """Plot a wheelset's contact geometry against its lateral displacement (mm, deg, mrad).

    Four panels: rolling radii ``r_L``, ``r_R``; rolling-radius difference ``Delta r``;
    contact angles ``delta_L``, ``delta_R``; wheelset roll and the contact point's position
    on each wheel profile. Contact-point jumps (two-point contact) are marked by dotted
    vertical lines.

    Parameters
    ----------
    geometry : railhunt.contact.geometry.ContactGeometry
        The table to plot.
    path : str or os.PathLike
        PNG file to write.
    """
    g = geometry
    y = g.y * 1e3
    fig = _new_figure(10.0, 7.0)
    axes = fig.subplots(2, 2, sharex=True)
    ax = axes[0, 0]
    ax.plot(y, g.r_left * 1e3, label="$r_L$")
    ax.plot(y, g.r_right * 1e3, label="$r_R$")
    ax.set_ylabel("rolling radius (mm)")
    ax.legend()
    ax = axes[0, 1]
    ax.plot(y, g.delta_r * 1e3, color="k")
    ax.set_ylabel(r"$\Delta r = r_L - r_R$ (mm)")
    ax = axes[1, 0]
    ax.plot(y, np.degrees(g.delta_left), label=r"$\delta_L$")
    ax.plot(y, np.degrees(g.delta_right), label=r"$\delta_R$")
    ax.set_ylabel("contact angle (deg)")
    ax.legend()
    ax = axes[1, 1]
    ax.plot(y, g.roll * 1e3, color="k", label="roll (mrad)")
    ax.plot(y, g.wheel_left * 1e3, label="contact on left wheel (mm)")
    ax.plot(y, g.wheel_right * 1e3, label="contact on right wheel (mm)")
    ax.set_ylabel("roll (mrad), contact position (mm)")
    ax.legend(fontsize="small")
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
        for yj in y[g.jump]:
            ax.axvline(yj, color="0.6", linestyle=":", linewidth=0.8)
    for ax in axes[1]:
        ax.set_xlabel("lateral wheelset displacement y (mm), + left")
    p = g.params
    fig.suptitle(f"{p.get('wheel', '')} on {p.get('rail', '')}, inclination "
                 f"{p.get('rail_inclination', 0):.4g}, gauge {p.get('gauge', 0) * 1e3:g} mm")
    return _save(fig, path)


# --------------------------------------------------------------------------- parameter studies

_SECTION_COLOURS = ("#1f4e79", "#5b9bd5", "#bdd7ee")


def _display_unit(name: str) -> tuple[str, float, str]:
    """Axis label, SI size of the display unit and tick-label name of a swept parameter."""
    from railhunt.studies.sections import load_table1
    from railhunt.vehicle import PARAMETERS

    entry = load_table1().get(name)
    if entry is not None:
        return entry.label, entry.scale, " = ".join((name, *entry.ties))
    unit = PARAMETERS[name].unit if name in PARAMETERS else ""
    return (f"{name} ({unit})" if unit and unit != "1" else name), 1.0, name


def plot_sweep(
    results: object,
    path: str | os.PathLike[str],
    parameters: list[str] | tuple[str, ...] | None = None,
) -> Path:
    """Critical speed and hunting frequency against each swept parameter (Figs. 10, 11).

    One panel per one-parameter line of the results, lettered (a), (b), ...: the
    parameter in its display unit (Table 1's: kN*s/m, MN/m, MN) on x; the nonlinear
    critical speed V_cr (km/h) black solid on the left axis; the hunting frequency (Hz,
    at the speed the sweep computed it) blue on a twin right axis, solid between
    neighbours from the same source (eigenvalue or limit cycle) and dashed where the
    source changes (the frequency jump). Points without a number are skipped (marked x
    on the axis for V_cr).

    Parameters
    ----------
    results : str, os.PathLike, SweepResults or sequence of dict
        Results of a one-parameter-at-a-time sweep (design ``"lines"``); see
        :func:`railhunt.studies.sections.result_rows`.
    path : str or os.PathLike
        Output file; the format follows the suffix.
    parameters : sequence of str, optional
        The lines to draw, in this order (default: every line of the results).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        The results hold a grid / random / Latin-hypercube design (several parameters
        varied at once: one parameter's curve would mix the others' changes), a
        requested parameter is not one of the lines, or the results have neither the
        critical speed nor the hunting frequency.
    """
    from railhunt.studies.sections import sweep_lines

    lines = sweep_lines(results)
    names = list(lines) if parameters is None else list(parameters)
    if not names:
        raise ValueError(f"no parameter to plot (lines: {', '.join(lines)})")
    for name in names:
        if name not in lines:
            raise ValueError(f"no line {name!r} in the results (lines: {', '.join(lines)})")
    columns = next(iter(lines.values())).columns
    if not {"critical_speed_kmh", "hunting_frequency_hz"} & columns:
        raise ValueError("the results hold neither critical_speed nor hunting_frequency (the "
                         "sweep's outputs): nothing to draw for Figs. 10/11")  # fmt: skip
    n = len(names)
    cols = n if n <= 3 else (2 if n == 4 else 3)
    rows = int(math.ceil(n / cols))
    fig = _new_figure(4.6 * cols, 3.7 * rows)
    for k, name in enumerate(names):
        ax = fig.add_subplot(rows, cols, k + 1)
        _sweep_panel(ax, lines[name], f"({chr(ord('a') + k)})")
    _sweep_legend(fig)
    return _save(fig, path)


def _sweep_panel(ax: Axes, line: SweepLine, letter: str) -> None:
    label, scale, _ = _display_unit(line.parameter)
    x = np.asarray(line.values, dtype=float) / scale
    v = np.asarray(line.critical_speed_kmh, dtype=float)
    f = np.asarray(line.frequency_hz, dtype=float)
    ok = np.isfinite(v)
    ax.plot(x[ok], v[ok], "k-o", lw=1.6, ms=3)
    if np.any(~ok & np.isfinite(x)):
        ax.plot(x[~ok], np.zeros(np.count_nonzero(~ok)), "x", color="0.4", ms=6, clip_on=False,
                transform=ax.get_xaxis_transform())  # fmt: skip
    ax.set_xlabel(label)
    ax.set_ylabel("critical speed V_cr (km/h)")
    ax.set_title(f"{letter} {label.split(' (')[0]}", loc="left")
    ax.grid(True, alpha=0.3)

    ax_f = ax.twinx()
    blue = "tab:blue"
    jumps = set(line.jumps())
    finite = np.flatnonzero(np.isfinite(f))
    run: list[int] = []
    for i, j in zip(finite, [*finite[1:], -1], strict=False):
        run.append(int(i))
        if j < 0 or int(i) in jumps:
            ax_f.plot(x[run], f[run], "-s", color=blue, lw=1.4, ms=3)
            if j >= 0:
                ax_f.plot(x[[i, j]], f[[i, j]], "--", color=blue, lw=1.4)
            run = []
    speed = line.frequency_speed_kmh
    at = f" at {speed:g} km/h" if math.isfinite(speed) else ""
    ax_f.set_ylabel(f"hunting frequency f{at} (Hz)", color=blue)
    ax_f.tick_params(axis="y", colors=blue)


def _sweep_legend(fig: Figure) -> None:
    from matplotlib.lines import Line2D

    blue = "tab:blue"
    handles = [
        Line2D([], [], color="k", marker="o", ms=3, label="critical speed V_cr (left axis)"),
        Line2D([], [], color=blue, marker="s", ms=3, label="hunting frequency f (right axis)"),
        Line2D([], [], color=blue, ls="--", label="jump of f (source changes)"),
    ]
    fig.legend(handles=handles, loc="outside upper center", ncols=3, fontsize="small")


def plot_sections(section_table: SectionTable, path: str | os.PathLike[str]) -> Path:
    """ΔV_cr and Δf per parameter and Table 1 section, like the paper's Fig. 12.

    (a) ΔV_cr (km/h) and (b) Δf (Hz, the frequency jump removed): one stacked bar per
    parameter, sections 1, 2, 3 from the bottom, the total above each bar. A parameter
    whose line does not cover all its sections or skipped points is marked with ``*``.

    Parameters
    ----------
    section_table : SectionTable
        Output of :func:`railhunt.studies.sections.section_changes`.
    path : str or os.PathLike
        Output file; the format follows the suffix.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    entries = list(section_table)
    if not entries:
        raise ValueError("the section table is empty: nothing to plot")
    n = len(entries)
    fig = _new_figure(max(6.0, 1.0 * n + 2.5), 7.0)
    ax_v, ax_f = fig.subplots(2, 1)
    x = np.arange(n)
    names = [_display_unit(e.parameter)[2] + ("" if e.complete else "*") for e in entries]
    for ax, attr, symbol, unit, title in (
        (ax_v, "speed_change_kmh", "ΔV_cr", "km/h", "(a) change of critical speed ΔV_cr"),
        (ax_f, "frequency_change_hz", "Δf", "Hz",
         "(b) change of hunting frequency Δf, the jump removed"),
    ):  # fmt: skip
        bottom = np.zeros(n)
        for k in range(3):
            h = np.array([getattr(e.sections[k], attr) if k < len(e.sections) else math.nan
                          for e in entries])  # fmt: skip
            h = np.where(np.isfinite(h), h, 0.0)
            ax.bar(x, h, 0.6, bottom=bottom, color=_SECTION_COLOURS[k], edgecolor="k", lw=0.5,
                   label=f"section {k + 1}")  # fmt: skip
            bottom += h
        for xi, e, top in zip(x, entries, bottom, strict=True):
            total = getattr(e, attr)
            text = "n/a" if not math.isfinite(total) else f"{total:.3g}"
            ax.annotate(text, (xi, top), xytext=(0, 2), textcoords="offset points",
                        ha="center", va="bottom", fontsize=8)  # fmt: skip
        ax.set_xticks(x, names)
        ax.set_ylabel(f"{symbol} ({unit})")
        ax.set_title(title, loc="left")
        ax.set_ylim(0, max(float(bottom.max()), 1e-9) * 1.3)
        ax.grid(True, axis="y", alpha=0.3)
        ax.legend(fontsize="small", loc="upper left", ncols=3)
    if not all(e.complete for e in entries):
        ax_f.set_xlabel("* the line does not cover every section, or points were skipped",
                        fontsize=8, color="0.3")  # fmt: skip
    return _save(fig, path)
