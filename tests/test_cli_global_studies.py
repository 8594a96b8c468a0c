"""``railhunt sensitivity`` and ``railhunt optimize`` through click's CliRunner."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from railhunt.cli import main

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def run(*args: str):
    try:
        runner = CliRunner(mix_stderr=False)
    except TypeError:  # click >= 8.2 always separates them
        runner = CliRunner()
    return runner.invoke(main, list(args))


def one_error_line(result, *fragments: str) -> None:
    assert result.exit_code == 2, (result.exit_code, result.stdout, result.stderr)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("railhunt: error: "), result.stderr
    for fragment in fragments:
        assert fragment in lines[0], (fragment, lines[0])


def test_sensitivity_json_png_and_resume(tmp_path):
    out, png = tmp_path / "s.csv", tmp_path / "s.png"
    args = ["sensitivity", "C_d1", "--tolerance", "0.2", "F_u", "--from", "3e3", "--to", "9e3",
            "--output", "linear_critical_speed_kmh", "--samples", "4", "--workers", "1",
            "--out", str(out)]
    first = run(*args, "--json", "--png", str(png))
    assert first.exit_code == 0, first.stderr
    data = json.loads(first.stdout)
    assert {"railhunt_version", "vehicle", "vehicle_fingerprint"} <= set(data)
    assert [(r["output"], r["factor"]) for r in data["indices"]] == [
        ("linear_critical_speed_kmh", "C_d1"), ("linear_critical_speed_kmh", "F_u")]
    assert {"S1", "S1_conf", "ST", "ST_conf"} <= set(data["indices"][0])
    assert data["indices"][1]["ST"] == 0.0  # the blow-off force cannot enter
    assert png.read_bytes().startswith(PNG_SIGNATURE)
    again = run(*args, "--resume", "--json")
    assert again.exit_code == 0, again.stderr
    redo = json.loads(again.stdout)
    assert redo["indices"] == data["indices"] and redo["resumed"] == 16 and redo["computed"] == 0
    table = run(*args, "--resume")
    assert "ST_conf" in table.stdout and "F_u" in table.stdout


@pytest.mark.parametrize(("args", "fragments"), [
    (["C_d1", "--from", "1e5", "--output", "linear_critical_speed_kmh"], ["C_d1", "--to"]),
    (["--from", "1e5", "C_d1", "--to", "2e5"], ["--from must follow the NAME"]),
    (["C_d1", "--tolerance", "0.1", "K_d", "--tolerance", "0.1", "--output", "V_cr"],
     ["--output V_cr", "critical_speed_kmh"]),
    (["C_d1", "--tolerance", "0.1", "K_d", "--tolerance", "0.1", "--samples", "100"],
     ["--samples 100", "power of 2"]),
    (["C_d3", "--tolerance", "0.1", "K_d", "--tolerance", "0.1"], ["C_d3"]),
    (["C_d1", "--tolerance", "0.1", "K_d", "--tolerance", "0.1", "--output", "wear_number"],
     ["--curve-radius"]),
    (["C_d1", "--tolerance", "0.1", "K_d", "--tolerance", "0.1", "--output", "wear_number",
      "--curve-radius", "10", "--curve-speed", "100"], ["--curve-radius", "10"]),
])
def test_sensitivity_input_errors(tmp_path, args, fragments):
    one_error_line(run("sensitivity", *args, "--out", str(tmp_path / "x.csv")), *fragments)
    assert not (tmp_path / "x.csv").exists()


def test_optimize_json_png(tmp_path):
    out, png = tmp_path / "p.csv", tmp_path / "p.png"
    result = run("optimize", "K_px", "--from", "2e6", "--to", "40e6", "C_d1", "--tolerance", "0.3",
                 "--objective", "max linear_critical_speed_kmh", "--objective", "min wear_number",
                 "--constraint", "linear_critical_speed_kmh >= 300", "--curve-radius", "600",
                 "--cant", "150", "--curve-speed", "120", "--population", "4",
                 "--generations", "1", "--workers", "1", "--out", str(out), "--png", str(png),
                 "--json")  # fmt: skip
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["evaluated"] == 4 and data["front"] and data["start"]["K_px"] == 85e6
    assert {"railhunt_version", "vehicle_fingerprint"} <= set(data)
    assert len(data["hypervolume"]) == 1
    assert png.read_bytes().startswith(PNG_SIGNATURE)
    # --cant is in mm, as in every command with a curve; the study stores SI
    meta = json.loads(out.with_name(out.name + ".sweep.json").read_text())
    assert meta["curve_cant"] == pytest.approx(0.150)


@pytest.mark.parametrize(("args", "fragments"), [
    (["--objective", "max critical_speed_kmh"], ["--objective is needed at least twice"]),
    (["--objective", "max critical_speed_kmh", "--objective", "least wear_number"],
     ["least wear_number", "max COLUMN"]),
    (["--objective", "max critical_speed_kmh", "--objective", "min wear_number",
      "--constraint", "x > 3"], ["x > 3", "COLUMN >= VALUE"]),
])
def test_optimize_input_errors(tmp_path, args, fragments):
    one_error_line(run("optimize", "K_px", "--tolerance", "0.1", *args, "--out",
                       str(tmp_path / "x.csv")), *fragments)  # fmt: skip
