"""Contact geometry from profiles: profiles, rigid contact search, EN 15302 conicity,
Hertz/Kalker creep coefficients, Polach's creep law and the profile-based vehicle."""

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import least_squares

from railhunt.contact.conicity import (
    ConicityError,
    equivalent_conicity,
    equivalent_conicity_regression,
    max_amplitude,
)
from railhunt.contact.fit import fit_polynomials, s1002_uic60_toml
from railhunt.contact.geometry import ContactGeometry, contact_geometry
from railhunt.contact.hertz import creep_coefficients, hertz_contact, kalker_coefficients
from railhunt.contact.profiles import (
    Profile,
    ProfileError,
    normal_distance,
    read_profile,
    s1002,
    shipped_profile,
    uic60,
)
from railhunt.kernel.creep import heuristic_saturation, polach_saturation

# The reference data beside the repository (../shared/data), or where this workplace keeps it.
SHARED = next((p for p in (Path(__file__).resolve().parents[2] / "shared" / "data",
                           Path("/work/shared/data")) if p.is_dir()),
              Path(__file__).resolve().parents[2] / "shared" / "data")  # fmt: skip
PROFILES = SHARED / "profiles"
EN15302 = SHARED / "en15302"
needs_shared = pytest.mark.skipif(not SHARED.is_dir(), reason="shared reference data absent")


# --------------------------------------------------------------------------- profiles


@needs_shared
def test_s1002_matches_benchmark_file():
    """Analytic EN 13715 S1002 vs MBench_S1002_v3.prw: within 0.05 mm, tread and flange."""
    wheel = read_profile(PROFILES / "MBench_S1002_v3.prw")
    assert wheel.kind == "wheel"
    assert wheel.y.min() < -0.069 and wheel.y.max() > 0.059  # flange back to outer edge
    # mirror flag applied: the flange (largest z, ~28 mm) is at negative y
    assert wheel.y[np.argmax(wheel.z)] == pytest.approx(-0.0549, abs=1e-3)
    assert wheel.z.max() == pytest.approx(0.028, abs=1e-5)
    dist = normal_distance(wheel.y, wheel.z, s1002(step=1e-5))
    assert dist.max() < 0.05e-3


@needs_shared
def test_uic60_matches_benchmark_file_inclined_1_40():
    """The benchmark's UIC60 points are the analytic 60E1 head inclined 1:40 (shifted).

    Fitting cant angle and offset: the cant comes out as atan(1/40) and the distance of
    every head point (down to 35 mm) to the analytic profile is below 0.05 mm.
    """
    rail = read_profile(PROFILES / "MBench_UIC60_v3.prr")
    assert rail.kind == "rail"
    m = rail.z < 0.035
    upright = uic60(0.0, depth_max=0.04, step=1e-5)

    def residual(p: np.ndarray) -> np.ndarray:
        th, dy, dz = p
        c, s = math.cos(th), math.sin(th)
        y, z = rail.y[m] - dy, rail.z[m] - dz
        # undo an inclination th (inverse of Profile.inclined's rotation)
        return normal_distance(c * y - s * z, s * y + c * z, upright)

    fit = least_squares(residual, [0.02, -0.007, 0.0], x_scale=[0.01, 0.001, 0.001])
    assert fit.x[0] == pytest.approx(math.atan(1 / 40), abs=2e-4)
    assert residual(fit.x).max() < 0.05e-3
    # and the generated 1:40 rail itself, with only an offset fitted
    inclined = uic60(1 / 40, depth_max=0.04, step=1e-5)
    fit2 = least_squares(lambda p: normal_distance(rail.y[m] - p[0], rail.z[m] - p[1],
                                                   inclined), [-0.007, 0.0])
    assert normal_distance(rail.y[m] - fit2.x[0], rail.z[m] - fit2.x[1], inclined).max() < 0.05e-3


def test_uic60_is_symmetric_tangent_continuous_and_72mm_wide():
    rail = uic60(0.0, step=1e-5)
    np.testing.assert_allclose(rail.z, rail.z[::-1], atol=1e-12)
    slope = np.degrees(np.arctan(np.diff(rail.z) / np.diff(rail.y)))
    assert np.max(np.abs(np.diff(slope))) < 0.1  # no kinks between the arcs (deg per 10 um)
    depth_at_36 = np.interp(0.036, rail.y, rail.z)
    assert 0.010 < depth_at_36 < 0.016  # R13 tangent point on the flank


