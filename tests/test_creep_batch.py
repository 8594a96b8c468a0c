"""The tabulated creep law evaluated for many contacts at once gives each contact the
bits of the law evaluated alone, and the right-hand side that uses it the bits of the
wheelset-by-wheelset right-hand side (straight track, a curve, a vehicle that mixes
contact mechanics)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numba import njit

import railhunt
from railhunt.kernel.creep_batch import N_BATCH_SLOTS, BatchSlot, table_creep_batch
from railhunt.kernel.creep_table import table_creep
from railhunt.kernel.layout import NO_CONTACT_WORK
from railhunt.kernel.rhs import rhs
from railhunt.model import Model


@pytest.fixture(scope="module")
def table() -> np.ndarray:
    model = Model(railhunt.Vehicle.shipped("s1002_uic60_per_point"), creep_law="exact-table")
    return model.args(80.0)[1].creep_table


@njit(cache=True)
def _one_by_one(w: np.ndarray, n: int, table: np.ndarray, out: np.ndarray) -> None:
    """Each contact through table_creep, as point_wheel_creep calls it."""
    for k in range(n):
        m = w[BatchSlot.MU_N, k]
        inv = 1.0 / m
        f11, f22, f23 = w[BatchSlot.F11, k], w[BatchSlot.F22, k], w[BatchSlot.F23, k]
        f33, c = w[BatchSlot.F33, k], w[BatchSlot.C, k]
        tx, ty, tm = table_creep(f11 * w[BatchSlot.XI, k] * inv, f22 * w[BatchSlot.ETA, k] * inv,
                                 f23 * w[BatchSlot.PHI, k] * inv, f23 / (f22 * c),
                                 f33 / (f23 * c), w[BatchSlot.AB, k], table)  # fmt: skip
        out[0, k] = m * tx
        out[1, k] = m * ty
        out[2, k] = m * c * tm


def _contacts(rng: np.random.Generator, n: int) -> np.ndarray:
    """Contacts over the whole range: creepages from 1e-7 (the law's linear branch) to
    full slip (the cap), both signs, ``a/b`` indices below, inside and beyond the table."""
    w = np.zeros((N_BATCH_SLOTS, n))
    w[BatchSlot.C] = rng.uniform(2e-3, 1.2e-2, n)
    w[BatchSlot.F11] = rng.uniform(0.3, 3.0, n) * 1e7
    w[BatchSlot.F22] = rng.uniform(0.3, 3.0, n) * 1e7
    w[BatchSlot.F23] = rng.uniform(0.3, 3.0, n) * 1e4
    w[BatchSlot.F33] = rng.uniform(0.3, 3.0, n) * 1e1
    w[BatchSlot.MU_N] = rng.uniform(5e3, 8e4, n)
    for slot, lo, hi in ((BatchSlot.XI, -7, -0.5), (BatchSlot.ETA, -7, -0.5),
                         (BatchSlot.PHI, -5, 0.5)):  # fmt: skip
        w[slot] = rng.choice([-1.0, 1.0], n) * 10.0 ** rng.uniform(lo, hi, n)
    w[BatchSlot.AB] = rng.uniform(-1.0, 14.0, n)
    w[BatchSlot.AB, : n // 3] = np.round(w[BatchSlot.AB, : n // 3])
    return w


def _same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return bool(np.array_equal(a.view(np.int64), b.view(np.int64)))


@pytest.mark.parametrize("n", [1, 2, 7, 8, 33])
def test_batch_gives_each_contact_the_bits_of_table_creep(table, n) -> None:
    rng = np.random.default_rng(n)
    for _ in range(40):
        w = _contacts(rng, n)
        w[BatchSlot.XI, 0] = 0.0  # xi = 0 exactly: F_x = 0
        if n > 1:
            w[BatchSlot.XI, 1] = -0.0
        out = np.zeros((3, n))
        _one_by_one(w, n, table, out)
        table_creep_batch(w, n, table)
        for row, slot in enumerate((BatchSlot.FX, BatchSlot.FY, BatchSlot.MZ)):
            assert _same_bits(w[slot, :n], out[row]), slot.name
    assert np.all(np.isfinite(w[BatchSlot.FX : BatchSlot.MZ + 1, :n]))


@settings(max_examples=60, deadline=None)
@given(xi=st.floats(-0.05, 0.05), eta=st.floats(-0.05, 0.05), phi=st.floats(-2.0, 2.0),
       ab=st.floats(-2.0, 15.0))  # fmt: skip
def test_batch_matches_table_creep_anywhere(table, xi, eta, phi, ab) -> None:
    w = _contacts(np.random.default_rng(0), 3)
    w[BatchSlot.XI], w[BatchSlot.ETA], w[BatchSlot.PHI], w[BatchSlot.AB] = xi, eta, phi, ab
    w[BatchSlot.XI, 1] = -xi
    out = np.zeros((3, 3))
    _one_by_one(w, 3, table, out)
    table_creep_batch(w, 3, table)
    for row, slot in enumerate((BatchSlot.FX, BatchSlot.FY, BatchSlot.MZ)):
        assert _same_bits(w[slot, :3], out[row])


def _states(model: Model, rng: np.random.Generator, count: int) -> list[np.ndarray]:
    """States from centred to flange contact, with rates and damper forces."""
    states = []
    nq = len(model.mass)
    for scale in np.linspace(0.0, 1.0, count):
        x = np.zeros(model.n_state)
        x[:nq] = rng.normal(0.0, 4e-3 * scale + 1e-5, nq)
        x[nq:2 * nq] = rng.normal(0.0, 0.05 * scale + 1e-4, nq)
        x[2 * nq:] = rng.normal(0.0, 2e3 * scale, model.n_state - 2 * nq)
        states.append(x)
    return states


def _rhs_both_ways(model: Model, v: float, x: np.ndarray, t: float = 0.0,
                   route: np.ndarray | None = None):
    speed, s = model.args(v, route=route)
    assert s.contact_work.shape[1] > 0
    staged, alone = np.empty(model.n_state), np.empty(model.n_state)
    rhs(t, x, speed, s, staged)
    rhs(t, x, speed, s._replace(contact_work=NO_CONTACT_WORK), alone)
    return staged, alone


def test_staged_rhs_has_the_bits_of_the_wheelset_by_wheelset_rhs() -> None:
    vehicle = railhunt.Vehicle.shipped("s1002_uic60_per_point")
    model = Model(vehicle, creep_law="exact-table")
    rng = np.random.default_rng(7)
    for x in _states(model, rng, 12):
        for v in (30.0, 83.3):
            staged, alone = _rhs_both_ways(model, v, x)
            assert _same_bits(staged, alone)
    # A curve: quasi-static wheel loads that differ left and right, the track's yaw rate.
    route = railhunt.Curve(radius=1500.0, cant=0.1, transition=50.0).steady_route()
    for x in _states(model, rng, 4):
        staged, alone = _rhs_both_ways(model, 60.0, x, t=4.0, route=route)
        assert _same_bits(staged, alone)


def test_the_jacobian_is_the_same_staged_or_not() -> None:
    model = Model(railhunt.Vehicle.shipped("s1002_uic60_per_point"), creep_law="exact-table")
    x = _states(model, np.random.default_rng(3), 3)[-1]
    from railhunt.kernel.rhs import jacobian

    speed, s = model.args(80.0)
    assert _same_bits(jacobian(x, speed, s, 0.0),
                      jacobian(x, speed, s._replace(contact_work=NO_CONTACT_WORK), 0.0))


def test_models_without_the_table_carry_no_work_array() -> None:
    for name in ("paper2019", "s1002_uic60_table", "s1002_uic60_per_point"):
        assert Model(railhunt.Vehicle.shipped(name)).args(50.0)[1].contact_work.shape[1] == 0
    two = Model(railhunt.Vehicle.shipped("s1002_uic60_two_point"), creep_law="exact-table")
    # Two-point wheelsets are not staged (each patch through table_creep): the array is
    # there but unused, and the rhs is the wheelset-by-wheelset one.
    x = _states(two, np.random.default_rng(5), 3)[-1]
    staged, alone = _rhs_both_ways(two, 60.0, x)
    assert _same_bits(staged, alone)
