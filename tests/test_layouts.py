"""Vehicle layouts (issue 18): the file format, the one assembly, physics checks of layouts
and the errors of bad layouts, through the library and the command line."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from railhunt.cli import main
from railhunt.kernel.layout import VEHICLE_17DOF, DamperParam
from railhunt.layout.expressions import Expression, ExpressionError, difference
from railhunt.layout.spec import LayoutError
from railhunt.model import Model
from railhunt.vehicle import Vehicle, load_vehicle
from railhunt.vehicle.files import shipped_path

DATA = Path(__file__).parent / "data"
ROOT = Path(__file__).parent.parent
PAPER = Vehicle.paper2019()
PAPER_TEXT = Path(str(shipped_path("paper2019"))).read_text(encoding="utf-8")


def write(tmp_path: Path, text: str, name: str = "layout.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def least_damped_oscillation(model: Model, speed: float, max_imag: float = 100.0) -> complex:
    """The oscillatory eigenvalue with the smallest damping ratio (Im below ``max_imag``)."""
    w = np.linalg.eigvals(model.jacobian(speed))
    osc = w[(w.imag > 1e-6) & (w.imag < max_imag)]
    return complex(osc[np.argmin(np.abs(osc.real) / np.abs(osc))])


# --------------------------------------------------------------------------- the paper's file


def test_fingerprint_through_the_layout_file():
    """The kernel's arrays, rhs and Jacobian at random states and the linear critical speed
    of the paper's vehicle, read from its layout file, hash as before the layout work
    (benchmarks/fingerprint_paper2019.txt; each wheelset's wheel/rail row is the old
    vector bit for bit)."""
    import sys

    sys.path.insert(0, str(ROOT))
    from benchmarks.fingerprint import fingerprint

    expected = dict(line.split(": ", 1) for line in
                    (ROOT / "benchmarks" / "fingerprint_paper2019.txt").read_text().splitlines())
    got = fingerprint()
    # The arrays, rhs and Jacobian are railhunt's own arithmetic: the same bits. The linear
    # critical speed goes through LAPACK's eigenvalues, whose last bits differ between
    # numpy/scipy builds (4.5e-13 km/h between the recorded value and numpy 2.4 / scipy
    # 1.17): it is compared to 1e-12 relative, far below anything a model change moves.
    speed = "linear_critical_speed"
    assert {k: v for k, v in got.items() if k != speed} == {
        k: v for k, v in expected.items() if k != speed}
    numbers = [re.findall(r"[-+0-9.e]+(?= km/h|\) Hz)", d[speed]) for d in (got, expected)]
    assert len(numbers[0]) == len(numbers[1]) == 2
    for a, b in zip(*numbers, strict=True):
        assert float(a) == pytest.approx(float(b), rel=1e-12)


def test_paper_layout_is_the_17_dof_vehicle():
    model = Model(PAPER)
    assert model.layout.state_names == VEHICLE_17DOF.state_names
    assert model.layout.dampers == ("d1", "d2", "d3", "d4")
    assert [b.kind for b in PAPER.layout.bodies] == ["car", "frame", "frame"] + ["wheelset"] * 4
    np.testing.assert_array_equal(model.wheelset_offsets(), [0.0, 2.5, 17.5, 20.0])
    assert model.mass_height() == pytest.approx(28000 / 4 * 1.592 + 3000 / 2 * 0.578 + 2400 * 0.43,
                                                rel=1e-12)


def test_to_toml_round_trip(tmp_path):
    path = PAPER.replace(C_d1=4.5e5).to_toml(tmp_path / "v.toml")
    back = load_vehicle(path)
    assert back.as_dict() == PAPER.replace(C_d1=4.5e5).as_dict()
    assert back.layout == PAPER.layout
    a, b = Model(back).system(), Model(PAPER.replace(C_d1=4.5e5)).system()
    for name in a._fields:
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    with pytest.raises(FileExistsError):
        PAPER.to_toml(path)
    PAPER.to_toml(path, overwrite=True)
    assert load_vehicle(path) == PAPER.replace()


def test_mirror_symmetry():
    """Mirrored elements make the vehicle odd-symmetric: rhs(-x) = -rhs(x), and the layout
    with every attachment point mirrored (y -> -y) has the same matrices."""
    model = Model(PAPER)
    rng = np.random.default_rng(18)
    for _ in range(3):
        x = rng.normal(scale=1e-3, size=model.n_state)
        x[model.layout.forces] *= 1e6
        np.testing.assert_allclose(model.derivative(-x, 60.0), -model.derivative(x, 60.0),
                                   rtol=1e-12, atol=1e-9)  # fmt: skip
    mirrored = re.sub(r'^(at(?:_b)? = \["[^"]*", )"([^"]+)"', r'\1"-(\2)"', PAPER_TEXT,
                      flags=re.M)  # fmt: skip
    assert mirrored != PAPER_TEXT
    asm, ref = load_vehicle(_tmp(mirrored)).assembly, PAPER.assembly
    np.testing.assert_allclose(asm.K_suspension, ref.K_suspension, rtol=1e-14, atol=1e-6)
    np.testing.assert_allclose(asm.C, ref.C, rtol=1e-14, atol=1e-8)
    # The mirrored dampers swap left and right.
    np.testing.assert_array_equal(asm.damper_rows[[1, 0, 3, 2]], ref.damper_rows)


def _tmp(text: str) -> Path:
    import tempfile

    folder = Path(tempfile.mkdtemp())
    return write(folder, text)


def test_suspension_alone_is_passive():
    """Without the wheel/rail forces and gravity, springs, dampers and Maxwell elements
    dissipate: no eigenvalue with a positive real part."""
    w = _suspension_eigenvalues(PAPER)
    assert np.max(w.real) < 1e-6 * np.max(np.abs(w))


def _suspension_eigenvalues(vehicle: Vehicle) -> np.ndarray:
    """Eigenvalues of the suspension alone (no wheel/rail forces, no gravity; the Maxwell
    elements linear, in their first stage)."""
    asm = vehicle.assembly
    n, nd = asm.layout.n_dof, asm.layout.n_damper
    inv_m = 1.0 / asm.mass
    a = np.zeros((2 * n + nd, 2 * n + nd))
    a[:n, n:2 * n] = np.eye(n)
    a[n:2 * n, :n] = -inv_m[:, None] * asm.K_suspension
    a[n:2 * n, n:2 * n] = -inv_m[:, None] * asm.C
    a[n:2 * n, 2 * n:] = -inv_m[:, None] * asm.damper_rows.T
    k_d, c_1 = asm.damper[:, DamperParam.K_D], asm.damper[:, DamperParam.C_D1]
    a[2 * n:, n:2 * n] = k_d[:, None] * asm.damper_rows
    a[2 * n:, 2 * n:] = -np.diag(k_d / c_1)
    return np.linalg.eigvals(a)


def test_suspension_forces_sum_to_zero():
    """Action = reaction: a rigid lateral shift or yaw of the whole vehicle deforms no
    element, so the suspension's forces on all bodies add up to zero."""
    asm = PAPER.assembly
    lay = asm.layout
    shift = np.zeros(lay.n_dof)
    turn = np.zeros(lay.n_dof)
    xs = {b.name: b.x(PAPER.values) for b in PAPER.layout.bodies}
    for b in lay.bodies:
        iy, ipsi, _ = lay.body_dofs(b.name)
        shift[iy] = 1.0
        turn[iy], turn[ipsi] = xs[b.name], 1.0
    for u in (shift, turn):
        for matrix in (asm.K_suspension, asm.C):
            np.testing.assert_allclose(matrix @ u, 0.0, atol=1e-6 * np.abs(matrix).max())
        np.testing.assert_allclose(asm.damper_rows @ u, 0.0, atol=1e-12)
        np.testing.assert_allclose(asm.stop_rows @ u, 0.0, atol=1e-12)


