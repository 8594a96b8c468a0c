"""Pareto fronts (railhunt.optimize): NSGA-II on the study machinery."""

from __future__ import annotations

import math

import numpy as np
import pytest

from railhunt import Vehicle
from railhunt.studies.optimize import optimize, parse_constraint, parse_objective
from railhunt.studies.sweep import evaluate_point

N_ZDT = 5


def zdt1(**x: float) -> dict[str, float]:
    """ZDT1 with N_ZDT variables; its front is f2 = 1 - sqrt(f1), x1..x4 = 0."""
    xs = [x[f"x{i}"] for i in range(N_ZDT)]
    g = 1.0 + 9.0 * sum(xs[1:]) / (N_ZDT - 1)
    return {"f1": xs[0], "f2": g * (1.0 - math.sqrt(xs[0] / g))}


ZDT_FACTORS = {f"x{i}": (0.0, 1.0) for i in range(N_ZDT)}


def test_zdt1_front_found_and_spread(tmp_path):
    r = optimize(zdt1, ZDT_FACTORS, ["min f1", "min f2"], population=32, generations=40, seed=1,
                 workers=1, out=tmp_path / "zdt1.csv")
    front = r.front
    gap = front["f2"] - (1.0 - np.sqrt(front["f1"]))
    assert np.all(gap >= -1e-12)  # nothing beats the true front
    assert np.median(gap) < 0.02 and np.max(gap) < 0.1
    assert front["f1"].min() < 0.02 and front["f1"].max() > 0.95  # spread over the front
    assert len(r.evaluated) == 32 * 40
    assert np.all(np.diff(r.hypervolume) >= -1e-12)  # the front never gets worse
    assert "on the front" in repr(r) and "<table" in r._repr_html_()
    assert r.to_dict()["front"] and r.figure(tmp_path / "zdt1.png").exists()


def test_resumed_run_reaches_the_same_front(tmp_path):
    whole = optimize(zdt1, ZDT_FACTORS, ["min f1", "min f2"], population=8, generations=5,
                     seed=4, workers=1, out=tmp_path / "whole.csv")

    def kill(done: int, total: int) -> None:
        if done == 19:
            raise KeyboardInterrupt

    part = tmp_path / "part.csv"
    with pytest.raises(KeyboardInterrupt):
        optimize(zdt1, ZDT_FACTORS, ["min f1", "min f2"], population=8, generations=5, seed=4,
                 workers=1, out=part, progress=kill)
    resumed = optimize(zdt1, ZDT_FACTORS, ["min f1", "min f2"], population=8, generations=5,
                       seed=4, workers=1, out=part, resume=True)
    assert resumed.front.equals(whole.front)
    assert resumed.hypervolume == whole.hypervolume


def test_paper_vehicle_front_recomputed_alone(tmp_path):
    v = Vehicle.paper2019()
    options = {"curve_radius": 600.0, "curve_cant": 0.15, "curve_speed_kmh": 120.0}
    r = optimize(v, {"K_px": (2e6, 40e6), "C_d1": ("tolerance", 0.3)},
                 ["max linear_critical_speed_kmh", "min wear_number"],
                 ["linear_critical_speed_kmh >= 300"], population=4, generations=2, seed=0,
                 workers=1, out=tmp_path / "pareto.csv", output_options=options)
    assert r.start is not None and r.start["linear_critical_speed_kmh"] == pytest.approx(441.318,
                                                                                         abs=1e-3)
    from railhunt.studies.design import Point
    from railhunt.studies.outputs import OutputOptions

    for _, design in r.front.iterrows():
        values = {"K_px": design["K_px"], "C_d1": design["C_d1"]}
        alone = evaluate_point(Point(0, "alone", values), v,
                               ("linear_critical_speed", "curving"),
                               output_options=OutputOptions(**options))
        assert alone["linear_critical_speed_kmh"] == design["linear_critical_speed_kmh"]
        assert alone["wear_number"] == design["wear_number"]
    assert r.figure() is not None


def test_parse_objectives_and_constraints():
    assert parse_objective("max critical_speed_kmh") == ("max", "critical_speed_kmh")
    assert parse_constraint("linear_critical_speed_kmh >= 385") == (
        "linear_critical_speed_kmh", ">=", 385.0)
    for bad in ("maximise x", "max", "max a b"):
        with pytest.raises(ValueError, match="max COLUMN"):
            parse_objective(bad)
    for bad in ("x > 3", "x >= y", ">= 3"):
        with pytest.raises(ValueError, match="COLUMN >= VALUE"):
            parse_constraint(bad)


def test_normal_factor_refused():
    with pytest.raises(ValueError, match="needs bounds"):
        optimize(zdt1, {"x0": ("normal", 0.5, 0.1), "x1": (0, 1)}, ["min f1", "min f2"],
                 workers=1)


def test_fronts_by_generation_match_the_pairwise_definition():
    """The vectorised, incremental fronts equal the definition checked pair by pair (no
    feasible row dominates a front row; duplicates kept once, the first), with many ties."""
    from railhunt.studies.pareto_result import fronts, non_dominated

    rng = np.random.default_rng(1)
    for _ in range(60):
        n, k, gens = int(rng.integers(5, 90)), int(rng.integers(2, 4)), int(rng.integers(1, 6))
        f = rng.integers(0, 6, size=(n, k)).astype(float)
        feasible = rng.random(n) < 0.8
        generation = np.sort(rng.integers(0, gens, size=n))
        by_generation = fronts(f, feasible, generation, gens)
        for gen in range(gens):
            idx = np.flatnonzero(feasible & (generation <= gen))
            keep: list[int] = []
            for i in idx:
                others = f[idx]
                dominated = np.any(np.all(others <= f[i], axis=1) & np.any(others < f[i], axis=1))
                if not dominated and not any(np.array_equal(f[i], f[j]) for j in keep):
                    keep.append(int(i))
            assert by_generation[gen].tolist() == keep
            assert non_dominated(f, feasible & (generation <= gen)).tolist() == keep
