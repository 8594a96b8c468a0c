"""Two-point contact in the kernel: the table over (y, psi), the wheelset forces against the
per-point model where each wheel has one patch, mirror symmetry, smoothness across the
two-point band, and the shipped two-point vehicle."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import railhunt
from railhunt.kernel.layout import WR, PatchColumn
from railhunt.kernel.wheelset import wheelset_contact
from railhunt.model import Model

TWO_POINT = "s1002_uic60_two_point"
PER_POINT = "s1002_uic60_per_point"
V = 300.0 / 3.6


@pytest.fixture(scope="module")
def models() -> tuple[Model, Model]:
    return Model(railhunt.Vehicle.shipped(PER_POINT)), Model(railhunt.Vehicle.shipped(TWO_POINT))


@pytest.fixture(scope="module")
def table():
    from railhunt.contact.patch_table import _vehicle_table
    from railhunt.contact.point_contact import POISSON, SHEAR_MODULUS

    spec = railhunt.Vehicle.shipped(TWO_POINT).contact
    return _vehicle_table(spec, 10900.0 * 9.81 / 2.0, SHEAR_MODULUS, POISSON, False)


def _forces(model: Model, y: float, dy: float = 0.0, psi: float = 0.0,
            yaw_rate: float = 0.0) -> np.ndarray:  # fmt: skip
    wr = model.system().wheel_rail[0]
    q = wr[WR.N]
    return np.array(wheelset_contact(y, dy, psi, psi, yaw_rate, yaw_rate, V, wr, q, q,
                                     model.system().creep_table))  # fmt: skip


def test_the_paper_and_per_point_vehicles_do_not_use_it(models):
    from railhunt.kernel.two_point import uses_two_point

    per_point, two_point = models
    assert not uses_two_point(per_point.system().wheel_rail[0])
    assert not uses_two_point(Model(railhunt.Vehicle.paper2019()).system().wheel_rail[0])
    assert uses_two_point(two_point.system().wheel_rail[0])
    assert two_point.contact_mechanics == ("two-point",) * 4


def test_shares_sum_to_one_and_two_patches_where_s1002_touches_twice(table):
    """Every wheel's patches carry its whole load at every node; the left wheel touches
    twice only around y = +4.5 ... +5.3 mm and on the flange's onset (centred yaw)."""
    shares = table.shares
    np.testing.assert_allclose(shares.sum(axis=-1), 1.0, atol=1e-9)
    j0 = table.psi.size // 2
    two = table.y[(shares[j0, :, 0] > 0).all(axis=-1)]
    assert two.size > 0
    assert np.all((two > 0.004) & (two < 0.0075)), two
    assert np.any((two > 0.0045) & (two < 0.0053))
    # mirror: the right wheel at -y is the left one at +y
    np.testing.assert_allclose(np.sort(shares[j0, ::-1, 1], axis=-1),
                               np.sort(shares[j0, :, 0], axis=-1), atol=1e-12)  # fmt: skip


def test_single_patch_forces_are_the_per_point_model(models):
    """Where each wheel has one patch and the wheelset neither yaws nor turns, its forces
    are the per-point model's: the same ellipse, coefficients, creepages and normal
    forces (1 %: the curvatures read from a 0.1-mm grid, the table's step)."""
    per_point, two_point = models
    for y in (0.001, 0.003, -0.002):
        for dy in (0.0, 0.05):
            a = _forces(per_point, y, dy)
            b = _forces(two_point, y, dy)
            assert b[0] == pytest.approx(a[0], rel=1e-2, abs=5.0)
            assert b[2] == pytest.approx(a[2], rel=1e-2, abs=5.0)


@pytest.mark.parametrize("y, dy, psi, rate", [(0.0048, 0.02, 0.003, 0.01),
                                              (0.007, -0.05, -0.004, 0.02),
                                              (0.002, 0.1, 0.008, -0.05)])
def test_mirror_symmetry(models, y, dy, psi, rate):
    """The mirrored wheelset feels the mirrored forces: F_y, M_z change sign and the
    left wheel's force is the right one's (1e-9 relative)."""
    _, two_point = models
    a = _forces(two_point, y, dy, psi, rate)
    b = _forces(two_point, -y, -dy, -psi, -rate)
    scale = np.abs(a).max()
    np.testing.assert_allclose(a[:2], -b[:2], atol=1e-9 * scale)
    np.testing.assert_allclose(a[2:], -b[[3, 2]], atol=1e-9 * scale)