def test_fixed_body_is_an_infinitely_heavy_one():
    """A ``fixed`` car body gives the linear critical speed of the same car body with mass
    and inertias 1e9 times larger (within 0.1 %)."""
    from railhunt.analysis.linear import linear_critical_speed

    block = PAPER_TEXT[PAPER_TEXT.index('[[body]]\nname = "car"'):PAPER_TEXT.index(
        '[[body]]\nname = "bogie1"')]  # fmt: skip
    fixed = PAPER_TEXT.replace(block, block.replace('kind = "car"', 'kind = "fixed"')
                               .replace('yaw_inertia = "J_cz"\nroll_inertia = "J_cx"\n', ""))
    heavy = PAPER_TEXT.replace(block, block.replace('"M_c"', '"M_c * 1e9"')
                               .replace('"J_cz"', '"J_cz * 1e9"')
                               .replace('roll_inertia = "J_cx"', 'coordinates = ["y", "psi"]'))
    v_fixed, v_heavy = load_vehicle(_tmp(fixed)), load_vehicle(_tmp(heavy))
    assert Model(v_fixed).layout.n_dof == 14
    s_fixed = linear_critical_speed(v_fixed).speed_kmh
    s_heavy = linear_critical_speed(v_heavy).speed_kmh
    assert math.isfinite(s_fixed)
    assert abs(s_fixed - s_heavy) <= 1e-3 * s_heavy


