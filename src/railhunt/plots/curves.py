"""Curved track: the stability map (critical speeds against the radius) and a curve entry
(wheelset displacements, yaw-damper forces against the blow-off force, Y/Q)."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from railhunt.plots.figure import new_figure, save_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from railhunt.curve import Curve
    from railhunt.simulation import SimulationResult
    from railhunt.vehicle import Vehicle

__all__ = ["curve_entry_figure", "deficiency_speed_kmh", "plot_curve_entry", "plot_stability_map",
           "stability_map_figure"]

#: Cant deficiency (m) of the dashed reference line of the stability map: 150 mm, about
#: the limit of cant deficiency allowed for conventional vehicles on high-speed lines.
REFERENCE_DEFICIENCY = 0.150
#: Where straight track sits on the radius axis: this factor times the largest finite radius.
_STRAIGHT_AT = 2.0


def deficiency_speed_kmh(radius: np.ndarray | float, cant: float,
                         cant_deficiency: float = REFERENCE_DEFICIENCY, g: float = 9.81,
                         ) -> np.ndarray:  # fmt: skip
    """Speed (km/h) at which a curve of ``radius`` (m) and ``cant`` (m) reaches
    ``cant_deficiency`` (m), over the 1500 mm rail-centre distance.

    Solves :meth:`railhunt.Curve.cant_deficiency` ``= cant_deficiency`` for the speed:
    ``v^2 = R (g sin(phi) + g h_d / s) / cos(phi)`` with ``sin(phi) = cant / s``.
    """
    from railhunt.curve import RAIL_CENTRE_DISTANCE
    from railhunt.units import ms_to_kmh

    s = RAIL_CENTRE_DISTANCE
    phi = math.asin(cant / s)
    a = g * math.sin(phi) + g * cant_deficiency / s
    return ms_to_kmh(np.sqrt(np.asarray(radius, dtype=float) * a / math.cos(phi)))


def _map_results(results: Any) -> Any:
    """A :class:`~railhunt.studies.store.SweepResults` from results or their file."""
    if isinstance(results, str | os.PathLike):
        from railhunt.studies.store import read_results

        return read_results(results)
    return results


def plot_stability_map(results: Any, path: str | os.PathLike[str]) -> Path:
    """Linear and nonlinear critical speed against the curve radius (a stability map).

    The radius (m) on a logarithmic axis, straight track (``radius = inf``) at the right
    edge past a break; the nonlinear critical speed (the bisection over a defect in the
    curve) black, the linear one (Hopf point of the curving equilibrium) blue, both in
    km/h. A radius whose search found no critical speed is marked by a triangle at the top
    (stable at every speed tried), one that failed by a cross at the bottom. With a fixed
    cant the grey dashed line is the speed at which the cant deficiency reaches 150 mm.

    Parameters
    ----------
    results : SweepResults or path-like
        Output of :func:`railhunt.stability_map`, or its results file.
    path : str or os.PathLike
        Output file; the format follows the suffix.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(stability_map_figure(results), path)


