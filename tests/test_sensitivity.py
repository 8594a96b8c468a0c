"""Global sensitivity (railhunt.sensitivity): known indices through the whole machinery."""

from __future__ import annotations

import math

import numpy as np
import pytest

from railhunt import Vehicle
from railhunt.studies.sensitivity import capped_value, sensitivity

PI = math.pi


def ishigami(x1: float, x2: float, x3: float) -> dict[str, float]:
    """Ishigami & Homma (1990), a = 7, b = 0.1."""
    return {"y": math.sin(x1) + 7.0 * math.sin(x2) ** 2 + 0.1 * x3**4 * math.sin(x1)}


G_A = (0.0, 1.0, 4.5, 9.0, 99.0, 99.0)


def g_function(**x: float) -> dict[str, float]:
    """Sobol's g-function with the coefficients G_A."""
    y = 1.0
    for k, a in enumerate(G_A):
        y *= (abs(4.0 * x[f"x{k}"] - 2.0) + a) / (1.0 + a)
    return {"g": y}


def ishigami_exact() -> tuple[np.ndarray, np.ndarray]:
    a, b = 7.0, 0.1
    v = a**2 / 8 + b * PI**4 / 5 + b**2 * PI**8 / 18 + 0.5
    v1 = 0.5 * (1 + b * PI**4 / 5) ** 2
    v2 = a**2 / 8
    v13 = b**2 * PI**8 * (1 / 18 - 1 / 50)
    return np.array([v1, v2, 0.0]) / v, np.array([v1 + v13, v2, v13]) / v


def g_exact() -> tuple[np.ndarray, np.ndarray]:
    vi = np.array([1.0 / (3.0 * (1.0 + a) ** 2) for a in G_A])
    total = np.prod(1.0 + vi) - 1.0
    st = np.array([vi[i] * np.prod(np.delete(1.0 + vi, i)) for i in range(vi.size)]) / total
    return vi / total, st


def _check_within(result, output: str, s1: np.ndarray, st: np.ndarray) -> None:
    for k, f in enumerate(result.factors):
        for key, exact in (("S1", s1[k]), ("ST", st[k])):
            value = result.index(output, f, key)
            conf = result.index(output, f, key + "_conf")
            assert abs(value - exact) <= conf, (f, key, value, exact, conf)


def test_ishigami_through_store(tmp_path):
    path = tmp_path / "ishigami.csv"
    r = sensitivity(ishigami, {"x1": (-PI, PI), "x2": ("uniform", -PI, PI), "x3": (-PI, PI)},
                    ["y"], samples=1024, seed=1, workers=1, out=path)
    assert r.points == 1024 * 5 and path.exists() and r.study.computed == r.points
    _check_within(r, "y", *ishigami_exact())
    df = r.to_dataframe()
    assert list(df.columns) == ["output", "factor", "S1", "S1_conf", "ST", "ST_conf"]
    assert "sobol" in repr(r) and "<table" in r._repr_html_()
    assert r.figure(tmp_path / "s.png").read_bytes().startswith(b"\x89PNG")


def test_g_function():
    factors = {f"x{k}": (0.0, 1.0) for k in range(len(G_A))}
    r = sensitivity(g_function, factors, ["g"], samples=2048, seed=3, workers=1)
    _check_within(r, "g", *g_exact())
    assert r.ranking("g")[:2] == ["x0", "x1"]


def test_kill_and_resume_same_indices_bit_for_bit(tmp_path):
    factors = {"x1": (-PI, PI), "x2": (-PI, PI), "x3": (-PI, PI)}
    whole = sensitivity(ishigami, factors, ["y"], samples=64, seed=5, workers=1,
                        out=tmp_path / "whole.csv")

    def kill(done: int, total: int) -> None:
        if done == 100:
            raise KeyboardInterrupt

    part = tmp_path / "part.csv"
    with pytest.raises(KeyboardInterrupt):
        sensitivity(ishigami, factors, ["y"], samples=64, seed=5, workers=1, out=part,
                    progress=kill)
    resumed = sensitivity(ishigami, factors, ["y"], samples=64, seed=5, workers=1, out=part,
                          resume=True)
    assert resumed.study.resumed == 100 and resumed.study.computed == 64 * 5 - 100
    assert resumed.indices == whole.indices
    assert part.read_bytes() == (tmp_path / "whole.csv").read_bytes()


def test_same_seed_same_intervals_even_seed_0():
    factors = {"x1": (-PI, PI), "x2": (-PI, PI), "x3": (-PI, PI)}
    runs = [sensitivity(ishigami, factors, ["y"], samples=32, seed=0, workers=1)
            for _ in range(2)]
    assert runs[0].indices == runs[1].indices


