"""The kernel's element laws for general layouts, against closed forms written by hand.

Vermeulen-Johnson saturation (``creep_law = "vermeulen-johnson"``), conical treads on
knife-edge rails (``contact = "conical"``), dead-band stops to the track (flanges), and one
wheel/rail parameter row per wheelset. Every expected value is computed here from the
formulas of docs/model.md and kernel/creep.py, never by the code under test; tolerances are
at rounding level unless a limit is taken.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import railhunt
from railhunt.curve import Curve
from railhunt.kernel.contact import conical_slots, wheel_geometry
from railhunt.kernel.creep import CreepLaw
from railhunt.kernel.layout import N_WR, WR, StopParam
from railhunt.kernel.rhs import rhs
from railhunt.kernel.wheelset import wheelset_contact
from railhunt.model import Model
from railhunt.track import SingleDefect

#: The Cooperrider bogie's wheel/rail data (cooperrider_bogie.md): G pi a b = 6.563e6 N,
#: phi = 0.60252, psi = 0.54219, mu = 0.15, a = 0.7163 m, r0 = 0.4572 m, lambda = 0.05.
GPIAB = 6.563e6
F11, F22 = GPIAB / 0.60252, GPIAB / 0.54219
MU, N_LOAD, A, R0, LAM = 0.15, 6.0e4, 0.7163, 0.4572, 0.05
SPEED = 60.0  # m/s


def row(law: int = CreepLaw.VERMEULEN_JOHNSON, *, f23: float = 0.0, f33: float = 0.0,
        contact_angle: float = 0.0, n_load: float = N_LOAD) -> np.ndarray:  # fmt: skip
    """A wheel/rail row of conical wheels (slots WR)."""
    wr = np.zeros(N_WR)
    wr[WR.F11], wr[WR.F22], wr[WR.F23], wr[WR.F33] = F11, F22, f23, f33
    wr[WR.MU], wr[WR.N], wr[WR.A], wr[WR.R0] = MU, n_load, A, R0
    for slot, value in conical_slots(LAM, contact_angle).items():
        wr[slot] = value
    wr[WR.CREEP_LAW] = law
    wr[WR.INV_MW], wr[WR.INV_JW], wr[WR.W], wr[WR.G] = 1 / 1022.0, 1 / 678.0, 1e4, 9.81
    return wr


def contact(wr, y=0.0, dy=0.0, psi=0.0, dpsi=0.0, v=SPEED):
    """Forces of the code under test on straight track at the static load."""
    n = wr[WR.N]
    return wheelset_contact(y, dy, psi, psi, dpsi, dpsi, v, wr, n, n)


def vj_hand(xi_x: float, xi_y: float, n_load: float = N_LOAD) -> tuple[float, float]:
    """Vermeulen-Johnson by hand (Vermeulen & Johnson 1964, as in cooperrider_bogie.md):
    u = sqrt((xi_x/phi)^2 + (xi_y/psi)^2), beta = G pi a b u / (mu N),
    F_R = mu N (beta - beta^2/3 + beta^3/27) below 3, mu N beyond; components along the
    normalised creepages (xi_x/phi, xi_y/psi) / u, opposing the creepage."""
    phi, psi = GPIAB / F11, GPIAB / F22
    u = math.hypot(xi_x / phi, xi_y / psi)
    if u == 0.0:
        return 0.0, 0.0
    beta = GPIAB * u / (MU * n_load)
    f_r = MU * n_load * (beta - beta**2 / 3 + beta**3 / 27 if beta < 3 else 1.0)
    return -f_r * (xi_x / phi) / u, -f_r * (xi_y / psi) / u


# ------------------------------------------------------------ Vermeulen-Johnson


@pytest.mark.parametrize("psi", [1e-5, 1e-4, 5e-4, 1e-3, 2e-3, 4e-3, 1e-2])
@pytest.mark.parametrize("dy", [0.0, 0.05, -0.2])
def test_vermeulen_johnson_closed_form(psi, dy):
    """A yawed, sliding wheelset (y = 0, both wheels alike): xi_x = (v cos psi + dy sin psi
    - v) / v, xi_y = (dy cos psi - v sin psi) / v on each wheel (Eq. 25 with r = r0);
    the lateral force 2 (F_y cos psi + F_x sin psi)."""
    fy, _, f_l, f_r = contact(row(), dy=dy, psi=psi)
    xi_x = (SPEED * math.cos(psi) + dy * math.sin(psi) - SPEED) / SPEED
    xi_y = (dy * math.cos(psi) - SPEED * math.sin(psi)) / SPEED
    fx_h, fy_h = vj_hand(xi_x, xi_y)
    expected = 2 * (fy_h * math.cos(psi) + fx_h * math.sin(psi))
    assert fy == pytest.approx(expected, rel=1e-12, abs=1e-9)
    assert f_l == pytest.approx(f_r, rel=1e-14)


@pytest.mark.parametrize("y", [1e-4, 1e-3, 5e-3, 2e-2])
def test_vermeulen_johnson_longitudinal_yaw_moment(y):
    """Displaced wheelset, no yaw: xi_x = -+lambda y / r0 on the left/right wheel; the
    longitudinal forces make the moment a (F_xR - F_xL)."""
    _, mz, _, _ = contact(row(), y=y)
    fx_l, _ = vj_hand(-LAM * y / R0, 0.0)
    fx_r, _ = vj_hand(+LAM * y / R0, 0.0)
    # (the kernel forms xi_x as (v - r omega) / v: cancellation of ~ eps r0 / (lambda y))
    assert mz == pytest.approx(A * (fx_r - fx_l), rel=1e-9)


def test_vermeulen_johnson_small_creep_is_linear():
    """beta -> 0: the forces tend to Kalker's f11 xi_x, f22 xi_y (relative error ~ beta/3)."""
    psi = 1e-8
    fy, _, _, _ = contact(row(), psi=psi)
    lin, _, _, _ = contact(row(CreepLaw.LINEAR), psi=psi)
    beta = F22 * psi / (MU * N_LOAD)
    assert fy == pytest.approx(lin, rel=beta)  # differs by beta/3 only
    assert fy != lin