def test_forces_are_smooth_across_the_two_point_band(models):
    """Across the band where the left wheel touches twice the lateral force has a
    continuous slope (Catmull-Rom in y, the shares' Hermite): at every node of either
    table in 4-6 mm the slopes on its two sides (10-nm differences) agree to 1e-3 of the
    largest slope there, where the per-point model's linear blend kinks (above 5 %)."""
    per_point, two_point = models
    nodes = np.arange(0.0040, 0.0060 + 1e-12, 1e-4)
    h = 1e-8

    def kinks(model: Model) -> float:
        jumps, slopes = [], []
        for y in nodes:
            f0, fp, fm = (_forces(model, y + d, 0.02)[0] for d in (0.0, h, -h))
            right, left = (fp - f0) / h, (f0 - fm) / h
            jumps.append(abs(right - left))
            slopes.append(max(abs(right), abs(left)))
        return float(max(jumps) / max(slopes))

    assert kinks(two_point) < 1e-3
    assert kinks(per_point) > 0.05


def test_yawed_flange_lateral_creepage_follows_the_contact_point(models):
    """On the flange (y = 8 mm) a yaw of +1 mrad changes the wheelset's lateral force by
    the flange patch's true lateral creepage, about ``-psi / cos(delta)``: several times
    what the per-point model (``-psi cos(delta)``) gives."""
    per_point, two_point = models
    d_two = _forces(two_point, 0.008, 0.0, 1e-3)[2] - _forces(two_point, 0.008)[2]
    d_one = _forces(per_point, 0.008, 0.0, 1e-3)[2] - _forces(per_point, 0.008)[2]
    assert d_two > 1.5 * d_one > 0.0


def test_shipped_two_point_vehicle_is_what_the_code_writes():
    from importlib import resources

    from railhunt.contact.shipped_layouts import s1002_uic60_two_point_toml

    path = Path(str(resources.files("railhunt") / "data" / "vehicles" / f"{TWO_POINT}.toml"))
    assert path.read_text(encoding="utf-8") == s1002_uic60_two_point_toml()


def test_two_point_needs_profiles():
    with pytest.raises(ValueError, match="'two-point' is invalid for this vehicle"):
        Model(railhunt.Vehicle.paper2019(), contact_mechanics="two-point")


def test_another_contact_table_is_refused_with_two_point_mechanics():
    """The two-point table is built from the vehicle's own profiles: another ``contact=``
    would be ignored silently, so it is refused in one line; the vehicle's own table (as
    the analyses pass it on) is accepted."""
    vehicle = railhunt.Vehicle.shipped(TWO_POINT)
    from railhunt.contact.profiles import shipped_profile

    other = railhunt.contact_geometry(shipped_profile("worn_hollow_2mm"),
                                      railhunt.uic60(0.0), rail_inclination=1 / 40)  # fmt: skip
    with pytest.raises(ValueError, match=r"contact= is invalid with contact_mechanics = "
                                         r"'two-point'") as info:  # fmt: skip
        Model(vehicle, contact=other)
    assert "\n" not in str(info.value)
    own = Model(vehicle, contact=vehicle.contact.geometry())
    assert own.contact_mechanics[0] == "two-point"


def test_table_columns_are_continuous_where_a_patch_takes_load(table):
    """A slot's geometry does not jump where its share rises from 0: its contact angle
    and rolling radius at the first loaded node are within 2 mm's worth of the previous
    node's (the slot follows its valley)."""
    j0 = table.psi.size // 2
    c = table.columns[j0, :, 0]
    for k in (0, 1):
        w = c[:, k, PatchColumn.W]
        onset = np.flatnonzero((w[1:] > 0) & (w[:-1] == 0)) + 1
        for i in onset:
            if w[i] < 0.5:  # a patch setting in (not a contact jumping whole)
                assert abs(c[i, k, PatchColumn.R] - c[i - 1, k, PatchColumn.R]) < 5e-4