def test_shipped_profiles_and_text_round_trip(tmp_path):
    wheel = shipped_profile("S1002")
    assert wheel.kind == "wheel" and wheel.name == "MBench_S1002_v3.prw"
    g = s1002(step=1e-3)
    csv = tmp_path / "w.csv"
    csv.write_text(
        "y_mm,z_mm\n" + "\n".join(f"{a * 1e3},{b * 1e3}" for a, b in zip(g.y, g.z, strict=True))
    )
    back = read_profile(csv, "wheel")
    np.testing.assert_allclose(back.y, g.y, atol=1e-12)
    np.testing.assert_allclose(back.z, g.z, atol=1e-12)
    mirrored = read_profile(csv, "wheel", mirror_y=True)
    np.testing.assert_allclose(mirrored.y, -g.y[::-1], atol=1e-12)


def test_profile_errors_name_the_problem(tmp_path):
    bad = tmp_path / "few.txt"
    bad.write_text("0 0\n1 1\n")
    with pytest.raises(ProfileError, match="fewer than 4"):
        read_profile(bad, "rail")
    unknown = tmp_path / "profile.dat"
    unknown.write_text("0 0\n1 1\n2 2\n3 3\n")
    with pytest.raises(ProfileError, match="kind"):
        read_profile(unknown)
    with pytest.raises(ProfileError, match="rail_inclination"):
        uic60(0.0).inclined(0.5)
    with pytest.raises(ProfileError, match="kind"):
        Profile(np.arange(5.0), np.zeros(5), "tyre")


# --------------------------------------------------------------------------- geometry


@pytest.fixture(scope="module")
def s1002_geometry() -> ContactGeometry:
    return contact_geometry(y_max=0.012, y_step=2e-4)


def test_symmetric_pair_mirror_symmetry(s1002_geometry):
    """r_L(y) = r_R(-y), delta_L(y) = delta_R(-y), roll(y) = -roll(-y)."""
    g = s1002_geometry
    assert g.y[0] == pytest.approx(-0.012) and g.y[-1] == pytest.approx(0.012)
    np.testing.assert_allclose(g.r_left, g.r_right[::-1], atol=1e-9)
    np.testing.assert_allclose(g.delta_left, g.delta_right[::-1], atol=1e-6)
    np.testing.assert_allclose(g.roll, -g.roll[::-1], atol=1e-9)
    np.testing.assert_array_equal(g.jump[1:], g.jump[1:][::-1])


def test_s1002_uic60_physics(s1002_geometry):
    g = s1002_geometry
    assert np.all(np.diff(g.delta_r) >= -1e-7)  # moving left never lowers Delta r
    # flange contact: the contact angle reaches the S1002 flange angle (70 deg) ...
    assert np.degrees(g.delta_left.max()) == pytest.approx(70.0, abs=0.2)
    # ... after a contact-point jump, at a flangeway clearance of 5-8 mm
    y_fl, y_fr = g.flange_contact_y()
    assert 0.005 < y_fl < 0.008 and y_fr == pytest.approx(-y_fl)
    assert np.any(g.jump & (np.abs(g.y - y_fl) < 1e-3))
    # rigid wheelset: contact points, radii and roll agree. With D the contact points'
    # lateral distance in the wheelset frame and phi = -roll (left wheel up),
    # Y_L - Y_R = D cos(phi) + Delta r sin(phi) and Z_L - Z_R = D sin(phi) - Delta r cos(phi).
    phi = -g.roll  # g.roll has the model's sign (left wheel down)
    c, s = np.cos(phi), np.sin(phi)
    d = (g.contact_distance - s * g.delta_r) / c
    dz = g.contact_left[:, 1] - g.contact_right[:, 1]
    np.testing.assert_allclose(dz, d * s - g.delta_r * c, atol=2e-8)
    assert np.all(np.sign(g.roll) == -np.sign(g.delta_r))


def _cone(gamma: float) -> Profile:
    y = np.linspace(-0.06, 0.06, 1201)
    return Profile(y, -gamma * y, "wheel", "cone")


