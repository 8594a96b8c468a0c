"""Assembled matrices and wheel/rail forces against closed forms derived by hand.

Guards for the restructuring of issue 12: every expected value here is written out from the
vehicle's parameters and the physics of docs/model.md (element table, Eqs. 25-33), never by
calling the code under test. Tolerances are at rounding level, so a changed term, sign or
lever arm fails by many orders of magnitude.

Notation: K, C are the stiffness and damping matrices of ``Model(v)`` (K includes the
gravitational roll terms); ``y``, ``psi``, ``phi`` are lateral displacement, yaw and roll;
``c`` car body, ``t1``/``t2`` front/rear bogie frame (at x = +l / -l), ``w1..w4`` wheelsets
(w1, w3 leading in their bogie, at +l1 from its centre).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import railhunt
from railhunt.kernel.creep import heuristic_saturation
from railhunt.model import N_STATE, STATE_NAMES, Model, wheelset_forces
from railhunt.suspension import DOF_NAMES, assemble, suspension_elements, yaw_damper_rows

N_DOF = len(DOF_NAMES)  # 17
#: Slices of the state: coordinates, their rates, the four yaw damper forces.
Q = slice(0, N_DOF)
DQ = slice(N_DOF, 2 * N_DOF)
F_D = slice(2 * N_DOF, N_STATE)

V = railhunt.Vehicle.paper2019()
I = {name: k for k, name in enumerate(DOF_NAMES)}  # noqa: E741
SPEED = 300 / 3.6  # m/s
#: Creep coefficient small enough to switch a creep force off (the rules need f11, f22 > 0).
TINY = 1e-9  # N


# ----------------------------------------------------------------- hand-built K and C


def _add(m: np.ndarray, a: str, b: str, value: float) -> None:
    """Add ``value`` to the symmetric pair of entries (a, b), (b, a) (once on the diagonal)."""
    i, k = I[a], I[b]
    m[i, k] += value
    if i != k:
        m[k, i] += value


def _primary(m, w, t, xr, kx, ky, kz, v):
    """Two axle boxes (y = +-b1) between wheelset ``w`` and bogie ``t``, the bogie point at
    (xr, +-b1, -h4): longitudinal, lateral and vertical coefficients kx, ky, kz each."""
    b1, h4 = v.b1, v.h4
    yw, pw, yt, pt, ft = f"y_{w}", f"psi_{w}", f"y_{t}", f"psi_{t}", f"phi_{t}"
    # Longitudinal: elongation -+b1 (psi_w - psi_t).
    _add(m, pw, pw, 2 * kx * b1**2)
    _add(m, pt, pt, 2 * kx * b1**2)
    _add(m, pw, pt, -2 * kx * b1**2)
    # Lateral: y_w - (y_t + xr psi_t - h4 phi_t).
    _add(m, yw, yw, 2 * ky)
    _add(m, yt, yt, 2 * ky)
    _add(m, pt, pt, 2 * ky * xr**2)
    _add(m, ft, ft, 2 * ky * h4**2)
    _add(m, yw, yt, -2 * ky)
    _add(m, yw, pt, -2 * ky * xr)
    _add(m, yw, ft, 2 * ky * h4)
    _add(m, yt, pt, 2 * ky * xr)
    _add(m, yt, ft, -2 * ky * h4)
    _add(m, pt, ft, -2 * ky * xr * h4)
    # Vertical: +-b1 phi_t (the wheelset does not roll).
    _add(m, ft, ft, 2 * kz * b1**2)


def _secondary(m, t, xc, kx, bx, ky, hc, ht, kz, bz):
    """A pair of elements (y = +-bx or +-bz) between car body and bogie ``t``, the car point
    at (xc, ., -hc), the bogie point at (0, ., +ht)."""
    yc, pc, fc, yt, pt, ft = "y_c", "psi_c", "phi_c", f"y_{t}", f"psi_{t}", f"phi_{t}"
    # Longitudinal: elongation -+bx (psi_t - psi_c).
    _add(m, pt, pt, 2 * kx * bx**2)
    _add(m, pc, pc, 2 * kx * bx**2)
    _add(m, pt, pc, -2 * kx * bx**2)
    # Lateral: (y_t + ht phi_t) - (y_c + xc psi_c - hc phi_c).
    _add(m, yt, yt, 2 * ky)
    _add(m, ft, ft, 2 * ky * ht**2)
    _add(m, yc, yc, 2 * ky)
    _add(m, pc, pc, 2 * ky * xc**2)
    _add(m, fc, fc, 2 * ky * hc**2)
    _add(m, yt, ft, 2 * ky * ht)
    _add(m, yt, yc, -2 * ky)
    _add(m, yt, pc, -2 * ky * xc)
    _add(m, yt, fc, 2 * ky * hc)
    _add(m, ft, yc, -2 * ky * ht)
    _add(m, ft, pc, -2 * ky * ht * xc)
    _add(m, ft, fc, 2 * ky * ht * hc)
    _add(m, yc, pc, 2 * ky * xc)
    _add(m, yc, fc, -2 * ky * hc)
    _add(m, pc, fc, -2 * ky * xc * hc)
    # Vertical: -+bz phi_t +- bz phi_c.
    _add(m, ft, ft, 2 * kz * bz**2)
    _add(m, fc, fc, 2 * kz * bz**2)
    _add(m, ft, fc, -2 * kz * bz**2)


def hand_K(v: railhunt.Vehicle, gravity: bool = True) -> np.ndarray:
    """Stiffness matrix written out element pair by element pair (docs/model.md's table)."""
    k = np.zeros((N_DOF, N_DOF))
    for t, xc, wheelsets in (("t1", v.l, ("w1", "w2")), ("t2", -v.l, ("w3", "w4"))):
        for w, xr in zip(wheelsets, (v.l1, -v.l1), strict=True):
            _primary(k, w, t, xr, v.K_px, v.K_py, v.K_pz, v)
        _secondary(k, t, xc, v.K_sx, v.b2, v.K_sy, v.h1, v.h3, v.K_sz, v.b2)
        if gravity:
            _add(k, f"phi_{t}", f"phi_{t}", -v.M_t * v.g * v.h4)
    if gravity:
        _add(k, "phi_c", "phi_c", -v.M_c * v.g * v.h1)
    return k


def hand_C(v: railhunt.Vehicle) -> np.ndarray:
    """Damping matrix: primary dampers beside the springs; secondary lateral dampers at
    (+-b2, heights h2 / h5), vertical dampers at +-b3, no secondary longitudinal damper."""
    c = np.zeros((N_DOF, N_DOF))
    for t, xc, wheelsets in (("t1", v.l, ("w1", "w2")), ("t2", -v.l, ("w3", "w4"))):
        for w, xr in zip(wheelsets, (v.l1, -v.l1), strict=True):
            _primary(c, w, t, xr, v.C_px, v.C_py, v.C_pz, v)
        _secondary(c, t, xc, 0.0, v.b2, v.C_sy, v.h2, v.h5, v.C_sz, v.b3)
    return c


@pytest.fixture(scope="module")
def model() -> Model:
    return Model(V)


def entry(m: np.ndarray, a: str, b: str) -> float:
    """Entry (a, b) of a coordinate x coordinate matrix by names."""
    return float(m[I[a], I[b]])


def exactly(expected: float) -> object:
    """Equal to rounding (the matrices are sums of a few products)."""
    return pytest.approx(expected, rel=1e-12, abs=1e-9)


# ------------------------------------------------------------------- named entries of K


def test_wheelset_yaw_diagonal_is_primary_yaw_stiffness(model):
    """2 K_px b1^2 on each wheelset's yaw (two longitudinal springs at +-b1)."""
    for j in range(1, 5):
        assert entry(model.K, f"psi_w{j}", f"psi_w{j}") == exactly(2 * V.K_px * V.b1**2)
        assert entry(model.C, f"psi_w{j}", f"psi_w{j}") == exactly(2 * V.C_px * V.b1**2)
        assert entry(model.K, f"y_w{j}", f"y_w{j}") == exactly(2 * V.K_py)


def test_car_lateral_diagonal_counts_four_air_springs(model):
    """4 K_sy and 4 C_sy on y_c: two bogies x two air springs / lateral dampers."""
    assert entry(model.K, "y_c", "y_c") == exactly(4 * V.K_sy)
    assert entry(model.C, "y_c", "y_c") == exactly(4 * V.C_sy)
    assert entry(model.K, "y_t1", "y_c") == exactly(-2 * V.K_sy)
    assert entry(model.K, "y_t1", "y_t1") == exactly(4 * V.K_py + 2 * V.K_sy)


def test_gravitational_roll_terms(model):
    """K = suspension + G, G = diag(-M_c g h1 on phi_c, -M_t g h4 on each phi_t); and the
    roll diagonals in full, from the parameters."""
    k_susp, _ = assemble(suspension_elements(V))
    g = np.zeros((N_DOF, N_DOF))
    g[I["phi_c"], I["phi_c"]] = -V.M_c * V.g * V.h1
    g[I["phi_t1"], I["phi_t1"]] = g[I["phi_t2"], I["phi_t2"]] = -V.M_t * V.g * V.h4
    np.testing.assert_allclose(model.K - k_susp, g, rtol=0, atol=1e-6)
    roll_c = 4 * V.K_sy * V.h1**2 + 4 * V.K_sz * V.b2**2 - V.M_c * V.g * V.h1
    roll_t = (4 * V.K_py * V.h4**2 + 4 * V.K_pz * V.b1**2 + 2 * V.K_sy * V.h3**2
              + 2 * V.K_sz * V.b2**2 - V.M_t * V.g * V.h4)  # fmt: skip
    assert entry(model.K, "phi_c", "phi_c") == exactly(roll_c)
    assert entry(model.K, "phi_t1", "phi_t1") == exactly(roll_t)
    assert entry(model.K, "phi_t2", "phi_t2") == exactly(roll_t)


def test_secondary_lever_arm_front_plus_l_rear_minus_l(model):
    """The air springs of the front bogie sit at x = +l, the rear ones at -l: the lateral
    coupling to the car body's yaw is -2 K_sy l (front) and +2 K_sy l (rear)."""
    assert entry(model.K, "y_t1", "psi_c") == exactly(-2 * V.K_sy * V.l)
    assert entry(model.K, "y_t2", "psi_c") == exactly(+2 * V.K_sy * V.l)
    assert entry(model.C, "y_t1", "psi_c") == exactly(-2 * V.C_sy * V.l)
    assert entry(model.C, "y_t2", "psi_c") == exactly(+2 * V.C_sy * V.l)
    yaw_c = 4 * V.K_sy * V.l**2 + 4 * V.K_sx * V.b2**2
    assert entry(model.K, "psi_c", "psi_c") == exactly(yaw_c)
    assert entry(model.K, "y_c", "phi_c") == exactly(-4 * V.K_sy * V.h1)
    roll_damping_c = 4 * V.C_sy * V.h2**2 + 4 * V.C_sz * V.b3**2
    assert entry(model.C, "phi_c", "phi_c") == exactly(roll_damping_c)
    assert entry(model.K, "y_c", "psi_c") == pytest.approx(0.0, abs=1e-6)  # front/rear cancel


def test_primary_lever_arms(model):
    """Primary lateral springs at x = +-l1 from the bogie centre and h4 below its centre of
    gravity; bogie yaw from longitudinal (b1), lateral (l1) and air springs (b2)."""
    assert entry(model.K, "y_w1", "psi_t1") == exactly(-2 * V.K_py * V.l1)
    assert entry(model.K, "y_w2", "psi_t1") == exactly(+2 * V.K_py * V.l1)
    assert entry(model.K, "y_w3", "psi_t2") == exactly(-2 * V.K_py * V.l1)
    assert entry(model.K, "y_w1", "phi_t1") == exactly(2 * V.K_py * V.h4)
    assert entry(model.K, "y_t1", "phi_t1") == exactly(-4 * V.K_py * V.h4 + 2 * V.K_sy * V.h3)
    assert entry(model.K, "psi_w1", "psi_t1") == exactly(-2 * V.K_px * V.b1**2)
    yaw_t = 4 * V.K_px * V.b1**2 + 4 * V.K_py * V.l1**2 + 2 * V.K_sx * V.b2**2
    assert entry(model.K, "psi_t1", "psi_t1") == exactly(yaw_t)
    assert entry(model.K, "psi_t2", "psi_t2") == exactly(yaw_t)
    assert entry(model.C, "y_t1", "phi_t1") == exactly(-4 * V.C_py * V.h4 + 2 * V.C_sy * V.h5)


# ------------------------------------------------------------ whole matrices, M, B_d


@pytest.mark.parametrize("vehicle", [V, V.replace(l=7.0, l1=1.4, h1=0.9, h3=0.2, h4=0.1,
                                                  b2=1.1, b3=1.25, K_sy=3e5, K_sx=1.5e5)],
                         ids=["paper2019", "altered"])  # fmt: skip
def test_whole_K_and_C_equal_the_hand_assembly(vehicle):
    """Every entry of K and C (the zeros included) equals the hand assembly; a second,
    altered vehicle keeps coincidences of the paper's numbers from hiding a wrong arm."""
    m = Model(vehicle)
    scale_k, scale_c = np.abs(m.K).max(), np.abs(m.C).max()
    np.testing.assert_allclose(m.K, hand_K(vehicle), rtol=1e-12, atol=1e-13 * scale_k)
    np.testing.assert_allclose(m.C, hand_C(vehicle), rtol=1e-12, atol=1e-13 * scale_c)
    k_susp, c_susp = assemble(suspension_elements(vehicle))
    np.testing.assert_allclose(k_susp, hand_K(vehicle, gravity=False), rtol=1e-12,
                               atol=1e-13 * scale_k)  # fmt: skip


def test_mass_diagonal(model):
    expected = [V.M_c, V.J_cz, V.J_cx] + [V.M_t, V.J_tz, V.J_tx] * 2 + [V.M_w, V.J_wz] * 4
    assert model.mass.tolist() == expected


def test_yaw_damper_rows():
    """Elongation of damper (front left, front right, rear left, rear right) = -+b4 (psi_t -
    psi_c): a longitudinal element at lateral arm +-b4 between car body and bogie."""
    b4 = V.b4
    expected = np.zeros((4, N_DOF))
    for d, (t, s) in enumerate((("t1", 1), ("t1", -1), ("t2", 1), ("t2", -1))):
        expected[d, I[f"psi_{t}"]] = -s * b4
        expected[d, I["psi_c"]] = +s * b4
    np.testing.assert_array_equal(yaw_damper_rows(V), expected)


def test_right_hand_side_uses_K_C_and_the_dampers(model):
    """With the wheelsets centred and still (no wheel/rail force), the accelerations of the
    right-hand side are -M^-1 (K q + C q' + B_d^T F) with the hand-built K, C, B_d, and
    the damper forces relax as K_d (B_d q' - F / C_d1) below blow-off."""
    rng = np.random.default_rng(12)
    x = np.zeros(N_STATE)
    bodies = [n for n in DOF_NAMES if not n.endswith(("w1", "w2", "w3", "w4"))]
    for n in bodies:
        x[STATE_NAMES.index(n)] = rng.normal(0, 1e-3)
        x[STATE_NAMES.index("d" + n)] = rng.normal(0, 1e-2)
    forces = rng.uniform(-1000.0, 1000.0, 4)  # N, below F_u = 3000 N
    x[F_D] = forces
    q, dq = x[Q], x[DQ]
    b4 = V.b4
    bd = np.zeros((4, N_DOF))
    for d, (t, s) in enumerate((("t1", 1), ("t1", -1), ("t2", 1), ("t2", -1))):
        bd[d, I[f"psi_{t}"]], bd[d, I["psi_c"]] = -s * b4, s * b4
    mass = np.array([V.M_c, V.J_cz, V.J_cx] + [V.M_t, V.J_tz, V.J_tx] * 2 + [V.M_w, V.J_wz] * 4)
    acc = -(hand_K(V) @ q + hand_C(V) @ dq + bd.T @ forces) / mass
    rate = V.K_d * (bd @ dq - forces / V.C_d1)
    out = model.derivative(x, SPEED)
    np.testing.assert_allclose(out[Q], dq, rtol=0, atol=0)
    np.testing.assert_allclose(out[DQ], acc, rtol=1e-10, atol=1e-12 * np.abs(acc).max())
    np.testing.assert_allclose(out[F_D], rate, rtol=1e-10, atol=1e-12 * np.abs(rate).max())


# ---------------------------------------------------------------- wheel/rail forces


def radius(v: railhunt.Vehicle, u: float) -> float:
    """Eq. 32 for a wheel displaced u toward its flange (m)."""
    return (v.r0 + v.lambda1 * u + v.lambda2 * u**2 + v.lambda3 * u**3 + v.lambda4 * u**4
            + v.lambda5 * u**5)  # fmt: skip


def angle(v: railhunt.Vehicle, u: float) -> float:
    """Eq. 33 with the paper's coefficients and u = -y_paper (below the cap for |u| < 8 mm)."""
    d = v.d0 - v.d1 * u + v.d4 * u**4 - v.d5 * u**5
    assert abs(d) < v.delta_max
    return d


def forces(v: railhunt.Vehicle, law: str, y: float, dy: float = 0.0, psi: float = 0.0,
           psi_rel: float | None = None, dpsi: float = 0.0,
           speed: float = SPEED) -> tuple[float, float]:  # fmt: skip
    """Lateral force and yaw moment of the code under test."""
    wr = Model(v, creep_law=law).wr
    return wheelset_forces(y, dy, psi, psi if psi_rel is None else psi_rel, dpsi, speed, wr)


def alpha(beta: float) -> float:
    """Eq. 28 by hand: alpha * beta = beta - beta^2/3 + beta^3/27 up to 3, then 1."""
    return (beta - beta**2 / 3 + beta**3 / 27) / beta if beta <= 3 else 1.0 / beta


def test_gravitational_lateral_force_restores():
    """Creep forces off: the force is N (tan delta_R - tan delta_L), toward the centre."""
    v = V.replace(f11=TINY, f22=TINY, f23=0.0, f33=0.0)
    for y in (-6e-3, -3e-3, -1e-3, 1e-3, 3e-3, 6e-3):
        expected = V.W * V.g / 2 * (math.tan(angle(V, -y)) - math.tan(angle(V, y)))
        f, m = forces(v, "linear", y)
        assert f == pytest.approx(expected, rel=1e-9)
        assert f * y < 0  # restoring
        assert abs(m) < 1e-6


def test_gravitational_yaw_moment():
    """N a sin(psi_rel) (tan delta_L + tan delta_R), destabilising (same sign as psi_rel)."""
    v = V.replace(f11=TINY, f22=TINY, f23=0.0, f33=0.0)
    y, psi_rel = 2e-3, 3e-3
    n_load = V.W * V.g / 2
    expected = n_load * V.a * math.sin(psi_rel) * (math.tan(angle(V, y)) + math.tan(angle(V, -y)))
    _, m = forces(v, "linear", y, psi=0.0, psi_rel=psi_rel)
    assert m == pytest.approx(expected, rel=1e-9)
    assert m > 0


def test_spin_creep_lateral_force_and_its_sign():
    """f11 = f22 ~ 0: on a wheelset displaced to +y the spin creepages -+Omega sin(delta)/v
    give F_y = f23/(2 r0) (sin 2 delta_L - sin 2 delta_R), pointing to +y (toward the flange:
    it counters part of the gravitational stiffness)."""
    v = V.replace(f11=TINY, f22=TINY, f33=0.0)
    for y in (1e-3, 3e-3, 5e-3):
        dl, dr = angle(V, y), angle(V, -y)
        spin = V.f23 / (2 * V.r0) * (math.sin(2 * dl) - math.sin(2 * dr))
        with_spin, _ = forces(v, "linear", y)
        without, _ = forces(v.replace(f23=0.0), "linear", y)
        assert with_spin - without == pytest.approx(spin, rel=1e-9)
        assert spin > 0.05 * abs(without)  # a material share, not rounding
        assert with_spin - without > 0


def test_spin_coupling_yaw_moment_of_a_yawed_wheelset():
    """f11 = f22 ~ 0, f33 = 0: a centred wheelset yawed by psi has the lateral creepage
    -sin(psi) cos(d0) on each wheel, whose f23 coupling gives M = -2 f23 sin(psi) cos(d0)^2
    (the gravitational moment is off: psi_rel = 0)."""
    v = V.replace(f11=TINY, f22=TINY, f33=0.0)
    for psi in (-2e-3, 1e-3, 3e-3):
        expected = -2 * V.f23 * math.sin(psi) * math.cos(V.d0) ** 2
        _, m = forces(v, "linear", 0.0, psi=psi, psi_rel=0.0)
        assert m == pytest.approx(expected, rel=1e-9)


def test_klingel_longitudinal_creep_yaw_moment():
    """A wheelset displaced to +y rolls on r_L > r_R: the longitudinal creep forces yaw it
    toward -y, M = f11 a (r_R - r_L) / r0 (Klingel)."""
    v = V.replace(f22=TINY, f23=0.0, f33=0.0)
    for y in (1e-3, 2e-3, 4e-3):
        expected = V.f11 * V.a * (radius(V, -y) - radius(V, y)) / V.r0
        _, m = forces(v, "linear", y)
        assert m == pytest.approx(expected, rel=1e-9)
        assert m < 0
        _, m_neg = forces(v, "linear", -y)
        assert m_neg == pytest.approx(-expected, rel=1e-9)


@pytest.mark.parametrize("beta", [0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 5.0, 20.0])
def test_heuristic_saturation_closed_form(beta):
    """alpha * beta = beta - beta^2/3 + beta^3/27 (beta <= 3), = 1 above: never above mu N."""
    a = heuristic_saturation(beta)
    expected = 1.0 if beta == 0 else alpha(beta)
    assert a == pytest.approx(expected, rel=1e-14)
    if beta >= 3:
        assert a * beta == pytest.approx(1.0, rel=1e-14)


@pytest.mark.parametrize("law", ["heuristic", "heuristic-per-wheel"])
@pytest.mark.parametrize("beta", [0.5, 1.0, 2.0, 3.0, 4.0, 8.0])
def test_saturated_lateral_force_of_a_sliding_wheelset(law, beta):
    """A centred wheelset moving sideways at dy (f23 = 0): each wheel's Kalker force is
    f22 (dy/v) cos(d0) = beta mu N; after saturation each wheel carries alpha(beta) beta mu N
    along its contact plane, i.e. mu N (all the friction) for beta >= 3."""
    v = V.replace(f23=0.0, f33=0.0)
    mu_n = V.mu * V.W * V.g / 2
    cd = math.cos(V.d0)
    dy = beta * mu_n * SPEED / (V.f22 * cd)
    f, m = forces(v, law, 0.0, dy=dy)
    per_wheel = alpha(beta) * beta * mu_n
    assert f == pytest.approx(-2 * cd * per_wheel, rel=1e-9)
    if beta >= 3:
        assert f == pytest.approx(-2 * cd * mu_n, rel=1e-9)
    assert abs(m) < 1e-6 * mu_n


def _hand_forces(v, law, y, dy, psi, psi_rel, dpsi, speed):
    """Eqs. 25-30 wheel by wheel, written independently (per-wheel vectors)."""
    n_load = v.W * v.g / 2
    omega = speed / v.r0
    f_lat = m_yaw = 0.0
    wheels = []
    for side in (+1, -1):  # left, right
        u = side * y
        r, d = radius(v, u), angle(v, u)
        xi_x = (speed * math.cos(psi) + dy * math.sin(psi) - side * v.a * dpsi - r * omega) / speed
        xi_y = (dy * math.cos(psi) - speed * math.sin(psi)) * math.cos(d) / speed
        xi_sp = (dpsi * math.cos(d) - side * omega * math.sin(d)) / speed
        fx = -v.f11 * xi_x
        fy = -v.f22 * xi_y - v.f23 * xi_sp
        mz = v.f23 * xi_y - v.f33 * xi_sp
        wheels.append([side, d, fx, fy, mz, math.hypot(fx, fy) / (v.mu * n_load)])
    betas = [w[5] for w in wheels]
    for side, d, fx, fy, mz, beta in wheels:
        if law == "heuristic":
            a = alpha(0.5 * sum(betas))
        elif law == "heuristic-per-wheel":
            a = alpha(beta)
        else:
            a = 1.0
        fx, fy = a * fx, a * fy
        f_lat += fy * math.cos(d) * math.cos(psi) + fx * math.sin(psi)
        m_yaw += -side * fx * v.a + mz * math.cos(d)
    tl, tr = math.tan(angle(v, y)), math.tan(angle(v, -y))
    f_lat += n_load * (tr - tl)
    m_yaw += n_load * v.a * math.sin(psi_rel) * (tl + tr)
    return f_lat, m_yaw


@pytest.mark.parametrize("law", ["linear", "heuristic", "heuristic-per-wheel"])
@pytest.mark.parametrize("state", [
    (2.5e-3, 0.03, 1.5e-3, 1.2e-3, 0.02),
    (-4e-3, -0.05, -2e-3, -2.5e-3, 0.04),
    (6e-3, 0.2, 4e-3, 4e-3, -0.3),
])  # fmt: skip
def test_wheelset_forces_at_general_states(law, state):
    """All terms together (creepages, Kalker, saturation, rotation into track axes, gravity)
    at displaced, moving, yawed states, for each law; the third state saturates hard."""
    y, dy, psi, psi_rel, dpsi = state
    f, m = forces(V, law, y, dy, psi, psi_rel, dpsi)
    f_hand, m_hand = _hand_forces(V, law, y, dy, psi, psi_rel, dpsi, SPEED)
    assert f == pytest.approx(f_hand, rel=1e-9)
    assert m == pytest.approx(m_hand, rel=1e-9)
