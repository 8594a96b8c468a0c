"""Contact patches of a yawed wheelset (railhunt.contact_patches): the contact locus and
its lead against closed forms, mirror symmetry, yaw 0 against the rigid contact table,
load sharing between two patches and the creepages of pure rolling."""

import json
import math

import numpy as np
import pytest

import railhunt
from railhunt.contact.geometry import contact_geometry
from railhunt.contact.patches import contact_patches
from railhunt.contact.profiles import Profile, s1002, uic60

Q = 53_410.0  # the paper's static wheel load W g / 2 (N)
INCL = 1.0 / 40.0


@pytest.fixture(scope="module")
def profiles() -> tuple[Profile, Profile]:
    return s1002(step=1e-5), uic60(0.0, step=1e-5)


def _cone(gamma: float) -> Profile:
    u = np.linspace(-0.06, 0.06, 1201)
    return Profile(u, -gamma * u, "wheel", "cone")


def _knife_edge(slope: float) -> Profile:
    t = np.linspace(-0.02, 0.02, 4001)
    return Profile(t, slope * np.abs(t), "rail", "knife edge")


def test_exported_from_the_package():
    assert railhunt.contact_patches is contact_patches
    assert "contact_patches" in railhunt.__all__


@pytest.mark.parametrize("y, yaw", [(0.0048, 0.003), (0.007, -0.008), (0.002, 0.01)])
def test_left_at_y_is_the_right_at_minus_y(profiles, y, yaw):
    """Mirror symmetry: the left wheel at (y, psi) is the right wheel at (-y, -psi), to
    1e-9 m (the sampling is mirrored exactly; brentq's roll to 1e-12)."""
    w, r = profiles
    a = contact_patches(w, r, y, yaw, rail_inclination=INCL, normal_load=Q)
    b = contact_patches(w, r, -y, -yaw, rail_inclination=INCL, normal_load=Q)
    assert a.roll == pytest.approx(-b.roll, abs=1e-10)
    for one, other in ((a.left, b.right), (a.right, b.left)):
        assert len(one) == len(other)
        for p, q in zip(one, other, strict=True):
            assert p.x == pytest.approx(q.x, abs=1e-9)
            assert p.y == pytest.approx(-q.y, abs=1e-9)
            for name in ("z", "rolling_radius", "contact_angle", "wheel_y", "rail_y", "gap"):
                assert getattr(p, name) == pytest.approx(getattr(q, name), abs=1e-9), name
            assert p.normal_force == pytest.approx(q.normal_force, rel=1e-6)


def test_yaw_zero_is_the_rigid_contact_table(profiles):
    """At zero yaw the first patch of each wheel is contact_geometry's point, to 1e-10 m
    and rad, and leads by nothing."""
    w, r = profiles
    geo = contact_geometry(w, r, rail_inclination=INCL, r0=0.46, y_max=0.009, y_step=1e-3)
    for k, y in enumerate(geo.y):
        c = contact_patches(w, r, float(y), 0.0, rail_inclination=INCL)
        assert c.roll == pytest.approx(geo.roll[k], abs=1e-10)
        for side, p in (("left", c.left[0]), ("right", c.right[0])):
            assert p.rolling_radius == pytest.approx(getattr(geo, f"r_{side}")[k], abs=1e-10)
            assert p.contact_angle == pytest.approx(getattr(geo, f"delta_{side}")[k],
                                                    abs=1e-10)  # fmt: skip
            assert p.wheel_y == pytest.approx(getattr(geo, f"wheel_{side}")[k], abs=1e-10)
            assert p.rail_y == pytest.approx(getattr(geo, f"rail_{side}")[k], abs=1e-10)
            point = getattr(geo, f"contact_{side}")[k]
            assert (p.y, p.z) == pytest.approx(tuple(point), abs=1e-10)
            assert p.x == 0.0


