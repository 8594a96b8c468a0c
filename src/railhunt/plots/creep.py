"""Creep-force curves of the creep laws on one patch: force and spin moment against creepage."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from railhunt.plots.figure import new_figure, save_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from railhunt.mechanics.curves import CreepCurves

#: Line style per law: the exact theory black and thick, the FASTSIM laws in blues.
STYLES = {
    "exact": {"color": "k", "lw": 2.2},
    "fastsim-modified": {"color": "tab:blue", "lw": 1.5},
    "fastsim": {"color": "tab:cyan", "lw": 1.3, "ls": "--"},
    "polach": {"color": "tab:orange", "lw": 1.3},
    "heuristic": {"color": "tab:red", "lw": 1.3, "ls": "-."},
    "vermeulen-johnson": {"color": "tab:purple", "lw": 1.3, "ls": ":"},
    "linear": {"color": "0.55", "lw": 1.0, "ls": (0, (5, 2, 1, 2))},
}
_LABELS = {"xi": r"longitudinal creepage $\xi$ (‰)", "eta": r"lateral creepage $\eta$ (‰)",
           "phi": r"spin creepage $\varphi$ (1/m)"}


def creep_figure(curves: CreepCurves) -> Figure:
    """The figure of :func:`plot_creep_curves`, not saved."""
    cv = curves
    scale = 1.0 if cv.sweep == "phi" else 1e3
    x = cv.values * scale
    mu_n = cv.mu * cv.normal_force
    fig = new_figure(10.0, 4.2)
    ax_f, ax_m = fig.subplots(1, 2, sharex=True)
    force = "fx" if cv.sweep == "xi" else "fy"
    for law in cv.laws:
        style = STYLES.get(law, {})
        values = cv.fx[law] if force == "fx" else cv.fy[law]
        ax_f.plot(x, values / mu_n, label=law, **style)
        ax_m.plot(x, cv.mz[law] / (mu_n * cv.c), label=law, **style)
    name = "F_x" if force == "fx" else "F_y"
    ax_f.set_ylabel(rf"${name} / \mu N$")
    ax_m.set_ylabel(r"$M_z / (\mu N c)$")
    for ax, title in ((ax_f, "(a) creep force"), (ax_m, "(b) spin moment")):
        ax.set_xlabel(_LABELS[cv.sweep])
        ax.set_title(title, loc="left", fontsize="medium")
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="0.6", lw=0.6)
    # the laws bounded by mu N set the force axis; the linear law, and Vermeulen-Johnson's
    # spin force, may run off it
    bounded = [law for law in cv.laws if law not in ("linear", "vermeulen-johnson")]
    if bounded and len(bounded) < len(cv.laws):
        peak = max(float(abs((cv.fx if force == "fx" else cv.fy)[law]).max()) / mu_n
                   for law in bounded)
        ax_f.set_ylim(-1.15 * max(peak, 1.0), 1.15 * max(peak, 1.0))
    ax_f.axhline(1.0, color="0.6", lw=0.6, ls=":")
    ax_f.axhline(-1.0, color="0.6", lw=0.6, ls=":")
    fixed = ", ".join(
        (rf"$\varphi$ = {v:g} 1/m" if k == "phi" else rf"$\{k}$ = {v * 1e3:g} ‰")
        for k, v in cv.fixed.items())
    fig.suptitle(f"a = {cv.a * 1e3:.3g} mm, b = {cv.b * 1e3:.3g} mm, N = "
                 f"{cv.normal_force / 1e3:.4g} kN, μ = {cv.mu:g}; {fixed}", fontsize="medium")
    ax_m.legend(fontsize="small", loc="best")
    return fig


def plot_creep_curves(curves: CreepCurves, path: str | os.PathLike[str]) -> Path:
    """Save the creep-force curves (force and spin moment, normalised by ``mu N`` and
    ``mu N c``, one line per law) to ``path``; returns the path."""
    return save_figure(creep_figure(curves), path)
