"""The compiled right-hand side against the closed forms of railhunt.analysis.closed_forms.

Small vehicles are assembled here by hand, straight into the kernel's bundle (no layout
file): a wheelset on springs to a fixed frame, and a rigid two-axle truck (two wheelsets
on very stiff springs in one frame). Conical wheels on knife-edge rails, Kalker's linear
law without spin, the Cooperrider bogie's numbers (cooperrider_bogie.md). The Jacobian's
eigenvalues must equal the roots of the derived quartic, cross the imaginary axis at the
Routh-Hurwitz speed, and the kinematic modes must run on the derived wavelengths. (The
matrix-level closed forms of the paper's vehicle are in test_closed_forms.py.)
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import brentq

from railhunt.analysis.closed_forms import (
    klingel_wavelength,
    rigid_truck_wavelength,
    sprung_wheelset_critical_speed,
    sprung_wheelset_quartic,
)
from railhunt.kernel.contact import conical_slots
from railhunt.kernel.creep import CreepLaw
from railhunt.kernel.layout import N_ROUTE, N_WR, WR, SystemArrays
from railhunt.kernel.rhs import jacobian

GPIAB = 6.563e6
F11, F22 = GPIAB / 0.60252, GPIAB / 0.54219
R0, A, LAM = 0.4572, 0.7163, 0.05
M_W, J_W = 1022.0, 678.0
M_F, J_F = 2918.9, 6780.0
B = 1.074
D1 = 0.620


def wheel_rail_row(f11=F11, f22=F22):
    wr = np.zeros(N_WR)
    wr[WR.F11], wr[WR.F22], wr[WR.MU], wr[WR.N], wr[WR.A], wr[WR.R0] = f11, f22, 0.15, 6e4, A, R0
    for slot, value in conical_slots(LAM).items():
        wr[slot] = value
    wr[WR.CREEP_LAW] = CreepLaw.LINEAR
    wr[WR.INV_MW], wr[WR.INV_JW], wr[WR.W], wr[WR.G] = 1 / M_W, 1 / J_W, 1e4, 9.81
    return wr


def bundle(mass, stiffness, wheelsets, delays, rows):
    """SystemArrays of a linear suspension ``M q'' + K q`` and wheelsets (no damper, no stop)."""
    n = len(mass)
    inv_m = 1.0 / np.asarray(mass, dtype=float)
    lin = -inv_m[:, None] * np.hstack([stiffness, np.zeros((n, n))])
    return SystemArrays(
        linear=np.ascontiguousarray(lin), damper_rows=np.zeros((0, n)),
        damper_acc=np.zeros((n, 0)), damper=np.zeros((0, 4)), wheel_rail=np.array(rows),
        wheelsets=np.array(wheelsets, dtype=np.int64), wheelset_delay=np.array(delays),
        track=np.zeros(4), track_samples=np.zeros(1), stop_rows=np.zeros((0, n)),
        stop_acc=np.zeros((n, 0)), stop=np.zeros((0, 3)), route=np.zeros((0, N_ROUTE)),
        bodies=np.array([[i, i + 1, -1] for i in range(0, n, 2)], dtype=np.int64),
        body_delay=np.zeros(n // 2), suspension=np.ascontiguousarray(lin),
        scratch=np.zeros(3 * n),
    )  # fmt: skip


def sprung_wheelset(k_y, k_psi, f11=F11, f22=F22):
    return bundle([M_W, J_W], np.diag([k_y, k_psi]), [[0, 1]], [0.0], [wheel_rail_row(f11, f22)])


def eigenvalues(system, speed):
    return np.linalg.eigvals(jacobian(np.zeros(2 * system.linear.shape[0]), speed, system, 0.0))


def kinematic(eig):
    """The slowest oscillating eigenvalue (the kinematic mode)."""
    osc = eig[np.abs(eig.imag) > 1e-9]
    return osc[np.argmin(np.abs(osc))]


K_Y = 2 * 1.823e6  # two primary lateral springs
K_PSI = 2 * 3.646e6 * D1**2  # two primary longitudinal springs at +-d1


@pytest.mark.parametrize("speed", [5.0, 30.0, 60.0, 120.0])
@pytest.mark.parametrize("springs", [(0.0, 0.0), (K_Y, K_PSI), (K_Y, 0.1 * K_PSI)])
def test_jacobian_eigenvalues_are_the_roots_of_the_quartic(speed, springs):
    """The derivation of the quartic (docs/model.md) against the kernel's linearisation."""
    eig = np.sort_complex(eigenvalues(sprung_wheelset(*springs), speed))
    roots = np.sort_complex(np.roots(sprung_wheelset_quartic(speed, M_W, J_W, *springs, F11,
                                                             F22, R0, A, LAM)))  # fmt: skip
    scale = np.max(np.abs(roots))
    assert np.max(np.abs(eig - roots)) < 1e-6 * scale


