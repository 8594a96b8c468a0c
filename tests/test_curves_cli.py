"""Curved track from the shell: ``railhunt curve``, ``railhunt stability-map``, the curve
options of ``simulate``/``critical-speed``/``bifurcation``, their figures and the
reproduction's section beyond the paper (small cases, in process)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import railhunt
from railhunt import Curve
from railhunt.cli.options import default_transition
from railhunt.studies.store import read_results
from test_cli import PNG_SIGNATURE, assert_input_error, run

PAPER = railhunt.Vehicle.paper2019()


def ok(*args: str):
    result = run(*args)
    assert result.exit_code == 0, (result.stdout, result.stderr)
    return result


# --------------------------------------------------------------------------- help


@pytest.mark.parametrize(("command", "words"), [
    ("curve", ["--radius", "--cant", "--speed", "--transition", "--direction", "--png", "Y/Q"]),
    ("stability-map", ["--radius", "--cant-deficiency", "--resume", "--workers", "inf"]),
    ("simulate", ["--curve-radius", "--cant", "--transition", "--direction"]),
    ("critical-speed", ["--curve-radius", "--cant", "--transition", "--direction"]),
    ("bifurcation", ["--curve-radius", "--cant", "--transition", "--direction"]),
])  # fmt: skip
def test_help_names_the_curve_options(command, words):
    text = ok(command, "--help").stdout
    for word in words:
        assert word in text, word
    assert "--vehicle" in text


def test_main_help_lists_the_curve_commands():
    text = ok("--help").stdout
    assert "curve" in text and "stability-map" in text


def test_default_transition_follows_the_radius():
    assert default_transition(3000.0) == 300.0
    assert default_transition(1000.0) == 100.0
    assert default_transition(300.0) == 30.0
    assert default_transition(60.0) == 20.0


# --------------------------------------------------------------------------- curve


def test_curve_prints_the_steady_curving_table():
    text = " ".join(ok("curve", "--radius", "3000", "--cant", "150", "--speed",
                       "300").stdout.split())  # fmt: skip
    for word in ("wheelset", "attack", "mrad", "ΣY (kN)", "Y/Q", "left", "right",
                 "unbalanced acceleration: 1.323 m/s^2", "cant deficiency 202.5 mm",
                 "car body -60.56 mm", "bump stops", "stable", "hunting mode 2.22 Hz"):
        assert word in text, word


def test_curve_json_is_the_curving_result_with_its_context():
    data = json.loads(ok("curve", "--radius", "3000", "--cant", "150", "--speed", "300",
                         "--json").stdout)  # fmt: skip
    curve = Curve(3000.0, 0.15)
    expected = railhunt.curving(PAPER, 300.0, curve).to_dict()
    for key, value in expected.items():
        if isinstance(value, str | bool) or key in ("warnings", "limits"):
            assert data[key] == value, key
        else:
            np.testing.assert_allclose(data[key], value, rtol=1e-12, atol=1e-15, err_msg=key)
    assert data["vehicle"] == "paper2019"
    assert data["curve"] == {"radius_m": 3000.0, "cant_mm": 150.0, "transition_m": 300.0,
                             "direction": "left"}  # fmt: skip
    assert data["balance_speed_kmh"] == pytest.approx(curve.balance_speed(g=PAPER.g) * 3.6)
    assert data["cant_deficiency_m"] == pytest.approx(curve.cant_deficiency(300 / 3.6, PAPER.g))
    right = json.loads(ok("curve", "--radius", "3000", "--cant", "150", "--speed", "300",
                          "--direction", "right", "--json").stdout)  # fmt: skip
    assert right["car_body_y_m"] == pytest.approx(-data["car_body_y_m"], rel=1e-6)
    assert right["curve"]["direction"] == "right"


def test_curve_png_draws_the_curve_entry(tmp_path):
    png = tmp_path / "entry.png"
    data = json.loads(ok("curve", "--radius", "1000", "--cant", "100", "--speed", "150",
                         "--transition", "50", "--png", str(png), "--json").stdout)
    assert png.read_bytes().startswith(PNG_SIGNATURE)
    entry = data["curve_entry"]
    assert entry["status"] == "ok" and entry["transition_m"] == 50.0
    assert 0 < entry["peak_damper_force_N"] < 50e3
    assert 0 < entry["peak_derailment_quotient_w1"] < 1


@pytest.mark.parametrize(("args", "fragments"), [
    (["--radius", "10", "--speed", "300"], ["--radius", "10 m", "[50, inf) m"]),
    (["--radius", "inf", "--speed", "300"], ["--radius", "finite"]),
    (["--radius", "3000", "--cant", "600", "--speed", "300"], ["--cant", "[0, 500] mm"]),
    (["--radius", "3000", "--cant", "-5", "--speed", "300"], ["--cant", "[0, 500] mm"]),
    (["--radius", "3000", "--speed", "0"], ["--speed", "(0, 1000] km/h"]),
    (["--radius", "3000", "--speed", "300", "--transition", "3000"],
     ["--transition", "[0, 2000] m"]),
    (["--radius", "3000", "--speed", "300", "--direction", "up"], ["--direction", "up"]),
    (["--speed", "300"], ["--radius"]),
    (["--radius", "100", "--speed", "300"], ["no steady-curving equilibrium", "--radius 100"]),
])  # fmt: skip
def test_curve_bad_values_name_the_flag_and_range(args, fragments):
    assert_input_error(run("curve", *args), *fragments)


# --------------------------------------------------------------------------- simulate


def test_simulate_through_a_curve(tmp_path):
    png, csv = tmp_path / "run.png", tmp_path / "run.csv"
    text = ok("simulate", "--speed", "150", "--duration", "3", "--curve-radius", "1000",
              "--cant", "100", "--transition", "30", "--direction", "right", "--png", str(png),
              "--csv", str(csv)).stdout  # fmt: skip
    # The curve starts 20 m after the 1 m + 20 m defect.
    assert "R = 1000 m to the right, cant 100 mm, transitions 30 m; entry from 41 m" in text
    assert "constant curve from 71 m (the leading wheelset there at 1.70 s)" in text
    assert "peak yaw damper force" in text and "peak |Y/Q|" in text
    assert png.read_bytes().startswith(PNG_SIGNATURE)
    header = csv.read_text().splitlines()[0]
    assert "Y_w1L [N]" in header and "YQ_w4R [1]" in header
    short = ok("simulate", "--speed", "100", "--duration", "0.5", "--initial-displacement",
               "2", "--curve-radius", "2000").stdout  # fmt: skip
    assert "entry from 20 m" in short and "not reached" in short


@pytest.mark.parametrize("flag", [["--cant", "150"], ["--transition", "100"],
                                  ["--direction", "right"]])  # fmt: skip
def test_curve_flags_need_the_radius(flag):
    for command in (["simulate", "--speed", "300"], ["critical-speed"], ["bifurcation"]):
        assert_input_error(run(*command, *flag), flag[0], "--curve-radius")


def test_curve_radius_is_checked(tmp_path):
    assert_input_error(run("simulate", "--speed", "300", "--curve-radius", "20"),
                       "--curve-radius", "[50, inf) m")  # fmt: skip


# --------------------------------------------------------------------------- critical-speed


def test_critical_speed_in_a_curve_json():
    args = ("critical-speed", "--tol", "5", "--start", "300", "--json")
    data = json.loads(ok(*args, "--curve-radius", "8000", "--cant", "150").stdout)
    assert data["curve"] == {"radius_m": 8000.0, "cant_mm": 150.0, "transition_m": 300.0,
                             "direction": "left"}  # fmt: skip
    lin = railhunt.linear_critical_speed(PAPER, curve=Curve(8000.0, 0.15))
    assert data["linear_critical_speed_kmh"] == pytest.approx(lin.speed_kmh)
    assert data["nonlinear_critical_speed_kmh"] == 305.0
    assert {"trials", "excitation", "bracketed", "method"} <= set(data)
    straight = json.loads(ok(*args).stdout)
    assert "curve" not in straight
    assert straight["nonlinear_critical_speed_kmh"] == 300.0  # 301 to 1 km/h


def test_critical_speed_table_names_the_curve():
    text = ok("critical-speed", "--tol", "5", "--curve-radius", "8000", "--cant",
              "150").stdout  # fmt: skip
    assert "in a curve, R = 8000 m to the left, cant 150 mm" in " ".join(text.split())
    assert "linear critical speed: 406.7 km/h" in text


def test_critical_speed_curve_excludes_stochastic():
    result = run("critical-speed", "--curve-radius", "2000", "--method", "stochastic")
    assert_input_error(result, "--curve-radius", "--method stochastic")


# --------------------------------------------------------------------------- bifurcation


class _Diagram:
    def to_dict(self, point_p_amplitude: float) -> dict:
        return {"hopf_speed_kmh": 400.0}


def test_bifurcation_passes_the_curve_and_reports_it(monkeypatch):
    calls = []

    def fake(vehicle, speed_range_kmh, **kwargs):
        calls.append((speed_range_kmh, kwargs))
        return _Diagram()

    monkeypatch.setattr(railhunt, "bifurcation_diagram", fake, raising=False)
    data = json.loads(ok("bifurcation", "--from", "380", "--to", "420", "--curve-radius",
                         "8000", "--cant", "150", "--json").stdout)  # fmt: skip
    assert calls == [((380.0, 420.0), {"curve": Curve(8000.0, 0.15, transition=300.0)})]
    assert data["curve"] == {"radius_m": 8000.0, "cant_mm": 150.0, "transition_m": 300.0,
                             "direction": "left"}  # fmt: skip
    calls.clear()
    data = json.loads(ok("bifurcation", "--json").stdout)
    assert calls == [((200.0, 500.0), {})] and "curve" not in data


# --------------------------------------------------------------------------- stability-map


def test_stability_map_end_to_end(tmp_path):
    out, csv, png = tmp_path / "map.csv", tmp_path / "table.csv", tmp_path / "map.png"
    data = json.loads(ok("stability-map", "--radius", "8000,inf", "--cant", "150",
                         "--workers", "1", "--out", str(out), "--csv", str(csv), "--png",
                         str(png), "--json").stdout)  # fmt: skip
    assert data["cant_mm"] == 150.0 and data["points"] == 2 and data["computed"] == 2
    assert data["outputs"] == ["linear_critical_speed", "critical_speed"]
    curve, straight = data["rows"]
    assert curve["radius_m"] == 8000.0 and not curve["straight_track"]
    assert straight["radius_m"] is None and straight["straight_track"]
    assert curve["critical_speed_kmh"] == 305.0 and straight["critical_speed_kmh"] == 301.0
    assert curve["linear_critical_speed_kmh"] == pytest.approx(406.67, abs=0.01)
    assert straight["linear_critical_speed_kmh"] == pytest.approx(441.32, abs=0.01)
    assert {r["status"] for r in data["rows"]} == {"ok"}
    assert png.read_bytes().startswith(PNG_SIGNATURE)
    assert csv.read_text().splitlines()[0].startswith("point,line,radius_m,cant_m")
    assert [r["radius_m"] for r in read_results(out).rows] == [8000.0, math.inf]


def test_stability_map_table_and_fixed_deficiency():
    text = ok("stability-map", "--radius", "4000,inf", "--cant-deficiency", "100",
              "--outputs", "linear_critical_speed", "--workers", "1").stdout  # fmt: skip
    assert "cant deficiency 100 mm" in text and "straight" in text
    assert "2 radii: 2 computed" in text


def test_an_interrupted_stability_map_resumes(tmp_path):
    out = tmp_path / "m.csv"
    args = ["stability-map", "--radius", "3000,6000,inf", "--cant", "150", "--outputs",
            "linear_critical_speed", "--workers", "1", "--out", str(out)]  # fmt: skip
    whole = json.loads(ok(*args, "--json").stdout)
    lines = out.read_text().splitlines(keepends=True)
    out.write_text("".join(lines[:2]) + lines[2][:15])  # one radius done, a torn line
    again = json.loads(ok(*args, "--resume", "--json").stdout)
    assert (again["resumed"], again["computed"]) == (1, 2)
    assert again["rows"] == whole["rows"]
    assert len(out.read_text().splitlines()) == 4  # header + each radius once
    done = ok(*args, "--resume").stdout
    assert "0 computed, 3 already there" in done


def test_ctrl_c_in_a_stability_map_says_how_to_resume(tmp_path, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(railhunt, "stability_map", interrupted, raising=False)
    result = run("stability-map", "--radius", "2000", "--workers", "1", "--out",
                 str(tmp_path / "x.csv"))  # fmt: skip
    assert result.exit_code == 130
    assert "interrupted" in result.stderr and "--resume" in result.stderr


@pytest.mark.parametrize(("args", "fragments"), [
    (["--radius", "2000", "--cant", "150", "--cant-deficiency", "100"],
     ["--cant", "--cant-deficiency", "exclude"]),
    (["--radius", "2000", "--resume"], ["--resume", "--out"]),
    (["--radius", "2000", "--out", "X", "--resume", "--overwrite"], ["--resume", "--overwrite"]),
    (["--radius", "2000", "--scheduler", "tcp://h:1", "--workers", "2"], ["--workers"]),
    (["--radius", "2000,30"], ["--radius", "'30'", "[50, inf)", "'inf'"]),
    (["--radius", "2000,x"], ["--radius", "'x'"]),
    (["--radius", "2000,2000"], ["--radius", "twice"]),
    (["--radius", "2000", "--cant", "900"], ["--cant", "[0, 500] mm"]),
    (["--radius", "2000", "--cant-deficiency", "-600"], ["--cant-deficiency", "[-500, 500]"]),
    (["--radius", "2000", "--outputs", "speed"], ["--outputs", "speed"]),
    (["--radius", "2000", "--workers", "0"], ["--workers"]),
    (["--cant", "150"], ["--radius"]),
])  # fmt: skip
def test_stability_map_input_errors(tmp_path, monkeypatch, args, fragments):
    monkeypatch.chdir(tmp_path)
    assert_input_error(run("stability-map", *args), *fragments)
    assert not (tmp_path / "X").exists()


# --------------------------------------------------------------------------- figures, report


def test_the_figures_are_written(tmp_path):
    from railhunt.plots import plot_curve_entry, plot_stability_map
    from railhunt.studies.store import SweepResults

    rows = [{"point": 0, "line": "radius", "radius_m": 2000.0, "cant_m": 0.15,
             "linear_critical_speed_kmh": math.nan, "linear_frequency_hz": math.nan,
             "critical_speed_kmh": math.nan, "status": "no-critical-speed", "message": ""},
            {"point": 1, "line": "radius", "radius_m": math.inf, "cant_m": 0.0,
             "linear_critical_speed_kmh": 441.3, "linear_frequency_hz": 4.0,
             "critical_speed_kmh": 301.0, "status": "ok", "message": ""}]  # fmt: skip
    meta = {"cant_m": 0.15, "columns": list(rows[0])}
    for subset in (rows, rows[1:], rows[:1]):
        path = plot_stability_map(SweepResults(subset, meta), tmp_path / "map.png")
        assert path.read_bytes().startswith(PNG_SIGNATURE)
    curve = Curve(300.0, 0.15, transition=20.0, start=5.0)
    runs = [railhunt.simulate(v, 60, duration=1.5, curve=curve)
            for v in (PAPER, PAPER.replace(F_u=railhunt.paper2019.NO_BLOWOFF))]
    path = plot_curve_entry(runs[0], PAPER, tmp_path / "entry.png", curve=curve,
                            without_blowoff=runs[1])  # fmt: skip
    assert path.read_bytes().startswith(PNG_SIGNATURE)


def test_the_step_beyond_the_paper(tmp_path):
    from railhunt.studies.records import Context, Settings
    from railhunt.studies.reproduce_curves import curves

    settings = Settings(map_radii=(8000.0, math.inf), map_nonlinear=False)
    step = curves(Context(PAPER, tmp_path, settings))
    assert step.name == "curves" and not step.headline
    assert [p.name for p in step.figures] == ["stability_map.png"]
    assert [r["radius (m)"] for r in step.table] == ["8000", "straight"]
    assert step.table[1]["linear critical speed (km/h)"] == "441.3"
    assert "nonlinear critical speed (km/h)" not in step.table[0]
    assert "not the paper's" in step.shows and "--quick" in step.how
    assert (tmp_path / "stability_map.csv").exists()
    assert Settings.quick().map_nonlinear is False and Settings().map_nonlinear is True
