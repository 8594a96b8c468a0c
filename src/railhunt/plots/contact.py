"""Contact geometry from profiles: rolling-radius difference, contact angles, roll."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:

    pass


from railhunt.plots.figure import new_figure, save_figure


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
    fig = new_figure(10.0, 7.0)
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
    return save_figure(fig, path)


# --------------------------------------------------------------------------- parameter studies