@pytest.mark.parametrize("psi", [0.02, 0.05, 0.2])
def test_vermeulen_johnson_large_creep_saturates_at_mu_n(psi):
    """beta >= 3: the resultant on each wheel is mu N exactly (no spin here)."""
    fy, _, f_l, _ = contact(row(), psi=psi)
    # each wheel: resultant in the contact plane of magnitude mu N; lateral share by hand
    xi_x = math.cos(psi) - 1.0
    xi_y = -math.sin(psi)
    fx_h, fy_h = vj_hand(xi_x, xi_y)
    assert math.hypot(fx_h, fy_h) == pytest.approx(MU * N_LOAD, rel=1e-14)
    assert f_l == pytest.approx(fy_h * math.cos(psi) + fx_h * math.sin(psi), rel=1e-12)
    assert abs(fy) <= 2 * MU * N_LOAD * (1 + 1e-12)


def test_vermeulen_johnson_is_c1_at_full_slip():
    """The force as a function of the yaw angle: continuous slope at beta = 3 (C1; the
    cubic's slope 1 - 2 beta/3 + beta^2/9 is 0 there, as is the constant's)."""
    psi3 = 3 * MU * N_LOAD / F22  # beta = 3 (xi_x = cos psi - 1 is negligible here)

    def slope(p, h=1e-7 * psi3):
        return (contact(row(), psi=p + h)[0] - contact(row(), psi=p - h)[0]) / (2 * h)

    below, above = slope(psi3 * (1 - 1e-4)), slope(psi3 * (1 + 1e-4))
    scale = 2 * F22  # slope at the origin
    assert abs(below - above) < 1e-3 * scale
    # slope -2 f22 at the origin (linear; relative deviation 2 beta / 3 ~ 1e-6 here)
    assert abs(slope(1e-12, 1e-13) - scale) < 1e-5 * scale


def test_vermeulen_johnson_equals_per_wheel_heuristic_without_spin_and_not_the_mean():
    """Without spin (f23 = 0) the law is Eq. 28's cubic per wheel; the paper's heuristic
    takes one factor from the wheels' mean beta and differs when the wheels differ (here
    by their loads, as in a curve)."""

    def run(law):
        return wheelset_contact(0.004, 0.1, 0.002, 0.002, 0.05, 0.05, SPEED, row(law),
                                0.6 * N_LOAD, 1.4 * N_LOAD)  # fmt: skip

    vj = run(CreepLaw.VERMEULEN_JOHNSON)
    per_wheel = run(CreepLaw.HEURISTIC_PER_WHEEL)
    mean = run(CreepLaw.HEURISTIC)
    assert vj == per_wheel
    assert abs(vj[1] - mean[1]) > 1e-3 * abs(vj[1])


def test_vermeulen_johnson_beta_excludes_spin():
    """With f23 != 0 the saturation factor comes from f11 xi_x and f22 xi_y alone and
    scales the spin force too: the lateral force is alpha (F_y,creep + F_y,spin)."""
    f23 = 3.0e3
    psi, dpsi = 0.003, 0.4
    wr = row(f23=f23)
    fy, _, f_l, _ = contact(wr, psi=psi, dpsi=dpsi)
    xi_x_l = (SPEED * math.cos(psi) - A * dpsi - SPEED) / SPEED
    xi_y = -math.sin(psi)
    spin = dpsi / SPEED  # contact angle 0: no omega sin(delta) part
    fx_l, fy_l = -F11 * xi_x_l, -F22 * xi_y
    beta = math.hypot(fx_l, fy_l) / (MU * N_LOAD)
    alpha = 1 - beta / 3 + beta**2 / 27 if beta <= 3 else 1 / beta
    expected = alpha * ((fy_l - f23 * spin) * math.cos(psi) + fx_l * math.sin(psi))
    assert f_l == pytest.approx(expected, rel=1e-12)