def stability_map_figure(results: Any) -> Figure:
    """The figure of :func:`plot_stability_map`, not saved."""
    res = _map_results(results)
    if not len(res):
        raise ValueError("the stability map has no rows: nothing to plot")
    cols = res.columns
    radius = res.column("radius_m")
    finite = np.isfinite(radius)
    top = float(radius[finite].max()) if finite.any() else 1000.0
    low = float(radius[finite].min()) if finite.any() else 1000.0
    straight_x = top * _STRAIGHT_AT
    x = np.where(finite, radius, straight_x)
    status = res.column("status")

    fig = new_figure(7.5, 5.4)
    ax = fig.add_subplot(1, 1, 1)
    series = (("critical_speed_kmh", "nonlinear critical speed (defect in the curve)", "k",
               "s", "-"),
              ("linear_critical_speed_kmh", "linear critical speed (Hopf point)", "tab:blue",
               "o", "--"))  # fmt: skip
    shown = [s for s in series if s[0] in cols]
    nothing = False
    for n, (col, label, colour, marker, ls) in enumerate(shown):
        v = res.column(col)
        ok = np.isfinite(v)
        curve_pts = ok & finite
        ax.plot(x[curve_pts], v[curve_pts], ls=ls, marker=marker, color=colour, ms=5,
                label=label)  # fmt: skip
        straight = ok & ~finite
        ax.plot(x[straight], v[straight], ls="none", marker=marker, color=colour, ms=6)
        if curve_pts.any() and straight.any():  # dotted across the break to straight track
            last = np.flatnonzero(curve_pts)[np.argmax(x[curve_pts])]
            ax.plot([x[last], straight_x], [v[last], v[straight][0]], ls=":", color=colour,
                    lw=0.9)  # fmt: skip
        missing = ~ok
        none = missing & np.array([s != "failed" for s in status])
        if none.any():  # above the top edge, off the speed scale: not a speed
            ax.plot(x[none], np.full(int(none.sum()), 1.03 + 0.045 * n), ls="none",
                    marker="^", color=colour, ms=7, mfc="none", mew=1.5,
                    transform=ax.get_xaxis_transform(), clip_on=False)  # fmt: skip
            nothing = True
    limit = np.array([_limit_kmh(str(row.get("message", ""))) for row in res.rows])
    if np.isfinite(limit).any():
        ax.plot(x[np.isfinite(limit)], limit[np.isfinite(limit)], ls="none", marker="_",
                color="r", ms=14, mew=2.0, label="curving limit: first limit of the "
                "validity envelope (searches stop there)")  # fmt: skip
    if nothing:
        ax.plot([], [], ls="none", marker="^", color="0.4", ms=7, mfc="none", mew=1.5,
                label="none found (above the frame): stable at every speed tried"
                if not np.isfinite(limit).any()
                else "none found (above the frame) below the curving limit")  # fmt: skip
    failed = np.array([s == "failed" for s in status])
    if failed.any():
        ax.plot(x[failed], np.full(int(failed.sum()), 0.03), ls="none", marker="x", color="r",
                ms=7, transform=ax.get_xaxis_transform(), label="failed (see the table)")
    meta = getattr(res, "meta", {}) or {}
    cant = meta.get("cant_m")
    if cant is None and "cant_m" in cols:
        values = res.column("cant_m")
        cant = float(np.max(values)) if values.size else None
    g = float(meta.get("vehicle", {}).get("parameters", {}).get("g", 9.81))
    reference = np.array([])
    if cant is not None and finite.any():
        grid = np.geomspace(low / 1.15, top * 1.15, 100)
        reference = deficiency_speed_kmh(grid, float(cant), g=g)
        ax.plot(grid, reference, ls="--", color="0.5",
                lw=1.2, label=f"cant deficiency {REFERENCE_DEFICIENCY * 1e3:.0f} mm "
                f"(cant {float(cant) * 1e3:g} mm)")  # fmt: skip
    _radius_axis(ax, radius[finite], straight_x, bool((~finite).any()))
    # The speed axis holds the critical speeds, the curving limits and the whole reference
    # line (which in tight curves runs far below them).
    speeds = [res.column(c) for c, *_ in shown] + [reference, limit]
    finite_speeds = np.concatenate([s[np.isfinite(s)] for s in speeds]) if speeds else []
    if len(finite_speeds):
        ax.set_ylim(max(0.0, 0.8 * float(np.min(finite_speeds))),
                    1.12 * float(np.max(finite_speeds)))  # fmt: skip
    ax.set_ylabel("critical speed (km/h)")
    if "cant_deficiency_m" in meta:
        what = f"cant deficiency held at {meta['cant_deficiency_m'] * 1e3:g} mm"
    else:
        what = f"cant {float(cant or 0.0) * 1e3:g} mm"
    ax.set_title(f"stability map: critical speed against curve radius ({what})", loc="left",
                 fontsize="medium")  # fmt: skip
    ax.grid(True, which="both", alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, fontsize="small")
    return fig


def _limit_kmh(message: str) -> float:
    """The speed of "curving limit at X km/h" in a stability map row's message (NaN)."""
    import re

    found = re.search(r"curving limit at ([0-9.]+) km/h", message)
    return float(found.group(1)) if found else math.nan


def _radius_axis(ax: Axes, radii: np.ndarray, straight_x: float, straight: bool) -> None:
    """Logarithmic radius axis in m, ticks at the finite ``radii``; straight track labelled
    at ``straight_x`` past a break (two slashes on the axis)."""
    from matplotlib.ticker import FixedLocator, NullFormatter, NullLocator

    radii = np.unique(radii)
    low, top = (float(radii.min()), float(radii.max())) if radii.size else (1000.0, 1000.0)
    ax.set_xscale("log")
    right = straight_x * 1.25 if straight else top * 1.25
    ax.set_xlim(low / 1.25, right)
    ticks = [float(r) for r in radii]
    if len(ticks) > 8:
        ticks = [r for r in (50, 100, 200, 300, 500, 1000, 2000, 3000, 5000, 10000, 20000,
                             50000, 100000, 200000, 500000, 1e6) if low / 1.25 <= r <= top * 1.25]
    labels = [f"{r:g}" for r in ticks]
    if straight:
        ticks.append(straight_x)
        labels.append("straight")
        brk = math.sqrt(top * straight_x)
        for dx in (0.985, 1.015):
            ax.plot([brk * dx / 1.02, brk * dx * 1.02], [-0.02, 0.02], color="k", lw=1.0,
                    transform=ax.get_xaxis_transform(), clip_on=False)  # fmt: skip
    ax.xaxis.set_major_locator(FixedLocator(ticks))
    ax.set_xticklabels(labels)
    ax.xaxis.set_minor_locator(NullLocator())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("curve radius R (m)")