def test_dropped_blocks_are_counted_not_nan():
    def holes(x1: float, x2: float) -> dict[str, float]:
        return {"y": math.nan if x1 > 0.9 else x1 + 2.0 * x2}

    r = sensitivity(holes, {"x1": (0.0, 1.0), "x2": (0.0, 1.0)}, ["y"], samples=256, seed=0,
                    workers=1)
    assert r.dropped["y"] > 0 and r.dropped["y"] % 4 == 0
    assert all(math.isfinite(row[k]) for row in r.indices for k in r.keys)


def test_morris_ranks_linear_function():
    r = sensitivity(lambda a, b, c: {"y": 10 * a + b + 0 * c}, {"a": (0, 1), "b": (0, 1),
                    "c": (0, 1)}, ["y"], method="morris", samples=20, seed=2, workers=1)
    assert r.index("y", "a", "mu_star") == pytest.approx(10.0)
    assert r.index("y", "c", "mu_star") == 0.0
    assert list(r.to_dataframe().columns) == ["output", "factor", "mu_star", "mu_star_conf",
                                              "sigma"]
    assert r.figure() is not None and "morris" in repr(r)


def test_capped_critical_speed():
    row = {"status": "no-critical-speed", "message": "stable at every speed tried, up to 800 km/h"}
    assert capped_value("critical_speed_kmh", row) == 800.0
    row = {"status": "no-critical-speed",
           "message": "hunting at every speed tried, down to 20 km/h"}
    assert capped_value("critical_speed_kmh", row) == 20.0
    assert capped_value("critical_speed_kmh", {"status": "failed", "message": "x"}) is None
    row = {"status": "failed", "message": "ValueError: the centred equilibrium stays stable up "
           "to 2000 km/h: no Hopf point", "fold_speed_kmh": math.nan}
    assert capped_value("fold_speed_kmh", row) == 2000.0


def test_blow_off_force_cannot_enter_linear_speed():
    v = Vehicle.paper2019()
    r = sensitivity(v, {"C_d1": ("tolerance", 0.2), "F_u": ("tolerance", 0.5)},
                    ["linear_critical_speed_kmh"], samples=8, seed=0, workers=1)
    assert abs(r.index("linear_critical_speed_kmh", "F_u", "ST")) < 1e-12
    assert r.index("linear_critical_speed_kmh", "C_d1", "ST") > 0.5


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"samples": 100}, "power of 2"),
    ({"method": "fast"}, "method"),
    ({"factors": {"x1": ("tolerance", 0.1), "x2": (0, 1)}}, "tolerance needs a vehicle"),
    ({"factors": {"x1": (1, 0), "x2": (0, 1)}}, "low must be below high"),
    ({"factors": {"x1": ("beta", 1, 2), "x2": (0, 1)}}, "is invalid"),
    ({"factors": {"x1": (0, 1)}}, "at least two"),
])
def test_bad_input_named(kwargs, match):
    args = {"factors": {"x1": (0, 1), "x2": (0, 1)}, "samples": 8}
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        sensitivity(lambda x1, x2: {"y": x1}, outputs=["y"], workers=1, **args)


def test_vehicle_factor_names_checked():
    from railhunt.vehicle import UnknownParameterError

    with pytest.raises(UnknownParameterError, match="C_d3"):
        sensitivity(Vehicle.paper2019(), {"C_d3": (1e5, 2e5), "K_d": (1e6, 2e6)}, samples=8)


def test_on_a_given_scheduler_same_indices_as_in_process(tmp_path):
    """The points run on a Dask cluster joined by its address; the file and the indices
    are those of the in-process run."""
    from railhunt.studies.execute import local_cluster

    v = Vehicle.paper2019()
    factors = {"C_d1": ("tolerance", 0.2), "K_px": ("tolerance", 0.2)}
    here = sensitivity(v, factors, ["linear_critical_speed_kmh"], samples=4, seed=2,
                       workers=1, out=tmp_path / "here.csv")
    cluster = local_cluster(2)
    try:
        there = sensitivity(v, factors, ["linear_critical_speed_kmh"], samples=4, seed=2,
                            scheduler=cluster.scheduler_address, out=tmp_path / "there.csv")
    finally:
        cluster.close()
    assert there.indices == here.indices
    assert (tmp_path / "there.csv").read_bytes() == (tmp_path / "here.csv").read_bytes()


def test_a_layout_vehicle_and_its_own_parameters():
    """Any vehicle railhunt describes: a two-axle wagon, a layout with other parameters."""
    v = Vehicle.shipped("two_axle_wagon")
    r = sensitivity(v, {"K_px": ("tolerance", 0.2), "K_py": ("tolerance", 0.2)},
                    ["linear_critical_speed_kmh"], samples=2, seed=0, workers=1)
    assert r.points == 8 and all(math.isfinite(row["ST"]) for row in r.indices)
