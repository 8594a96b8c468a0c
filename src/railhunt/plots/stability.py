"""Stability figures: root locus, bifurcation diagrams (Figs. 7a, 13), hunting frequency (7b)."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.lines import Line2D

from railhunt.plots.figure import new_figure, save_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from railhunt.analysis.branches import Branch
    from railhunt.analysis.continuation import BifurcationDiagram
    from railhunt.analysis.linear import EigenResult, LinearCriticalSpeed


def plot_root_locus(
    eigen_result: EigenResult,
    path: str | os.PathLike[str],
    linear: LinearCriticalSpeed | None = None,
) -> Path:
    """Plot the root locus and the hunting-mode damping ratio versus speed to a file.

    The figure of :func:`root_locus_figure`, saved to ``path`` (the format follows the
    suffix); returns the path.
    """
    return save_figure(root_locus_figure(eigen_result, linear), path)


def root_locus_figure(
    eigen_result: EigenResult,
    linear: LinearCriticalSpeed | None = None,
) -> Figure:
    """The root locus and the hunting-mode damping ratio versus speed.

    Left: every eigenvalue of the linearised model in the upper half plane, real part
    (1/s) against frequency ``Im/2pi`` (Hz), coloured by speed (km/h), with the hunting
    mode drawn as a connected line. The view is zoomed on the hunting mode; the number of
    eigenvalues outside the view is noted. Right: hunting-mode damping ratio (%) against
    speed (km/h); it crosses zero at the linear critical speed.

    Parameters
    ----------
    eigen_result : EigenResult
        Output of :func:`railhunt.eigen_analysis`.
    linear : LinearCriticalSpeed, optional
        Output of :func:`railhunt.linear_critical_speed`; marked on both panels when given.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (Agg canvas), not saved.
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
    # The hunting mode: a line through its eigenvalues, each marker coloured by its speed
    # on the same scale as the others (so that a speed can be read off the mode itself).
    ax_r.plot(hunt.real, freq_h, "-", color="tab:red", lw=1.2, zorder=2)
    ax_r.scatter(hunt.real, freq_h, c=speeds, s=30, cmap="viridis", vmin=speeds.min(),
                 vmax=max(speeds.max(), speeds.min() + 1), edgecolors="tab:red",
                 linewidths=1.0, zorder=3, label="hunting mode (colour: speed)")  # fmt: skip
    ax_r.axvline(0.0, color="k", lw=0.8)
    crossings = _zero_crossings(speeds, zeta, freq_h)
    for k, (v, f, rising) in enumerate(crossings):
        word = "unstable above" if rising else "stable again above"
        ax_r.annotate(f"{v:.0f} km/h: {word}", (0.0, f), xytext=(12, -16 - 14 * (k % 2)),
                      textcoords="offset points", fontsize="x-small", color="k",
                      arrowprops={"arrowstyle": "-", "color": "0.4", "lw": 0.8})  # fmt: skip

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
    for v, _, rising in crossings:  # every zero crossing, the second one near 480 km/h too
        ax_z.plot(v, 0.0, "D", color="k" if rising else "tab:green", ms=6, zorder=3)
        ax_z.annotate(f"{v:.0f} km/h", (v, 0.0), xytext=(6, 6),
                      textcoords="offset points", fontsize="x-small")  # fmt: skip
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
    return fig


def _zero_crossings(speeds: np.ndarray, zeta: np.ndarray,
                    freq: np.ndarray) -> list[tuple[float, float, bool]]:  # fmt: skip
    """Speeds (km/h) where the hunting damping ratio crosses zero, by linear
    interpolation, with the frequency (Hz) there and whether it turns unstable."""
    out = []
    for i in range(zeta.size - 1):
        a, b = zeta[i], zeta[i + 1]
        if np.isfinite(a) and np.isfinite(b) and (a > 0) != (b > 0) and a != b:
            w = a / (a - b)
            out.append((float(speeds[i] + w * (speeds[i + 1] - speeds[i])),
                        float(freq[i] + w * (freq[i + 1] - freq[i])), bool(b < a)))  # fmt: skip
    return out


