"""The input files that ship for the README and the examples, and the wear model behind one.

The generated files (the worn wheel, the rail, the track alignment) must be exactly what
their generators write today, so that their documented source stays true; the hollow-wear
model is checked against its formula; a written profile reads back unchanged.
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

import railhunt
from railhunt.contact.profiles import ProfileError, read_profile, shipped_profile, write_profile
from railhunt.contact.wear import hollow_wear_depth, hollow_worn, worn_s1002

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "examples" / "data"
PACKAGE_WORN = ROOT / "src" / "railhunt" / "data" / "profiles" / "worn_s1002.prw"


def _make_data():
    spec = importlib.util.spec_from_file_location("make_data", DATA / "make_data.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_worn_wheel_ships_twice_identically_and_is_the_generators_output(
        tmp_path: Path) -> None:  # fmt: skip
    fresh = tmp_path / "worn_s1002.prw"
    worn_s1002(fresh)
    assert PACKAGE_WORN.read_bytes() == fresh.read_bytes()
    assert (DATA / "worn_s1002.prw").read_bytes() == fresh.read_bytes()


def test_the_rail_and_the_track_are_the_generators_output(tmp_path: Path) -> None:
    make = _make_data()
    make.make_rail(tmp_path / "my_rail.txt")
    assert (DATA / "my_rail.txt").read_text() == (tmp_path / "my_rail.txt").read_text()
    make.make_alignment(tmp_path / "track_alignment.csv")
    shipped = np.loadtxt(DATA / "track_alignment.csv", delimiter=",", skiprows=1)
    fresh = np.loadtxt(tmp_path / "track_alignment.csv", delimiter=",", skiprows=1)
    assert shipped.shape == fresh.shape == (3001, 2)
    assert np.allclose(shipped, fresh, atol=1e-4)  # mm, the file's last digit


def test_the_data_folders_say_where_every_file_comes_from() -> None:
    readme = (DATA.parent / "README.md").read_text(encoding="utf-8")
    for path in DATA.iterdir():
        if path.suffix != ".py":
            assert f"`{path.name}`" in readme, f"examples/README.md does not describe {path.name}"
    profiles = (PACKAGE_WORN.parent / "README.md").read_text(encoding="utf-8")
    assert "`worn_s1002.prw`" in profiles and "MIT" in profiles and "generated" in profiles


def test_hollow_wear_follows_its_formula() -> None:
    h, c, w = 2e-3, 5e-3, 60e-3
    y = np.array([-0.030, -0.025, 0.0, 0.005, 0.020, 0.035, 0.040])
    expected = [0.0, 0.0, h * math.cos(math.pi * (0 - c) / w) ** 2, h,
                h * math.cos(math.pi * 15e-3 / w) ** 2, 0.0, 0.0]
    assert np.allclose(hollow_wear_depth(y, h, c, w), expected, atol=1e-15)
    new = railhunt.s1002(step=2.5e-4)
    worn = hollow_worn(new)
    assert np.interp(0.0, worn.y, worn.z) == pytest.approx(0.0, abs=1e-15)
    # away from the band the shape is the new one, shifted by the depth removed at y = 0
    d0 = h * math.cos(math.pi * c / w) ** 2
    outside = np.abs(new.y - c) > w / 2
    assert np.allclose(worn.z[outside], new.z[outside] + d0, atol=1e-12)
    assert hollow_worn(new, depth=0.0).z == pytest.approx(new.z)


@pytest.mark.parametrize(("name", "value"), [("depth", -1e-3), ("depth", 6e-3),
                                             ("centre", 0.05), ("width", 0.0)])  # fmt: skip
def test_hollow_wear_rejects_values_out_of_range(name: str, value: float) -> None:
    with pytest.raises(ProfileError, match=f"{name} = .* m is invalid: must be in"):
        hollow_worn(railhunt.s1002(), **{name: value})


def test_the_worn_wheel_raises_the_conicity() -> None:
    rail = railhunt.uic60()
    new = railhunt.contact_geometry(railhunt.s1002(step=1e-5), rail, rail_inclination=1 / 40)
    worn = railhunt.contact_geometry(shipped_profile("S1002_worn"), rail,
                                     rail_inclination=1 / 40)  # fmt: skip
    assert railhunt.equivalent_conicity(new.y, new.delta_r, 3e-3) == pytest.approx(0.1834,
                                                                                  abs=1e-3)
    assert railhunt.equivalent_conicity(worn.y, worn.delta_r, 3e-3) == pytest.approx(0.438,
                                                                                   abs=2e-3)
    # worn.toml's r0 is the worn geometry's centred rolling radius, within the model's 1 um
    vehicle = railhunt.load_vehicle(DATA / "worn.toml")
    table = vehicle.contact.geometry()
    assert abs(np.interp(0.0, table.y, table.r_left) - vehicle.r0) < 1e-6


@pytest.mark.parametrize("suffix", [".prw", ".txt"])
def test_a_written_profile_reads_back(tmp_path: Path, suffix: str) -> None:
    profile = hollow_worn(railhunt.s1002(step=5e-4), depth=1e-3)
    back = read_profile(write_profile(profile, tmp_path / f"p{suffix}", "a\nb"), "wheel")
    assert back.kind == "wheel" and back.y.size == profile.y.size
    assert np.max(np.abs(back.y - profile.y)) < 1e-10
    assert np.max(np.abs(back.z - profile.z)) < 1e-10
    rail = write_profile(railhunt.uic60(), tmp_path / "r.prr")
    assert read_profile(rail).kind == "rail"