def _parabolic_rail(radius: float) -> Profile:
    y = np.linspace(-0.03, 0.03, 6001)
    return Profile(y, y * y / (2 * radius), "rail", "parabola")


@pytest.mark.parametrize("gamma", [0.025, 0.05, 0.1])
def test_cone_on_narrow_rail_is_analytic(gamma):
    """A cone (slope gamma) on a narrow crown (R = 5 mm), analytic to first order in roll.

    The rail contact sits where the rail's slope equals the cone's in the track frame, so
    ``delta_L = atan(gamma) + phi`` (``phi = -roll``: left wheel up); the rolled wheelset
    shifts its wheels laterally by ``phi * r`` and the contact points move on the rails by
    ``t_L``, ``t_R``, hence
    ``Delta r = 2 gamma y + gamma phi (r_L + r_R) - gamma (t_L - t_R)``, and with
    ``phi = Delta r / D`` (``D`` the contact distance) ``Delta r ~ 2 gamma y / (1 - 2 gamma
    r0 / D)`` up to the crown's relative ``2 gamma R / D ~ 3e-4``.
    """
    g = contact_geometry(_cone(gamma), _parabolic_rail(0.005), rail_inclination=0.0,
                         y_max=0.006, y_step=5e-4)
    nz = g.y != 0
    phi = -g.roll  # left wheel up
    expected = (2 * gamma * g.y + gamma * phi * (g.r_left + g.r_right)
                - gamma * (g.rail_left - g.rail_right))
    np.testing.assert_allclose(g.delta_r[nz] / expected[nz], 1.0, atol=2e-5)
    np.testing.assert_allclose(g.delta_left - phi, math.atan(gamma), atol=2e-5)
    np.testing.assert_allclose(g.delta_right + phi, math.atan(gamma), atol=2e-5)
    assert not g.jump.any()
    d = g.contact_distance[np.argmin(np.abs(g.y))]
    gamma_eff = gamma / (1 - 2 * gamma * g.r0 / d)
    np.testing.assert_allclose(g.delta_r[nz] / (2 * g.y[nz]), gamma_eff, rtol=2e-3)
    assert equivalent_conicity(g.y, g.delta_r, 0.004) == pytest.approx(gamma_eff, rel=2e-3)


def test_geometry_rejects_bad_parameters():
    with pytest.raises(ProfileError, match="gauge"):
        contact_geometry(gauge=3.0)
    with pytest.raises(ProfileError, match="expected a wheel and a rail"):
        contact_geometry(uic60(), uic60())


# --------------------------------------------------------------------------- conicity


