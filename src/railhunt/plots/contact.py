"""Contact geometry from profiles: rolling radii, contact angles, roll, contact positions."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.lines import Line2D

from railhunt.plots.figure import new_figure, save_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from railhunt.contact.geometry import ContactGeometry

#: Colours of the left and right wheel (and rail) in every panel.
LEFT, RIGHT = "tab:blue", "tab:orange"
#: Colour of the contact-point jump lines.
JUMP = "0.45"


def contact_geometry_figure(geometry: ContactGeometry) -> Figure:
    """The figure of :func:`plot_contact_geometry`, not saved."""
    g = geometry
    y = g.y * 1e3
    fig = new_figure(10.0, 9.0)
    axes = fig.subplots(3, 2, sharex=True)
    panels = (
        (axes[0, 0], "(a) rolling radius (mm)", g.r_left * 1e3, g.r_right * 1e3),
        (axes[0, 1], r"(b) rolling-radius difference $\Delta r = r_L - r_R$ (mm)",
         g.delta_r * 1e3, None),
        (axes[1, 0], "(c) contact angle (deg)", np.degrees(g.delta_left),
         np.degrees(g.delta_right)),
        (axes[1, 1], "(d) wheelset roll (mrad)", g.roll * 1e3, None),
        (axes[2, 0], "(e) contact point on the wheel profile (mm)", g.wheel_left * 1e3,
         g.wheel_right * 1e3),
        (axes[2, 1], "(f) contact point on the rail profile (mm)", g.rail_left * 1e3,
         g.rail_right * 1e3),
    )  # fmt: skip
    jumps = y[np.asarray(g.jump, dtype=bool)]
    for ax, title, left, right in panels:
        if right is None:
            ax.plot(y, left, color="k", lw=1.3)
        else:
            ax.plot(y, left, color=LEFT, lw=1.3)
            ax.plot(y, right, color=RIGHT, lw=1.3)
        ax.set_title(title, loc="left", fontsize="medium")
        ax.grid(True, alpha=0.3)
        for yj in jumps:
            ax.axvline(yj, color=JUMP, linestyle=":", linewidth=0.9, zorder=0)
    for ax in axes[0]:  # the jumps' positions, once, above the top panels
        for yj in jumps:
            ax.annotate(f"{yj:+.1f}", (yj, 1.0), xycoords=("data", "axes fraction"),
                        xytext=(-2 if yj < 0 else 2, -3), textcoords="offset points",
                        rotation=90, ha="right" if yj < 0 else "left", va="top",
                        fontsize=7, color=JUMP)  # fmt: skip
    for ax in axes[2]:
        ax.set_xlabel("lateral wheelset displacement y (mm), + left")
    handles = [Line2D([], [], color=LEFT, lw=1.3, label="left wheel / rail"),
               Line2D([], [], color=RIGHT, lw=1.3, label="right wheel / rail"),
               Line2D([], [], color="k", lw=1.3, label="wheelset"),
               Line2D([], [], color=JUMP, ls=":", lw=0.9,
                      label="contact-point jump (two-point contact) at y (mm)")]  # fmt: skip
    fig.legend(handles=handles, loc="outside lower center", ncols=4, fontsize="small")
    p = g.params
    fig.suptitle(f"{p.get('wheel', '')} on {p.get('rail', '')}, inclination "
                 f"{inclination_text(p.get('rail_inclination', 0.0))}, gauge "
                 f"{p.get('gauge', 0) * 1e3:g} mm, {_conicity_text(g)}")  # fmt: skip
    return fig


def inclination_text(tangent: float) -> str:
    """A rail inclination as engineers write it: ``1:40`` for 0.025, ``none`` for 0
    (a tangent that is not 1:n for a whole n is written as ``1:37.5``)."""
    if not tangent:
        return "none"
    n = 1.0 / float(tangent)
    return f"1:{n:.0f}" if abs(n - round(n)) < 1e-6 else f"1:{n:.3g}"


def _conicity_text(g: ContactGeometry, amplitude: float = 3e-3) -> str:
    """The EN 15302 equivalent conicity at ``amplitude`` (m), or why it has none."""
    from railhunt.contact.conicity import ConicityError, equivalent_conicity

    try:
        value = equivalent_conicity(g.y, g.delta_r, amplitude)
    except (ConicityError, ValueError):
        return f"equivalent conicity at {amplitude * 1e3:g} mm: not defined"
    return f"equivalent conicity {value:.3f} at {amplitude * 1e3:g} mm (EN 15302)"


def plot_contact_geometry(geometry: ContactGeometry, path: str | os.PathLike[str]) -> Path:
    """Plot a wheelset's contact geometry against its lateral displacement.

    Six panels, one unit per axis, against the lateral displacement y (mm): (a) rolling
    radii ``r_L``, ``r_R`` (mm); (b) the rolling-radius difference ``Delta r`` (mm); (c)
    contact angles ``delta_L``, ``delta_R`` (deg); (d) wheelset roll (mrad); (e), (f) the
    contact point's lateral position on each wheel and rail profile (mm, profile axes).
    Left is blue, right orange in every panel. Contact-point jumps (two-point contact) are
    dotted vertical lines, their y written at the top. One legend, below the panels.

    Parameters
    ----------
    geometry : railhunt.contact.geometry.ContactGeometry
        The table to plot.
    path : str or os.PathLike
        Output file; the format follows the suffix.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(contact_geometry_figure(geometry), path)


def conicity_histogram_figure(names: list[str], conicities: list[float],
                              amplitude: float = 3e-3) -> Figure:  # fmt: skip
    """The figure of :func:`plot_conicity_histogram`, not saved."""
    values = np.array([v for v in conicities if np.isfinite(v)], dtype=float)
    fig = new_figure(6.5, 3.6)
    ax = fig.subplots()
    top = max(0.6, float(values.max()) + 0.05) if values.size else 0.6
    bins = np.arange(0.0, top + 0.025, 0.025)
    ax.hist(values, bins=bins, color=LEFT, edgecolor="white")
    ax.set_xlabel(f"equivalent conicity at {amplitude * 1e3:g} mm (EN 15302)")
    ax.set_ylabel("wheelsets")
    ax.yaxis.get_major_locator().set_params(integer=True)
    if len(names) <= 12:
        for name, value in zip(names, conicities, strict=True):
            if np.isfinite(value):
                ax.annotate(name, (value, 0), xytext=(0, 4), textcoords="offset points",
                            rotation=90, fontsize=7, ha="center", va="bottom")  # fmt: skip
    ax.set_title(f"{len(names)} wheelset{'s' if len(names) != 1 else ''}", fontsize=9)
    return fig


def plot_conicity_histogram(names: list[str], conicities: list[float],
                            path: str | os.PathLike[str],
                            amplitude: float = 3e-3) -> Path:  # fmt: skip
    """Histogram of a fleet's equivalent conicities (bins of 0.025), each wheel named
    (up to 12) at its value.

    Parameters
    ----------
    names : list of str
        The wheels.
    conicities : list of float
        Their equivalent conicities (NaN: left out).
    path : str or os.PathLike
        Output file; the format follows the suffix.
    amplitude : float
        The amplitude (m) they are taken at, for the axis label.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(conicity_histogram_figure(names, conicities, amplitude), path)
