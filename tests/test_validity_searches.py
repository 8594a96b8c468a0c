"""Every search reports the limits of the validity envelope it reaches (issue 20): the
linear search in a curve stops at the curving limit like the nonlinear one, and the
stochastic and straight-track searches carry the limits their runs reach."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import railhunt
from railhunt import Curve, Vehicle
from railhunt.cli import main
from railhunt.validity import LIMIT_NAMES

PAPER = Vehicle.paper2019()
ROOT = Path(__file__).resolve().parents[1]


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


def test_the_stochastic_search_carries_the_limits_its_runs_reach():
    # main: no warnings and no limits, though the runs above the criterion's speed reach
    # the limits simulate() reports for the same run.
    from railhunt.analysis.stochastic import run_on_track

    track = railhunt.track_irregularity("german-high", length=400.0, seed=1)
    res = railhunt.stochastic_critical_speed(PAPER, track, start_kmh=300.0, step_kmh=40.0,
                                             tol_kmh=40.0)  # fmt: skip
    assert res.trials and all(isinstance(a.limits, list) for a in res.trials)
    top = max(res.trials, key=lambda a: a.speed_kmh)
    sim, _ = run_on_track(PAPER, top.speed_kmh, track)
    assert [lim.to_dict() for lim in top.limits] == [lim.to_dict() for lim in sim.limits]
    assert top.limits, "the fastest run breaks the criterion: it reaches a limit too"
    # every run's limits in the details; one summary per kind in the warnings, and none
    # says "limit reached" (they stop nothing)
    assert len(res.details) == sum(len(a.limits) for a in res.trials)
    assert f"{top.speed_kmh:g} km/h: {top.limits[0].text}" in res.details
    kinds = {lim.name for a in res.trials for lim in a.limits}
    assert [s.name for s in res.limit_summary] == [n for n in LIMIT_NAMES if n in kinds]
    assert res.warnings == [s.text for s in res.limit_summary]
    assert not any("limit reached" in w for w in res.warnings + res.details)
    assert all(lim.place.endswith(" km/h") for lim in res.limits)


def test_a_straight_track_search_reports_the_limits_its_trials_reach():
    # main: no warnings; the 310 km/h trial hunts with Y/Q above Nadal's 0.8 (the paper's
    # defect drives the wheels hard even at a stable speed). The limits change no verdict.
    res = railhunt.critical_speed(PAPER, start_kmh=300.0, step_kmh=10.0, tol_kmh=10.0)
    assert res.speed_kmh == 300.0
    assert [(t.speed_kmh, t.verdict) for t in res.trials] == [(300.0, "stable"),
                                                              (310.0, "hunting")]  # fmt: skip
    hunting = res.trials[1]
    assert "Y/Q" in {lim.name for lim in hunting.limits}
    yq = next(lim for lim in hunting.limits if lim.name == "Y/Q")
    assert yq.value > 0.8 and yq.place.startswith("wheelset ")
    assert f"310 km/h: {yq.text}" in res.details
    assert any(lim.place.endswith(", 310 km/h") for lim in res.limits)
    assert len(res.limits) == sum(len(t.limits) for t in res.trials)
    # one summary per kind: the largest value, where, at which speeds; it decides nothing
    summary = {s.name: s for s in res.limit_summary}
    assert summary["Y/Q"].value == yq.value and summary["Y/Q"].speeds_kmh == (310.0,)
    assert summary["Y/Q"].decided is False and "changes no verdict" in summary["Y/Q"].line
    assert not any("limit reached" in w for w in res.warnings)
    # docs/critical-speeds.md quotes this search's line as the library gives it
    page = " ".join((ROOT / "docs" / "critical-speeds.md").read_text(encoding="utf-8").split())
    assert f"`310 km/h: {yq.text}`" in page


def test_the_critical_speed_json_lists_the_trials_limits():
    result = run("critical-speed", "--start", "300", "--step", "10", "--tol", "10", "--json")
    data = json.loads(result.stdout)
    assert data["nonlinear_critical_speed_kmh"] == 300.0
    assert any(w.startswith("310 km/h: Y/Q") for w in data["details"])
    assert any(w.startswith("Y/Q beyond 0.8 (EN 14363) at 310 km/h") for w in data["warnings"])
    assert {s["name"]: s["speeds_kmh"] for s in data["limit_summary"]}["Y/Q"] == [310.0]
    assert all(s["decided"] is False for s in data["limit_summary"])
    assert any(d["name"] == "Y/Q" and d["place"].endswith("310 km/h") for d in data["limits"])
    assert [d["name"] for d in data["trials"][1]["limits"]] == ["Y/Q", "ΣY"]
    assert data["linear_warnings"] == [] and data["linear_curving_limit"] is None


def test_a_run_is_judged_on_2_m_sliding_means_as_en_14363_judges_it():
    """An impact's single-sample peak of Y/Q is not a limit in a run; Y/Q held over more
    than the window is. A steady state (window 1) is judged row by row."""
    from railhunt.validity import check_wheels, sliding_mean

    q0 = 50e3
    Q = np.full((200, 2), q0)
    spike = np.zeros((200, 2))
    spike[100, 0] = 1.5 * q0
    held = np.zeros((200, 2))
    held[50:150, 0] = 0.9 * q0
    none = np.zeros((200, 1))
    assert [lim.name for lim in check_wheels(spike, Q, none, q0)] == ["Y/Q"]
    assert check_wheels(spike, Q, none, q0, window=20) == []
    assert [lim.name for lim in check_wheels(held, Q, none, q0, window=20)] == ["Y/Q"]
    assert sliding_mean(np.arange(6.0), 3).tolist() == [0.0, 0.5, 1.0, 2.0, 3.0, 4.0]
