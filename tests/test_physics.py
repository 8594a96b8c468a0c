"""Physics checks of the assembled model against analytic results and invariants."""

from __future__ import annotations

import math

import numpy as np
import pytest

import railhunt
from railhunt.model import N_STATE, STATE_NAMES, Model
from railhunt.suspension import (
    DOF_NAMES,
    assemble,
    damper_force_steady,
    damper_velocity,
    suspension_elements,
)

PAPER = railhunt.Vehicle.paper2019()


def free_wheelset_vehicle(conicity: float = 0.05) -> railhunt.Vehicle:
    """Wheelsets practically free of the bogie, on conical wheels (no contact-angle terms)."""
    return PAPER.replace(
        K_px=1e-3, K_py=1e-3, C_px=0.0, C_py=0.0,
        lambda1=conicity, lambda2=0.0, lambda3=0.0, lambda4=0.0, lambda5=0.0,
        d0=0.0, d1=0.0, d4=0.0, d5=0.0,
    )  # fmt: skip


def test_centred_state_is_an_equilibrium():
    model = Model(PAPER)
    for kmh in (100.0, 300.0, 500.0):
        dx = model.derivative(np.zeros(N_STATE), kmh / 3.6)
        assert np.max(np.abs(dx)) < 1e-9


def test_suspension_matrices_symmetric_and_passive():
    """Action equals reaction: symmetric, positive semi-definite K and C, and no force
    for a rigid-body motion of the whole vehicle (this fails with the paper's +l for the
    rear bogie in Eq. 5 or a wrong lever arm)."""
    k, c = assemble(suspension_elements(PAPER))
    assert np.allclose(k, k.T) and np.allclose(c, c.T)
    assert np.linalg.eigvalsh(k).min() > -1e-6 * np.abs(k).max()
    assert np.linalg.eigvalsh(c).min() > -1e-6 * np.abs(c).max()
    # Rigid lateral translation.
    q = np.zeros(17)
    q[[DOF_NAMES.index(n) for n in DOF_NAMES if n.startswith("y_")]] = 1.0
    assert np.max(np.abs(k @ q)) < 1e-6 * np.abs(k).max()
    # Rigid yaw of the whole vehicle about the car body centre: y_i = x_i * psi, psi_i = psi.
    arm, arm1 = PAPER.l, PAPER.l1
    x_pos = {"c": 0.0, "t1": arm, "t2": -arm, "w1": arm + arm1, "w2": arm - arm1,
             "w3": -arm + arm1, "w4": -arm - arm1}  # fmt: skip
    q = np.zeros(17)
    for name, xp in x_pos.items():
        q[DOF_NAMES.index(f"psi_{name}")] = 1e-3
        q[DOF_NAMES.index(f"y_{name}")] = 1e-3 * xp
    assert np.max(np.abs(k @ q)) < 1e-9 * np.abs(k).max()
    assert np.max(np.abs(c @ q)) < 1e-9 * np.abs(c).max()


def test_suspension_alone_is_passive():
    """Wheel/rail forces off (and the gravitational roll terms, which are not elements):
    no eigenvalue of the suspended vehicle, yaw dampers included, in the right half plane."""
    model = Model(PAPER)
    n = 17
    g = np.zeros((n, n))
    g[2, 2] = PAPER.M_c * PAPER.g * PAPER.h1
    g[5, 5] = g[8, 8] = PAPER.M_t * PAPER.g * PAPER.h4
    a = np.zeros((N_STATE, N_STATE))
    a[:n, n : 2 * n] = np.eye(n)
    a[n : 2 * n, : 2 * n] = model.lin
    a[n : 2 * n, :n] -= g / model.mass[:, None]  # lin holds +g/M (destabilising); remove it
    a[n : 2 * n, 2 * n :] = model.dd
    a[2 * n :, n : 2 * n] = PAPER.K_d * model.bd
    a[2 * n :, 2 * n :] = -PAPER.K_d / PAPER.C_d1 * np.eye(4)
    w = np.linalg.eigvals(a)
    # Without rails the vehicle has free rigid-body modes: zero eigenvalues in Jordan blocks,
    # which rounding splits into pairs +-sqrt(eps * |A|). Anything above that is a real
    # instability (an active element would give rates of order 0.1-10 1/s).
    tol = 10 * math.sqrt(np.finfo(float).eps * np.abs(a).max())
    assert w.real.max() < tol