# --------------------------------------------------------------------------- every layout

def _layouts() -> list[tuple[str, Vehicle]]:
    from railhunt.vehicle import shipped_vehicles

    out = [(name, Vehicle.shipped(name)) for name in shipped_vehicles()]
    example = ROOT / "examples" / "data" / "articulated_pair.toml"
    if example.is_file():
        out.append(("articulated_pair", load_vehicle(example)))
    return out


LAYOUTS = _layouts()


@pytest.mark.parametrize(("name", "vehicle"), LAYOUTS, ids=[n for n, _ in LAYOUTS])
def test_every_layout_is_odd_symmetric(name, vehicle):
    """Mirrored elements: rhs(-x) = -rhs(x) at random states (the left/right symmetry the
    half-period shooting uses)."""
    model = Model(vehicle)
    rng = np.random.default_rng(7)
    for _ in range(3):
        x = rng.normal(scale=1e-3, size=model.n_state)
        x[model.layout.forces] *= 1e6
        a, b = model.derivative(-x, 40.0), -model.derivative(x, 40.0)
        np.testing.assert_allclose(a, b, rtol=1e-10, atol=1e-9 * np.abs(b).max())


@pytest.mark.parametrize(("name", "vehicle"), LAYOUTS, ids=[n for n, _ in LAYOUTS])
def test_every_layouts_suspension_is_passive(name, vehicle):
    assert np.max(_suspension_eigenvalues(vehicle).real) < 1e-6 * np.max(
        np.abs(_suspension_eigenvalues(vehicle)))  # fmt: skip


@pytest.mark.parametrize(("name", "vehicle"), LAYOUTS, ids=[n for n, _ in LAYOUTS])
def test_every_layouts_internal_forces_sum_to_zero(name, vehicle):
    """The springs and dampers between moving bodies: a rigid lateral shift or yaw of the
    whole vehicle deforms none, so their forces on all bodies add up to zero."""
    from railhunt.suspension import assemble, suspension_elements

    asm = vehicle.assembly
    lay = asm.layout
    k, c = assemble(suspension_elements(vehicle), lay)
    xs = {b.name: b.x(vehicle.values) for b in vehicle.layout.bodies}
    shift, turn = np.zeros(lay.n_dof), np.zeros(lay.n_dof)
    for b in lay.bodies:
        iy, ipsi, _ = lay.body_dofs(b.name)
        shift[iy] = 1.0
        if ipsi >= 0:
            turn[iy], turn[ipsi] = xs[b.name], 1.0
    for u in (shift, turn):
        for matrix in (k, c):
            np.testing.assert_allclose(matrix @ u, 0.0, atol=1e-9 * max(np.abs(matrix).max(), 1))


@pytest.mark.parametrize(("name", "vehicle"), LAYOUTS, ids=[n for n, _ in LAYOUTS])
def test_every_layout_writes_a_file_that_loads_back_to_the_same_numbers(tmp_path, name,
                                                                        vehicle):  # fmt: skip
    back = load_vehicle(vehicle.to_toml(tmp_path / f"{name}.toml"))
    assert back.as_dict() == vehicle.as_dict() and back.layout == vehicle.layout
    a, b = Model(back).system(), Model(vehicle).system()
    for field in a._fields:
        np.testing.assert_array_equal(getattr(a, field), getattr(b, field), err_msg=field)


