"""Messages name the flag, not the Python name; estimates are calibrated, long runs ask
for --yes; tables fit in 80 columns."""

from __future__ import annotations

import re

import pytest

from test_cli import assert_input_error, run
from test_cli_robustness import forbid

SWEEP = ["sweep", "C_d1", "--from", "1e5", "--to", "2e5"]


@pytest.mark.parametrize(("args", "flag", "python"), [
    (["critical-speed", "--start", "5"], "--start 5.0 km/h", "start_kmh"),
    ([*SWEEP, "--design", "random", "--samples", "0"], "--samples 0", "samples ="),
    ([*SWEEP, "--frequency-speed", "0"], "--frequency-speed 0.0 km/h", "frequency_speed_kmh"),
    (["sweep", "--table1", "--points-per-section", "1"], "--points-per-section 1",
     "points_per_section"),
])  # fmt: skip
def test_messages_name_the_flag(tmp_path, monkeypatch, args, flag, python):
    forbid(monkeypatch, "railhunt:critical_speed")  # the sweep's own checks come first
    line = assert_input_error(run(*args, "--out", str(tmp_path / "x.csv"))
                              if args[0] == "sweep" else run(*args), flag)  # fmt: skip
    assert python not in line


def test_an_invalid_search_is_refused_before_its_estimate(monkeypatch):
    forbid(monkeypatch, "railhunt:critical_speed")
    result = run("critical-speed", "--start", "5")
    assert "note:" not in result.stderr


def test_a_derived_name_is_explained_not_suggested(tmp_path):
    line = assert_input_error(run("sweep", "v_u", "--from", "1", "--to", "2", "--out",
                                  str(tmp_path / "x.csv")), "v_u is derived", "F_u")  # fmt: skip
    assert "did you mean 'v_u'" not in line


def test_a_binary_irregularity_file_is_named(tmp_path):
    path = tmp_path / "track.csv"
    path.write_bytes(b"\x00\x01\x02\xff\xfe\x00")
    assert_input_error(run("simulate", "--speed", "300", "--irregularity", str(path)),
                       "--irregularity", str(path), "not a text CSV file")  # fmt: skip


def _estimate(result) -> float:
    found = re.search(r"this will take about ([\d.]+) (s|min|h)", result.stderr)
    assert found, result.stderr
    return float(found.group(1)) * {"s": 1.0, "min": 60.0, "h": 3600.0}[found.group(2)]


def test_table1_and_a_wide_bifurcation_are_not_announced_as_minutes(tmp_path, monkeypatch):
    # Measured on the reference machine: Table 1 (91 points, 2 workers) in 21 s, a
    # bifurcation diagram to 2000 km/h in 6 s (benchmarks/workload.py); the estimates
    # were 7 min and 81 s.
    import railhunt.workload as workload

    forbid(monkeypatch, "railhunt:sweep", "railhunt:bifurcation_diagram")
    monkeypatch.setattr(workload, "NOTICE_SECONDS", 0.0)
    table1 = _estimate(run("sweep", "--table1", "--workers", "2", "--out",
                           str(tmp_path / "t.csv")))  # fmt: skip
    assert 21.0 / 2 < table1 < 21.0 * 2
    wide = _estimate(run("bifurcation", "--to", "2000"))
    assert 6.0 / 2 < wide < 6.0 * 2


def test_a_run_of_hours_names_its_step_and_asks_for_yes(monkeypatch):
    forbid(monkeypatch, "railhunt:simulate")
    args = ["simulate", "--speed", "300", "--duration", "1e5", "--output-dt", "10", "--set",
            "C_d1=300"]  # fmt: skip
    assert_input_error(run(*args), "about 3.9 h", "K_d/C_d1", "C_d1", "--yes")
    result = run(*args, "--yes")
    assert type(result.exception).__name__ == "Computed"


def _body_rows(text: str) -> list[str]:
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("┡"))
    end = next(i for i, line in enumerate(lines) if line.startswith("└"))
    return lines[start + 1:end]


@pytest.mark.parametrize("args", [
    ["critical-speed", "--set", "C_d1=3000"],
    ["sweep", "C_d1", "--from", "1e5", "--to", "2e5", "K_d", "--from", "5e6", "--to", "1e7",
     "--num", "2", "--design", "grid", "--tie", "C_d2=C_d1", "--workers", "1", "--out", "OUT"],
])  # fmt: skip
def test_tables_fit_in_80_columns(tmp_path, monkeypatch, args):
    monkeypatch.setenv("COLUMNS", "80")
    argv = [str(tmp_path / "s.csv") if a == "OUT" else a for a in args]
    result = run(*argv)
    assert result.exit_code == 0, result.stderr
    table = [line for line in result.stdout.splitlines() if line[:1] in "┏┃┡│└"]
    assert max(len(line) for line in table) <= 80
    rows = _body_rows(result.stdout)
    wrapped = [r for r in rows if r.split("│")[1].strip() == ""]
    assert rows and wrapped == [], "\n".join(rows)