def test_routh_hurwitz_critical_speed_is_the_hopf_point():
    """Below V_c every eigenvalue is in the left half plane, above it the hunting pair has
    crossed, at V_c itself with frequency sqrt(a1/a3)."""
    sol = sprung_wheelset_critical_speed(M_W, J_W, K_Y, K_PSI, F11, F22, R0, A, LAM)
    assert 10.0 < sol.critical_speed < 500.0
    system = sprung_wheelset(K_Y, K_PSI)

    def growth(v):
        return float(np.max(eigenvalues(system, v).real))

    assert growth(0.99 * sol.critical_speed) < 0.0 < growth(1.01 * sol.critical_speed)
    crossing = brentq(growth, 0.9 * sol.critical_speed, 1.1 * sol.critical_speed, xtol=1e-9)
    assert crossing == pytest.approx(sol.critical_speed, rel=1e-5)
    eig = eigenvalues(system, crossing)
    hunting = eig[np.argmax(eig.real)]
    assert abs(hunting.imag) / (2 * math.pi) == pytest.approx(sol.frequency, rel=1e-5)


def test_free_wheelset_is_unstable_at_every_speed():
    sol = sprung_wheelset_critical_speed(M_W, J_W, 0.0, 0.0, F11, F22, R0, A, LAM)
    assert sol.critical_speed == 0.0
    for v in (1.0, 10.0, 100.0):
        assert np.max(eigenvalues(sprung_wheelset(0.0, 0.0), v).real) > 0.0


def test_klingel_wavelength_of_a_wheelset_on_weak_springs():
    """Weak springs, low speed: the kinematic mode's wavelength 2 pi V / omega is
    Klingel's within 0.1 % (inertia and springs shift it by ~1e-4)."""
    speed = 5.0
    lam = kinematic(eigenvalues(sprung_wheelset(1e3, 1e3), speed))
    assert 2 * math.pi * speed / abs(lam.imag) == pytest.approx(
        klingel_wavelength(R0, A, LAM), rel=1e-3)
    assert klingel_wavelength(R0, A, LAM) == pytest.approx(2 * math.pi * math.sqrt(R0 * A / LAM))


def rigid_truck(f11, f22, k=1e9):
    """Frame (y_f, psi_f) and two wheelsets at +-B on lateral springs k (two per wheelset)
    and longitudinal springs k at +-D1: q = [y1, psi1, y2, psi2, y_f, psi_f]."""
    kmat = np.zeros((6, 6))
    for i, x in ((0, B), (2, -B)):
        for row, k_el in ((np.eye(6)[i] - np.eye(6)[4] - x * np.eye(6)[5], 2 * k),
                          (np.eye(6)[i + 1] - np.eye(6)[5], 2 * k * D1**2)):  # fmt: skip
            kmat += k_el * np.outer(row, row)
    wr = wheel_rail_row(f11, f22)
    return bundle([M_W, J_W, M_W, J_W, M_F, J_F], kmat, [[0, 1], [2, 3]], [0.0, 2 * B],
                  [wr, wr])  # fmt: skip


@pytest.mark.parametrize("ratio", [1.0, F22 / F11, 0.5])
def test_rigid_truck_kinematic_wavelength(ratio):
    """2 pi sqrt((r0 a / lambda)(1 + (f22/f11) b^2/a^2)) within 0.3 % at 5 m/s; with
    Cooperrider's f22/f11 = 1.11 the equal-coefficient formula is 3.8 % off."""
    speed = 5.0
    f22 = F11 * ratio
    lam = kinematic(eigenvalues(rigid_truck(F11, f22), speed))
    wavelength = 2 * math.pi * speed / abs(lam.imag)
    assert wavelength == pytest.approx(rigid_truck_wavelength(R0, A, LAM, B, F11, f22), rel=3e-3)
    if ratio != 1.0:
        equal = rigid_truck_wavelength(R0, A, LAM, B)
        assert abs(wavelength / equal - 1) > 1e-2


def test_rigid_truck_formula_limits():
    assert rigid_truck_wavelength(R0, A, LAM, 0.0) == klingel_wavelength(R0, A, LAM)
    assert rigid_truck_wavelength(R0, A, LAM, B) == pytest.approx(
        2 * math.pi * math.sqrt(R0 * A / LAM * (1 + B**2 / A**2)), rel=1e-15)


@given(name=st.sampled_from(["r0", "a", "conicity"]),
       bad=st.sampled_from([0.0, -1.0, math.nan, math.inf, "x", None]))  # fmt: skip
def test_bad_input_names_the_parameter(name, bad):
    args = {"r0": R0, "a": A, "conicity": LAM}
    args[name] = bad
    with pytest.raises(ValueError, match=f"^{name} = "):
        klingel_wavelength(**args)
    with pytest.raises(ValueError, match=f"^{name} = "):
        rigid_truck_wavelength(b=B, **args)
    with pytest.raises(ValueError, match=f"^{name} = "):
        sprung_wheelset_critical_speed(M_W, J_W, K_Y, K_PSI, F11, F22, **args)


def test_negative_spring_is_refused():
    with pytest.raises(ValueError, match="^k_yaw = -1"):
        sprung_wheelset_critical_speed(M_W, J_W, K_Y, -1.0, F11, F22, R0, A, LAM)