def test_free_wheelset_hunts_at_klingel_frequency():
    """A free conical wheelset oscillates at f = v / (2 pi) * sqrt(lambda / (r0 a)).

    Klingel's kinematic result neglects inertia; at 10 m/s the inertial correction is below
    0.5 % for this wheelset, so 1 % is the stated tolerance.
    """
    conicity = 0.05
    vehicle = free_wheelset_vehicle(conicity)
    speed = 10.0
    klingel = speed / (2 * math.pi) * math.sqrt(conicity / (vehicle.r0 * vehicle.a))
    model = Model(vehicle, creep_law="linear")
    w, vecs = np.linalg.eig(model.jacobian(speed))
    iy = STATE_NAMES.index("y_w1")
    wheel_modes = [
        w[k] for k in range(w.size)
        if w[k].imag > 0 and np.abs(vecs[iy, k]) > 0.1 * np.abs(vecs[:17, k]).max()
    ]  # fmt: skip
    freq = max(wheel_modes, key=lambda z: z.real).imag / (2 * math.pi)
    assert freq == pytest.approx(klingel, rel=0.01)
    # And in the time domain: zero crossings of a small free oscillation.
    res = railhunt.simulate(
        vehicle, speed * 3.6, duration=4.0, creep_law="linear", dt=2e-4,
        excitation=railhunt.InitialDisplacement(1e-5, wheelsets=(1,)),
    )  # fmt: skip
    y = res["y_w1"]
    crossings = res.t[1:][np.diff(np.sign(y)) != 0]
    period = 2 * np.mean(np.diff(crossings))
    assert 1.0 / period == pytest.approx(klingel, rel=0.01)


def _hunting_eigenpair(model: Model, speed: float) -> tuple[complex, np.ndarray]:
    from railhunt.analysis.linear import eigenvalues, hunting_mode_index

    w, vecs = eigenvalues(model, speed)
    k = hunting_mode_index(w, vecs, model.vehicle.a)
    return w[k], vecs[:, k]


@pytest.mark.parametrize("kmh", [380.0, 480.0])
def test_eigenvalue_matches_small_amplitude_simulation(kmh):
    """Growth/decay rate and frequency of a small hunting oscillation agree with the
    hunting eigenvalue (2 % on frequency, 0.1 1/s on the rate)."""
    model = Model(PAPER)
    speed = kmh / 3.6
    lam, vec = _hunting_eigenpair(model, speed)
    x0 = np.real(vec) / np.max(np.abs(vec[:17])) * 1e-6
    res = railhunt.simulate(PAPER, kmh, duration=3.0, x0=x0, output_dt=1e-3, model=model)
    y = res["y_w1"]
    # Envelope from the peaks of |y|.
    a = np.abs(y)
    idx = np.nonzero((a[1:-1] >= a[:-2]) & (a[1:-1] > a[2:]))[0] + 1
    idx = idx[res.t[idx] > 0.5]
    rate = np.polyfit(res.t[idx], np.log(a[idx]), 1)[0]
    crossings = res.t[1:][np.diff(np.sign(y)) != 0]
    crossings = crossings[crossings > 0.5]
    freq = 1.0 / (2 * np.mean(np.diff(crossings)))
    assert freq == pytest.approx(lam.imag / (2 * math.pi), rel=0.02)
    assert rate == pytest.approx(lam.real, abs=0.1)
    assert np.sign(rate) == np.sign(lam.real)


