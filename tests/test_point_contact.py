"""Per-point contact mechanics: curvatures, ellipses, coefficients, normal force, symmetry.

References: the Hertz ellipse and Kalker's coefficients of the centred contact
(:func:`railhunt.contact.hertz.creep_coefficients`, the values behind the shipped
vehicles), the analytic curvature of circles, the vertical equilibrium of each wheel, the
mirror symmetry of the wheelset, the linear limit of the tabulated law.
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources

import numpy as np
import pytest

import railhunt
from railhunt.contact.curvature import profile_curvature
from railhunt.contact.hertz import creep_coefficients
from railhunt.contact.point_contact import point_contact
from railhunt.kernel.creep_table import table_creep
from railhunt.kernel.layout import WR
from railhunt.kernel.point_contact import point_wheel_creep, point_wheelset_contact
from railhunt.layout.spec import LayoutError
from railhunt.model import Model

PER_POINT = "s1002_uic60_per_point"


@pytest.fixture(scope="module")
def geometry():
    return railhunt.Vehicle.shipped("s1002_uic60_table").contact.geometry()


LAWS = ("heuristic-per-wheel", "polach", "exact-table")


def _synthetic_table():
    """A creep table with smooth, made-up corrections (no solver): the compiled law's
    structure (bounds, symmetry, linear limit) holds whatever the table holds."""
    from railhunt.contact.creep_table import CreepTable

    n_ab, nx, ny, ns = 4, 5, 9, 9
    sx, sy, ss = np.meshgrid(np.linspace(0, 1, nx), np.linspace(-1, 1, ny),
                             np.linspace(-1, 1, ns), indexing="ij")  # fmt: skip
    values = np.empty((n_ab, nx, ny, ns, 3))
    for k in range(n_ab):
        values[k, ..., 0] = 0.3 * sx * (1 - sy**2) * (1 + 0.1 * k)  # odd in s_x
        values[k, ..., 1] = 0.4 * np.sin(1.5 * sy) * np.cos(ss) - 0.2 * ss  # odd in (s_y, s_s)
        values[k, ..., 2] = -0.3 * ss * (1 + sx**2) + 0.1 * sy
    log_ab = np.log(0.5) + 0.5 * np.arange(n_ab)
    return CreepTable(log_ab=log_ab, values=values, poisson=0.3,
                      coefficients=np.ones((n_ab, 4)))  # fmt: skip


@pytest.fixture(scope="module")
def table():
    return _synthetic_table()


@pytest.fixture(scope="module")
def models(table):
    """Per-point wheel/rail rows and creep tables by law (exact-table: the synthetic table
    and a wheel/rail row that reads it)."""
    from railhunt.kernel.creep import CREEP_LAWS

    v = railhunt.Vehicle.shipped(PER_POINT)
    out = {}
    for law in LAWS:
        base = "heuristic-per-wheel" if law == "exact-table" else law
        wr = Model(v, creep_law=base).wr.copy()
        arr = np.zeros(0)
        if law == "exact-table":
            wr[WR.CREEP_LAW] = CREEP_LAWS[law]
            arr = table.kernel_array
        out[law] = (wr, arr)
    return out


def test_curvature_of_circles_at_any_slope() -> None:
    """A circle of radius R has curvature 1/R wherever it is read, also at 60 degrees (a
    quadratic fit over +-0.1 R of arc is 0.13 % high: the circle's quartic term)."""
    for radius in (0.013, 0.3):
        t = np.linspace(-1.2, 1.2, 20001)
        y, z = radius * np.sin(t), radius * (1.0 - np.cos(t))
        at = radius * np.sin(np.array([0.0, 0.5, 1.05]))
        k = profile_curvature(y, z, at, half_width=min(2e-3, 0.1 * radius))
        assert np.allclose(k, 1.0 / radius, rtol=2e-3)


def test_centred_ellipse_and_coefficients_are_hertz_and_kalker(geometry) -> None:
    """At the centred contact the per-point coefficients are creep_coefficients' for the
    same curvatures, N = Q / cos(delta) and the wheel's radius r / cos(delta) (the normal
    section along the rolling direction); the UIC60 crown reads R300."""
    pc = point_contact(geometry)
    i0 = int(np.argmin(np.abs(pc.y)))
    q = 10900.0 * 9.8 / 2.0
    assert pc.rail_curvature[0, i0] == pytest.approx(1.0 / 0.3, rel=1e-3)
    d = pc.delta[0, i0]
    ref = creep_coefficients(q / math.cos(d), pc.radius[0, i0] / math.cos(d),
                             wheel_transverse_radius=1.0 / pc.wheel_curvature[0, i0],
                             rail_transverse_radius=1.0 / pc.rail_curvature[0, i0],
                             young=2.1e11, nu=0.3)  # fmt: skip
    f = pc.coefficients(q)
    a, b = pc.ellipse(q)
    assert (a[0, i0], b[0, i0]) == pytest.approx((ref.a, ref.b), rel=1e-9)
    assert [c[0, i0] for c in f] == pytest.approx([ref.f11, ref.f22, ref.f23, ref.f33],
                                                 rel=1e-9)  # fmt: skip
    # ... and within 0.3 % of the shipped vehicle's centred coefficients (curvatures fitted
    # over +-2 mm of y there, of arc here).
    shipped = railhunt.Vehicle.shipped("s1002_uic60_table")
    for c, name in zip(f, ("f11", "f22", "f23", "f33"), strict=True):
        assert c[0, i0] == pytest.approx(getattr(shipped, name), rel=3e-3)
    # Mirror: the right wheel at -y is the left wheel at +y.
    assert np.allclose(pc.a1[1], pc.a1[0, ::-1]) and np.allclose(pc.c23[1], pc.c23[0, ::-1])


def test_flange_ellipse_is_long_and_within_range(geometry) -> None:
    pc = point_contact(geometry)
    flange = pc.delta[0] > 0.9
    assert flange.any()
    assert np.all(pc.a_over_b[0, flange] > 10.0) and np.all(pc.a_over_b <= 20.0 + 1e-9)


def _state(rng: np.random.Generator) -> tuple[float, ...]:
    return (rng.uniform(-0.01, 0.01), rng.normal() * 0.1, rng.normal() * 0.004,
            rng.normal() * 0.1, 80.0)  # fmt: skip


@pytest.mark.parametrize("law", LAWS)
def test_vertical_equilibrium_of_each_wheel(models, law) -> None:
    """N cos(delta) +- T sin(delta) = Q for each wheel (T the in-plane lateral creep force),
    so the two wheels carry the axle's weight W g; |(F_x, F_y)| <= mu N."""
    wr, table = models[law]
    rng = np.random.default_rng(3)
    q = wr[WR.N]
    mu = wr[WR.MU]
    for _ in range(40):
        y, dy, psi, dpsi, v = _state(rng)
        out = point_wheel_creep(y, dy, math.cos(psi), math.sin(psi), dpsi, v, wr, q, q,
                                table)  # fmt: skip
        fxl, fyl, _, fxr, fyr, _ = out[:6]
        n_l, n_r, d_l, d_r = out[12:16]
        up_l = n_l * math.cos(d_l) + fyl * math.sin(d_l)
        up_r = n_r * math.cos(d_r) - fyr * math.sin(d_r)
        assert up_l == pytest.approx(q, rel=1e-12) and up_r == pytest.approx(q, rel=1e-12)
        assert up_l + up_r == pytest.approx(wr[WR.W] * wr[WR.G], rel=1e-12)
        assert math.hypot(fxl, fyl) <= mu * n_l * (1 + 1e-12)
        assert math.hypot(fxr, fyr) <= mu * n_r * (1 + 1e-12)


@pytest.mark.parametrize("law", LAWS)
def test_mirror_symmetry_of_the_wheelset_force(models, law) -> None:
    """y, dy, psi, dpsi -> their negatives: the lateral force and yaw moment change sign."""
    wr, table = models[law]
    q = wr[WR.N]
    rng = np.random.default_rng(7)
    for _ in range(40):
        y, dy, psi, dpsi, v = _state(rng)
        f = point_wheelset_contact(y, dy, psi, psi, dpsi, v, wr, q, q, table)
        g = point_wheelset_contact(-y, -dy, -psi, -psi, -dpsi, v, wr, q, q, table)
        scale = abs(f[0]) + abs(f[1]) + 1.0
        assert abs(f[0] + g[0]) < 1e-9 * scale and abs(f[1] + g[1]) < 1e-9 * scale
        assert f[4] == pytest.approx(g[5], rel=1e-12)  # N_left(y) = N_right(-y)


def test_table_law_linear_limit_is_kalker(table) -> None:
    """Tiny normalised creepages: the tabulated law is Kalker's linear law."""
    table = table.kernel_array
    my, ms = 0.4, 2.2
    for u in ((1e-5, 0.0, 0.0), (0.0, 1e-5, 0.0), (0.0, 0.0, 1e-5), (3e-6, -2e-6, 4e-6)):
        t = table_creep(*u, my, ms, 3.0, table)
        lin = (-u[0], -(u[1] + u[2]), my * u[1] - ms * u[2])
        assert t == pytest.approx(lin, rel=1e-4, abs=1e-12)


def test_table_law_is_bounded_and_symmetric(table) -> None:
    table = table.kernel_array
    rng = np.random.default_rng(11)
    for _ in range(300):
        u = rng.normal(size=3) * 10.0 ** rng.uniform(-2, 3)
        ab = rng.uniform(0, 3)
        tx, ty, tm = table_creep(u[0], u[1], u[2], 0.5, 1.0, ab, table)
        assert math.hypot(tx, ty) <= 1.0
        mx, my_, mm = table_creep(-u[0], u[1], u[2], 0.5, 1.0, ab, table)
        assert (mx, my_, mm) == pytest.approx((-tx, ty, tm), abs=1e-15)
        nx, ny, nm = table_creep(u[0], -u[1], -u[2], 0.5, 1.0, ab, table)
        assert (nx, ny, nm) == pytest.approx((tx, -ty, -tm), abs=1e-12)


def test_shipped_per_point_vehicle_is_what_the_code_writes() -> None:
    from railhunt.contact.shipped_layouts import s1002_uic60_per_point_toml

    path = resources.files("railhunt") / "data" / "vehicles" / f"{PER_POINT}.toml"
    assert path.read_text(encoding="utf-8") == s1002_uic60_per_point_toml()
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    assert data["wheel_rail"]["contact_mechanics"] == "per-point"


def test_centred_mechanics_of_the_per_point_vehicle_is_s1002_uic60_table() -> None:
    """The new vehicle with contact_mechanics='centred' is the s1002_uic60_table vehicle:
    the same state derivative to the bit."""
    old = Model(railhunt.Vehicle.shipped("s1002_uic60_table"))
    new = Model(railhunt.Vehicle.shipped(PER_POINT), contact_mechanics="centred")
    rng = np.random.default_rng(5)
    x = rng.normal(size=old.n_state) * 1e-3
    assert np.array_equal(old.derivative(x, 80.0), new.derivative(x, 80.0))


def _layout_text(**wheel_rail: str) -> str:
    path = resources.files("railhunt") / "data" / "vehicles" / f"{PER_POINT}.toml"
    text = path.read_text(encoding="utf-8")
    for key, value in wheel_rail.items():
        text = text.replace(next(line for line in text.splitlines()
                                 if line.startswith(f"{key} = ")), f"{key} = {value}", 1)
    return text


@pytest.mark.parametrize(("change", "message"), [
    ({"contact_mechanics": '"everywhere"'}, "contact_mechanics = 'everywhere' is unknown"),
    ({"contact": '"polynomial"'}, "'per-point' needs contact = 'profiles'"),
    ({"contact_mechanics": '"centred"', "creep_law": '"exact-table"'},
     "creep_law = 'exact-table' needs contact_mechanics"),
    ({"poisson": "0.7"}, "poisson = 0.7 is invalid"),
])  # fmt: skip
def test_bad_layout_keys_get_one_clear_line(tmp_path, change, message) -> None:
    path = tmp_path / "v.toml"
    path.write_text(_layout_text(**change), encoding="utf-8")
    with pytest.raises(LayoutError, match=message.replace("(", r"\(")):
        railhunt.load_vehicle(path)


def test_model_refuses_exact_table_without_per_point_or_table() -> None:
    with pytest.raises(ValueError, match="'exact-table' is invalid with contact_mechanics"):
        Model(railhunt.Vehicle.shipped("s1002_uic60_table"), creep_law="exact-table")
    with pytest.raises(ValueError, match="needs profile contact"):
        Model(railhunt.Vehicle.paper2019(), contact_mechanics="per-point")
    from railhunt.contact.creep_table import SHIPPED

    if not (resources.files("railhunt").joinpath(*SHIPPED)).is_file():
        with pytest.raises(ValueError, match="'exact-table' is not available"):
            Model(railhunt.Vehicle.shipped(PER_POINT), creep_law="exact-table")


def test_contact_creep_command_tabulates_ellipse_coefficients_and_normal_force() -> None:
    import json

    from click.testing import CliRunner

    from railhunt.cli import main

    res = CliRunner().invoke(main, ["contact", "--creep", "--y-max", "2", "--step", "0.5",
                                    "--amplitude", "1", "--load", "60", "--json"])  # fmt: skip
    assert res.exit_code == 0, res.output
    data = json.loads(res.output)
    left = data["creep"]["left"]
    delta = np.array(data["delta_left_rad"])
    assert np.allclose(left["normal_force_n"], 60e3 / np.cos(delta), rtol=1e-12)
    ab = np.array(left["a_m"]) / np.array(left["b_m"])
    assert np.allclose(ab, left["a_over_b"]) and len(left["c33"]) == delta.size == 9
    res = CliRunner().invoke(main, ["contact", "--creep", "--poisson", "0.6"])
    assert res.exit_code == 2 and "--poisson" in res.output


def test_table_build_reproduces_a_smooth_law_between_the_nodes() -> None:
    """The builder and the compiled interpolation on a smooth stand-in solver (Kalker's
    linear law whose every component saturates with the creepages' magnitude, up to 10 %
    off the table's own analytic part): exact at the nodes; between them an RMS error of
    0.022 mu N (0.18 at worst, where large lateral creepage and spin nearly cancel: the
    tensor grid resolves magnitudes, not directions, at large creepages); continuous first
    derivatives across a node."""
    from railhunt.contact.creep_table import build_creep_table

    k11, k22, k23, k33 = 4.0, 3.5, 1.5, 1.2

    def solver(xi, eta, phi, a, b, mu, n_load, g, nu):
        c = math.sqrt(a * b)
        lin = np.array([-g * c * c * k11 * xi, -g * c * c * (k22 * eta + c * k23 * phi),
                        g * c**3 * (k23 * eta - c * k33 * phi)])  # fmt: skip
        u = np.array([g * c * c * k11 * xi, g * c * c * k22 * eta, g * c**3 * k23 * phi])
        r2 = float(u @ u) / (mu * n_load) ** 2
        l2 = (lin[0] ** 2 + lin[1] ** 2) / (mu * n_load) ** 2
        return tuple(lin / math.sqrt(1.0 + r2 + l2) * (1.0 + 0.1 * r2 / (1.0 + r2)))

    table = build_creep_table(solver, a_over_b=np.array([0.5, 1.0]), n_x=9, n_y=17, n_s=25)
    from railhunt.contact.creep_table import _u_of_s

    ks = math.sqrt(1.0 + (k33 / k23) ** 2)
    node = (float(_u_of_s(0.25, 0.5)), float(_u_of_s(0.625, 0.5)), float(_u_of_s(0.5, 0.25)) / ks)
    u_node = (node[0], node[1] - node[2], node[2])  # s_y is the lateral linear force
    ref = solver(u_node[0] * 1e4 / (1e11 * 25e-6 * k11), u_node[1] * 1e4 / (1e11 * 25e-6 * k22),
                 u_node[2] * 1e4 / (1e11 * 125e-9 * k23), 5e-3, 5e-3, 1.0, 1e4, 1e11, 0.3)
    got = table.normalised(*u_node, 1.0, moment=(k23 / k22, k33 / k23))
    assert got == pytest.approx((ref[0] / 1e4, ref[1] / 1e4, ref[2] / 50.0), abs=1e-6)
    moment = (k23 / k22, k33 / k23)
    rng = np.random.default_rng(2)
    c = 5e-3
    err = []
    for _ in range(400):
        u = rng.normal(size=3) * 10.0 ** rng.uniform(-1, 1, size=3)
        ref = solver(u[0] * 1e4 / (1e11 * c * c * k11), u[1] * 1e4 / (1e11 * c * c * k22),
                     u[2] * 1e4 / (1e11 * c**3 * k23), c, c, 1.0, 1e4, 1e11, 0.3)
        got = table.normalised(*u, 1.0, moment=moment)
        err.append(np.subtract(got, (ref[0] / 1e4, ref[1] / 1e4, ref[2] / (1e4 * c))))
    rms = np.sqrt(np.mean(np.square(err), axis=0))
    assert np.all(rms < 0.03), rms
    assert np.abs(err).max() < 0.25
    # C1: one-sided difference quotients agree across a node of s_x (u_x = 3: s_x = 0.5).
    h = 1e-6
    f = [table.normalised(3.0 + d, 0.4, 0.1, 1.0, moment=moment)[0] for d in (-h, 0.0, h)]
    assert (f[1] - f[0]) / h == pytest.approx((f[2] - f[1]) / h, rel=1e-3)


def test_shipped_table_against_the_exact_solver() -> None:
    """The shipped table's law, fed creepages normalised with Kalker's coefficients as in the
    right-hand side, against the grid-converged exact theory (40 x 40 extrapolated from
    20 x 20, the table's own solver) at points between its nodes and slices: RMS 0.025 of
    mu N (force) and mu N c (moment) or better, 0.15 at worst (the build measured RMS
    0.005 / 0.016 / 0.018, worst 0.024 / 0.124 / 0.138 for F_x / F_y / M_z over 200 points;
    this sample of 30: RMS 0.004 / 0.018 / 0.018, worst 0.013 / 0.050 / 0.052)."""
    from railhunt.contact.creep_table import shipped_creep_table
    from railhunt.data.creep.build_creep_table import accuracy

    table = shipped_creep_table()
    assert table.meta["solver"] == "railhunt.creep_forces(law='exact', grid=40)"
    assert table.values.shape == (13, 11, 25, 25, 3)
    acc = accuracy(table, points=30, seed=4)
    assert max(acc["rms_fx"], acc["rms_fy"], acc["rms_mz"]) < 0.025, acc
    assert max(acc["max_fx"], acc["max_fy"], acc["max_mz"]) < 0.08, acc


def test_a_model_s_contact_mechanics_reach_the_linear_critical_speed():
    """``linear_critical_speed(vehicle, model=...)`` takes the model as it is: the
    per-point vehicle run with centred mechanics is the centred table vehicle to the bit,
    and the continuation of the hunting branch is seeded from the model (not from a new
    model of the vehicle's own mechanics)."""
    from railhunt.analysis.hunting_branch import _branch

    vp = railhunt.Vehicle.shipped("s1002_uic60_per_point")
    centred = Model(vp, contact_mechanics="centred")
    lin = railhunt.linear_critical_speed(vp, model=centred)
    table = railhunt.linear_critical_speed(railhunt.Vehicle.shipped("s1002_uic60_table"))
    assert lin.speed_kmh == table.speed_kmh
    assert abs(lin.speed_kmh - railhunt.linear_critical_speed(vp).speed_kmh) > 10.0
    branch = _branch(centred)
    assert branch is not None and branch.critical_kmh == lin.speed_kmh
    with pytest.raises(ValueError, match="model= is invalid together with creep_law="):
        railhunt.linear_critical_speed(vp, model=centred, creep_law="polach")
