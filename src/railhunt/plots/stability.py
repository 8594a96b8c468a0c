"""Stability figures: root locus, bifurcation diagrams (Figs. 7a, 13), hunting frequency (7b)."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:

    from railhunt.analysis.continuation import BifurcationDiagram
    from railhunt.analysis.linear import EigenResult, LinearCriticalSpeed


from railhunt.plots.figure import new_figure, save_figure


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

    fig = new_figure(12.0, 4.8)
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
    return save_figure(fig, path)


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
    fig = new_figure(7.5, 4.8)
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
    return save_figure(fig, path)


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
    fig = new_figure(7.0, 4.2)
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
    return save_figure(fig, path)




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
    fig = new_figure(4.2 * cols, 3.3 * rows)
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
    return save_figure(fig, path)