# --------------------------------------------------------------- conical treads


@given(y=st.floats(-0.02, 0.02), gamma=st.sampled_from([0.0, 0.02, 0.05]))
@settings(max_examples=40, deadline=None)
def test_conical_geometry_is_exact(y, gamma):
    """r = r0 +- lambda y and the constant contact angle, bit for bit."""
    r_l, r_r, d_l, d_r = wheel_geometry(y, row(contact_angle=gamma))
    assert (r_l, r_r) == (R0 + y * LAM, R0 + (-y) * LAM)
    assert d_l == d_r == gamma


@given(y=st.floats(1e-6, 0.02), sign=st.sampled_from([-1.0, 1.0]))
@settings(max_examples=25, deadline=None)
def test_knife_edge_has_no_gravitational_stiffness_and_no_spin(y, sign):
    """contact_angle = 0: a displaced wheelset that neither yaws nor moves feels exactly no
    lateral force (no gravitational stiffness; the spin creepage is exactly 0, so even a
    spin coefficient adds nothing), only the Klingel yaw moment."""
    y *= sign
    for law in (CreepLaw.VERMEULEN_JOHNSON, CreepLaw.LINEAR):
        fy, mz, f_l, f_r = contact(row(law, f23=5e3, f33=1e3), y=y)
        assert fy == 0.0 and f_l == 0.0 and f_r == 0.0
        if law == CreepLaw.LINEAR:
            # (xi_x = (v - r omega) / v: cancellation of ~ eps r0 / (lambda y))
            assert mz == pytest.approx(-2 * A * F11 * LAM * y / R0, rel=1e-8)


def test_constant_contact_angle_gives_only_the_gravitational_yaw_moment():
    """A constant contact angle gamma: equal lateral load components cancel (no
    gravitational stiffness); a yawed wheelset feels N a sin(psi) 2 tan(gamma)."""
    gamma, psi = 0.05, 0.001
    wr = row(CreepLaw.LINEAR, contact_angle=gamma)
    wr[WR.F11] = wr[WR.F22] = 1e-9  # creep forces off
    fy, mz, _, _ = contact(wr, y=0.003)
    assert abs(fy) < 1e-9
    _, mz, _, _ = contact(wr, psi=psi)
    assert mz == pytest.approx(2 * N_LOAD * A * math.sin(psi) * math.tan(gamma), rel=1e-6)


# ------------------------------------------------------------ stops to the track

PAPER = railhunt.Vehicle.paper2019()
MODEL = Model(PAPER)
NQ = MODEL.lin.shape[0]
IY1 = int(MODEL.system().wheelsets[0, 0])


def flange_system(model, gap, k1, k3, excitation=None, route=None):
    """The paper's bundle with one flange (stop to the track) on the leading wheelset
    added to its two bump stops."""
    s = model.system(excitation, route)
    b = np.zeros((1, NQ))
    b[0, IY1] = 1.0
    rows = np.vstack([s.stop_rows, b])
    acc = np.hstack([s.stop_acc, -(b.T / model.mass[:, None])])
    par = np.zeros((1, len(StopParam)))
    par[0] = gap, k1, k3
    ws = np.r_[np.full(s.stop.shape[0], -1), 0].astype(np.int64)
    return s._replace(stop_rows=rows, stop_acc=np.ascontiguousarray(acc),
                      stop=np.vstack([s.stop, par]), stop_wheelset=ws)  # fmt: skip


def rhs_of(s, x, t=0.0, v=SPEED):
    out = np.empty(x.shape[0])
    rhs(t, x, v, s, out)
    return out


@pytest.mark.parametrize("y", [-0.012, -0.0091, 0.0, 0.005, 0.0091, 0.0095, 0.02])
def test_flange_dead_band_force(y):
    """Cooperrider's flange: 0 inside +-delta, k0 (y -+ delta) (+ k3 u^3) beyond."""
    gap, k0, k3 = 0.0091, 1.4616e7, 2.0e9
    x = np.zeros(2 * NQ + 4)
    x[IY1] = y
    diff = rhs_of(flange_system(MODEL, gap, k0, k3), x) - rhs_of(MODEL.system(), x)
    u = max(abs(y) - gap, 0.0)
    force = math.copysign(k0 * u + k3 * u**3, y)
    assert diff[NQ + IY1] == pytest.approx(-force / PAPER.M_w, rel=1e-12, abs=1e-12)
    others = np.delete(diff, NQ + IY1)
    assert np.all(others == 0.0)