@pytest.mark.parametrize("gamma", [0.05, 0.3])
@pytest.mark.parametrize("yaw", [0.005, -0.02])
def test_yawed_cone_on_a_knife_edge_is_closed_form(gamma, yaw):
    """A cone ``r = R0 - gamma s`` (axle coordinate ``s``) centred on knife edges:
    the locus is ``sin(theta) = gamma tan(psi)``, the contact section solves
    ``s cos(psi) + r(s) sin(theta) sin(psi) = Y_k`` (linear in ``s``) and the lead is
    ``r sin(theta) / cos(psi)``; the right wheel's the opposite."""
    slope = 5.0
    c = contact_patches(_cone(gamma), _knife_edge(slope), 0.0, yaw, r0=0.46)
    y_tape = 0.5 * 1.360 + 0.070
    y_k = 0.5 * 1.435 + 0.014 / slope  # the edge: the gauge point 14 mm under it
    tg = gamma  # the cone's slope dr/ds
    st = tg * math.tan(yaw)
    big_r = 0.46 + y_tape * tg
    s = (y_k - big_r * st * math.sin(yaw)) / (math.cos(yaw) - tg * st * math.sin(yaw))
    radius = big_r - s * tg
    lead = radius * st / math.cos(yaw)
    left, right = c.left[0], c.right[0]
    assert abs(c.roll) < 1e-10
    assert left.wheel_y == pytest.approx(s - y_tape, abs=6e-6)  # half a sample
    assert left.rolling_radius == pytest.approx(radius, abs=6e-6 * tg + 1e-9)
    assert left.x == pytest.approx(lead, rel=1e-6)
    assert right.x == pytest.approx(-lead, rel=1e-6)
    assert left.y == pytest.approx(y_k, abs=2e-6)  # the edge's kink, within a sample


@pytest.mark.parametrize("delta", [math.radians(60.0), math.radians(70.0)])
@pytest.mark.parametrize("yaw", [0.005, 0.01])
def test_lead_of_a_yawed_circular_flange_is_closed_form(delta, yaw):
    """A flange of circular section (radius rho about a circle of radius r_c) on a plane
    rail inclined at delta: the touching point of the yawed torus is at the angle
    ``tan(theta) = sin(psi) tan(delta)`` on its centre circle, so its lead ahead of the
    axle is ``x = r_c sin(theta) / cos(psi) + rho sin(delta) tan(psi)`` (4-13 mm here)."""
    rho, r0, u_c = 0.012, 0.46, -0.06
    u = np.linspace(u_c - 0.9 * rho, u_c + 0.99 * rho, 20001)
    wheel = Profile(u, np.sqrt(rho**2 - (u - u_c) ** 2) - rho, "wheel", "circular flange")
    t = np.linspace(-0.05, 0.05, 1001)
    rail = Profile(t, -t * math.tan(delta), "rail", "plane")
    c = contact_patches(wheel, rail, 0.0, yaw, r0=r0)
    theta = math.atan(math.sin(yaw) * math.tan(delta))
    lead = (r0 - rho) * math.sin(theta) / math.cos(yaw) + rho * math.sin(delta) * math.tan(yaw)
    assert c.left[0].contact_angle == pytest.approx(delta, abs=1e-9)
    # 1 um: the lead changes by 80 um from one 10-um sample of the flange to the next
    assert c.left[0].x == pytest.approx(lead, abs=1e-6)
    assert c.right[0].x == pytest.approx(-lead, abs=1e-6)
    assert 0.003 < abs(lead) < 0.015


def test_two_patches_share_the_wheel_load(profiles):
    """Where S1002 touches UIC60 1:40 on two tread patches (|y| ~ 4.5-5.3 mm): the patches'
    vertical shares sum to the wheel load (1e-9), both patches sink by one approach
    (Hertz: ``N = K ((Delta - g) cos d)^(3/2)``), and the patch of the higher gap (the one a
    single-point search drops) carries 5-61 % of the load, as an elastic contact code finds
    there."""
    from railhunt.contact.patches import ellipse_constants

    w, r = profiles
    dropped = []
    for y in (0.0048, 0.0049, 0.0050):
        c = contact_patches(w, r, y, 0.0, rail_inclination=INCL, normal_load=Q)
        assert len(c.left) == 2 and len(c.right) == 1
        assert sum(p.vertical_load for p in c.left) == pytest.approx(Q, rel=1e-9)
        approach = []
        for p in c.left:
            d1 = ellipse_constants(p.contact_angle, p.rolling_radius, p.wheel_curvature,
                                   p.rail_curvature, 2.1e11, 0.3)[2]  # fmt: skip
            approach.append(p.gap + d1 * p.normal_force ** (2 / 3) / math.cos(p.contact_angle))
        assert approach[0] == pytest.approx(approach[1], rel=1e-6)
        assert c.left[1].gap > 0.0 and c.left[0].gap == 0.0
        dropped.append(c.left[1].vertical_load / Q)
    assert min(dropped) > 0.05 and max(dropped) < 0.61


def test_a_single_patch_carries_the_whole_load(profiles):
    w, r = profiles
    c = contact_patches(w, r, 0.002, 0.0, rail_inclination=INCL, normal_load=(Q, 0.8 * Q))
    assert len(c.left) == len(c.right) == 1
    assert c.left[0].vertical_load == pytest.approx(Q, rel=1e-9)
    assert c.right[0].vertical_load == pytest.approx(0.8 * Q, rel=1e-9)
    assert c.left[0].a > c.left[0].b > 0.0


