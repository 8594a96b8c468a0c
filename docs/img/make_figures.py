"""Regenerate the figures of docs/curves.md (run from the repository root)::

    python docs/img/make_figures.py            # both figures
    python docs/img/make_figures.py --entry    # only the curve entry

``stability_map.png``: linear and nonlinear critical speed of the paper's vehicle in curves
of 2000, 4000 and 8000 m with 150 mm cant, and on straight track
(:func:`railhunt.stability_map`, :func:`railhunt.plots.plot_stability_map`).

``curve_entry.png``: the paper's vehicle at 80 km/h into a 300 m curve with 150 mm cant
through a 40 m transition, with the yaw damper's blow-off (F_u = 3 kN) and without it
(F_u = ``railhunt.paper2019.NO_BLOWOFF``, grey) (:func:`railhunt.simulate`,
:func:`railhunt.plots.plot_curve_entry`). Prints the peak yaw damper force of both runs.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

import railhunt
from railhunt.paper2019 import NO_BLOWOFF
from railhunt.plots import plot_curve_entry, plot_stability_map
from railhunt.units import kmh_to_ms

HERE = Path(__file__).resolve().parent
RADII = (2000.0, 4000.0, 8000.0, math.inf)  # m
CANT = 0.15  # m
ENTRY = railhunt.Curve(300.0, cant=CANT, transition=40.0, start=30.0)
ENTRY_SPEED_KMH = 80.0


def stability_map_figure(vehicle: railhunt.Vehicle) -> Path:
    """The stability map (one process: four radii take a few seconds)."""
    results = railhunt.stability_map(vehicle, RADII, CANT, workers=1)
    for row in results.rows:
        print(f"R = {row['radius_m']:g} m: nonlinear {row['critical_speed_kmh']:.0f} km/h, "
              f"linear {row['linear_critical_speed_kmh']:.1f} km/h {row['message']}")
    return plot_stability_map(results, HERE / "stability_map.png")


def curve_entry_figure(vehicle: railhunt.Vehicle) -> Path:
    """The tight curve entry with and without the blow-off."""
    length = ENTRY.start + ENTRY.transition + 2 * (vehicle.l + vehicle.l1) + 40.0
    duration = length / kmh_to_ms(ENTRY_SPEED_KMH)
    runs = {}
    for label, v in (("with blow-off", vehicle), ("without", vehicle.replace(F_u=NO_BLOWOFF))):
        runs[label] = railhunt.simulate(v, ENTRY_SPEED_KMH, duration=duration, curve=ENTRY)
        peak = np.max(np.abs([runs[label][f"F_d{k}"] for k in range(1, 5)]))
        print(f"curve entry {label}: peak yaw damper force {peak * 1e-3:.2f} kN "
              f"({runs[label].status})")
    return plot_curve_entry(runs["with blow-off"], vehicle, HERE / "curve_entry.png",
                            curve=ENTRY, without_blowoff=runs["without"])  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--map", action="store_true", help="only the stability map")
    group.add_argument("--entry", action="store_true", help="only the curve entry")
    args = parser.parse_args()
    vehicle = railhunt.Vehicle.paper2019()
    if not args.entry:
        print(f"wrote {stability_map_figure(vehicle)}")
    if not args.map:
        print(f"wrote {curve_entry_figure(vehicle)}")


if __name__ == "__main__":
    main()
