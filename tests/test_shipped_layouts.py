"""The shipped layouts (and the articulated example) as vehicles: structure and references.

For every layout: it loads, mirror symmetry of the right-hand side, the suspension alone is
passive, the suspension's forces on all bodies sum to zero (action = reaction); a fixed
body behaves like a very heavy one. For the Cooperrider bogie, the Hopf point against the
literature; for the sprung wheelset of docs/layouts.md, against Routh-Hurwitz.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import railhunt
from railhunt.analysis.closed_forms import sprung_wheelset_critical_speed
from railhunt.kernel.layout import WR
from railhunt.kernel.rhs import jacobian, rhs
from railhunt.model import Model

ROOT = Path(__file__).resolve().parents[1]
ARTICULATED = ROOT / "examples" / "data" / "articulated_pair.toml"
SHIPPED = ("cooperrider_bogie", "two_axle_wagon", "three_axle_bogie_car")
LAYOUTS = (*SHIPPED, "articulated_pair")


def vehicle(name: str) -> railhunt.Vehicle:
    if name == "articulated_pair":
        return railhunt.Vehicle.from_toml(ARTICULATED)
    return railhunt.Vehicle.shipped(name)


@pytest.fixture(scope="module", params=LAYOUTS)
def model(request) -> Model:
    return Model(vehicle(request.param))


def test_shipped_vehicles_are_listed():
    names = set(railhunt.vehicle.shipped_vehicles())
    assert set(SHIPPED) <= names


def test_sizes(model):
    expected = {"cooperrider_bogie": (7, 2, 0), "two_axle_wagon": (7, 2, 0),
                "three_axle_bogie_car": (21, 6, 4), "articulated_pair": (27, 6, 8)}
    n_dof, n_ws, n_damper = expected[model.vehicle.name]
    assert model.layout.n_dof == n_dof
    assert model.system().wheelsets.shape[0] == n_ws
    assert model.layout.n_damper == n_damper


def _mirror_permutation(model: Model) -> np.ndarray:
    """State index -> index of its mirror image: coordinates and rates change sign in
    place; each yaw damper's force is its mirror twin's (same sign), the twin being the
    damper whose elongation row is the negative of its own."""
    n = model.layout.n_state
    perm = np.arange(n)
    rows = model.system().damper_rows
    f0 = model.layout.force0
    for d in range(rows.shape[0]):
        twins = [e for e in range(rows.shape[0]) if np.allclose(rows[e], -rows[d], atol=1e-12)]
        assert len(twins) == 1, f"damper {d} has no mirror twin"
        perm[f0 + d] = f0 + twins[0]
    return perm


def test_mirror_symmetry(model):
    """x -> mirror(x): the derivative mirrors (y, psi, phi and their rates change sign,
    left and right dampers swap), at random states on ideal straight track."""
    s = model.system()
    n, nq = model.layout.n_state, model.layout.n_dof
    sign = np.r_[-np.ones(2 * nq), np.ones(n - 2 * nq)]
    perm = _mirror_permutation(model)
    rng = np.random.default_rng(3)
    for _ in range(4):
        x = rng.normal(size=n) * np.r_[np.full(nq, 3e-3), np.full(nq, 3e-2),
                                       np.full(n - 2 * nq, 2e3)]  # fmt: skip
        xm = np.empty(n)
        xm[perm] = sign * x
        out, out_m = np.empty(n), np.empty(n)
        rhs(0.0, x, 55.0, s, out)
        rhs(0.0, xm, 55.0, s, out_m)
        expected = np.empty(n)
        expected[perm] = sign * out
        scale = np.abs(out).max()
        assert np.max(np.abs(out_m - expected)) < 1e-9 * scale


def test_suspension_alone_is_passive(model):
    """No wheel/rail forces (creep coefficients 0, cylindrical wheels on knife edges): no
    eigenvalue of the Jacobian in the right half plane."""
    s = model.system()
    wr = s.wheel_rail.copy()
    wr[:, [WR.F11, WR.F22, WR.F23, WR.F33]] = 0.0
    wr[:, WR.LAMBDA1:WR.D5 + 1] = 0.0
    wr[:, WR.TABLE:] = 0.0
    quiet = s._replace(wheel_rail=wr)
    eig = np.linalg.eigvals(jacobian(np.zeros(model.layout.n_state), 50.0, quiet, 0.0))
    assert eig.real.max() < 1e-6 * np.abs(eig).max()


def _balance_rows(model: Model) -> tuple[np.ndarray, np.ndarray]:
    """Rows that sum, from generalised forces Q, the lateral forces of all bodies and their
    yaw moments about the leading wheelset (body b sits ``body_delay[b]`` behind it)."""
    nq = model.layout.n_dof
    s = model.system()
    lateral, yaw = np.zeros(nq), np.zeros(nq)
    for (iy, ip, _), behind in zip(s.bodies, s.body_delay, strict=True):
        lateral[iy] = 1.0
        yaw[iy] = -behind
        yaw[ip] = 1.0
    return lateral, yaw


def test_action_equals_reaction(model):
    """The suspension's generalised forces (K q, C q', every damper and stop row) carry no
    net lateral force and no net yaw moment: each element acts on both its bodies with
    equal and opposite forces. A fixed body takes reactions, so it is left out."""
    if any(b.kind == "fixed" for b in model.vehicle.layout.bodies):
        pytest.skip("a fixed body takes the reactions")
    lateral, yaw = _balance_rows(model)
    s = model.system()
    m = model.mass
    k_c = -m[:, None] * s.suspension  # [K_suspension, C]
    rows = [k_c.T, s.damper_rows, s.stop_rows]
    for block in rows:
        for r in np.atleast_2d(block):
            scale = max(np.abs(r).max(), 1.0)
            assert abs(lateral @ r) < 1e-9 * scale
            assert abs(yaw @ r) < 1e-9 * scale * 30.0  # arms up to 30 m


def _hopf_speed(v: railhunt.Vehicle, low: float, high: float, slowest: float) -> float:
    """Speed (m/s) where the largest real part among the eigenvalues faster than
    ``slowest`` (rad/s) crosses zero."""
    model = Model(v)

    def growth(speed: float) -> float:
        w = np.linalg.eigvals(model.jacobian(speed))
        return float(w[np.abs(w) > slowest].real.max())

    return brentq(growth, low, high, xtol=1e-6)


def test_fixed_body_equals_a_very_heavy_one(tmp_path):
    """The Cooperrider bogie's fixed car body against the same body as a car with mass and
    inertias 1e9 times the frame's: the hunting Hopf point within 0.1 %. (The heavy body
    adds its own slow modes, |lambda| ~ 6e-4 rad/s, whose growth rate ~ 5e-9 1/s scales
    as 1/mass: weakly unstable at every speed, so they are left out of the comparison.)"""
    src = Path(railhunt.__file__).parent / "data" / "vehicles" / "cooperrider_bogie.toml"
    text = src.read_text(encoding="utf-8")
    heavy = text.replace('kind = "fixed"', 'kind = "car"\nmass = "heavy * m_f"\n'
                         'yaw_inertia = "heavy * I_f"\nroll_inertia = "heavy * I_fr"', 1)
    heavy += '\n[parameters.heavy]\nvalue = 1e9\nallow = true\n'  # implausible on purpose
    heavy = heavy.replace('name = "cooperrider_bogie"', 'name = "cooperrider_heavy_body"')
    path = tmp_path / "heavy.toml"
    path.write_text(heavy, encoding="utf-8")
    fixed = _hopf_speed(railhunt.Vehicle.shipped("cooperrider_bogie"), 60.0, 75.0, 0.1)
    body = _hopf_speed(railhunt.Vehicle.from_toml(path), 60.0, 75.0, 0.1)
    assert body == pytest.approx(fixed, rel=1e-3)


def test_cooperrider_hopf_point_against_the_literature():
    """Cooperrider's bogie in Kaas-Petersen's SI form loses its stability at a subcritical
    ('hard') Hopf bifurcation at v0 = 68.66 m/s (R. Seydel's collection of bifurcation
    examples, the railway bogie, with B. Hassard's equations and values). The recalled
    values (cooperrider_bogie.md) allow 0.5 %; railhunt gives 68.64 m/s at 4.00 Hz."""
    result = railhunt.linear_critical_speed(railhunt.Vehicle.shipped("cooperrider_bogie"))
    assert result.speed_kmh / 3.6 == pytest.approx(68.66, rel=5e-3)
    assert 3.5 < result.frequency_hz < 4.5


def _docs_example() -> str:
    text = (ROOT / "docs" / "layouts.md").read_text(encoding="utf-8")
    return re.search(r"```toml\n(.*?)```", text, re.S).group(1)


def test_the_docs_example_is_the_sprung_wheelset_of_routh_hurwitz(tmp_path):
    """The complete example of docs/layouts.md (a wheelset on springs to a fixed frame,
    conical wheels on knife edges, linear creep) has the closed-form critical speed and
    frequency of railhunt.analysis.closed_forms within 1e-5."""
    path = tmp_path / "sprung_wheelset.toml"
    path.write_text(_docs_example(), encoding="utf-8")
    v = railhunt.Vehicle.from_toml(path)
    p = v.as_dict()
    expected = sprung_wheelset_critical_speed(
        p["m_w"], p["J_w"], 2 * p["k_y"], 2 * p["k_x"] * p["b"] ** 2, p["f11"], p["f22"],
        p["r0"], p["a"], 0.05)
    result = railhunt.linear_critical_speed(v)
    assert result.speed_kmh / 3.6 == pytest.approx(expected.critical_speed, rel=1e-5)
    assert result.frequency_hz == pytest.approx(expected.frequency, rel=1e-5)
    assert math.isfinite(expected.critical_speed)


def test_cooperrider_hopf_is_subcritical_and_its_cycles_turn_on_the_flanges():
    """Seydel's 'hard loss of stability': the cycles born at the Hopf point are unstable
    and turn at a fold below it; the fold's amplitude lies just beyond the flange
    clearance delta = 9.1 mm (the flange springs are what stabilises the large cycles)."""
    v = railhunt.Vehicle.shipped("cooperrider_bogie")
    diagram = railhunt.bifurcation_diagram(v, speed_range_kmh=(200.0, 280.0))
    assert diagram.hopf_type == "subcritical"
    assert diagram.hopf_speed_kmh == pytest.approx(247.1, abs=0.1)
    fold = min(diagram.folds, key=lambda f: f.speed_kmh)
    assert 230.0 < fold.speed_kmh < diagram.hopf_speed_kmh
    assert v.delta < fold.amplitude < v.delta + 2e-3
