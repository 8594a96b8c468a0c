"""Figures that do not mislead: each check reads the drawn figure back (no image
comparison): where markers sit, what is coloured by what, what the titles say."""

from __future__ import annotations

import math

import numpy as np
from matplotlib.collections import PathCollection

from railhunt.analysis.linear import EigenResult
from railhunt.plots import (
    bifurcation_figure,
    contact_geometry_figure,
    root_locus_figure,
    stability_map_figure,
)
from railhunt.studies.store import SweepResults
from test_cli import run
from test_figures import _contact, _diagram, _eigen


def _map(radii, nonlinear, linear, cant=0.15) -> SweepResults:
    rows = [{"point": k, "line": "", "radius_m": r, "cant_m": cant if math.isfinite(r) else 0.0,
             "critical_speed_kmh": v, "linear_critical_speed_kmh": lin,
             "status": "ok" if math.isfinite(v) else "no-critical-speed", "message": ""}
            for k, (r, v, lin) in enumerate(zip(radii, nonlinear, linear,
                                                strict=True))]  # fmt: skip
    return SweepResults(rows, {"cant_m": cant})


def test_none_found_markers_are_off_the_speed_scale():
    fig = stability_map_figure(_map([1000.0, 4000.0, 8000.0], [180.0, 280.0, math.nan],
                                    [250.0, 400.0, 470.0]))  # fmt: skip
    ax = fig.axes[0]
    triangles = [line for line in ax.lines if line.get_marker() == "^" and len(line.get_ydata())]
    assert triangles
    for line in triangles:  # drawn in axes coordinates above the frame, not as a speed
        assert line.get_transform() != ax.transData
        assert np.all(np.asarray(line.get_ydata()) > 1.0)


def test_the_cant_deficiency_line_stays_inside_the_axes_in_tight_curves():
    fig = stability_map_figure(_map([150.0, 300.0, 1000.0], [150.0, 200.0, 260.0],
                                    [200.0, 260.0, 330.0]))  # fmt: skip
    ax = fig.axes[0]
    dashed = [line for line in ax.lines if line.get_linestyle() == "--" and
              line.get_color() == "0.5"]  # fmt: skip
    assert len(dashed) == 1
    lo, hi = ax.get_ylim()
    y = np.asarray(dashed[0].get_ydata())
    assert lo <= y.min() and y.max() <= hi


def _two_crossings() -> EigenResult:
    """A hunting mode unstable from 400 to about 480 km/h, stable again above."""
    base, _ = _eigen()
    speeds = np.arange(300.0, 560.0, 20.0)
    re = -0.0005 * (speeds - 400.0) * (speeds - 480.0)
    hunting = re + 1j * 2 * math.pi * (3.0 + speeds / 1000.0)
    eig = np.array([[h, np.conj(h)] for h in hunting])
    return EigenResult(speeds_kmh=speeds, eigenvalues=eig, hunting=hunting)


def test_the_root_locus_colours_the_hunting_mode_by_speed_and_labels_every_crossing():
    fig = root_locus_figure(_two_crossings())
    ax_r, ax_z = fig.axes[0], fig.axes[1]
    coloured = [c for c in ax_r.collections if isinstance(c, PathCollection)
                and c.get_array() is not None and c.get_array().size == 13]  # fmt: skip
    assert len(coloured) == 2  # every eigenvalue, and the hunting mode on the same scale
    texts = [t.get_text() for t in ax_z.texts]
    assert any(t.startswith("400 km/h") for t in texts)
    assert any(t.startswith("480 km/h") for t in texts)
    labels = " ".join(t.get_text() for t in ax_r.texts)
    assert "480 km/h: stable again above" in labels


def test_unstable_branches_are_told_apart_from_stable_ones_by_more_than_the_dash():
    fig = bifurcation_figure(_diagram())
    ax = fig.axes[0]
    branch_lines = [line for line in ax.lines if len(line.get_xdata()) > 2]
    stable = [line for line in branch_lines if line.get_linestyle() == "-"]
    unstable = [line for line in branch_lines if line.get_linestyle() not in ("-", "None")]
    assert stable and unstable
    assert all(line.get_marker() == "o" and line.get_markerfacecolor() == "white"
               for line in unstable)  # fmt: skip
    assert all(line.get_marker() in ("None", None, "") for line in stable)


def test_the_contact_figure_writes_1_to_40_and_the_equivalent_conicity():
    geo = _contact()
    title = contact_geometry_figure(geo)._suptitle.get_text()
    assert "inclination 1:40" in title and "0.025" not in title
    assert "equivalent conicity" in title


def test_damper_png_says_when_no_limit_cycle_is_in_range(tmp_path):
    png = tmp_path / "d.png"
    result = run("frequency", "--from", "250", "--to", "260", "--step", "10",
                 "--damper-png", str(png))  # fmt: skip
    assert result.exit_code == 0, result.stderr
    assert "no limit cycle in 250-260 km/h" in result.stderr
    assert png.exists()
