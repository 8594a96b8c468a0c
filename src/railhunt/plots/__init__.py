"""Figures: time histories, phase planes, root loci, bifurcation diagrams, contact geometry,
parameter sweeps and their Table 1 sections, stability maps, curve entries, spectrograms,
creep-force curves.

Everything is drawn on :class:`matplotlib.figure.Figure` objects rendered by the Agg
canvas, so no GUI backend (and no global ``pyplot`` state) is ever involved; the functions
are safe to call from scripts, tests and worker processes without a display.

Each ``plot_X(..., path)`` saves a figure to a file and returns the path; its
``X_figure(...)`` returns the same figure unsaved (for a notebook, or to adjust it), and is
what the image-comparison tests (tests/test_figures.py) compare with their baselines.

Units on the axes are the engineer's units, not SI: lateral displacements in mm, lateral
velocities in mm/s, times in s, frequencies in Hz, speeds in km/h and swept parameters in
the paper's Table 1 units (kN*s/m, MN/m, MN); curve radii and distances in m, forces in kN.
"""

from railhunt.plots.contact import (
    conicity_histogram_figure,
    contact_geometry_figure,
    plot_conicity_histogram,
    plot_contact_geometry,
)
from railhunt.plots.creep import creep_figure, plot_creep_curves
from railhunt.plots.curves import (
    curve_entry_figure,
    plot_curve_entry,
    plot_stability_map,
    stability_map_figure,
)
from railhunt.plots.figure import PHASE_FROM, new_figure, save_figure
from railhunt.plots.patches import contact_patches_figure, plot_contact_patches
from railhunt.plots.spectrogram import plot_spectrogram, spectrogram_figure
from railhunt.plots.stability import (
    WHEELSET_CHOICES,
    bifurcation_family_figure,
    bifurcation_figure,
    hunting_frequency_figure,
    plot_bifurcation,
    plot_bifurcation_family,
    plot_hunting_frequency,
    plot_root_locus,
    root_locus_figure,
)
from railhunt.plots.studies import plot_sections, plot_sweep, sections_figure, sweep_figure
from railhunt.plots.time import (
    damper_histories_figure,
    plot_damper_histories,
    plot_damper_velocity,
    plot_time_histories,
    plot_time_history,
    time_histories_figure,
    time_history_figure,
)

__all__ = [
    "PHASE_FROM",
    "WHEELSET_CHOICES",
    "bifurcation_family_figure",
    "bifurcation_figure",
    "conicity_histogram_figure",
    "contact_geometry_figure",
    "contact_patches_figure",
    "creep_figure",
    "curve_entry_figure",
    "damper_histories_figure",
    "hunting_frequency_figure",
    "new_figure",
    "plot_bifurcation",
    "plot_bifurcation_family",
    "plot_conicity_histogram",
    "plot_contact_geometry",
    "plot_contact_patches",
    "plot_creep_curves",
    "plot_curve_entry",
    "plot_damper_histories",
    "plot_damper_velocity",
    "plot_hunting_frequency",
    "plot_root_locus",
    "plot_sections",
    "plot_spectrogram",
    "plot_stability_map",
    "plot_sweep",
    "plot_time_histories",
    "plot_time_history",
    "root_locus_figure",
    "save_figure",
    "sections_figure",
    "spectrogram_figure",
    "stability_map_figure",
    "sweep_figure",
    "time_histories_figure",
    "time_history_figure",
]
