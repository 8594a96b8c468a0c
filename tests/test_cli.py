"""Tests of the command line interface (railhunt.cli) through click's CliRunner."""

import csv
import json
import math

import pytest
from click.testing import CliRunner

from railhunt.cli import main

COMMANDS = [
    "simulate", "eigen", "critical-speed", "parameters", "spectrogram", "bifurcation", "frequency",
    "sweep", "sections", "plot", "reproduce",
]
#: Commands that take no vehicle: a measured signal's or a results file's analysis, the
#: paper's reproduction.
NO_VEHICLE = {"spectrogram", "sections", "plot", "reproduce"}
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def run(*args: str):
    """Invoke ``railhunt *args`` with stdout and stderr kept apart."""
    try:
        runner = CliRunner(mix_stderr=False)
    except TypeError:  # click >= 8.2 always separates them
        runner = CliRunner()
    return runner.invoke(main, list(args))


def assert_input_error(result, *fragments: str) -> str:
    """Exit status 2, one 'railhunt: error:' line on stderr naming ``fragments``."""
    assert result.exit_code == 2, (result.exit_code, result.stdout, result.stderr)
    assert isinstance(result.exception, SystemExit), result.exception
    assert "Traceback" not in result.stderr + result.stdout
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, result.stderr
    line = lines[0]
    assert line.startswith("railhunt: error: "), line
    for fragment in fragments:
        assert fragment in line, (fragment, line)
    return line


def critical_json(*extra: str) -> dict:
    result = run("critical-speed", "--tol", "5", "--json", *extra)
    assert result.exit_code == 0, result.stderr
    return json.loads(result.stdout)  # the whole of stdout is one JSON object


@pytest.fixture(scope="module")
def default_json() -> dict:
    return critical_json()


# --------------------------------------------------------------------------- help


def test_main_help_teaches():
    result = run("--help")
    assert result.exit_code == 0
    text = result.stdout
    for word in ("hunting", "limit cycle", "km/h", "mm", "SI", *COMMANDS):
        assert word in text, word


@pytest.mark.parametrize("command", COMMANDS)
def test_command_help(command):
    result = run(command, "--help")
    assert result.exit_code == 0, result.stderr
    assert f"railhunt {command}" in result.stdout
    if command not in NO_VEHICLE:
        assert "--vehicle" in result.stdout and "--set" in result.stdout


# --------------------------------------------------------------------------- critical-speed


def test_critical_speed_json(default_json):
    data = default_json
    for key in ("nonlinear_critical_speed_kmh", "linear_critical_speed_kmh"):
        assert isinstance(data[key], float) and math.isfinite(data[key]), key
    assert 100 < data["nonlinear_critical_speed_kmh"] < 600
    assert data["nonlinear_critical_speed_kmh"] < data["linear_critical_speed_kmh"]
    assert data["linear_hunting_frequency_hz"] > 0
    assert data["bracketed"] is True
    assert data["trials"], "trials are listed"
    assert {t["verdict"] for t in data["trials"]} == {"stable", "hunting"}


def test_softer_yaw_damper_lowers_linear_critical_speed(default_json):
    soft = critical_json("--set", "C_d1=150e3")
    assert soft["linear_critical_speed_kmh"] < default_json["linear_critical_speed_kmh"]
    assert "C_d1" in soft["vehicle"]


def test_critical_speed_table():
    result = run("critical-speed", "--tol", "5")
    assert result.exit_code == 0, result.stderr
    assert "nonlinear critical speed" in result.stdout
    assert "linear critical speed" in result.stdout
    assert "hunting" in result.stdout and "stable" in result.stdout
    assert result.stderr == ""  # no progress display off a terminal


# --------------------------------------------------------------------------- simulate


def test_simulate_writes_csv_and_png(tmp_path):
    csv_file, png_file = tmp_path / "run.csv", tmp_path / "run.png"
    result = run(
        "simulate",
        "--speed",
        "300",
        "--duration",
        "2",
        "--csv",
        str(csv_file),
        "--png",
        str(png_file),
    )
    assert result.exit_code == 0, result.stderr
    assert "status:" in result.stdout and "final amplitude" in result.stdout
    with csv_file.open(newline="") as fh:
        rows = list(csv.reader(fh))
    assert any(name.startswith("y_w1") for name in rows[0])
    assert len(rows) > 100
    assert float(rows[-1][0]) == pytest.approx(2.0)
    data = png_file.read_bytes()
    assert data.startswith(PNG_SIGNATURE) and len(data) > 10_000


