"""Every search reports the limits of the validity envelope it reaches (issue 20): the
linear search in a curve stops at the curving limit like the nonlinear one, and the
stochastic and straight-track searches carry the limits their runs reach."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

import railhunt
from railhunt import Curve, Vehicle
from railhunt.cli import main

PAPER = Vehicle.paper2019()


def run(*args: str):
    return CliRunner().invoke(main, list(args))


def test_the_linear_search_in_a_curve_stops_at_the_curving_limit():
    # main: "not found (stable at every speed searched)" up to 1000 km/h in a 1000 m curve
    # without cant, where the cant deficiency leaves the model's range at 119 km/h.
    lin = railhunt.linear_critical_speed(PAPER, curve=Curve(1000.0, 0.0))
    assert lin.limit_reached and lin.limit.speed_kmh == pytest.approx(119.0, abs=1.0)
    assert lin.warnings[0].startswith("limit reached: curving limit at 119 km/h: cant")
    assert "cant deficiency" in {lim.name for lim in lin.limits}
    assert "stable up to 118 km/h, where the search stopped" in lin.text
    # Straight track: no limit, no warning (the fingerprint's search is unchanged).
    assert railhunt.linear_critical_speed(PAPER, min_kmh=400.0, max_kmh=460.0).warnings == []