def test_flange_acts_relative_to_the_rails_with_the_wheelsets_delay():
    """On a track defect the flange sees y_w - y_rail at the wheelset's own track position;
    in a curve it ignores the bodies' geometric offsets (the wheelset already follows its
    rails)."""
    gap, k0 = 0.0091, 1.4616e7
    bump = SingleDefect(0.006, 10.0, 0.0)
    speed, t = 20.0, 0.25  # leading wheelset at s = 5 m: the rail is 6 mm to the left
    x = np.zeros(2 * NQ + 4)
    x[IY1] = 0.018
    diff = (rhs_of(flange_system(MODEL, gap, k0, 0.0, bump), x, t, speed)
            - rhs_of(MODEL.system(bump), x, t, speed))  # fmt: skip
    assert diff[NQ + IY1] == pytest.approx(-k0 * (0.018 - 0.006 - gap) / PAPER.M_w, rel=1e-9)
    route = Curve(radius=600.0, cant=0.1, transition=20.0).route()
    diff = (rhs_of(flange_system(MODEL, gap, k0, 0.0, route=route), x, 3.0)
            - rhs_of(MODEL.system(route=route), x, 3.0))  # fmt: skip
    assert diff[NQ + IY1] == pytest.approx(-k0 * (0.018 - gap) / PAPER.M_w, rel=1e-9)


# ------------------------------------------------------- one row per wheelset


def random_states(n, seed=7):
    rng = np.random.default_rng(seed)
    scale = np.r_[np.full(NQ, 0.004), np.full(NQ, 0.05), np.full(4, 500.0)]
    return rng.normal(size=(n, 2 * NQ + 4)) * scale


def test_identical_rows_padded_wider_give_identical_rhs():
    """The paper's bundle repeats one row per wheelset; padding rows with unused zeros
    (as for a longer contact table elsewhere) changes no bit."""
    s = MODEL.system(SingleDefect(0.005, 10.0, 1.0))
    assert s.wheel_rail.shape == (4, N_WR)
    assert np.all(s.wheel_rail == s.wheel_rail[0])
    wide = s._replace(wheel_rail=np.hstack([s.wheel_rail, np.zeros((4, 40))]))
    for x in random_states(5):
        assert np.array_equal(rhs_of(s, x, 0.7, 70.0), rhs_of(wide, x, 0.7, 70.0))


def test_each_wheelset_reads_its_own_row():
    """Lower the load of wheelset 3 alone: only wheelset 3's accelerations change, and they
    equal the forces of its own row computed directly."""
    s = MODEL.system()
    wr = s.wheel_rail.copy()
    wr[2, WR.N] *= 0.7
    wr[2, WR.INV_MW] *= 1.3  # and a lighter wheelset
    changed = s._replace(wheel_rail=wr)
    iy, ip = (int(i) for i in s.wheelsets[2])
    for x in random_states(4, seed=11):
        diff = rhs_of(changed, x) - rhs_of(s, x)
        moved = {NQ + iy, NQ + ip}
        assert all(diff[i] == 0.0 for i in range(diff.size) if i not in moved)
        assert diff[NQ + iy] != 0.0
        n = wr[2, WR.N]
        fy_new, _, _, _ = wheelset_contact(x[iy], x[NQ + iy], x[ip], x[ip], x[NQ + ip],
                                           x[NQ + ip], SPEED, wr[2], n, n)  # fmt: skip
        n0 = s.wheel_rail[2, WR.N]
        fy_old, _, _, _ = wheelset_contact(x[iy], x[NQ + iy], x[ip], x[ip], x[NQ + ip],
                                           x[NQ + ip], SPEED, s.wheel_rail[2], n0, n0)  # fmt: skip
        expected = fy_new * wr[2, WR.INV_MW] - fy_old * s.wheel_rail[2, WR.INV_MW]
        assert diff[NQ + iy] == pytest.approx(expected, rel=1e-9, abs=1e-6)


def test_rows_may_mix_contact_tables_and_polynomials():
    """A contact table on one wheelset, the polynomials on the others: the table row is
    longer, the others are zero-padded, and each uses its own geometry."""
    table_model = Model(railhunt.Vehicle.shipped("s1002_uic60_table"))
    s_tab, s_poly = table_model.system(), MODEL.system()
    width = s_tab.wheel_rail.shape[1]
    mixed = np.zeros((4, width))
    mixed[:, :N_WR] = s_poly.wheel_rail
    mixed[1] = s_tab.wheel_rail[1]
    s = s_poly._replace(wheel_rail=mixed)
    for j in range(4):
        y = 0.003
        expected = wheel_geometry(y, s_tab.wheel_rail[1] if j == 1 else s_poly.wheel_rail[j])
        assert wheel_geometry(y, s.wheel_rail[j]) == expected