def test_fixed_body_of_the_cooperrider_bogie_is_an_infinitely_heavy_one():
    from railhunt.analysis.linear import linear_critical_speed

    text = Path(str(shipped_path("cooperrider_bogie"))).read_text(encoding="utf-8")
    block = 'kind = "fixed"\nx = 0.0\nheight = "r0 + h1 + h2"\n'
    assert block in text
    heavy = text.replace(block, block.replace('"fixed"', '"car"') + 'coordinates = ["y", "psi"]'
                         '\nmass = "1e9 * m_f"\nyaw_inertia = "1e9 * I_f"\n')
    s_fixed = linear_critical_speed(Vehicle.shipped("cooperrider_bogie")).speed_kmh
    assert math.isfinite(s_fixed)
    # The heavy body adds its own modes, almost undamped at |lambda| ~ 1e-3 1/s, whose
    # real parts are finite-difference noise (+-1e-8 1/s): the crossing is that of the
    # other modes.
    model = Model(load_vehicle(_tmp(heavy)))

    def growth(kmh: float) -> float:
        w = np.linalg.eigvals(model.jacobian(kmh / 3.6))
        return float(np.max(w.real[np.abs(w) > 1e-2]))

    from scipy.optimize import brentq

    s_heavy = brentq(growth, 0.8 * s_fixed, 1.2 * s_fixed, xtol=1e-3)
    assert abs(s_fixed - s_heavy) <= 1e-3 * s_heavy


# --------------------------------------------------------------------------- kinematics


def test_single_wheelset_runs_on_klingels_wavelength():
    """A wheelset on weak springs, conical treads, no contact angle: at 1 m/s its kinematic
    oscillation has the wavelength 2 pi sqrt(r0 a / lambda) (Klingel), to 1e-6."""
    v = load_vehicle(DATA / "layout_wheelset.toml")
    lam = least_damped_oscillation(Model(v), 1.0)
    wavelength = 2 * math.pi * 1.0 / lam.imag
    assert wavelength == pytest.approx(2 * math.pi * math.sqrt(v.r0 * v.a / v.lam), rel=1e-6)


@pytest.mark.parametrize("ratio", [1.0, 0.5, 2.0])
def test_rigid_truck_kinematic_wavelength(ratio):
    """Two wheelsets at +-b held rigidly in one frame. With inertia negligible the creep
    forces balance: the lateral ones give dy/dt = v psi, the yaw moments
    (f11 a^2 + f22 b^2) dpsi/dt = -v f11 a lambda y / r0, so the wavelength is
    2 pi sqrt((r0 a / lambda) (1 + (f22 / f11) b^2 / a^2)); f11 = f22 gives the classic
    2 pi sqrt((r0 a / lambda)(1 + b^2/a^2)). Within 1e-4 at 1 m/s (springs of 1e9 N/m)."""
    base = load_vehicle(DATA / "layout_truck.toml")
    v = base.replace(f22=base.f11 * ratio)
    lam = least_damped_oscillation(Model(v), 1.0)
    expected = 2 * math.pi * math.sqrt(v.r0 * v.a / v.lam * (1 + ratio * v.b**2 / v.a**2))
    assert 2 * math.pi / lam.imag == pytest.approx(expected, rel=1e-4)


def test_layout_without_yaw_dampers_simulates():
    """A layout with no Maxwell element and no frame runs: channels named from its bodies."""
    from railhunt import InitialDisplacement, simulate

    v = load_vehicle(DATA / "layout_wheelset.toml")
    run = simulate(v, 20.0, duration=1.0, excitation=InitialDisplacement(amplitude=1e-3))
    assert run.ok and run.x.shape[1] == 4
    assert run["y_w1"][0] == pytest.approx(1e-3)
    assert "SY_w1" in run.derived and not any(k.startswith("dd") for k in run.derived)


# --------------------------------------------------------------------------- bad layouts

