"""MiniProf wheel and rail files: read back to the profile written, in railhunt's axes and
units, smoothed within the noise; garbled files refused naming the file and the line; the
fleet command's table and JSON."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import railhunt
from railhunt.contact.bands import two_point_bands
from railhunt.contact.profiles import (
    Profile,
    ProfileError,
    _s1002_mm,
    normal_distance,
    read_profile,
    s1002,
    shipped_profile,
    uic60,
    write_profile,
)
from railhunt.contact.wear import MEASURED_LIKE, measured_like
from test_cli import run

WHEEL = s1002(step=2.5e-4)
RAIL = uic60(0.0, step=2.5e-4)


@pytest.fixture(scope="module")
def mbench_conicity() -> float:
    """Equivalent conicity of the SIMPACK-file S1002 on UIC60 1:40, at 3 mm."""
    wheel = shipped_profile("S1002")
    geo = railhunt.contact_geometry(wheel, uic60(0.0, step=1e-5), rail_inclination=1 / 40)
    return railhunt.equivalent_conicity(geo.y, geo.delta_r, 3e-3)


def test_a_miniprof_s1002_reads_back_within_1_um(tmp_path):
    path = write_profile(WHEEL, tmp_path / "s1002.whl")
    back = read_profile(path, smooth=0)
    assert back.kind == "wheel" and back.meta["format"] == "miniprof"
    # the back-face band (0.5 mm next to the flange back) is dropped, the rest is S1002
    assert back.y[0] == pytest.approx(-0.06925, abs=1e-9) and back.y[-1] == pytest.approx(0.060)
    assert np.max(np.abs(back.z - _s1002_mm(back.y * 1e3) * 1e-3)) < 1e-6
    rail = read_profile(write_profile(RAIL, tmp_path / "uic60.ban"), smooth=0)
    assert rail.kind == "rail" and np.max(normal_distance(rail.y, rail.z, RAIL)) < 1e-6


def test_miniprof_axes_are_mirrored_and_shifted_as_miniprof_writes_them(tmp_path):
    path = write_profile(WHEEL, tmp_path / "s1002.whl")
    rows = [line.split() for line in path.read_text().splitlines() if line[:1].isdigit()]
    x, h = np.array(rows, dtype=float).T
    assert x[0] == 0.0 and x[-1] == pytest.approx(130.0)   # from the flange back, mm
    assert h.max() > 25.0                                     # the flange stands up (Y up)
    rail_rows = [line.split() for line in write_profile(RAIL, tmp_path / "r.ban").read_text()
                 .splitlines() if line[:1] in "-0123456789" and " " in line]  # fmt: skip
    assert np.array(rail_rows, dtype=float)[:, 1].max() == pytest.approx(0.0)  # top at 0, Y up


def test_the_read_back_s1002_conicity_equals_the_simpack_file_s_within_1_percent(
    tmp_path, mbench_conicity
):
    back = read_profile(write_profile(WHEEL, tmp_path / "s1002.whl"))
    geo = railhunt.contact_geometry(back, uic60(0.0, step=1e-5), rail_inclination=1 / 40)
    tan_ge = railhunt.equivalent_conicity(geo.y, geo.delta_r, 3e-3)
    assert tan_ge == pytest.approx(mbench_conicity, rel=0.01)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_noisy_measurement_is_smoothed_to_within_its_noise(tmp_path, seed):
    sigma = 10e-6
    rng = np.random.default_rng(seed)
    noisy = Profile(WHEEL.y, WHEEL.z + rng.normal(0.0, sigma, WHEEL.y.size), "wheel", "n")
    back = read_profile(write_profile(noisy, tmp_path / "noisy.whl"))
    assert back.meta["noise"] == pytest.approx(sigma, rel=0.3)  # estimated from the points
    d = normal_distance(back.y, back.z, WHEEL)
    assert math.sqrt(np.mean(d**2)) < sigma          # RMS: within the noise
    assert np.max(d) < 5 * sigma
    raw = read_profile(tmp_path / "noisy.whl", smooth=0)
    assert math.sqrt(np.mean(normal_distance(raw.y, raw.z, WHEEL) ** 2)) > 0.5 * sigma


def test_the_shipped_measured_like_wheels_are_their_generator_s_output():
    from importlib import resources

    for name, (depth, centre, width, seed) in MEASURED_LIKE.items():
        ref = resources.files("railhunt") / "data" / "profiles" / name
        assert ref.read_text(encoding="utf-8") == measured_like(depth, centre, width, seed,
                                                                name=name)  # fmt: skip


def test_a_worn_wheel_s_conicity_is_higher_than_the_new_one_s(mbench_conicity):
    rail = uic60(0.0, step=1e-5)
    worn = shipped_profile("worn_hollow_2mm")
    assert worn.meta["miniprof.back_face_points"] > 50      # the back face is dropped
    geo = railhunt.contact_geometry(worn, rail, rail_inclination=1 / 40)
    tan_ge = railhunt.equivalent_conicity(geo.y, geo.delta_r, 3e-3)
    assert tan_ge > 2.0 * mbench_conicity
    # the hollow tread adds a two-point band at 2-3 mm, where the new wheel has none
    assert any(2e-3 <= a and b <= 3e-3 for a, b in two_point_bands(geo, worn, rail))


def test_the_two_point_bands_of_s1002_on_uic60_straddle_the_tread_jump():
    rail = uic60(0.0, step=1e-5)
    new = s1002(step=1e-5)
    geo = railhunt.contact_geometry(new, rail, rail_inclination=1 / 40)
    bands = two_point_bands(geo, new, rail)
    assert any(a <= 4.8e-3 <= b for a, b in bands)           # the jump at 4.8-4.9 mm
    assert any(a <= -4.8e-3 <= b for a, b in bands)          # and its mirror
    assert not any(a <= 8e-3 <= b for a, b in bands)         # not on the flange run-up


HEADER = "Filename=x.whl\nColumnDef=X,Y\n\n"


def good_lines() -> list[str]:
    return [f"{(y + 0.070) * 1e3:.4f} {z * 1e3:.4f}" for y, z in zip(WHEEL.y, WHEEL.z,
                                                                    strict=True)]  # fmt: skip


@pytest.mark.parametrize(
    ("change", "line", "words"),
    [
        (lambda ls: ls.__setitem__(40, "12.5 abc"), 44, "not a number"),
        (lambda ls: ls.__setitem__(40, "12.5 nan"), 44, "not a number"),
        (lambda ls: ls.__setitem__(40, "12.5 3.2 7.7"), 44, "has 3 values"),
        (lambda ls: ls.insert(40, "XYPoints=7"), 44, "header line among the points"),
        (lambda ls: ls.__setitem__(300, "10.0000 5.0000"), 304, "folds back"),
        (lambda ls: ls.__setitem__(40, "12,5 3,2"), 44, "decimal commas"),
    ],
)
def test_a_garbled_miniprof_file_is_refused_naming_the_file_and_line(tmp_path, change, line,
                                                                      words):  # fmt: skip
    lines = good_lines()
    change(lines)
    path = tmp_path / "garbled.whl"
    path.write_text(HEADER + "\n".join(lines) + "\n")
    with pytest.raises(ProfileError, match=words) as info:
        read_profile(path)
    message = str(info.value)
    assert str(path) in message and f"line {line}" in message and "\n" not in message


def test_other_refusals_name_the_file(tmp_path):
    few = tmp_path / "few.whl"
    few.write_text(HEADER + "\n".join(good_lines()[::40]) + "\n")
    with pytest.raises(ProfileError, match="only .* points") as info:
        read_profile(few)
    assert str(few) in str(info.value)
    metres = tmp_path / "metres.ban"
    metres.write_text("ColumnDef=X,Y\n\n" + "\n".join(
        f"{y:.7f} {-z:.7f}" for y, z in zip(RAIL.y, RAIL.z, strict=True)) + "\n")
    with pytest.raises(ProfileError, match="metres"):
        read_profile(metres)
    mirrored = tmp_path / "mirrored.whl"
    mirrored.write_text(HEADER + "\n".join(
        f"{130 - (y + 0.070) * 1e3:.4f} {z * 1e3:.4f}" for y, z in zip(WHEEL.y, WHEEL.z,
                                                                      strict=True)) + "\n")
    with pytest.raises(ProfileError, match="mirror_y"):
        read_profile(mirrored)
    negative = tmp_path / "negative.whl"   # X negative toward the field side: mirror_y
    negative.write_text(HEADER + "\n".join(
        f"{-(y + 0.070) * 1e3:.4f} {z * 1e3:.4f}" for y, z in zip(WHEEL.y, WHEEL.z,
                                                                 strict=True)) + "\n")
    back = read_profile(negative, mirror_y=True, smooth=0)
    assert np.max(np.abs(back.z - _s1002_mm(back.y * 1e3) * 1e-3)) < 1e-6


def test_repair_drops_the_points_that_fold_back(tmp_path):
    lines = good_lines()
    lines[300] = "10.0000 5.0000"
    path = tmp_path / "fold.whl"
    path.write_text(HEADER + "\n".join(lines) + "\n")
    back = read_profile(path, repair=True, smooth=0)
    assert back.meta["miniprof.dropped_fold_lines"] == [304]


@settings(max_examples=60, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=40),
                max_size=30))  # fmt: skip
def test_random_garbage_is_refused_in_one_line_naming_the_file(tmp_path, rows):
    path = tmp_path / "garbage.whl"
    path.write_text("\n".join(rows), encoding="utf-8")
    with pytest.raises(ProfileError) as info:
        read_profile(path)
    assert str(path) in str(info.value) and "\n" not in str(info.value).strip()


def test_the_conicity_command_tabulates_the_shipped_wheels(tmp_path):
    from importlib import resources

    folder = resources.files("railhunt") / "data" / "profiles"
    files = [str(folder / name) for name in MEASURED_LIKE]
    result = run("conicity", "S1002", *files, "--png", str(tmp_path / "fleet.png"))
    assert result.exit_code == 0, result.output
    assert "0.183" in result.output and "worn_hollow_2mm.whl" in result.output
    assert "±4.3…5.3" in result.output
    assert (tmp_path / "fleet.png").stat().st_size > 5000
    data = json.loads(run("conicity", "S1002", *files, "--json").output)
    rows = {w["name"]: w for w in data["wheels"]}
    assert rows["S1002"]["equivalent_conicity"] == pytest.approx(0.1834, abs=5e-4)
    assert rows["worn_hollow_2mm.whl"]["equivalent_conicity"] > 0.4
    assert [-0.0053, -0.0043] in rows["S1002"]["two_point_bands_m"]
    assert "railhunt_version" in data


def test_the_conicity_command_refuses_a_garbled_file_in_one_line(tmp_path):
    path = tmp_path / "bad.whl"
    path.write_text(HEADER + "0 1\n2 x\n")
    result = run("conicity", str(path))
    assert result.exit_code == 2 and "bad.whl" in result.output and "line 5" in result.output


@pytest.mark.slow
def test_critical_speeds_of_one_worn_wheel(tmp_path):
    from importlib import resources

    path = resources.files("railhunt") / "data" / "profiles" / "worn_hollow_2mm.whl"
    data = json.loads(run("conicity", str(path), "--critical-speed", "--json").output)
    row = data["wheels"][0]
    # the hollow wheel's conicity (0.44 against 0.18) lowers both speeds well below the
    # new wheel's 327 km/h (linear) and 213 km/h (nonlinear) on s1002_uic60_table
    assert 100.0 < row["linear_critical_speed_kmh"] < 300.0
    assert 100.0 < row["nonlinear_critical_speed_kmh"] < 213.0
    assert data["vehicle"].startswith("s1002_uic60_table")


def test_a_vehicle_keeps_the_smoothing_of_its_measured_wheel(tmp_path):
    """The smoothing given with a wheel goes into the vehicle's [contact] section: its
    geometry reads the file with it (here 0: the raw points, whose conicity differs from
    the smoothed ones'), and the vehicle file written and read back keeps it."""
    from importlib import resources

    from railhunt.studies.fleet import with_wheel

    path = str(resources.files("railhunt") / "data" / "profiles" / "worn_hollow_2mm.whl")
    base = railhunt.Vehicle.shipped("s1002_uic60_table")
    raw = with_wheel(base, path, smooth=0.0)
    default = with_wheel(base, path)
    assert raw.contact.smooth == 0.0 and default.contact.smooth is None
    g_raw, g_default = raw.contact.geometry(), default.contact.geometry()
    # the raw points' contact jumps differ from the smoothed profile's somewhere along y
    assert np.max(np.abs(g_raw.r_left - g_default.r_left)) > 1e-7
    file = tmp_path / "raw.toml"
    raw.to_toml(file)
    again = railhunt.Vehicle.from_toml(file)
    assert again.contact.smooth == 0.0
    assert np.array_equal(again.contact.geometry().r_left, g_raw.r_left)


@pytest.mark.parametrize("value", [-1e-5, 1e-3, float("nan"), "noisy", True])
def test_a_contact_smoothing_out_of_range_is_refused_naming_it(value):
    from railhunt.vehicle.contact import ContactSpec

    with pytest.raises(ValueError, match=r"contact smooth = .* is invalid: must be"):
        ContactSpec(smooth=value)


def test_the_conicity_command_writes_the_fleet_as_csv(tmp_path):
    import csv
    from importlib import resources

    path = resources.files("railhunt") / "data" / "profiles" / "worn_hollow_2mm.whl"
    out = tmp_path / "fleet.csv"
    result = run("conicity", "S1002", str(path), "--csv", str(out))
    assert result.exit_code == 0, result.output
    rows = list(csv.DictReader(out.open()))
    assert [r["wheel"] for r in rows] == ["S1002", "worn_hollow_2mm.whl"]
    # the same conicities as the JSON output (0.183 and 0.436 at 3 mm)
    data = json.loads(run("conicity", "S1002", str(path), "--json").output)
    for row, wheel in zip(rows, data["wheels"], strict=True):
        assert float(row["equivalent_conicity"]) == pytest.approx(
            wheel["equivalent_conicity"], rel=1e-5)
        bands = [[float(v) * 1e-3 for v in pair.split(":")]
                 for pair in row["two_point_bands_mm"].split(";")]  # fmt: skip
        assert np.allclose(bands, wheel["two_point_bands_m"], atol=1e-7)
    assert (tmp_path / "fleet.csv.meta.json").is_file()
