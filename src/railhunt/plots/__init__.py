"""Figures: time histories, phase planes, root loci, bifurcation diagrams, contact geometry,
parameter sweeps and their Table 1 sections, stability maps and curve entries.

Everything is drawn on :class:`matplotlib.figure.Figure` objects rendered by the Agg
canvas, so no GUI backend (and no global ``pyplot`` state) is ever involved; the functions
are safe to call from scripts, tests and worker processes without a display.

Units on the axes are the engineer's units, not SI: lateral displacements in mm, lateral
velocities in mm/s, times in s, frequencies in Hz, speeds in km/h and swept parameters in
the paper's Table 1 units (kN*s/m, MN/m, MN); curve radii and distances in m, forces in kN.
"""

from railhunt.plots.contact import plot_contact_geometry
from railhunt.plots.curves import plot_curve_entry, plot_stability_map
from railhunt.plots.figure import PHASE_FROM, new_figure, save_figure
from railhunt.plots.stability import (
    plot_bifurcation,
    plot_bifurcation_family,
    plot_hunting_frequency,
    plot_root_locus,
)
from railhunt.plots.studies import plot_sections, plot_sweep
from railhunt.plots.time import (
    plot_damper_histories,
    plot_damper_velocity,
    plot_time_histories,
    plot_time_history,
)

__all__ = [
    "PHASE_FROM",
    "new_figure",
    "plot_bifurcation",
    "plot_bifurcation_family",
    "plot_contact_geometry",
    "plot_curve_entry",
    "plot_damper_histories",
    "plot_damper_velocity",
    "plot_hunting_frequency",
    "plot_root_locus",
    "plot_sections",
    "plot_stability_map",
    "plot_sweep",
    "plot_time_histories",
    "plot_time_history",
    "save_figure",
]