BAD = [
    ('bodies = ["bogie1", "wheelset1"]', 'bodies = ["bogie1", "wheelset9"]',
     "unknown body 'wheelset9'"),
    ('bodies = ["bogie1", "wheelset1"]', 'bodies = ["bogie1", "bogie1"]',
     "joins body 'bogie1' to itself"),
    ('name = "bogie2"', 'name = "bogie1"', "the name 'bogie1' is taken"),
    ('mass = "M_t"', 'mass = "-M_t"', "mass = -3000.0 is invalid: must be > 0"),
    ('mass = "M_w"', 'mass = "M_w + nonsense"', "unknown parameter(s) 'nonsense'"),
    ('kind = "frame"', 'kind = "bogie"', "kind = 'bogie' is unknown"),
    ('axis = "x"', 'axis = "w"', "axis = 'w' is invalid"),
    ('blowoff_force = "F_u"\n', "", "a maxwell needs stiffness, damping, damping2, "
     "blowoff_force; missing blowoff_force"),
    ('half_gauge = "a"\n', "", "has no wheel/rail data for half_gauge"),
    ('mass = "M_w"', 'mass = "__import__(\'os\')"', "the only functions are"),
]


@pytest.mark.parametrize(("old", "new", "message"), BAD)
def test_bad_layouts_one_clear_error(tmp_path, old, new, message):
    assert old in PAPER_TEXT
    path = write(tmp_path, PAPER_TEXT.replace(old, new, 1))
    with pytest.raises(ValueError) as info:
        load_vehicle(path)
    assert message in str(info.value)
    assert str(path) in str(info.value)
    result = CliRunner().invoke(main, ["critical-speed", "--vehicle", str(path), "--json"])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("railhunt: error:") and message in lines[0]


def test_free_mode_is_named(tmp_path):
    """A coordinate no element restrains: a free mode, named; a free wheelset is allowed."""
    text = (DATA / "layout_truck.toml").read_text(encoding="utf-8")
    free = text + '''
[[body]]
name = "box"
kind = "car"
x = 0.0
height = 1.0
mass = 1000.0
yaw_inertia = 1000.0
roll_inertia = 1000.0

[[element]]
kind = "spring"
bodies = ["box", "frame"]
axis = "y"
at = [0.0, 0.0, 1.0]
stiffness = 1.0e5
'''
    with pytest.raises(LayoutError, match=r"coordinate psi_c of body 'box' is restrained "
                                          r"by no element \(a free mode\)"):  # fmt: skip
        load_vehicle(write(tmp_path, free))
    rig = (DATA / "layout_wheelset.toml").read_text(encoding="utf-8")
    alone = rig[:rig.index("[[element]]")]
    with pytest.warns(UserWarning, match="wheelset 'wheelset' is joined to no body"):
        load_vehicle(write(tmp_path, alone, "alone.toml"))


def test_cycle_in_parameters(tmp_path):
    text = PAPER_TEXT.replace("[parameters.M_c]\nvalue = 28000.0",
                              '[parameters.M_c]\nvalue = "M_t * 2"', 1)
    text = text.replace("[parameters.M_t]\nvalue = 3000.0",
                        '[parameters.M_t]\nvalue = "M_c / 2"', 1)
    with pytest.raises(LayoutError, match="cycle: M_c -> M_t -> M_c"):
        load_vehicle(write(tmp_path, text))


def test_set_and_replace_act_on_the_layouts_parameters():
    v = load_vehicle(DATA / "layout_truck.toml")
    assert v.replace(b=1.5).b == 1.5
    assert Model(v.replace(b=1.5)).wheelset_offsets()[1] == 3.0
    with pytest.raises(ValueError, match="did you mean 'f11'"):
        v.replace(f1l=1.0)
    result = CliRunner().invoke(main, ["eigen", "--vehicle", str(DATA / "layout_truck.toml"),
                                       "--set", "b=1.5", "--from", "50", "--to", "100"])
    assert result.exit_code == 0, result.output


# --------------------------------------------------------------------------- expressions

NAMES = st.sampled_from(["a", "b", "c"])


@st.composite
def expressions(draw, depth: int = 3) -> tuple[str, float]:
    """A random arithmetic expression and its value for a=1.5, b=-2.25, c=4."""
    values = {"a": 1.5, "b": -2.25, "c": 4.0}
    if depth == 0 or draw(st.booleans()):
        if draw(st.booleans()):
            name = draw(NAMES)
            return name, values[name]
        x = draw(st.floats(min_value=-100, max_value=100, allow_nan=False))
        return repr(x), x
    left, lv = draw(expressions(depth - 1))
    right, rv = draw(expressions(depth - 1))
    op = draw(st.sampled_from(["+", "-", "*"]))
    if draw(st.booleans()):
        return f"-({left})", -lv
    value = {"+": lv + rv, "-": lv - rv, "*": lv * rv}[op]
    return f"({left}) {op} ({right})", value


