"""Newton's method with Krylov Jacobian refreshes (railhunt.analysis.newton_krylov).

References: GMRES against a direct solve; Newton-Krylov against plain Newton on an
analytic system with a known root; shooting with Krylov refreshes against plain shooting
from the same unsettled start (the hunting frequency's case): the same orbit to Newton's
tolerance.
"""

from __future__ import annotations

import numpy as np
import pytest

from railhunt import SingleDefect, Vehicle
from railhunt.analysis.critical import Judgement, run_until_verdict
from railhunt.analysis.frequency import _extremum_state, _maxima, _spectrum_peak
from railhunt.analysis.newton import newton
from railhunt.analysis.newton_krylov import gmres, newton_krylov
from railhunt.analysis.periodic import periodic_orbit, shoot_orbit
from railhunt.model import Model
from railhunt.simulation import auto_step
from railhunt.units import kmh_to_ms


def test_gmres_solves_to_its_tolerance_and_needs_one_product_with_the_exact_inverse():
    """Preconditioned by a perturbed matrix, GMRES meets rtol = 1e-10 against the direct
    solve; preconditioned by the matrix itself, one product suffices."""
    rng = np.random.default_rng(3)
    a = np.eye(30) * 4 + rng.standard_normal((30, 30))
    b = rng.standard_normal(30)
    rough = a + 0.3 * rng.standard_normal((30, 30))
    count = []

    def matvec(v):
        count.append(1)
        return a @ v

    x, ok = gmres(matvec, b, lambda v: np.linalg.solve(rough, v), np.zeros(30), 1e-10, 30)
    assert ok
    assert np.linalg.norm(a @ x - b) <= 1e-10 * np.linalg.norm(b) * 1.01
    np.testing.assert_allclose(x, np.linalg.solve(a, b), rtol=1e-8, atol=1e-10)
    count.clear()
    _, ok = gmres(matvec, b, lambda v: np.linalg.solve(a, v), np.zeros(30), 1e-10, 30)
    assert ok and len(count) <= 2  # the start's residual and one Krylov product


def _broyden_tridiagonal(x: np.ndarray) -> np.ndarray:
    """Broyden's tridiagonal test function (More, Garbow & Hillstrom 1981, no. 30)."""
    xm = np.concatenate([[0.0], x[:-1]])
    xp = np.concatenate([x[1:], [0.0]])
    return (3 - 2 * x) * x - xm - 2 * xp + 1


def _fd_jacobian(fun, calls):
    def jac(x, r):
        calls.append(1)
        h = 1e-7
        return np.column_stack([(fun(x + h * e) - r) / h for e in np.eye(x.size)])
    return jac


def test_newton_krylov_finds_newtons_root_with_fewer_jacobians():
    """From a far start (damped steps), both methods reach the same root of Broyden's
    tridiagonal system to 1e-10; the Krylov refreshes call the Jacobian less often."""
    x0 = np.full(40, -10.0)  # far: the first steps are halved
    plain, krylov = [], []
    xa, na, _, oka, _ = newton(_broyden_tridiagonal, _fd_jacobian(_broyden_tridiagonal, plain),
                               x0, tol=1e-12, max_iter=60)  # fmt: skip
    xb, nb, _, okb, _ = newton_krylov(_broyden_tridiagonal,
                                      _fd_jacobian(_broyden_tridiagonal, krylov), x0,
                                      tol=1e-12, max_iter=60)  # fmt: skip
    assert oka and okb and na < 1e-12 and nb < 1e-12
    np.testing.assert_allclose(xb, xa, atol=1e-10)
    assert len(krylov) < len(plain)


def test_krylov_shooting_finds_the_same_orbit_from_an_unsettled_run():
    """From the end of the run over the defect at 350 km/h (not yet on the cycle), shooting
    with Krylov refreshes converges to the orbit plain shooting finds: period and
    amplitude agree to 1e-8 (Newton's tolerance is 1e-8 on scaled residuals)."""
    model = Model(Vehicle.paper2019())
    speed_kmh = 350.0
    dt = auto_step(model, kmh_to_ms(speed_kmh))
    _, t, x, code, *_ = run_until_verdict(model, speed_kmh, Judgement(), SingleDefect(),
                                          np.zeros(model.layout.n_state), dt=dt)  # fmt: skip
    assert code == 0
    f_fft, _ = _spectrum_peak(t, x[:, model.layout.y_w1], 8.0, 200.0)
    start = _extremum_state(model, speed_kmh, t, x, _maxima(x[:, model.layout.y_w1], 1)[0],
                            dt)  # fmt: skip
    plain = periodic_orbit(model, speed_kmh, start, 1.0 / f_fft, dt=dt)
    shot = shoot_orbit(model, speed_kmh, start, 1.0 / f_fft, dt=dt, krylov=True)
    assert shot.period == pytest.approx(plain.period, rel=1e-8)
    assert shot.amplitude == pytest.approx(plain.amplitude, rel=1e-8)
    orbit = shot.orbit()  # the Floquet multipliers, computed on demand
    assert orbit.stable == plain.stable
    np.testing.assert_allclose(np.abs(orbit.multipliers[:4]), np.abs(plain.multipliers[:4]),
                               rtol=1e-4)  # fmt: skip
