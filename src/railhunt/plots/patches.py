"""The contact-point chart of a wheelset's contact patches along its lateral displacement."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from matplotlib.lines import Line2D

from railhunt.plots.contact import LEFT, RIGHT, inclination_text
from railhunt.plots.figure import new_figure, save_figure

if TYPE_CHECKING:
    from collections.abc import Sequence

    from matplotlib.figure import Figure

    from railhunt.contact.patches import WheelsetContact


def contact_patches_figure(contacts: Sequence[WheelsetContact]) -> Figure:
    """The figure of :func:`plot_contact_patches`, not saved."""
    if not contacts:
        raise ValueError("contacts is empty: give the patches of at least one displacement")
    fig = new_figure(10.0, 7.5)
    axes = fig.subplots(2, 2, sharex=True)
    panels = ((axes[0, 0], "(a) contact point on the wheel profile (mm)", "wheel_y", 1e3),
              (axes[0, 1], "(b) rolling radius (mm)", "rolling_radius", 1e3),
              (axes[1, 0], "(c) contact lead ahead of the axle (mm)", "x", 1e3),
              (axes[1, 1], "(d) share of the wheel load (%)", None, 100.0))  # fmt: skip
    loaded = any(p.normal_force > 0 for c in contacts for p in c.left + c.right)
    for ax, title, name, scale in panels:
        for side, colour in (("left", LEFT), ("right", RIGHT)):
            for rank, marker in ((0, "o"), (1, "^")):
                ys, vals, sizes = [], [], []
                for c in contacts:
                    patches = getattr(c, side)
                    if len(patches) <= rank:
                        continue
                    p = patches[rank]
                    total = sum(q.vertical_load for q in patches)
                    share = p.vertical_load / total if total > 0 else 1.0
                    value = share if name is None else getattr(p, name)
                    ys.append(c.y * 1e3)
                    vals.append(value * scale)
                    sizes.append(4.0 + 26.0 * share if loaded else 8.0)
                if ys:
                    ax.scatter(ys, vals, s=sizes, color=colour, marker=marker, lw=0,
                               alpha=0.85 if rank == 0 else 1.0)  # fmt: skip
        ax.set_title(title, loc="left", fontsize="medium")
        ax.grid(True, alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("lateral wheelset displacement y (mm), + left")
    handles = [Line2D([], [], color=LEFT, marker="o", ls="", label="left wheel, patch 1"),
               Line2D([], [], color=LEFT, marker="^", ls="", label="left wheel, patch 2"),
               Line2D([], [], color=RIGHT, marker="o", ls="", label="right wheel, patch 1"),
               Line2D([], [], color=RIGHT, marker="^", ls="", label="right wheel, patch 2")]
    fig.legend(handles=handles, loc="outside lower center", ncols=4, fontsize="small")
    c0 = contacts[0]
    p = c0.params
    load = p.get("normal_load")
    tail = (f", wheel load {load[0] * 1e-3:.4g} kN (marker size: share)" if load else "")
    fig.suptitle(f"{p.get('wheel', '')} on {p.get('rail', '')}, inclination "
                 f"{inclination_text(p.get('rail_inclination', 0.0))}, yaw "
                 f"{c0.yaw * 1e3:.3g} mrad{tail}")  # fmt: skip
    return fig


def plot_contact_patches(contacts: Sequence[WheelsetContact],
                         path: str | os.PathLike[str]) -> Path:  # fmt: skip
    """Plot a wheelset's contact patches against its lateral displacement.

    Four panels against y (mm), every patch a marker (circle: the lowest gap, triangle: a
    second patch; left blue, right orange), sized by its share of the wheel load when the
    patches carry one: (a) the contact point on the wheel profile (mm, profile axes),
    (b) the rolling radius (mm), (c) the lead ahead of the axle (mm; 0 without yaw),
    (d) the patch's share of the wheel load (%).

    Parameters
    ----------
    contacts : sequence of WheelsetContact
        The patches at each displacement, e.g. from
        :func:`railhunt.contact.patches.contact_patches_along`.
    path : str or os.PathLike
        Output file; the format follows the suffix.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    return save_figure(contact_patches_figure(contacts), path)