def test_mirror_symmetry():
    """Mirrored initial state (y, psi, phi and all rates and forces -> minus) and mirrored
    track give the mirrored response."""
    rng = np.random.default_rng(7)
    x0 = np.zeros(N_STATE)
    x0[:34] = rng.normal(scale=1e-3, size=34)
    defect = railhunt.SingleDefect(amplitude=0.004, wavelength=15.0)
    mirror = railhunt.SingleDefect(amplitude=-0.004, wavelength=15.0)
    a = railhunt.simulate(PAPER, 350, duration=3.0, x0=x0, excitation=defect)
    b = railhunt.simulate(PAPER, 350, duration=3.0, x0=-x0, excitation=mirror)
    assert a.ok and b.ok
    scale = np.abs(a.x).max(axis=0) + 1e-30
    assert np.max(np.abs(a.x + b.x) / scale) < 1e-9


def test_yaw_damper_steady_characteristic():
    """Driven at constant velocity, the Maxwell damper settles on the two-stage curve of
    Fig. 4b: slope C_d1 up to v_u = F_u / C_d1, then C_d2, odd in the velocity."""
    kd, c1, c2, fu = PAPER.K_d, PAPER.C_d1, PAPER.C_d2, PAPER.F_u
    v_u = fu / c1
    assert v_u == pytest.approx(0.01, rel=1e-12)  # Table 2's blow-off velocity
    for vel in (-0.2, -0.05, -0.011, -0.005, 0.002, 0.009, 0.0105, 0.03, 0.1, 0.3):
        f, dt = 0.0, 1e-5
        for _ in range(100000):  # 1 s: 33 time constants C_d1 / K_d, 500 of C_d2 / K_d
            f += dt * kd * (vel - damper_velocity(f, c1, c2, fu))
        expected = c1 * vel if abs(vel) <= v_u else math.copysign(fu + c2 * (abs(vel) - v_u), vel)
        assert f == pytest.approx(expected, rel=1e-6)
        assert damper_force_steady(vel, c1, c2, fu) == pytest.approx(expected, rel=1e-12)
    # Continuity at the blow-off point and slopes on both sides.
    eps = 1e-7
    assert damper_force_steady(v_u, c1, c2, fu) == pytest.approx(fu)
    s1 = (damper_force_steady(v_u - eps, c1, c2, fu) - damper_force_steady(v_u - 2 * eps, c1, c2,
          fu)) / eps  # fmt: skip
    s2 = (damper_force_steady(v_u + 2 * eps, c1, c2, fu) - damper_force_steady(v_u + eps, c1, c2,
          fu)) / eps  # fmt: skip
    assert s1 == pytest.approx(c1, rel=1e-4) and s2 == pytest.approx(c2, rel=1e-4)


def test_gravitational_stiffness_restores_and_creep_yaws_back():
    """Sign conventions: a wheelset displaced to +y feels a restoring lateral force from the
    normal loads and is yawed toward -y by the longitudinal creep forces."""
    from railhunt.model import wheelset_forces

    model = Model(PAPER)
    fy, mz = wheelset_forces(0.002, 0.0, 0.0, 0.0, 0.0, 80.0, model.wr)
    assert mz < 0
    # With creep forces removed (mu -> tiny saturates them), the normal loads restore.
    weak = Model(PAPER.replace(mu=1e-9))
    fy_grav, _ = wheelset_forces(0.002, 0.0, 0.0, 0.0, 0.0, 80.0, weak.wr)
    assert fy_grav < 0


def test_hunting_mode_branch_is_continuous():
    """The hunting branch from 20 to 500 km/h is one mode: its frequency rises monotonically
    with speed (kinematic hunting, f ~ v at low speed) and its damping ratio never jumps by
    more than 0.05 between 20 km/h steps."""
    from railhunt.analysis.linear import eigen_analysis

    result = eigen_analysis(PAPER, np.arange(20.0, 520.0, 20.0))
    assert np.all(np.diff(result.hunting_frequency_hz) > 0)
    assert np.max(np.abs(np.diff(result.hunting_damping_ratio))) < 0.05
