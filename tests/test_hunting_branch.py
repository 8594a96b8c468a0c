"""The hunting mode below the critical speed is the crossing pair's continuation.

The Cooperrider bogie (cooperrider_bogie.md) hunts with its frame moving more than its
wheelsets; below its Hopf point (247.1 km/h, 4.00 Hz) the frequency must come from the
mode that crosses there, not from another wheelset mode (4.77 Hz). The paper's vehicle,
whose crossing mode is a wheelset mode, keeps its per-speed pick.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import railhunt
from railhunt import Model, Vehicle
from railhunt.analysis.hunting_branch import crossing_mode_index, hunting_mode_at
from railhunt.analysis.linear import linear_critical_speed
from railhunt.analysis.modes import eigenvalues, hunting_mode_index
from railhunt.units import kmh_to_ms

COOPERRIDER = Vehicle.shipped("cooperrider_bogie")


def test_cooperrider_frequency_below_the_hopf_point_is_the_crossing_modes():
    """Released at 240 km/h (7 km/h below V_cr) the motion decays and its frequency is the
    eigenvalue's: within 0.15 Hz of the crossing's 3.997 Hz (the frequency of the crossing
    pair changes by about 0.014 Hz per km/h here), not the 4.77 Hz wheelset mode."""
    lin = linear_critical_speed(COOPERRIDER)
    f = railhunt.hunting_frequency(COOPERRIDER, 240.0)
    assert f.source == "eigenvalue"
    assert abs(f.frequency_hz - lin.frequency_hz) < 0.15
    assert f.frequency_hz < lin.frequency_hz  # the frequency rises with speed


def test_continuation_is_continuous_and_crosses_at_the_hopf_point():
    """Just below and above V_cr the continuation's real part changes sign and its frequency
    is within 0.01 Hz of the crossing's; it rises monotonically with speed below V_cr."""
    model = Model(COOPERRIDER)
    lin = linear_critical_speed(COOPERRIDER)
    picks = {}
    for kmh in (150.0, 200.0, lin.speed_kmh - 0.5, lin.speed_kmh + 0.5):
        w, vecs = eigenvalues(model, kmh_to_ms(kmh))
        k = crossing_mode_index(model, kmh, w)
        assert k is not None and hunting_mode_at(model, kmh, w, vecs) == k
        picks[kmh] = w[k]
    below, above = picks[lin.speed_kmh - 0.5], picks[lin.speed_kmh + 0.5]
    assert below.real < 0 < above.real
    for lam in (below, above):
        assert abs(lam.imag / (2 * math.pi) - lin.frequency_hz) < 0.01
    freqs = [picks[k].imag for k in sorted(picks)]
    assert np.all(np.diff(freqs) > 0)


@pytest.mark.parametrize("kmh", [250.0, 320.0, 440.0])
def test_paper_vehicle_keeps_its_per_speed_pick(kmh):
    """The paper's crossing mode is a wheelset mode: the pick is the one of
    hunting_mode_index (so Figs. 7b and 10 do not move)."""
    model = Model(Vehicle.paper2019())
    w, vecs = eigenvalues(model, kmh_to_ms(kmh))
    assert hunting_mode_at(model, kmh, w, vecs) == hunting_mode_index(
        w, vecs, model.half_gauge, model.layout)  # fmt: skip
    assert crossing_mode_index(model, kmh, w) == hunting_mode_index(
        w, vecs, model.half_gauge, model.layout)  # fmt: skip


def test_hopf_branch_is_measured_on_the_wheelset_that_moves_most():
    """The articulated pair's crossing mode lives on its rear bogie (y_w1 moves 0.066 of
    y_w6): its Hopf branch is measured, and its phase fixed, on y_w6; the paper's vehicle
    keeps y_w1 (0.12 of its rear wheelset's motion), so its diagram does not move."""
    from pathlib import Path

    from railhunt.analysis.hopf_start import hopf_mode_shape as _hopf_start
    from railhunt.analysis.hopf_start import measure_coordinate
    from railhunt.analysis.periodic import Shooting

    example = Path(__file__).parent.parent / "examples" / "data" / "articulated_pair.toml"
    for vehicle, wheelset in ((Vehicle.paper2019(), 0), (Vehicle.from_toml(example), 5)):
        model = Model(vehicle)
        shape, _ = _hopf_start(model, linear_critical_speed(vehicle).speed_kmh)
        coordinate = measure_coordinate(model, shape)
        assert coordinate == model.layout.wheelset_y[wheelset]
        assert shape[coordinate] == pytest.approx(1.0)
        assert np.max(np.abs(shape[model.layout.wheelset_y])) < 1.0 + 1e-9 or wheelset == 0
        shoot = Shooting(model, phase_coordinate=coordinate)
        assert shoot.phase_index == model.layout.rate0 + coordinate
    with pytest.raises(ValueError, match="phase_coordinate"):
        Shooting(Model(Vehicle.paper2019()), phase_coordinate=10_000)