#: What the amplitude axis of a bifurcation diagram shows: the leading wheelset's lateral
#: amplitude (the paper's output, and the one point P is defined on) or the largest of all
#: wheelsets' (a branch on which mainly the rear bogie hunts then shows its real size).
WHEELSET_CHOICES = ("leading", "largest")
#: Colours of the branches, in the order of ``diagram.branches``.
_BRANCH_COLOURS = ("C0", "C2", "C4", "C5")


def _check_wheelset(wheelset: str) -> None:
    if wheelset not in WHEELSET_CHOICES:
        raise ValueError(f"wheelset = {wheelset!r} is invalid: must be one of "
                         f"{', '.join(map(repr, WHEELSET_CHOICES))}")  # fmt: skip


def branch_amplitude(branch: Branch, wheelset: str = "leading") -> np.ndarray:
    """The amplitude (m) a diagram plots for each orbit of ``branch``.

    ``"leading"``: the leading wheelset's (``branch.amplitude``); ``"largest"``: the
    largest of ``branch.wheelset_amplitudes`` (every wheelset's amplitude), the leading
    wheelset's when a branch carries no per-wheelset amplitudes.
    """
    _check_wheelset(wheelset)
    w = np.asarray(branch.wheelset_amplitudes, dtype=float)
    if wheelset == "leading" or w.ndim != 2 or w.shape[0] != branch.amplitude.size:
        return np.asarray(branch.amplitude, dtype=float)
    return np.max(w, axis=1)


def hunting_bogie(branch: Branch) -> str:
    """Which bogie hunts on ``branch``: ``"front"``, ``"rear"``, ``"both"`` or ``""``.

    Per orbit, a bogie hunts mainly when its wheelsets' largest amplitude is more than
    twice the other bogie's (wheelsets 1-2 front, 3-4 rear); the branch takes the verdict
    of most of its orbits above 0.1 mm. ``""`` when the branch has no four wheelset
    amplitudes or no orbit above 0.1 mm.
    """
    w = np.asarray(branch.wheelset_amplitudes, dtype=float)
    if w.ndim != 2 or w.shape[1] != 4:
        return ""
    front, rear = w[:, :2].max(axis=1), w[:, 2:].max(axis=1)
    seen = np.maximum(front, rear) > 1e-4
    if not seen.any():
        return ""
    votes = {"rear": int(np.count_nonzero(seen & (rear > 2 * front))),
             "front": int(np.count_nonzero(seen & (front > 2 * rear)))}  # fmt: skip
    votes["both"] = int(np.count_nonzero(seen)) - votes["rear"] - votes["front"]
    return max(votes, key=lambda k: votes[k])


def _branch_name(diagram: BifurcationDiagram, n: int) -> str:
    branch = diagram.branches[n]
    name = "Hopf branch" if branch.origin == "hopf" else f"branch {n + 1}"
    who = hunting_bogie(branch)
    return f"{name} ({who} bogie{'s hunt' if who == 'both' else ' hunts'})" if who else name


def _point_p(diagram: BifurcationDiagram, amplitude: float,
             wheelset: str) -> tuple[float, float]:  # fmt: skip
    """Point P (km/h, plotted amplitude in m): where the leading wheelset's amplitude
    first crosses ``amplitude`` between two unstable orbits, as
    :meth:`BifurcationDiagram.point_p_kmh`; NaN, NaN when none does."""
    best = (math.inf, math.nan)
    for branch in diagram.branches:
        a, s, st = branch.amplitude, branch.speed_kmh, branch.stable
        shown = branch_amplitude(branch, wheelset)
        for i in range(a.size - 1):
            if (a[i] - amplitude) * (a[i + 1] - amplitude) > 0 or a[i] == a[i + 1]:
                continue
            if st[i] or st[i + 1]:
                continue
            w = (amplitude - a[i]) / (a[i + 1] - a[i])
            speed = float(s[i] + w * (s[i + 1] - s[i]))
            if speed < best[0]:
                best = (speed, float(shown[i] + w * (shown[i + 1] - shown[i])))
    return best if math.isfinite(best[0]) else (math.nan, math.nan)


def _amplitude_label(wheelset: str, short: bool = False) -> str:
    if wheelset == "largest":
        return ("largest wheelset amplitude (mm)" if short else
                "amplitude of the largest wheelset, max(y_w1..y_w4) (mm)")
    return "y_w1 amplitude (mm)" if short else "amplitude of leading wheelset y_w1 (mm)"