def test_simulate_initial_displacement():
    result = run("simulate", "--speed", "200", "--duration", "1", "--initial-displacement", "3")
    assert result.exit_code == 0, result.stderr
    assert "displaced by 3 mm" in result.stdout


# --------------------------------------------------------------------------- eigen


def test_eigen_table_csv_png_and_vehicle_file(tmp_path):
    vehicle = tmp_path / "soft.toml"
    vehicle.write_text(
        '[vehicle]\nname = "soft"\nbase = "paper2019"\n\n[parameters]\nC_d1 = 150000.0\n'
    )
    csv_file, png_file = tmp_path / "eig.csv", tmp_path / "eig.png"
    result = run(
        "eigen",
        "--from",
        "100",
        "--to",
        "300",
        "--step",
        "50",
        "--vehicle",
        str(vehicle),
        "--csv",
        str(csv_file),
        "--png",
        str(png_file),
    )
    assert result.exit_code == 0, result.stderr
    assert "soft" in result.stdout and "linear critical speed" in result.stdout
    lines = csv_file.read_text().splitlines()
    assert lines[0].startswith("speed_kmh,hunting_frequency_hz")
    assert len(lines) == 1 + 5
    assert png_file.read_bytes().startswith(PNG_SIGNATURE)


# --------------------------------------------------------------------------- input errors


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (["critical-speed", "--set", "C_d1=-5"], ["C_d1", "-5"]),
        (["critical-speed", "--set", "nosuch=1"], ["nosuch"]),
        (["critical-speed", "--set", "C_d1"], ["C_d1", "NAME=VALUE"]),
        (["critical-speed", "--set", "C_d1=abc"], ["C_d1", "abc"]),
        (["critical-speed", "--set", "v_u=3"], ["v_u", "derived"]),
        (["critical-speed", "--set", "l1=30"], ["l1", "30"]),
        (["simulate", "--speed", "-3"], ["--speed", "-3"]),
        (["simulate", "--speed", "nan"], ["--speed", "nan"]),
        (["simulate"], ["--speed"]),
        (["simulate", "--speed", "300", "--vehicle", "no/such/vehicle.toml"], ["vehicle.toml"]),
        (["simulate", "--speed", "300", "--amplitude", "80"], ["--amplitude", "80"]),
        (["simulate", "--speed", "300", "--method", "euler"], ["--method", "euler"]),
        (["simulate", "--speed", "300", "--csv", "no/such/dir/x.csv"], ["--csv", "no/such/dir"]),
        (["eigen", "--from", "300", "--to", "100"], ["--to", "--from"]),
        (["critical-speed", "--tol", "20"], ["--tol", "20"]),
        (["no-such-command"], ["no-such-command"]),
    ],
)
def test_bad_input_is_one_line_exit_2(args, fragments):
    assert_input_error(run(*args), *fragments)


def test_bad_vehicle_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[parameters]\nC_d1 = -1.0\n[vehicle]\nbase = 'paper2019'\n")
    assert_input_error(run("eigen", "--vehicle", str(bad)), "bad.toml", "C_d1", "-1")
    broken = tmp_path / "broken.toml"
    broken.write_text("this is = = not toml\n")
    assert_input_error(run("parameters", "--vehicle", str(broken)), "broken.toml")


# --------------------------------------------------------------------------- bifurcation, frequency


def test_bifurcation_json_and_png(tmp_path):
    """A short range around the Hopf point: JSON keys, the Hopf speed and a PNG."""
    png = tmp_path / "bif.png"
    result = run("bifurcation", "--from", "420", "--to", "460", "--json", "--png", str(png))
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    for key in ("hopf_speed_kmh", "fold_speed_kmh", "hopf_type", "branches", "point_p", "folds"):
        assert key in data, key
    assert data["hopf_type"] in ("subcritical", "supercritical-a", "supercritical-b")
    assert abs(data["hopf_speed_kmh"] - 441.3) < 0.5
    assert png.read_bytes()[:8] == PNG_SIGNATURE


def test_bifurcation_rejects_inverted_range():
    assert_input_error(run("bifurcation", "--from", "400", "--to", "300"), "--to", "--from")


def test_frequency_table_jump_and_pngs(tmp_path):
    png, damper = tmp_path / "f.png", tmp_path / "d.png"
    result = run("frequency", "--from", "340", "--to", "400", "--step", "30", "--json",
                 "--png", str(png), "--damper-png", str(damper))
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    sources = [p["source"] for p in data["points"]]
    assert sources[0] == "eigenvalue" and sources[-1] == "limit-cycle"
    assert data["jump"]["to_hz"] - data["jump"]["from_hz"] > 1.0
    assert png.read_bytes()[:8] == PNG_SIGNATURE
    assert damper.read_bytes()[:8] == PNG_SIGNATURE


