"""``railhunt vehicles`` and ``railhunt vehicle NAME|FILE``."""

from __future__ import annotations

import tomllib
from pathlib import Path

from click.testing import CliRunner

from railhunt.cli import main
from railhunt.vehicle import shipped_vehicles
from railhunt.vehicle.files import shipped_path

ROOT = Path(__file__).resolve().parents[1]


def run(*args: str):
    return CliRunner().invoke(main, list(args))


def test_vehicles_lists_every_shipped_vehicle_with_its_description_and_source():
    result = run("vehicles")
    assert result.exit_code == 0
    lines = result.output.strip().splitlines()
    assert [line.split(":", 1)[0] for line in lines] == list(shipped_vehicles())
    for name in ("cooperrider_bogie", "two_axle_wagon", "three_axle_bogie_car"):
        meta = tomllib.loads(shipped_path(name).read_text(encoding="utf-8"))["vehicle"]
        line = next(x for x in lines if x.startswith(name + ":"))
        assert meta["description"] in line and meta["source"] in line


def test_vehicle_prints_the_layout_and_draws_it(tmp_path):
    png = tmp_path / "coop.png"
    result = run("vehicle", "cooperrider_bogie", "--png", str(png))
    assert result.exit_code == 0, result.output
    assert "7 coordinates, 2 wheelsets, 0 yaw dampers" in result.output
    assert "2 stop to the track" in result.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_vehicle_reads_a_layout_file(tmp_path):
    result = run("vehicle", str(ROOT / "examples" / "data" / "articulated_pair.toml"),
                 "--png", str(tmp_path / "a.png"))
    assert result.exit_code == 0, result.output
    assert "27 coordinates, 6 wheelsets, 8 yaw dampers" in result.output


def test_vehicle_refuses_an_unknown_name_in_one_line():
    result = run("vehicle", "no_such_vehicle")
    assert result.exit_code == 2
    assert "'no_such_vehicle' is neither a file nor a shipped vehicle" in result.output


def test_eigen_draws_the_hunting_mode_of_any_layout(tmp_path):
    png = tmp_path / "mode.png"
    result = run("eigen", "--vehicle", "cooperrider_bogie", "--from", "200", "--to", "260",
                 "--step", "20", "--mode-png", str(png))
    assert result.exit_code == 0, result.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_hunting_mode_shape_is_the_crossing_eigenvector():
    """The drawn shape is normalised to a largest lateral amplitude of 1 (phase 0) and
    belongs to an eigenvalue on the imaginary axis at the Hopf point."""
    import numpy as np
    import pytest

    import railhunt
    from railhunt.plots.layout import hunting_mode_shape

    model, speed, lam, q = hunting_mode_shape(railhunt.Vehicle.shipped("cooperrider_bogie"), None)
    assert abs(lam.real) < 1e-3
    assert lam.imag / (2 * np.pi) == pytest.approx(4.0, abs=0.05)
    lateral = np.concatenate([model.layout.body_y, model.layout.wheelset_y]).astype(int)
    assert np.max(np.abs(q[lateral])) == pytest.approx(1.0)
    assert 240.0 < speed < 250.0