def _en_case(case: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    dr = np.loadtxt(EN15302 / f"dr_ce_{case}.dat").ravel() * 1e-3
    y = np.linspace(-6.8e-3, 6.8e-3, dr.size)
    return y, dr, np.loadtxt(EN15302 / f"ben_{case}.dat")


@needs_shared
@pytest.mark.parametrize("case", ["E1", "E2", "E3", "E5"])
def test_en15302_reference_cases_inside_annex_f_band(case):
    """Annex B conicity inside tan(ge) +- min(0.05, 0.5 tan(ge)) at every supported amplitude."""
    y, dr, ben = _en_case(case)
    assert dr.size == 137
    limit = max_amplitude(y, dr)
    amplitudes = ben[:, 0] * 1e-3
    supported = amplitudes[amplitudes <= limit + 1e-12]
    assert supported.size >= 45  # E1-E3: 1.0-6.8 mm; E5 (offset centre): 1.0-5.4 mm
    for row in ben[amplitudes <= limit + 1e-12]:
        tan_ge = equivalent_conicity(y, dr, row[0] * 1e-3)
        assert row[3] - 1e-9 <= tan_ge <= row[2] + 1e-9, (case, row[0], tan_ge, row[1])
        assert abs(tan_ge - row[1]) < 0.01  # in fact much closer than the band
    with pytest.raises(ConicityError, match="amplitude"):
        equivalent_conicity(y, dr, limit + 2e-4)


@given(gamma=st.floats(0.01, 0.6), amplitude=st.floats(2e-4, 9e-3))
@settings(max_examples=25, deadline=None)
def test_conicity_of_a_cone_is_its_angle(gamma, amplitude):
    y = np.linspace(-0.01, 0.01, 41)
    tan_ge = equivalent_conicity(y, 2 * gamma * y, amplitude)
    assert tan_ge == pytest.approx(gamma, rel=1e-6)
    assert equivalent_conicity_regression(y, 2 * gamma * y, amplitude) == pytest.approx(gamma)


def test_conicity_with_offset_cone_and_step():
    """Offset Delta r (unequal diameters) shifts the centre but not a cone's conicity;
    a symmetric step (piecewise cone) raises it above the tread cone."""
    y = np.linspace(-0.01, 0.01, 201)
    assert equivalent_conicity(y, 0.2 * y + 4e-4, 0.003) == pytest.approx(0.1, rel=1e-6)
    stepped = 0.2 * y + np.where(np.abs(y) > 0.004, np.sign(y) * 2e-3, 0.0)
    assert equivalent_conicity(y, stepped, 0.003) == pytest.approx(0.1, rel=1e-6)
    assert equivalent_conicity(y, stepped, 0.006) > 0.15


def test_conicity_rejects_bad_input():
    y = np.linspace(-0.01, 0.01, 41)
    with pytest.raises(ConicityError, match="amplitude"):
        equivalent_conicity(y, 0.1 * y, -1.0)
    with pytest.raises(ConicityError, match="increasing"):
        equivalent_conicity(y[::-1], 0.1 * y, 0.003)
    with pytest.raises(ConicityError, match="method"):
        equivalent_conicity(y, 0.1 * y, 0.003, method="fft")
    with pytest.raises(ConicityError, match="sign"):
        equivalent_conicity(y, 0.1 * y + 1.0, 0.003)


# --------------------------------------------------------------------------- Hertz, Kalker


def test_hertz_circular_limit():
    """A = B = 1/(2R): a = b = (3 N R / (4 E*))^(1/3)."""
    n, r, e, nu = 5e4, 0.4, 2.1e11, 0.3
    h = hertz_contact(n, 1 / (2 * r), 1 / (2 * r), e, nu)
    e_star = e / (2 * (1 - nu**2))
    expected = (3 * n * r / (4 * e_star)) ** (1 / 3)
    assert h.a == pytest.approx(expected, rel=1e-10)
    assert h.b == pytest.approx(expected, rel=1e-10)
    assert h.p0 == pytest.approx(3 * n / (2 * math.pi * expected**2), rel=1e-10)
    near = hertz_contact(n, 1 / (2 * r), 1 / (2 * r) * (1 + 1e-9), e, nu)
    assert near.a == pytest.approx(expected, rel=1e-6)


@given(load=st.floats(1e3, 2e5), ratio=st.floats(1.01, 50.0))
@settings(max_examples=30, deadline=None)
def test_hertz_ellipse_invariants(load, ratio):
    """Longer axis along the smaller curvature; size ~ N^(1/3); swapping axes swaps a, b."""
    h = hertz_contact(load, 1.0, ratio)
    assert h.a > h.b
    h8 = hertz_contact(8 * load, 1.0, ratio)
    assert h8.a == pytest.approx(2 * h.a, rel=1e-8) and h8.b == pytest.approx(2 * h.b, rel=1e-8)
    sw = hertz_contact(load, ratio, 1.0)
    assert sw.a == pytest.approx(h.b, rel=1e-10) and sw.b == pytest.approx(h.a, rel=1e-10)
    # total load from the Hertz pressure: N = (2/3) pi a b p0
    assert 2 / 3 * math.pi * h.a * h.b * h.p0 == pytest.approx(load, rel=1e-10)


def test_kalker_table_values_and_interpolation():
    # Kalker (1990) Table E.3, circular contact, nu = 0.25
    assert kalker_coefficients(1.0, 0.25) == pytest.approx((4.12, 3.67, 1.47, 1.19))
    # a/b = 0.1 and b/a = 0.1, nu = 0 and 0.5
    assert kalker_coefficients(0.1, 0.0)[:3] == pytest.approx((2.51, 2.51, 0.334))
    assert kalker_coefficients(10.0, 0.5)[:3] == pytest.approx((12.9, 16.0, 18.0))
    # linear between rows a/b = 0.5 and 0.6, nu = 0.25: C11 = (3.62 + 3.72)/2
    assert kalker_coefficients(0.55, 0.25)[0] == pytest.approx(3.67)
    # nu = 0: C11 = C22 (Kalker), at every a/b
    for g in (0.1, 0.33, 1.0, 2.5, 10.0):
        c = kalker_coefficients(g, 0.0)
        assert c[0] == pytest.approx(c[1])
    with pytest.raises(ValueError, match="a_over_b"):
        kalker_coefficients(25.0, 0.3)  # the table (extended) covers a/b = 0.05 ... 20
    with pytest.raises(ValueError, match="a_over_b"):
        kalker_coefficients(0.04, 0.3)
    with pytest.raises(ValueError, match="nu"):
        kalker_coefficients(1.0, 0.7)


@pytest.mark.parametrize("nu", [0.0, 0.25, 0.5])
def test_kalker_table_approaches_its_narrow_ellipse_asymptotes(nu):
    """At a/b = 0.1 the table is within 7 % of Kalker's a/b -> 0 asymptotes:
    C11 = pi^2/(4(1-nu)), C22 = pi^2/4, C23 = pi sqrt(g)/(3(1-nu)) (1 + nu(ln(16/g) - 5)),
    C33 = pi^2/(16 (1-nu) g) (a check of the transcribed C33 column)."""
    g = 0.1
    c11, c22, c23, c33 = kalker_coefficients(g, nu)
    assert c11 == pytest.approx(math.pi**2 / (4 * (1 - nu)), rel=0.03)
    assert c22 == pytest.approx(math.pi**2 / 4, rel=0.03)
    asym23 = math.pi * math.sqrt(g) / (3 * (1 - nu)) * (1 + nu * (math.log(16 / g) - 5))
    assert c23 == pytest.approx(asym23, rel=0.07)
    assert c33 == pytest.approx(math.pi**2 / (16 * (1 - nu) * g), rel=0.07)


def test_creep_coefficients_near_table_2():
    """Paper's wheel load, r = 0.43 m wheel (straight tread) on the R300 UIC60 crown.

    f11 = G a b C11 comes out at 9.2 MN (the paper's Table 2: 8.4 MN, within 10 %)."""
    c = creep_coefficients(10900 * 9.8 / 2, 0.43, math.inf, 0.3, young=2.1e11, nu=0.3)
    assert c.f11 == pytest.approx(8.4e6, rel=0.1)
    g = 2.1e11 / 2.6
    assert c.f11 == pytest.approx(g * c.a * c.b * c.c11, rel=1e-12)
    assert c.f23 == pytest.approx(g * (c.a * c.b) ** 1.5 * c.c23, rel=1e-12)
    assert c.f33 == pytest.approx(g * (c.a * c.b) ** 2 * c.c33, rel=1e-12)
    with pytest.raises(ValueError, match="non-conformal"):
        creep_coefficients(5e4, 0.43, -0.2, 0.3)


# --------------------------------------------------------------------------- creep laws


@pytest.mark.parametrize("law", [heuristic_saturation, polach_saturation])
def test_creep_laws_linear_then_saturated(law):
    """alpha -> 1 (Kalker's linear law) as beta -> 0; alpha * beta -> 1 (mu N) as beta -> inf."""
    for beta in (0.0, 1e-6, 1e-3):
        assert law(beta) == pytest.approx(1.0, abs=2 * beta + 1e-12)
    assert law(1e4) * 1e4 == pytest.approx(1.0, abs=1e-3)
    betas = np.linspace(0.0, 20.0, 2001)
    force = np.array([law(b) * b for b in betas])
    assert np.all(np.diff(force) >= -1e-15) and force.max() <= 1.0 + 1e-12


def test_polach_in_the_model_matches_kalker_then_mu_n():
    from railhunt.model import Model, wheelset_forces
    from railhunt.vehicle import Vehicle

    # centred contact angle 0: no spin creepage from rolling, only the yaw angle's
    v = Vehicle.paper2019().replace(d0=0.0)
    wr_p, wr_l = Model(v, "polach").wr, Model(v, "linear").wr
    speed = 50.0
    small = wheelset_forces(0.0, 0.0, 1e-7, 1e-7, 0.0, speed, wr_p)
    linear = wheelset_forces(0.0, 0.0, 1e-7, 1e-7, 0.0, speed, wr_l)
    assert small[0] == pytest.approx(linear[0], rel=1e-4)
    # large yaw angle: the two wheels' lateral creep forces saturate at mu N each
    big = wheelset_forces(0.0, 0.0, 0.05, 0.0, 0.0, speed, wr_p)[0]
    grav = wheelset_forces(0.0, 0.0, 0.0, 0.0, 0.0, speed, wr_p)[0]
    mu_n = v.mu * v.N
    creep = abs(big - grav)
    assert 2 * mu_n * 0.97 < creep <= 2 * mu_n * 1.0001


# --------------------------------------------------------------------------- fit, vehicle


def test_fit_recovers_exact_polynomials():
    y = np.linspace(-0.008, 0.008, 161)
    lam = (0.15, 3.0, -1500.0, 2e5, 3e7)
    d = (0.05, -9.0, 3e7, -2e9)

    def r(u):
        return 0.43 + sum(c * u ** (k + 1) for k, c in enumerate(lam))

    def ang(u):
        return d[0] - d[1] * u + d[2] * u**4 - d[3] * u**5

    z = np.zeros_like(y)
    pts = np.column_stack([y, z])
    g = ContactGeometry(y, r(y), r(-y), ang(y), ang(-y), z, pts + [0.75, 0], pts - [0.75, 0],
                        z, z, z, z, np.zeros(y.size, bool), 0.43)
    fit = fit_polynomials(g, 0.008)
    c = fit.coefficients
    assert c["r0"] == pytest.approx(0.43) and c["a"] == pytest.approx(0.75)
    assert [c[f"lambda{k}"] for k in range(1, 6)] == pytest.approx(lam, rel=1e-6)
    assert [c["d0"], c["d1"], c["d4"], c["d5"]] == pytest.approx(d, rel=1e-6)
    assert fit.radius_max < 1e-11 and fit.angle_max < 1e-9


def test_shipped_profile_vehicle_is_what_the_code_computes():
    from importlib import resources

    from railhunt.vehicle import Vehicle

    shipped = (resources.files("railhunt") / "data" / "vehicles" / "s1002_uic60.toml")
    a = tomllib.loads(shipped.read_text(encoding="utf-8"))["parameters"]
    b = tomllib.loads(s1002_uic60_toml())["parameters"]
    assert a.keys() == b.keys()
    for name in a:
        assert a[name]["value"] == pytest.approx(b[name]["value"], rel=1e-7, abs=1e-12), name
    v = Vehicle.shipped("s1002_uic60")
    assert v.r0 == pytest.approx(0.4299, abs=1e-4)
    assert 5e6 < v.f11 < 2e7 and v.M_c == Vehicle.paper2019().M_c


# --------------------------------------------------------------------------- CLI


def _run(*args):
    from click.testing import CliRunner

    from railhunt.cli import main

    try:
        runner = CliRunner(mix_stderr=False)
    except TypeError:
        runner = CliRunner()
    return runner.invoke(main, list(args))


def test_cli_contact_json_png_csv(tmp_path):
    png, csv = tmp_path / "c.png", tmp_path / "c.csv"
    res = _run("contact", "--step", "0.2", "--json", "--png", str(png), "--csv", str(csv))
    assert res.exit_code == 0, res.stderr
    data = json.loads(res.stdout)
    assert 0.1 < data["equivalent_conicity"] < 0.3
    assert len(data["y_m"]) == 121 and data["y_m"][-1] == pytest.approx(0.012)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert csv.read_text().splitlines()[0].startswith("y_mm,r_left_mm")


@needs_shared
def test_cli_contact_file_profiles_agree_with_analytic():
    """Benchmark files (rail already inclined) vs analytic profiles inclined 1:40."""
    files = _run("contact", "--step", "0.2", "--json",
                 "--wheel", str(PROFILES / "MBench_S1002_v3.prw"),
                 "--rail", str(PROFILES / "MBench_UIC60_v3.prr"), "--inclination", "none")
    analytic = _run("contact", "--step", "0.2", "--json")
    a, b = json.loads(files.stdout), json.loads(analytic.stdout)
    assert a["equivalent_conicity"] == pytest.approx(b["equivalent_conicity"], abs=2e-3)
    np.testing.assert_allclose(a["r_left_m"], b["r_left_m"], atol=2e-5)


@pytest.mark.parametrize(
    "args, fragment",
    [
        (("--inclination", "steep"), "inclination"),
        (("--gauge", "-3"), "--gauge"),
        (("--amplitude", "20"), "--amplitude"),
        (("--wheel", "/nonexistent.prw"), "--wheel"),
    ],
)
def test_cli_contact_errors(args, fragment):
    res = _run("contact", "--step", "0.5", *args)
    assert res.exit_code == 2, res.stdout
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("railhunt: error: ")
    assert fragment in lines[0]


def test_profile_vehicle_runs_through_critical_speed():
    from importlib import resources

    path = resources.files("railhunt") / "data" / "vehicles" / "s1002_uic60.toml"
    res = _run("critical-speed", "--vehicle", str(path), "--tol", "5", "--json")
    assert res.exit_code == 0, res.stderr
    data = json.loads(res.stdout)
    assert data["vehicle"] == "s1002_uic60" and data["bracketed"] is True
    assert 100 < data["nonlinear_critical_speed_kmh"] < data["linear_critical_speed_kmh"]


# --------------------------------------------------------------------------- tabulated RHS


def _polynomial_table(v, y):
    from types import SimpleNamespace

    from railhunt.contact.polynomial import contact_angle, rolling_radius

    def r(u):
        return np.array([rolling_radius(x, v.r0, v.lambda1, v.lambda2, v.lambda3, v.lambda4,
                                        v.lambda5) for x in u])

    def d(u):
        return np.array([contact_angle(x, v.d0, v.d1, v.d4, v.d5, v.delta_max) for x in u])

    return SimpleNamespace(y=y, r_left=r(y), r_right=r(-y), delta_left=d(y),
                           delta_right=d(-y))


def test_tabulated_geometry_reproduces_the_polynomials():
    """The paper's polynomials, tabulated every 0.05 mm, give the same forces and the same
    linear critical speed (interpolation error O(h^2) ~ 1e-10 m in the radii)."""
    from railhunt.analysis.linear import linear_critical_speed
    from railhunt.model import N_STATE, WHEELSET_Y, Model
    from railhunt.vehicle import Vehicle

    v = Vehicle.paper2019()
    table = _polynomial_table(v, np.linspace(-0.012, 0.012, 481))
    poly, tab = Model(v), Model(v, contact=table)
    x = np.zeros(N_STATE)
    for k, j in enumerate(WHEELSET_Y):
        x[j] = 0.001 * (k + 1) * (-1) ** k
        x[j + 1] = 0.0005 * (k - 1.5)
    a, b = poly.derivative(x, 80.0), tab.derivative(x, 80.0)
    np.testing.assert_allclose(b, a, rtol=1e-5, atol=1e-6 * np.max(np.abs(a)))
    assert linear_critical_speed(v, contact=table).speed_kmh == pytest.approx(
        linear_critical_speed(v).speed_kmh, abs=0.1)
    with pytest.raises(ValueError, match="uniformly"):
        Model(v, contact=_polynomial_table(v, np.array([-0.01, 0.0, 0.002, 0.01])))


# --------------------------------------------------------------------------- [contact] in vehicles


def test_shipped_table_vehicle_is_what_the_code_computes():
    """s1002_uic60_table.toml = s1002_uic60's parameters + a [contact] section, and the model
    built from it runs on the tabulated geometry (same linear speed as passing the table)."""
    from importlib import resources

    from railhunt import linear_critical_speed
    from railhunt.vehicle import ContactSpec, Vehicle

    shipped = resources.files("railhunt") / "data" / "vehicles" / "s1002_uic60_table.toml"
    a = tomllib.loads(shipped.read_text(encoding="utf-8"))
    b = tomllib.loads(s1002_uic60_toml(table=True))
    assert a["contact"] == b["contact"]
    for name in a["parameters"]:
        assert a["parameters"][name]["value"] == pytest.approx(
            b["parameters"][name]["value"], rel=1e-7, abs=1e-12), name
    v = Vehicle.shipped("s1002_uic60_table")
    assert v.contact == ContactSpec(rail_inclination=0.025)
    poly = Vehicle.shipped("s1002_uic60")
    assert v.as_dict() == poly.as_dict() and v != poly
    by_spec = linear_critical_speed(v)
    by_table = linear_critical_speed(poly, contact=contact_geometry())
    assert by_spec.speed_kmh == pytest.approx(by_table.speed_kmh, abs=0.05)
    # The table, not the polynomials, drives it: they give a different Hopf point.
    assert abs(by_spec.speed_kmh - linear_critical_speed(poly).speed_kmh) > 10.0


def test_contact_section_from_profile_files(tmp_path):
    """A vehicle file whose [contact] names the benchmark profile files (paths relative to
    the vehicle file; the benchmark rail is already inclined, so rail_inclination = 0)
    gives the same Hopf point as the analytic profiles (the files agree to 1e-5 mm)."""
    import shutil

    from railhunt import linear_critical_speed, load_vehicle
    from railhunt.vehicle import Vehicle

    shutil.copy(PROFILES / "MBench_S1002_v3.prw", tmp_path / "wheel.prw")
    shutil.copy(PROFILES / "MBench_UIC60_v3.prr", tmp_path / "rail.prr")
    path = tmp_path / "files.toml"
    path.write_text('[vehicle]\nbase = "s1002_uic60"\nname = "files"\n\n[contact]\n'
                    'wheel = "wheel.prw"\nrail = "rail.prr"\nrail_inclination = 0.0\n')
    v = load_vehicle(path)
    assert v.contact.rail == str((tmp_path / "rail.prr").resolve())
    analytic = linear_critical_speed(Vehicle.shipped("s1002_uic60_table")).speed_kmh
    assert linear_critical_speed(v).speed_kmh == pytest.approx(analytic, abs=1.0)
    # Round trip through to_toml keeps the section.
    again = load_vehicle(v.to_toml(tmp_path / "again.toml"))
    assert again.contact == v.contact and again == v


@pytest.mark.parametrize(
    ("section", "fragment"),
    [
        ('wheel = "S1002"\nspeed = 3\n', "unknown key"),
        ('wheel = "no/such.prw"\n', "neither S1002"),
        ("rail_inclination = 0.5\n", "rail_inclination"),
        ("gauge = 1.3\nback_to_back = 1.36\n", "gauge"),
        ('wheel = 3\n', "wheel"),
    ],
)
def test_contact_section_errors(tmp_path, section, fragment):
    from railhunt import load_vehicle
    from railhunt.vehicle import VehicleFileError

    path = tmp_path / "bad.toml"
    path.write_text('[vehicle]\nbase = "s1002_uic60"\n\n[contact]\n' + section)
    with pytest.raises(VehicleFileError, match=fragment) as info:
        load_vehicle(path)
    assert "bad.toml" in str(info.value)


def test_contact_needs_matching_r0():
    """The creepages are measured from r0: a [contact] whose centred rolling radius differs
    from the vehicle's r0 by more than 1 um is refused, naming r0."""
    from railhunt.model import Model
    from railhunt.vehicle import ContactSpec, Vehicle

    v = Vehicle.paper2019().replace(contact=ContactSpec(wheel_radius=0.46))
    with pytest.raises(ValueError, match="r0"):
        Model(v)


def test_cli_runs_the_table_vehicle_by_name():
    res = _run("critical-speed", "--vehicle", "s1002_uic60_table", "--tol", "5", "--json")
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["linear_critical_speed_kmh"] == pytest.approx(326.8, abs=0.5)


def test_explicit_table_must_match_r0():
    """The paper's vehicle (r0 = 0.43 m) on the S1002 table (centred radius 0.429906 m):
    the 0.094 mm mismatch would load every centred wheel with a longitudinal creep force."""
    from railhunt.model import Model
    from railhunt.vehicle import Vehicle

    with pytest.raises(ValueError, match="r0"):
        Model(Vehicle.paper2019(), contact=contact_geometry())


@needs_shared
@pytest.mark.parametrize("shift", [0.0, 2e-6, 5e-6, 1e-5])
def test_max_amplitude_is_always_accepted(shift):
    y, dr, _ = _en_case("E5")
    limit = max_amplitude(y, dr + shift)
    assert 0.004 < limit < 0.0068
    assert equivalent_conicity(y, dr + shift, limit) > 0