def plot_curve_entry(run: SimulationResult, vehicle: Vehicle, path: str | os.PathLike[str],
                     *, curve: Curve | None = None,
                     without_blowoff: SimulationResult | None = None) -> Path:  # fmt: skip
    """A run through a curve entry: wheelsets, yaw dampers and the leading wheelset's Y/Q.

    Against the distance the leading wheelset has travelled (m): (a) the lateral
    displacement of each wheelset relative to the track (mm); (b) the force of each yaw
    damper (kN) with the blow-off force ``±F_u`` as dashed lines; (c) the derailment
    quotient Y/Q of the leading wheelset's left and right wheel. The entry transition of
    ``curve`` (as the leading wheelset meets it) is shaded.

    Parameters
    ----------
    run : SimulationResult
        A run of :func:`railhunt.simulate` with ``curve=`` (it has the channels
        ``F_d1``.., ``YQ_w1L``, ``YQ_w1R``).
    vehicle : Vehicle
        The vehicle of the run (its blow-off force ``F_u``).
    path : str or os.PathLike
        Output file; the format follows the suffix.
    curve : Curve, optional
        The run's curve: shades its entry transition and names it in the title.
    without_blowoff : SimulationResult, optional
        The same run with the blow-off switched off (``F_u`` = ``NO_BLOWOFF``): its damper
        forces and Y/Q are drawn grey for comparison.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(curve_entry_figure(run, vehicle, curve=curve,
                                          without_blowoff=without_blowoff), path)  # fmt: skip


def curve_entry_figure(run: SimulationResult, vehicle: Vehicle, *, curve: Curve | None = None,
                       without_blowoff: SimulationResult | None = None) -> Figure:  # fmt: skip
    """The figure of :func:`plot_curve_entry`, not saved."""
    from railhunt.paper2019 import NO_BLOWOFF

    fig = new_figure(8.0, 8.6)
    ax_y, ax_f, ax_q = fig.subplots(3, 1, sharex=True)
    s = run.speed * np.asarray(run.t)
    n_wheelsets = sum(1 for k in range(1, 9) if f"y_w{k}" in run.channel_names)
    n_dampers = sum(1 for k in range(1, 9) if f"F_d{k}" in run.channel_names)
    colours = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")
    for k in range(1, n_wheelsets + 1):
        ax_y.plot(s, run[f"y_w{k}"] * 1e3, color=colours[(k - 1) % 6], lw=1.0,
                  label=f"wheelset {k}")  # fmt: skip
    ax_y.set_ylabel("lateral displacement\nrelative to the track (mm)")
    ax_y.set_title("(a) wheelsets", loc="left", fontsize="medium")

    if without_blowoff is not None:
        s0 = without_blowoff.speed * np.asarray(without_blowoff.t)
        for k in range(1, n_dampers + 1):
            ax_f.plot(s0, without_blowoff[f"F_d{k}"] * 1e-3, color="0.6", lw=0.9,
                      label="no blow-off" if k == 1 else None)  # fmt: skip
        ax_q.plot(s0, without_blowoff["YQ_w1L"], color="0.6", lw=0.9, ls="--")
        ax_q.plot(s0, without_blowoff["YQ_w1R"], color="0.6", lw=0.9,
                  label="right / left wheel, no blow-off")  # fmt: skip
    for k in range(1, n_dampers + 1):
        ax_f.plot(s, run[f"F_d{k}"] * 1e-3, color=colours[(k - 1) % 6], lw=1.0,
                  label=f"F_d{k}")  # fmt: skip
    f_u = vehicle.blowoff_force
    if f_u < NO_BLOWOFF:  # NaN (no yaw damper) draws no line
        for sign in (1, -1):
            ax_f.axhline(sign * f_u * 1e-3, color="k", ls="--", lw=1.0,
                         label=f"blow-off force F_u = {f_u * 1e-3:g} kN"
                         if sign > 0 else None)  # fmt: skip
    ax_f.set_ylabel("yaw damper force (kN)")
    ax_f.set_title("(b) yaw dampers", loc="left", fontsize="medium")

    ax_q.plot(s, run["YQ_w1L"], color="tab:blue", lw=1.0, ls="--", label="left wheel")
    ax_q.plot(s, run["YQ_w1R"], color="tab:red", lw=1.0, label="right wheel")
    from railhunt.validity import YQ_LIMIT

    ax_q.axhline(YQ_LIMIT, color="k", ls=":", lw=1.0,
                 label=f"Nadal limit Y/Q = {YQ_LIMIT:g} (EN 14363)")  # fmt: skip
    ax_q.set_ylabel("Y/Q of the leading wheelset")
    ax_q.set_title("(c) derailment quotient", loc="left", fontsize="medium")
    ax_q.set_xlabel("distance travelled by the leading wheelset (m)")

    title = f"curve entry at {run.speed_kmh:g} km/h"
    if curve is not None:
        title += (f": R = {curve.radius:g} m, cant {curve.cant * 1e3:g} mm, transition "
                  f"{curve.transition:g} m")
        for ax in (ax_y, ax_f, ax_q):
            ax.axvspan(curve.start, curve.start + curve.transition, color="0.9", zorder=0,
                       label="entry transition (leading wheelset)" if ax is ax_y
                       else None)  # fmt: skip
    if run.status != "ok":
        title += f" ({run.status})"
    fig.suptitle(title)
    for ax in (ax_y, ax_f, ax_q):
        ax.axhline(0.0, color="0.5", lw=0.5)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="x-small", loc="best", ncols=2)
    return fig