def test_pure_rolling_has_no_creepage(profiles):
    """A cylindrical wheelset yawed and rolling along its own heading (``dy = V tan psi``,
    ``omega r cos psi = V``) slips nowhere: no creepage (1e-12) and no spin (1e-6 1/m: the
    crown's slope at the refined contact, ~5e-8 rad). A centred S1002
    wheelset rolling at ``omega = V / r`` has no longitudinal or lateral creepage and the
    spin ``-sin(delta) / r`` (left) of its coned tread."""
    u = np.linspace(-0.06, 0.07, 131)
    cylinder = Profile(u, np.zeros_like(u), "wheel", "cylinder")
    yaw, v = 0.008, 40.0
    c = contact_patches(cylinder, uic60(0.0, step=1e-5), 0.003, yaw)
    r = c.left[0].rolling_radius
    cr = c.creepages(v, v / (r * math.cos(yaw)), lateral_velocity=v * math.tan(yaw))
    for side in ("left", "right"):
        ((xi, eta, phi),) = cr[side]
        assert abs(xi) < 1e-12 and abs(eta) < 1e-12 and abs(phi) < 1e-6
    w, rail = profiles
    c = contact_patches(w, rail, 0.0, 0.0, rail_inclination=INCL)
    p = c.left[0]
    ((xi, eta, phi),) = c.creepages(v, v / p.rolling_radius)["left"]
    assert xi == pytest.approx(0.0, abs=1e-12) and eta == pytest.approx(0.0, abs=1e-12)
    assert phi == pytest.approx(-math.sin(p.contact_angle) / p.rolling_radius, rel=1e-9)
    ((_, _, phi_r),) = c.creepages(v, v / p.rolling_radius)["right"]
    assert phi_r == pytest.approx(-phi, rel=1e-9)


def test_flange_lateral_creepage_of_a_yawed_wheelset(profiles):
    """On the flange the true lateral creepage of a yawed wheelset is about
    ``-psi / cos(delta)``, three times the single-point model's ``-psi cos(delta)`` at 55
    degrees (the contact point leads and the wheel rolls along the rail)."""
    w, r = profiles
    yaw, v = 0.005, 50.0
    c = contact_patches(w, r, 0.008, yaw, rail_inclination=INCL)
    p = c.left[0]
    assert p.contact_angle > math.radians(50.0)
    assert p.x == pytest.approx(p.rolling_radius * math.tan(p.contact_angle) * yaw, rel=0.03)
    ((_, eta, _),) = c.creepages(v, v / 0.46)["left"]
    assert eta == pytest.approx(-yaw / math.cos(p.contact_angle), rel=0.05)
    assert abs(eta) > 2.5 * yaw * math.cos(p.contact_angle)


def test_bad_arguments_are_one_clear_line(profiles):
    w, r = profiles
    with pytest.raises(ValueError, match=r"yaw = 0\.2 is invalid: must be in \[-0\.05, 0\.05\]"):
        contact_patches(w, r, 0.0, 0.2)
    with pytest.raises(ValueError, match="penetration"):
        contact_patches(w, r, 0.0, penetration=(1e-4, 1e-4, 1e-4))
    with pytest.raises(ValueError, match="y = 0.5 is invalid"):
        contact_patches(w, r, 0.5)
    c = contact_patches(w, r, 0.0)
    with pytest.raises(ValueError, match="speed"):
        c.creepages(0.0, 1.0)


def test_cli_patches_json_table_and_chart(tmp_path):
    """``railhunt contact --patches --yaw``: one JSON object (SI) whose yawed flange leads,
    the table, and the contact-point chart."""
    from test_cli import run

    res = run("contact", "--patches", "--yaw", "5", "--y-max", "8", "--step", "1", "--json")
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["yaw_rad"] == pytest.approx(0.005)
    flange = data["contacts"][-1]["left"][0]  # y = +8 mm: on the flange
    assert flange["contact_angle"] > math.radians(45.0) and flange["x"] > 0.003
    assert sum(p["vertical_load"] for p in data["contacts"][-1]["left"]) == (
        pytest.approx(53410.0, rel=1e-6))
    png = tmp_path / "patches.png"
    res = run("contact", "--patches", "--y-max", "5", "--step", "0.25", "--png", str(png))
    assert res.exit_code == 0, res.output
    assert "two-point contact at" in res.stdout and png.stat().st_size > 10_000
