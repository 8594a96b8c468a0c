"""Order of the time integrators on the (nearly) linear vehicle against expm(J t).

With Kalker's linear creep law and a 0.1 um disturbance the vehicle is linear to about
1e-11 (the cubic terms of the contact geometry scale with the amplitude squared), so the
exact solution is ``expm(J t) x0`` with J the Jacobian at the centred state. RK4's global
error must fall 16-fold when the step is halved (order 4); Dormand-Prince 5(4)'s must fall
with its tolerance and stay below it.

J is built here by Richardson-extrapolated central differences of the model's own
right-hand side (steps 1e-5 and 2e-5 m): ``Model.jacobian`` uses 1e-7 steps, whose rounding
(about 1e-8 relative in the creepage terms) would put a floor above RK4's error at 1 ms.
That J agrees with ``Model.jacobian`` is checked too.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm

import railhunt
from railhunt.model import N_STATE, STATE_NAMES, Model
from railhunt.simulation import integrate_model
from railhunt.suspension import DOF_NAMES

V = railhunt.Vehicle.paper2019()
SPEED = 300 / 3.6  # m/s
AMPLITUDE = 1e-7  # m
DURATION = 0.5  # s
Q = slice(0, len(DOF_NAMES))  # the 17 coordinates (m, rad): errors are compared on these
F_D = [STATE_NAMES.index(f"F_d{k}") for k in range(1, 5)]  # yaw damper forces (N)


@pytest.fixture(scope="module")
def linear_case():
    model = Model(V, creep_law="linear")

    def central(h_q: float, h_f: float) -> np.ndarray:
        jac = np.empty((N_STATE, N_STATE))
        for k in range(N_STATE):
            e = np.zeros(N_STATE)
            e[k] = h_f if k in F_D else h_q
            jac[:, k] = (model.derivative(e, SPEED) - model.derivative(-e, SPEED)) / (2 * e[k])
        return jac

    jac = (4 * central(1e-5, 1e-1) - central(2e-5, 2e-1)) / 3
    x0 = np.zeros(N_STATE)
    x0[[STATE_NAMES.index(f"y_w{j}") for j in range(1, 5)]] = AMPLITUDE  # all displaced
    x0[STATE_NAMES.index("psi_w1")] = AMPLITUDE  # the leading one yawed, 0.1 urad
    exact = expm(jac * DURATION) @ x0
    return model, jac, x0, exact


def _error(x_end: np.ndarray, exact: np.ndarray) -> float:
    return float(np.max(np.abs(x_end[Q] - exact[Q])) / np.max(np.abs(exact[Q])))


def test_reference_jacobian_agrees_with_model_jacobian(linear_case):
    model, jac, _, _ = linear_case
    jm = model.jacobian(SPEED)
    significant = np.abs(jac) > 1e-9 * np.abs(jac).max()
    assert np.all(np.abs(jm - jac)[significant] <= 1e-6 * np.abs(jac)[significant])
    assert np.max(np.abs(jm - jac)[~significant]) < 1e-8
    # The centred running at 300 km/h is stable: the reference decays.
    assert np.max(np.linalg.eigvals(jac).real) < 0


def test_rk4_is_fourth_order(linear_case):
    """Errors at dt = 4, 2, 1 ms (the default step is 1 ms): each halving divides the error
    by 2^4 = 16 (measured errors 3.3e-6, 2.1e-7, 1.3e-8: ratios 15.8 and 16.3); accepted
    12-20. A first-order scheme gives 2."""
    model, _, x0, exact = linear_case
    errors = []
    for dt in (4e-3, 2e-3, 1e-3):
        _, x, status, _ = integrate_model(model, SPEED, DURATION, x0, method="rk4", dt=dt)
        assert status == 0
        errors.append(_error(x[-1], exact))
    ratios = [errors[0] / errors[1], errors[1] / errors[2]]
    assert 12.0 < ratios[0] < 20.0, (errors, ratios)
    assert 12.0 < ratios[1] < 20.0, (errors, ratios)
    assert errors[2] < 3e-8  # measured 1.3e-8 relative at 1 ms


def test_dopri5_error_falls_with_rtol(linear_case):
    """Dormand-Prince 5(4): the error stays below rtol and falls at least 10-fold for each
    100-fold tighter rtol (measured 1.6e-5, 8.1e-7, 4.6e-9 for rtol 1e-3, 1e-5, 1e-7)."""
    model, _, x0, exact = linear_case
    errors = []
    for rtol in (1e-3, 1e-5, 1e-7):
        atol = np.full(N_STATE, 1e-3 * AMPLITUDE * rtol)  # relative control throughout
        t, x, status, _ = integrate_model(model, SPEED, DURATION, x0, method="dopri5",
                                          rtol=rtol, atol=atol)  # fmt: skip
        assert status == 0 and t[-1] == pytest.approx(DURATION, abs=1e-12)
        errors.append(_error(x[-1], exact))
        assert errors[-1] < rtol, (rtol, errors)
    assert errors[0] > 10 * errors[1] > 100 * errors[2], errors