def _draw_diagram(ax: Axes, d: BifurcationDiagram, wheelset: str, lw: float) -> None:
    """Equilibrium, branches (stable solid, unstable dashed) and the Hopf point on ``ax``."""
    lo, hi = d.speed_range_kmh
    hopf = d.hopf_speed_kmh
    # The equilibrium lies on the amplitude axis' lower edge: drawn unclipped, on top.
    ax.plot([lo, min(hopf, hi)], [0, 0], "k-", lw=lw * 1.25, clip_on=False, zorder=4)
    if hopf < hi:
        ax.plot([hopf, hi], [0, 0], "k--", lw=lw * 0.75, clip_on=False, zorder=4)
    for n, branch in enumerate(d.branches):
        c = _BRANCH_COLOURS[n % len(_BRANCH_COLOURS)]
        amp = branch_amplitude(branch, wheelset) * 1e3
        for first, last, stable in branch.segments():
            sl = slice(first, last + 1)
            if stable:
                ax.plot(branch.speed_kmh[sl], amp[sl], "-", color=c, lw=lw)
            else:  # dashed and thin with open circles: told apart where branches run close
                n_pts = last + 1 - first
                ax.plot(branch.speed_kmh[sl], amp[sl], ls=(0, (3, 2)), color=c, lw=lw * 0.5,
                        marker="o", ms=1.6 * lw, mfc="white", mew=0.6 * lw,
                        markevery=max(1, n_pts // 20))  # fmt: skip
    ax.plot([hopf], [0], "o", color="C3", ms=4 * lw, zorder=5, clip_on=False)


def bifurcation_figure(
    diagram: BifurcationDiagram,
    point_p_amplitude: float | None = 3e-3,
    *,
    wheelset: str = "leading",
) -> Figure:
    """The figure of :func:`plot_bifurcation`, not saved."""
    _check_wheelset(wheelset)
    fig = new_figure(7.5, 5.6)
    ax = fig.add_subplot(1, 1, 1)
    lo, hi = diagram.speed_range_kmh
    hopf = diagram.hopf_speed_kmh
    _draw_diagram(ax, diagram, wheelset, 2.0)
    handles = [Line2D([], [], color="k", lw=2.5, label="equilibrium, stable"),
               Line2D([], [], color="k", ls="--", lw=1.5, label="equilibrium, unstable")]
    for n in range(len(diagram.branches)):
        c = _BRANCH_COLOURS[n % len(_BRANCH_COLOURS)]
        handles.append(Line2D([], [], color=c, lw=2,
                              label=f"{_branch_name(diagram, n)}: stable (solid) / unstable "
                              "(dashed, open circles)"))  # fmt: skip
    handles.append(Line2D([], [], ls="none", marker="o", color="C3", ms=8,
                          label=f"Hopf point A, V_lim = {hopf:.1f} km/h"))  # fmt: skip
    for branch in diagram.branches:
        shown = branch_amplitude(branch, wheelset)
        for fold in branch.folds:  # the fold's own amplitude, or the plotted one at its orbit
            amp = fold.amplitude if wheelset == "leading" else shown[fold.index]
            ax.plot([fold.speed_kmh], [amp * 1e3], "s", color="C1", ms=6, zorder=5)
    if diagram.folds:
        handles.append(Line2D([], [], ls="none", marker="s", color="C1", ms=6, label="folds"))
    v_nl = diagram.fold_speed_kmh
    if math.isfinite(v_nl):
        ax.axvline(v_nl, color="C1", lw=1.0, ls=":")
        handles.append(Line2D([], [], color="C1", lw=1.0, ls=":",
                              label=f"lowest limit cycle V_nl = {v_nl:.1f} km/h"))  # fmt: skip
    elif diagram.fold_below_range:
        handles.append(Line2D([], [], ls="none", label=f"lowest limit cycle below {lo:g} km/h "
                              "(a branch leaves the range)"))  # fmt: skip
    if point_p_amplitude is not None:
        mm = point_p_amplitude * 1e3
        vp, shown = _point_p(diagram, point_p_amplitude, wheelset)
        if wheelset == "leading":
            ax.axhline(mm, color="0.5", lw=0.8, ls=":")
            handles.append(Line2D([], [], color="0.5", lw=0.8, ls=":",
                                  label=f"{mm:g} mm disturbance of the leading wheelset"))
        if math.isfinite(vp):
            ax.plot([vp], [shown * 1e3], "D", color="C3", ms=7, zorder=6)
            handles.append(Line2D([], [], ls="none", marker="D", color="C3", ms=7,
                                  label=f"P: y_w1 = {mm:g} mm on an unstable branch, "
                                  f"{vp:.1f} km/h"))  # fmt: skip
        else:
            handles.append(Line2D([], [], ls="none", label=f"P: no unstable branch reaches "
                                  f"y_w1 = {mm:g} mm"))  # fmt: skip
    ax.set_xlim(lo, hi)
    ax.set_ylim(0.0, _top(diagram, wheelset, point_p_amplitude))
    ax.set_xlabel("speed (km/h)")
    ax.set_ylabel(_amplitude_label(wheelset))
    ax.set_title(f"Bifurcation diagram ({diagram.hopf_type} Hopf bifurcation)")
    ax.grid(True, alpha=0.3)
    fig.legend(handles=handles, loc="outside lower center", ncols=2, fontsize=7.5)
    return fig


def _top(diagram: BifurcationDiagram, wheelset: str, extra: float | None = None) -> float:
    """Upper amplitude limit (mm): 8 % above the largest plotted amplitude (at least 1 mm)."""
    amps = [float(np.max(branch_amplitude(b, wheelset))) for b in diagram.branches
            if b.amplitude.size]  # fmt: skip
    top = max([*amps, extra or 0.0, 1e-3]) * 1e3
    return 1.08 * top


def plot_bifurcation(
    diagram: BifurcationDiagram,
    path: str | os.PathLike[str],
    point_p_amplitude: float | None = 3e-3,
    *,
    wheelset: str = "leading",
) -> Path:
    """Bifurcation diagram like the paper's Fig. 7a.

    Amplitude (mm) against speed (km/h): stable limit cycles solid, unstable dashed, the
    centred equilibrium along the speed axis (stable solid up to the Hopf point, dashed
    above), the Hopf point, the folds and the lowest limit cycle V_nl marked, and the
    paper's point P where a disturbance of ``point_p_amplitude`` (m) of the leading
    wheelset meets an unstable branch. The legend sits below the axes and names, for each
    branch, the bogie whose wheelsets hunt most on it.

    Parameters
    ----------
    diagram : BifurcationDiagram
        Output of :func:`railhunt.bifurcation_diagram`.
    path : str or os.PathLike
        Output file; the format follows the suffix.
    point_p_amplitude : float or None
        Disturbance (m) that defines point P; None draws no point P.
    wheelset : {"leading", "largest"}
        The amplitude on the vertical axis: the leading wheelset's ``y_w1`` (the paper's
        output, default) or the largest of the four wheelsets'. With ``"largest"`` a
        branch on which the rear bogie hunts shows its real size instead of the leading
        wheelset's fraction of a millimetre; point P is still defined on ``y_w1`` and is
        drawn on its branch.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(bifurcation_figure(diagram, point_p_amplitude, wheelset=wheelset), path)


def plot_hunting_frequency(
    speeds_kmh: np.ndarray,
    frequency_hz: np.ndarray,
    sources: list[str],
    path: str | os.PathLike[str],
    initial_amplitude: float = 3e-3,
) -> Path:
    """Hunting frequency versus speed like the paper's Fig. 7b, the jump drawn dashed.

    Frequencies (Hz) against speed (km/h) from the hunting eigenvalue (disturbance
    decays) as circles joined by a line, from the limit cycle as squares; the jump between
    them (points Q1, Q2) dashed. ``sources`` holds ``"eigenvalue"`` or ``"limit-cycle"``
    per speed; ``initial_amplitude`` (m) is the release named in the title. Returns the
    file written (the format follows the suffix of ``path``).
    """
    return save_figure(hunting_frequency_figure(speeds_kmh, frequency_hz, sources,
                                                initial_amplitude), path)  # fmt: skip


def hunting_frequency_figure(
    speeds_kmh: np.ndarray,
    frequency_hz: np.ndarray,
    sources: list[str],
    initial_amplitude: float = 3e-3,
) -> Figure:
    """The figure of :func:`plot_hunting_frequency`, not saved."""
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
    return fig


def bifurcation_family_figure(
    family: list[tuple[float, BifurcationDiagram]],
    parameter: str = "F_u",
    unit: str = "kN",
    scale: float = 1e-3,
    *,
    wheelset: str = "leading",
) -> Figure:
    """The figure of :func:`plot_bifurcation_family`, not saved."""
    _check_wheelset(wheelset)
    if not family:
        raise ValueError("family is empty: give at least one (value, diagram) pair")
    n = len(family)
    cols = min(n, 3)
    rows = int(math.ceil(n / cols))
    fig = new_figure(4.2 * cols, 3.1 * rows + 0.9)
    axes = fig.subplots(rows, cols, sharey=True, squeeze=False)
    top = max(_top(d, wheelset) for _, d in family)
    for k, (value, d) in enumerate(family):
        ax = axes.flat[k]
        lo, hi = d.speed_range_kmh
        _draw_diagram(ax, d, wheelset, 1.6)
        if math.isfinite(d.fold_speed_kmh):
            ax.axvline(d.fold_speed_kmh, color="C1", lw=1.0, ls=":")
        text = "no blow-off" if value >= 1e8 else f"{value * scale:g} {unit}"
        v_nl = (f"V_nl {d.fold_speed_kmh:.0f} km/h" if math.isfinite(d.fold_speed_kmh)
                else "V_nl below the range")  # fmt: skip
        ax.set_title(f"{parameter} = {text}: {d.hopf_type}, {v_nl}", fontsize=9)
        ax.set_xlim(lo, hi)
        ax.set_ylim(0.0, top)
        ax.grid(True, alpha=0.3)
        if k >= n - cols:
            ax.set_xlabel("speed (km/h)", fontsize=8)
        if k % cols == 0:
            ax.set_ylabel(_amplitude_label(wheelset, short=True), fontsize=8)
        ax.tick_params(labelsize=8)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    handles = [Line2D([], [], color="k", lw=2, label="equilibrium: stable"),
               Line2D([], [], color="k", ls="--", lw=1.2, label="equilibrium: unstable"),
               Line2D([], [], color="0.3", lw=1.6, label="limit cycles: stable"),
               Line2D([], [], color="0.3", ls="--", lw=1.0, label="limit cycles: unstable"),
               Line2D([], [], color="C0", lw=1.6, label="branch born at the Hopf point"),
               Line2D([], [], color="C2", lw=1.6, label="branch from a simulated large cycle"),
               Line2D([], [], ls="none", marker="o", color="C3", label="Hopf point"),
               Line2D([], [], color="C1", ls=":", lw=1.0,
                      label="lowest limit cycle (nonlinear critical speed)")]  # fmt: skip
    fig.legend(handles=handles, loc="outside lower center", ncols=4, fontsize=7.5)
    what = "largest wheelset" if wheelset == "largest" else "leading wheelset"
    fig.suptitle(f"Bifurcation diagrams against {parameter} ({what} amplitude, one scale "
                 "for all panels)", fontsize=10)  # fmt: skip
    return fig


def plot_bifurcation_family(
    family: list[tuple[float, BifurcationDiagram]],
    path: str | os.PathLike[str],
    parameter: str = "F_u",
    unit: str = "kN",
    scale: float = 1e-3,
    *,
    wheelset: str = "leading",
) -> Path:
    """Bifurcation diagrams of a parameter family side by side, like the paper's Fig. 13.

    One panel per member: amplitude (mm) against speed (km/h), stable limit cycles solid,
    unstable dashed, the equilibrium on the speed axis, the Hopf point and the lowest limit
    cycle (dotted) marked, the type and the nonlinear critical speed in the title. All
    panels share one amplitude scale starting at 0, so that the members' cycles compare at
    a glance; one legend below the panels.

    Parameters
    ----------
    family : list of (float, BifurcationDiagram)
        Parameter value (SI) and its diagram, in panel order; a value of 1e8 or more is
        shown as "no blow-off".
    path : str or os.PathLike
        Output file; the format follows the suffix.
    parameter, unit : str
        Name of the varied parameter and the unit its value is shown in.
    scale : float
        Factor from the SI value to ``unit`` (1e-3 for N to kN).
    wheelset : {"leading", "largest"}
        Amplitude on the vertical axis, as in :func:`plot_bifurcation`.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(bifurcation_family_figure(family, parameter, unit, scale,
                                                 wheelset=wheelset), path)  # fmt: skip
