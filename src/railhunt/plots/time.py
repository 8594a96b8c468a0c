"""Time histories and phase planes (the paper's Figs. 6 and 8), damper velocities."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from railhunt.simulation import SimulationResult


from railhunt.plots.figure import PHASE_FROM, new_figure, save_figure


def plot_time_history(
    result: SimulationResult,
    path: str | os.PathLike[str],
    channel: str = "y_w1",
    phase_from: float = PHASE_FROM,
    verdict: str | None = None,
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
    verdict : str, optional
        The run's stability verdict (e.g. ``"hunting, 9.63 mm"``), shown in the title
        apart from the solver's status (which only says how the integration ended).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(time_history_figure(result, channel, phase_from, verdict), path)


def time_history_figure(result: SimulationResult, channel: str = "y_w1",
                        phase_from: float = PHASE_FROM,
                        verdict: str | None = None) -> Figure:  # fmt: skip
    """The figure of :func:`plot_time_history`, not saved."""
    fig = new_figure(11.0, 4.2)
    ax_t, ax_p = fig.subplots(1, 2, width_ratios=(1.6, 1.0))
    _draw_time_history(ax_t, ax_p, result, channel, phase_from, verdict)
    return fig


def _draw_time_history(ax_t: Axes, ax_p: Axes, result: SimulationResult, channel: str,
                       phase_from: float, verdict: str | None = None) -> None:  # fmt: skip
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
    state = result.status if verdict is None else f"{verdict} (solver: {result.status})"
    ax_t.set_title(f"{_wheelset_label(wheelset)} at {speed:.0f} km/h: {state}")
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
    return save_figure(time_histories_figure(results, channel, phase_from), path)


def time_histories_figure(results: list[SimulationResult], channel: str = "y_w1",
                          phase_from: float = PHASE_FROM) -> Figure:  # fmt: skip
    """The figure of :func:`plot_time_histories`, not saved."""
    if not results:
        raise ValueError("results is empty: give at least one simulation result")
    fig = new_figure(11.0, 3.6 * len(results))
    axes = fig.subplots(len(results), 2, width_ratios=(1.6, 1.0), squeeze=False)
    for (ax_t, ax_p), result in zip(axes, results, strict=True):
        _draw_time_history(ax_t, ax_p, result, channel, phase_from)
    return fig


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
    return save_figure(damper_histories_figure(cases), path)


def damper_histories_figure(
    cases: list[tuple[str, np.ndarray, np.ndarray, np.ndarray, float]],
) -> Figure:
    """The figure of :func:`plot_damper_histories`, not saved."""
    if not cases:
        raise ValueError("cases is empty: give at least one time history")
    fig = new_figure(5.2 * len(cases), 5.2)
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
    return fig