@settings(max_examples=200)
@given(expressions())
def test_expression_evaluates_like_python_arithmetic(case):
    text, value = case
    expr = Expression(text)
    assert expr({"a": 1.5, "b": -2.25, "c": 4.0}) == value
    assert difference(expr, expr, {"a": 1.5, "b": -2.25, "c": 4.0}) == 0.0


@given(st.text(max_size=30))
def test_expression_refuses_anything_else(text):
    try:
        expr = Expression(text)
    except ExpressionError:
        return
    assert all(name.isidentifier() for name in expr.names)


def test_expression_difference_cancels_shared_terms():
    values = {"r0": 0.43, "h4": 0.148, "h3": 0.162, "h1": 0.852, "l": 8.3, "l1": 1.3}
    assert difference(Expression("r0 + h4 + h3"), Expression("r0 + h4 + h3 + h1"),
                      values) == -0.852  # fmt: skip
    assert difference(Expression("l + l1"), Expression("l"), values) == 1.3
    assert (8.3 + 1.3) - 8.3 != 1.3  # what the cancellation avoids
    for bad in ("os.system", "a[0]", "'x'", "lambda: 1", "a if b else c", "a < b", "f(a)"):
        with pytest.raises(ExpressionError):
            Expression(bad)


def test_study_design_on_a_layouts_own_parameters():
    """Sweeps and ties check names and values against the vehicle's own table."""
    from railhunt.studies.design import build_design

    v = Vehicle.shipped("cooperrider_bogie")
    points = build_design(v, {"k4": [1e5, 2e5]}, ties={"k5": "k4"})
    assert [p.values for p in points] == [{"k4": 1e5, "k5": 1e5}, {"k4": 2e5, "k5": 2e5}]
    with pytest.raises(ValueError, match="did you mean 'k4'"):
        build_design(v, {"k44": [1.0]})
    with pytest.raises(ValueError, match="unknown vehicle parameter 'C_d1'"):
        build_design(v, {"C_d1": [1.0]})


def test_the_crossing_of_a_stiffly_held_frame_is_hunting():
    """The Cooperrider bogie's frame moves laterally a little more than its wheelsets in
    the crossing mode (1.0 against 0.9): it is still the hunting instability."""
    from railhunt.analysis.linear import linear_critical_speed

    assert linear_critical_speed(Vehicle.shipped("cooperrider_bogie")).is_hunting_mode
    assert linear_critical_speed(PAPER).is_hunting_mode


def test_the_hopf_start_is_the_crossing_pair():
    """A locomotive's two nearly equal bogie modes: the continuation starts from the pair
    that crosses at the Hopf point, not from the damped one the per-speed pick prefers."""
    from railhunt.analysis.hopf_start import hopf_mode_shape as _hopf_start
    from railhunt.analysis.linear import linear_critical_speed

    v = Vehicle.shipped("three_axle_bogie_car")
    lc = linear_critical_speed(v, tol_kmh=1e-3)
    _, period = _hopf_start(Model(v), lc.speed_kmh)
    assert 1.0 / period == pytest.approx(lc.frequency_hz, rel=1e-3)


def test_a_branch_jittering_in_speed_makes_one_fold():
    """Folds are turns confirmed by a retreat of more than 0.5 km/h: a branch that jitters
    in speed along a plateau (two-axle wagon, wheel against its flange) turns once; on a
    clean branch every sign change of the speed step is a fold, as before."""
    from railhunt.analysis.branches import _turns

    jitter = np.array([404.07, 403.5, 402.67, 402.79, 401.7, 401.78, 400.85, 400.91, 399.0,
                       397.0, 396.65, 397.04, 396.7, 397.1, 399.0, 401.0, 404.0])
    assert _turns(jitter) == [10]
    rng = np.random.default_rng(0)
    for _ in range(300):
        t = np.linspace(0, 1, int(rng.integers(5, 60)))
        speed = 300 + 50 * np.sin(2 * np.pi * rng.uniform(0.3, 3) * t + rng.uniform(0, 6))
        dv = np.diff(speed)
        assert _turns(speed) == [i for i in range(1, dv.size) if dv[i - 1] * dv[i] < 0]
