"""Result objects in notebooks and data tools: summary repr, HTML table, DataFrame, xarray.

Each result is built by hand from known numbers (no physics runs), so every expected value
here is the input itself or a one-line formula of it.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

from railhunt.analysis.branches import BifurcationDiagram, Branch, Fold
from railhunt.analysis.critical import CriticalSpeedResult, Trial
from railhunt.analysis.curving import CurvingResult
from railhunt.analysis.frequency import HuntingFrequency
from railhunt.analysis.linear import EigenResult, LinearCriticalSpeed
from railhunt.analysis.periodic import PeriodicOrbit
from railhunt.analysis.ramp import RampResult
from railhunt.analysis.stochastic import Assessment, StochasticCriticalSpeedResult
from railhunt.contact.geometry import ContactGeometry
from railhunt.curve import Curve
from railhunt.kernel.layout import N_DAMPER, N_STATE, STATE_NAMES
from railhunt.results import ResultDisplay, format_value
from railhunt.simulation import SimulationResult
from railhunt.studies.store import SweepResults

pd = pytest.importorskip("pandas")


def critical() -> CriticalSpeedResult:
    trials = [Trial(300.0, "stable", 1e-6, -0.5, 12.0, True, "ok"),
              Trial(310.0, "hunting", 8e-3, 0.0, 9.5, True, "ok"),
              Trial(305.0, "stable", 2e-6, -0.2, 15.0, False, "ok")]  # fmt: skip
    return CriticalSpeedResult(305.0, trials)


def eigen() -> EigenResult:
    speeds = np.array([200.0, 300.0, 400.0])
    hunting = np.array([-2.0 + 15.0j, -1.0 + 20.0j, 0.5 + 25.0j])
    eig = np.tile(hunting[:, None], (1, N_STATE))
    return EigenResult(speeds, eig, hunting)


def simulation(n: int = 2001) -> SimulationResult:
    t = np.linspace(0.0, 2.0, n)
    x = np.zeros((n, N_STATE))
    x[:, STATE_NAMES.index("y_w1")] = 0.004 * np.sin(2 * np.pi * 4.0 * t)
    return SimulationResult(t, x, 330 / 3.6, "ok", "reached t = 2.000 s",
                            np.zeros((n, N_DAMPER)), excitation_end=0.5,
                            derived={"SY_w1": 1e3 * t})  # fmt: skip


def branch(speeds: list[float], amps: list[float], stable: list[bool]) -> Branch:
    n = len(speeds)
    return Branch(np.array(speeds), np.array(amps), np.full(n, 0.2), np.array(stable),
                  np.full(n, 0.9), np.zeros((n, 4)), "hopf", [Fold(speeds[1], amps[1], 1)])


def diagram() -> BifurcationDiagram:
    b0 = branch([440.0, 300.0, 350.0], [0.0, 0.004, 0.008], [False, False, True])
    b1 = branch([420.0, 310.0], [0.009, 0.010], [True, True])
    b1.origin = "simulation"
    return BifurcationDiagram([b0, b1], 440.0, 440.5, 4.0, 300.0, "subcritical",
                              (200.0, 500.0), True, "done")  # fmt: skip


def frequency() -> HuntingFrequency:
    n = 5000
    return HuntingFrequency(400.0, 5.4, "limit-cycle", "hunting", 0.01, 3.8, 0.03, 5.41,
                            5.4, np.arange(n) * 0.01, np.zeros(n), np.zeros((n, 4)), 0.01)


def ramp(n: int = 1000) -> RampResult:
    speeds = 400.0 - 0.25 * np.arange(n)
    return RampResult(292.0, speeds, np.linspace(0.01, 0.0, n), 0.01)


def curving() -> CurvingResult:
    y_force = np.array([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0], [7.0, 8.0]]) * 1e3
    q = np.full((4, 2), 60e3)
    return CurvingResult(
        250.0, Curve(radius=3000.0, cant=0.15), np.zeros(N_STATE),
        np.array([-3e-3, -2e-3, -1e-3, 0.0]), np.array([1e-4, 2e-4, 3e-4, 4e-4]), y_force, q,
        y_force / q, np.array([-1e3, -2e3, -3e3, -4e3]), 0.62, 0.095, 0.0, np.zeros(2),
        np.zeros(2), True, 0.15, complex(-2.0, 14.0), np.zeros(N_STATE, dtype=complex))


def contact() -> ContactGeometry:
    y = np.linspace(-0.01, 0.01, 201)
    r_l, r_r = 0.43 + 0.2 * y, 0.43 - 0.2 * y  # a cone of conicity 0.2
    delta = np.full(y.size, 0.05)
    pts = np.zeros((y.size, 2))
    return ContactGeometry(y, r_l, r_r, delta, delta, -0.001 * y, pts, pts, y, y, y, y,
                           np.zeros(y.size, dtype=bool), 0.43, {"wheel": "cone", "rail": "flat"})


def sweep() -> SweepResults:
    rows = [{"point": i, "line": "C_d1", "C_d1": c, "critical_speed_kmh": v,
             "status": "ok", "message": ""}
            for i, (c, v) in enumerate([(100e3, 250.0), (300e3, 301.0), (600e3, 330.0)])]
    return SweepResults(rows, {"columns": list(rows[0]), "parameter_columns": ["C_d1"]})


def orbit() -> PeriodicOrbit:
    return PeriodicOrbit(400 / 3.6, np.zeros(N_STATE), 0.2, 0.008,
                         np.array([1.0, 0.5, 0.1]), True, 1e-10, 4, True,
                         np.array([0.008, 0.007, 0.002, 0.001]))  # fmt: skip


def assessment() -> Assessment:
    d = np.array([50.0, 60.0, 70.0])
    return Assessment(300.0, 3.6, d, np.full((3, 4), 1e4), np.full((3, 4), 2.0), 22.8e3, 5.22)


def stochastic() -> StochasticCriticalSpeedResult:
    a = assessment()
    return StochasticCriticalSpeedResult(299.0, 298.0, [a, a])


BUILDERS = [critical, eigen, simulation, diagram, frequency, ramp, curving, contact, sweep,
            orbit, assessment, stochastic,
            lambda: LinearCriticalSpeed(441.3, 3.98, complex(0.0, 25.0), True)]  # fmt: skip


@pytest.mark.parametrize("build", BUILDERS, ids=lambda b: b.__name__)
def test_every_result_shows_a_short_summary_and_an_html_table(build) -> None:
    result = build()
    assert isinstance(result, ResultDisplay)
    text = repr(result)
    assert text.splitlines()[0] == type(result).__name__
    assert len(text.splitlines()) <= 16 and len(text) < 1200, text
    page = result._repr_html_()
    assert page.startswith("<table") and page.endswith("</table>")
    assert page.count("<tr>") == len(text.splitlines())  # header row + one per summary line
    frame = result.to_dataframe()
    assert isinstance(frame, pd.DataFrame) and len(frame) >= 1
    assert set(frame.attrs["units"]) == set(frame.columns) | {frame.index.name} - {None}


def test_a_long_ramp_prints_three_lines_not_a_thousand_numbers() -> None:
    r = ramp(1000)
    assert repr(r) == ("RampResult\n  limit cycle died at     292 km/h\n"
                       "  amplitude at the start  0.01 m\n  segments                1000")
    frame = r.to_dataframe()
    assert frame.shape == (1000, 2)
    assert frame["speed_kmh"].iloc[-1] == 400.0 - 0.25 * 999


def test_critical_speed_table_has_one_row_per_trial() -> None:
    r = critical()
    assert "nonlinear critical speed  305 km/h" in repr(r)
    assert "lowest speed hunting      310 km/h" in repr(r)
    frame = r.to_dataframe()
    assert list(frame["speed_kmh"]) == [300.0, 310.0, 305.0]
    assert list(frame["verdict"]) == ["stable", "hunting", "stable"]
    assert frame.attrs["units"]["amplitude"] == "m"


def test_eigen_table_is_the_hunting_mode_per_speed() -> None:
    frame = eigen().to_dataframe()
    assert np.allclose(frame["hunting_frequency_hz"], np.array([15.0, 20.0, 25.0]) / (2 * np.pi))
    zeta = np.array([2.0 / abs(-2 + 15j), 1.0 / abs(-1 + 20j), -0.5 / abs(0.5 + 25j)])
    assert np.allclose(frame["hunting_damping_ratio"], zeta)
    assert "at speed                     400 km/h" in repr(eigen())


def test_linear_critical_speed_is_one_row() -> None:
    frame = LinearCriticalSpeed(441.3, 3.98, complex(-1e-5, 25.0), True).to_dataframe()
    assert frame.to_dict("records") == [{"speed_kmh": 441.3, "frequency_hz": 3.98,
                                         "eigenvalue_real": -1e-5, "eigenvalue_imag": 25.0,
                                         "is_hunting_mode": True}]  # fmt: skip


def test_simulation_table_is_indexed_by_time_with_units() -> None:
    run = simulation()
    frame = run.to_dataframe()
    assert frame.index.name == "t" and frame.shape == (2001, len(run.channel_names))
    assert np.array_equal(frame["y_w1"].to_numpy(), run["y_w1"])
    units = frame.attrs["units"]
    assert (units["t"], units["y_w1"], units["psi_w1"], units["dy_w1"], units["F_d1"],
            units["v_d1"], units["SY_w1"]) == ("s", "m", "rad", "m/s", "N", "m/s", "N")
    assert "largest |y_w1|      0.004 m" in repr(run)
    assert "speed               330 km/h" in repr(run)


def test_simulation_as_xarray_has_time_as_coordinate_and_units() -> None:
    pytest.importorskip("xarray")
    run = simulation(11)
    ds = run.to_xarray()
    assert list(ds.coords) == ["t"] and ds.sizes["t"] == 11
    assert ds["t"].attrs["units"] == "s"
    assert ds["y_w1"].attrs["units"] == "m" and ds["SY_w1"].attrs["units"] == "N"
    assert np.array_equal(ds["y_w1"].values, run["y_w1"])
    assert ds.attrs["speed_kmh"] == pytest.approx(330.0) and ds.attrs["status"] == "ok"
    assert len(ds.data_vars) == len(run.channel_names)


def test_bifurcation_table_lists_every_orbit_of_every_branch() -> None:
    d = diagram()
    frame = d.to_dataframe()
    assert list(frame["branch"]) == [0, 0, 0, 1, 1]
    assert list(frame["origin"]) == ["hopf"] * 3 + ["simulation"] * 2
    assert list(frame["speed_kmh"]) == [440.0, 300.0, 350.0, 420.0, 310.0]
    assert np.allclose(frame["frequency_hz"], 1 / 0.2)
    text = repr(d)
    assert "Hopf type                           subcritical" in text
    assert "lowest limit cycle (fold)           300 km/h" in text
    # point P: the unstable part of branch 0 crosses 3 mm between 440 (0 mm) and 300 (4 mm)
    assert f"point P (3 mm)                      {440 - 140 * 0.75:.4g} km/h" in text
    assert "orbits                              5" in text


def test_frequency_table_keeps_nan_as_nan() -> None:
    f = frequency()
    f.orbit_frequency_hz = math.nan
    frame = f.to_dataframe()
    assert frame.shape == (1, 10)  # to_dict's numbers and texts, orbit_rejected included
    assert frame.attrs["units"]["orbit_rejected"] == ""
    assert math.isnan(frame["orbit_frequency_hz"].iloc[0])
    assert frame["source"].iloc[0] == "limit-cycle"
    assert "5000" not in repr(f)  # the histories stay out of the summary


def test_curving_table_is_one_row_per_wheel() -> None:
    c = curving()
    frame = c.to_dataframe()
    assert list(frame["wheelset"]) == [1, 1, 2, 2, 3, 3, 4, 4]
    assert list(frame["side"]) == ["left", "right"] * 4
    assert list(frame["Y"]) == [1e3 * k for k in range(1, 9)]
    assert list(frame["sum_Y"]) == [-1e3, -1e3, -2e3, -2e3, -3e3, -3e3, -4e3, -4e3]
    assert np.allclose(frame["Y_over_Q"], frame["Y"] / 60e3)
    assert f"largest Y/Q              {8e3 / 60e3:.4g}" in repr(c)
    assert f"hunting frequency        {14 / (2 * math.pi):.4g} Hz" in repr(c)


def test_contact_summary_gives_the_conicity_of_a_cone() -> None:
    g = contact()
    # Delta r = 0.4 y: the equivalent conicity of a cone of half-angle tan = 0.2 is 0.2.
    line = next(ln for ln in repr(g).splitlines() if "equivalent conicity" in ln)
    assert float(line.split()[-1]) == pytest.approx(0.2, rel=2e-3)
    frame = g.to_dataframe()
    assert np.allclose(frame["delta_r"], 0.4 * frame["y"])


def test_sweep_summary_and_units() -> None:
    s = sweep()
    text = repr(s)
    assert "critical_speed_kmh  250 to 330 km/h" in text and "points              3" in text
    frame = s.to_dataframe()
    assert list(frame["C_d1"]) == [100e3, 300e3, 600e3]
    assert frame.attrs["units"]["C_d1"] == "N*s/m"
    assert frame.attrs["units"]["critical_speed_kmh"] == "km/h"


def test_stochastic_and_assessment_tables() -> None:
    s = stochastic()
    frame = s.to_dataframe()
    assert list(frame["sum_y_ratio"]) == pytest.approx([1e4 / 22.8e3] * 2)
    assert list(frame["verdict"]) == ["stable", "stable"]
    a = assessment().to_dataframe()
    assert list(a.columns) == ["distance"] + [f"sum_y_rms_w{j}" for j in range(1, 5)] + [
        f"acceleration_rms_w{j}" for j in range(1, 5)]


def test_html_escapes_its_text() -> None:
    s = sweep()
    s.rows[0]["line"] = "<b>"
    s.meta["parameter_columns"] = ["<x>"]
    page = s._repr_html_()
    assert "<x>" not in page and "&lt;x&gt;" in page


@pytest.mark.parametrize(("value", "text"), [
    (True, "yes"), (np.bool_(False), "no"), (3, "3"), (np.int64(7), "7"), (301.0, "301"),
    (441.3180177874659, "441.3"), (math.nan, "nan"), (complex(-1.5, 25.0), "-1.5+25j"),
    (None, "-"), ("ok", "ok"), (np.float64(0.00206254), "0.002063"),
])  # fmt: skip
def test_format_value(value: object, text: str) -> None:
    assert format_value(value) == text


def test_a_missing_pandas_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas -> ImportError
    with pytest.raises(ImportError, match=r"pip install 'railhunt\[pandas\]'"):
        critical().to_dataframe()
    repr(critical())  # the summary needs no pandas


def test_a_missing_xarray_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(ImportError, match=r"to_xarray\(\) needs xarray.*railhunt\[xarray\]"):
        simulation(3).to_xarray()


def test_importing_railhunt_results_loads_neither_pandas_nor_xarray() -> None:
    import subprocess

    code = ("import sys, railhunt, railhunt.results, railhunt.simulation, "
            "railhunt.analysis.critical; print('pandas' in sys.modules, 'xarray' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)  # fmt: skip
    assert out.stdout.split() == ["False", "False"]