def test_frequency_rejects_bad_amplitude():
    assert_input_error(run("frequency", "--initial-amplitude", "-3"), "--initial-amplitude")


@pytest.mark.parametrize("value", ["3,abc", "-1", "0", "3,,4"])
def test_bifurcation_rejects_bad_fu_family(value):
    assert_input_error(run("bifurcation", "--fu-family", value), "--fu-family")


def test_family_png_needs_family(tmp_path):
    assert_input_error(run("bifurcation", "--family-png", str(tmp_path / "f.png")),
                       "--family-png", "--fu-family")


# --------------------------------------------------------------------------- sweep


def test_sweep_json_and_table(tmp_path):
    out = tmp_path / "s.csv"
    args = ["sweep", "K_px", "--from", "2e7", "--to", "6e7", "--num", "3", "--outputs",
            "linear_critical_speed", "--workers", "1", "--out", str(out)]  # fmt: skip
    result = run(*args, "--json")
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["points"] == 3 and data["computed"] == 3 and data["lost"] == 0
    assert [r["K_px"] for r in data["rows"]] == [2e7, 4e7, 6e7]
    assert all(300 < r["linear_critical_speed_kmh"] < 700 for r in data["rows"])
    again = run(*args, "--resume")
    assert again.exit_code == 0, again.stderr
    assert "0 computed" in again.stdout and "3 already there" in again.stdout


@pytest.mark.parametrize(
    ("args", "fragments"),
    [
        (["C_d1", "--from", "1e5", "--to", "2e5", "K_d", "--from", "1e6", "--num", "2"],
         ["--to", "1 times", "2 NAMEs"]),
        (["Cd1", "--from", "1e5", "--to", "2e5"], ["Cd1", "C_d1"]),
        (["mu", "--from", "0.1", "--to", "2.0", "--num", "3"], ["mu", "1.5"]),
        (["mu", "--from", "0.3", "--to", "0.1"], ["mu", "not a range"]),
        (["mu", "--from", "0.1", "--to", "0.3", "--resume", "--overwrite"], ["--resume"]),
        (["mu", "--from", "0.1", "--to", "0.3", "--outputs", "speed"], ["--outputs", "speed"]),
        (["mu", "--from", "0.1", "--to", "0.3", "--tie", "f22"], ["f22", "FOLLOWER=LEADER"]),
        (["mu", "--from", "0.1", "--to", "0.3", "--design", "lhs"], ["samples"]),
        (["mu", "--from", "0.1", "--to", "0.3", "--workers", "0"], ["workers"]),
        ([], ["NAME", "--table1"]),
        (["--table1", "--from", "1"], ["--table1", "--from"]),
        (["--table1", "K_py"], ["K_py", "Table 1"]),
        (["--table1", "--points-per-section", "1"], ["--points-per-section 1"]),
    ],
)
def test_sweep_input_errors(tmp_path, args, fragments):
    result = run("sweep", *args, "--out", str(tmp_path / "e.csv"))
    assert_input_error(result, *fragments)
    assert not (tmp_path / "e.csv").exists()


def test_sweep_table1_is_the_papers_study(tmp_path):
    """--table1 runs each chosen Table 1 parameter over its sections, f22 tied to f11."""
    out = tmp_path / "t1.csv"
    result = run("sweep", "--table1", "f11", "C_d2", "--points-per-section", "2", "--outputs",
                 "linear_critical_speed", "--workers", "1", "--out", str(out))  # fmt: skip
    assert result.exit_code == 0, result.stderr
    from railhunt.studies.store import read_results

    res = read_results(out)
    assert res.lines == ["f11", "C_d2"]
    f11 = res.line("f11")
    assert list(f11.column("f11")) == [2e6, 5e6, 8e6, 11e6]
    assert list(f11.column("f22")) == list(f11.column("f11"))
    assert list(res.line("C_d2").column("C_d2")) == [1e3, 40e3, 80e3, 120e3]


def test_sweep_refuses_to_overwrite(tmp_path):
    out = tmp_path / "x.csv"
    out.write_text("keep me")
    result = run("sweep", "mu", "--from", "0.1", "--to", "0.3", "--out", str(out))
    assert_input_error(result, "exists", "--resume")
    assert out.read_text() == "keep me"
