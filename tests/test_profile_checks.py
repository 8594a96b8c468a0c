"""Garbage profile files are refused naming the file and the likely mistake; a measuring
spike is kept with a warning; a file saved with a UTF-8 byte-order mark is read."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import railhunt
from railhunt.contact.profiles import ProfileError, read_profile, s1002, uic60, write_profile
from test_cli import assert_input_error, run

WHEEL = s1002(step=5e-4)
RAIL = uic60(0.0, step=5e-4)


def columns(path, y_mm, z_mm, fmt="{y:.4f} {z:.4f}") -> str:
    path.write_text("# y z (mm)\n" + "".join(fmt.format(y=a, z=b) + "\n"
                                            for a, b in zip(y_mm, z_mm, strict=True)))  # fmt: skip
    return str(path)


def test_the_shipped_and_standard_profiles_pass_without_a_warning(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for profile in (WHEEL, RAIL, s1002(step=1e-3)):
            back = read_profile(write_profile(profile, tmp_path / f"{profile.kind}.txt"),
                                profile.kind)  # fmt: skip
            assert back.y.size == profile.y.size


@pytest.mark.parametrize("separator", [" ", ";", "\t"])
def test_decimal_commas_are_refused(tmp_path, separator):
    path = columns(tmp_path / "comma.txt", WHEEL.y * 1e3, WHEEL.z * 1e3,
                   fmt="{y:.2f}" + separator + "{z:.2f}")  # fmt: skip
    text = open(path).read().replace(".", ",")
    (tmp_path / "comma.txt").write_text(text)
    with pytest.raises(ProfileError, match="decimal commas") as info:
        read_profile(path, "wheel")
    assert path in str(info.value) and "line 2" in str(info.value)


def test_a_rail_head_given_as_the_wheel_is_refused(tmp_path):
    path = columns(tmp_path / "head.txt", RAIL.y * 1e3, RAIL.z * 1e3)
    with pytest.raises(ProfileError, match="looks like a rail head") as info:
        read_profile(path, "wheel")
    assert path in str(info.value) and "--rail" in str(info.value)


def test_a_wheel_given_as_the_rail_is_refused(tmp_path):
    path = columns(tmp_path / "wheel.txt", WHEEL.y * 1e3, WHEEL.z * 1e3)
    with pytest.raises(ProfileError, match="looks like a wheel"):
        read_profile(path, "rail")


def test_a_simpack_wheel_file_given_as_the_rail_names_its_header():
    from railhunt.contact.profiles import SHIPPED
    from railhunt.contact.profiles import resources as _resources

    wheel = _resources.files("railhunt.data.profiles") / SHIPPED["S1002"]
    result = run("contact", "--rail", str(wheel))
    assert_input_error(result, "--rail", "is a wheel profile", "SIMPACK header type = 1")


@pytest.mark.parametrize("n", [4, 10, 19])
def test_a_profile_of_a_few_points_is_refused(tmp_path, n):
    y = np.linspace(-30.0, 30.0, n)
    with pytest.raises(ProfileError, match=f"only {n} points"):
        read_profile(columns(tmp_path / "few.txt", y, 0.001 * y**2), "wheel")


@pytest.mark.parametrize(("factor", "fragment"), [(1e-3, "in metres"), (1e6, "not millimetres"),
                                                  (1e3, "not millimetres")])  # fmt: skip
def test_values_that_are_not_millimetres_are_refused(tmp_path, factor, fragment):
    path = columns(tmp_path / "unit.txt", WHEEL.y * 1e3 * factor, WHEEL.z * 1e3 * factor,
                   fmt="{y:.9g} {z:.9g}")  # fmt: skip
    with pytest.raises(ProfileError, match=fragment):
        read_profile(path, "wheel")


def test_coordinates_far_too_large_are_one_line_in_the_cli(tmp_path):
    path = columns(tmp_path / "huge.txt", WHEEL.y * 1e9, WHEEL.z * 1e9, fmt="{y:.9g} {z:.9g}")
    assert_input_error(run("contact", "--wheel", path), "--wheel", "not millimetres")


def test_a_single_spike_is_kept_with_a_warning(tmp_path):
    y, z = WHEEL.y * 1e3, WHEEL.z * 1e3
    z = z.copy()
    k = int(np.argmin(np.abs(y - 10.0)))
    z[k] += 5.0
    path = columns(tmp_path / "spike.txt", y, z)
    with pytest.warns(UserWarning, match=rf"point {k + 1} \(y = 10 mm\) stands \+(4\.99|5) mm"):
        profile = read_profile(path, "wheel")
    assert profile.y.size == y.size


def test_a_byte_order_mark_is_skipped(tmp_path):
    path = tmp_path / "bom.txt"
    columns(path, WHEEL.y * 1e3, WHEEL.z * 1e3)
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes().replace(b"# y z (mm)\n", b""))
    profile = read_profile(path, "wheel")
    assert profile.y.size == WHEEL.y.size  # the first point is not lost to the mark


@pytest.mark.parametrize("gauge_mm", ["1400", "1421"])
def test_a_gauge_too_narrow_for_the_flanges_is_refused_before_the_search(gauge_mm, monkeypatch):
    import railhunt.contact.geometry as geometry

    def search(*args, **kwargs):
        raise AssertionError("the contact search started")

    monkeypatch.setattr(geometry, "brentq", search)
    assert_input_error(run("contact", "--gauge", gauge_mm), "too narrow", "over its flanges")


def test_an_impossible_gauge_in_a_vehicle_file_is_one_line(tmp_path):
    path = tmp_path / "narrow.toml"
    path.write_text('[vehicle]\nbase = "paper2019"\nname = "narrow"\n[contact]\ngauge = 1.37\n')
    for command in (["critical-speed"], ["frequency"]):
        assert_input_error(run(*command, "--vehicle", str(path)), str(path), "[contact]",
                           "too narrow")  # fmt: skip


def test_the_contact_of_a_realistic_gauge_still_works():
    geo = railhunt.contact_geometry(gauge=1.435)
    assert geo.y.size > 0
