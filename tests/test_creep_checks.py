"""Checks that discriminate: a creep law with a wrong sign or without its spin term fails
the linear-law check every law passes; bad input of ``creep_forces`` (drawn by hypothesis)
is one line naming the argument; the tabulated law's compiled stencil, its small-creepage
skip and its exact symmetries.

References: Kalker's linear theory (fx = -G c^2 C11 xi, fy = -G c^2 (C22 eta + c C23 phi),
mz = G c^3 (C23 eta - c C33 phi), his Table E.3 coefficients through
``kalker_coefficients``). Tolerances are stated in each test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from railhunt import creep_forces, kalker_coefficients
from railhunt.mechanics.laws import LAWS

G, NU = 8.2e10, 0.28
PATCH = dict(a=6e-3, b=4e-3, mu=0.3, normal_force=60e3, shear_modulus=G, poisson=NU)
#: Pure creepages at about 1 % of saturation: longitudinal, lateral, spin (1/m).
SMALL = ((1e-5, 0.0, 0.0), (0.0, 1e-5, 0.0), (0.0, 0.0, 5e-3))


def kalker_linear(xi: float, eta: float, phi: float) -> tuple[float, float, float]:
    c11, c22, c23, c33 = kalker_coefficients(PATCH["a"] / PATCH["b"], NU)
    c = math.sqrt(PATCH["a"] * PATCH["b"])
    return (-G * c * c * c11 * xi, -G * c * c * (c22 * eta + c * c23 * phi),
            G * c**3 * (c23 * eta - c * c33 * phi))


def linear_law_holds(forces, rel: float, moment: bool = True) -> bool:
    """Whether ``forces(xi, eta, phi) -> (fx, fy, mz)`` is Kalker's linear law within
    ``rel`` at :data:`SMALL` (``fy`` of the pure spin included: the spin term)."""
    for k, creep in enumerate(SMALL):
        got, ref = forces(*creep), kalker_linear(*creep)
        if not got[min(k, 1)] == pytest.approx(ref[min(k, 1)], rel=rel):
            return False
        if moment and k and not got[2] == pytest.approx(ref[2], rel=rel):
            return False
    return True


def _law(law: str):
    def forces(xi, eta, phi):
        r = creep_forces(xi, eta, phi, law=law, **PATCH)
        return r.fx, r.fy, r.mz

    return forces


@pytest.mark.parametrize("law", ["heuristic", "polach", "fastsim-modified", "exact"])
def test_a_wrong_sign_or_a_missing_spin_term_fails_the_linear_check(law):
    """The check of every law's small-creepage limit (3 %, exact 6 %, as in
    test_creep_laws) passes for the law and fails for the law with ``F_y``'s sign turned,
    with ``F_x``'s turned, without its spin term (``phi`` dropped) and with the spin
    moment's sign turned."""
    rel = 0.06 if law == "exact" else 0.03
    moment = not law.startswith("fastsim")  # FASTSIM's M_z is not Kalker's (not compared)
    good = _law(law)
    assert linear_law_holds(good, rel, moment)
    mutants = {
        "F_y sign": lambda x, e, p: (good(x, e, p)[0], -good(x, e, p)[1], good(x, e, p)[2]),
        "F_x sign": lambda x, e, p: (-good(x, e, p)[0], *good(x, e, p)[1:]),
        "no spin": lambda x, e, p: good(x, e, 0.0),
    }
    if moment:
        mutants["M_z sign"] = lambda x, e, p: (*good(x, e, p)[:2], -good(x, e, p)[2])
    for name, bad in mutants.items():
        assert not linear_law_holds(bad, rel, moment), name


def test_the_tabulated_law_carries_the_spin_terms_with_their_signs():
    """At small normalised creepages the compiled table law is Kalker's linear law in its
    normalised form (1e-9): pure spin u_s gives t_y = -u_s (the spin's lateral force) and
    t_m = -m_s u_s; lateral creepage gives t_m = +m_y u_y. Dropping the spin or turning a
    sign would change these by 100 % or more."""
    from railhunt.contact.creep_table import shipped_creep_table
    from railhunt.kernel.creep_table import table_creep

    arr = shipped_creep_table().kernel_array
    my, ms, u = 0.35, 0.6, 1e-3
    tx, ty, tm = table_creep(0.0, 0.0, u, my, ms, 3.0, arr)
    assert (tx, ty, tm) == pytest.approx((0.0, -u, -ms * u), rel=1e-5, abs=1e-12)
    tx, ty, tm = table_creep(0.0, u, 0.0, my, ms, 3.0, arr)
    assert (tx, ty, tm) == pytest.approx((0.0, -u, my * u), rel=1e-5, abs=1e-12)
    tx, ty, tm = table_creep(u, 0.0, 0.0, my, ms, 3.0, arr)
    assert (tx, ty, tm) == pytest.approx((-u, 0.0, 0.0), rel=1e-5, abs=1e-12)


# --------------------------------------------------------------------------- bad input

_GOOD = dict(xi=1e-3, eta=0.0, phi=0.0, a=6e-3, b=4e-3, mu=0.3, normal_force=6e4)
_UNITS = {"a": " m", "b": " m", "normal_force": " N", "mu": "", "phi": " 1/m", "xi": "",
          "eta": ""}


def _message(**changed) -> str:
    args = {**_GOOD, **changed}
    creep = [args.pop(k) for k in ("xi", "eta", "phi")]
    with pytest.raises(ValueError) as info:
        creep_forces(*creep, law="heuristic", **args)
    return str(info.value)


@given(name=st.sampled_from(["a", "b", "normal_force"]),
       value=st.floats(max_value=0.0, allow_nan=False) | st.just(math.inf))
@settings(max_examples=40, deadline=None)
def test_non_positive_semi_axes_or_load_are_one_line_naming_them(name, value):
    msg = _message(**{name: value})
    assert msg.startswith(f"{name} = {float(value)!r}{_UNITS[name]} is invalid: must be "
                          "finite and > 0") and "\n" not in msg


@given(value=st.floats(max_value=0.0, allow_nan=False) | st.just(math.nan))
@settings(max_examples=30, deadline=None)
def test_mu_not_positive_is_one_line(value):
    msg = _message(mu=value)
    assert msg.startswith(f"mu = {float(value)!r} is invalid: must be finite and > 0")
    assert "\n" not in msg


@given(name=st.sampled_from(["xi", "eta", "phi"]),
       value=st.sampled_from([math.nan, math.inf, -math.inf]),
       size=st.integers(1, 4), where=st.integers(0, 3))
@settings(max_examples=40, deadline=None)
def test_non_finite_creepages_are_one_line_naming_the_argument_and_entry(name, value, size,
                                                                          where):
    where = where % size
    arr = np.full(size, 1e-4)
    arr[where] = value
    msg = _message(**{name: arr})
    assert msg.startswith(f"{name}[{where}] = {value!r}{_UNITS[name]} is invalid: must be "
                          "finite") and "\n" not in msg


@given(law=st.text(min_size=0, max_size=12).filter(lambda s: s not in LAWS))
@settings(max_examples=30, deadline=None)
def test_unknown_laws_are_one_line_listing_the_laws(law):
    with pytest.raises(ValueError) as info:
        creep_forces(1e-3, 0.0, 0.0, law=law, **PATCH)
    msg = str(info.value)
    assert msg.startswith(f"law = {law!r} is invalid: must be one of 'exact'")
    assert all(repr(name) in msg for name in LAWS)


# --------------------------------------------------------------------------- the table law


def test_the_compiled_stencil_equals_its_reference():
    """The vector stencil (compiled) and its pure-Python reference agree to rounding
    (1e-13) on random control points, weights and offsets."""
    from numba import njit

    from railhunt.kernel.creep_table import slice_stencil

    @njit
    def compiled(t, k, sx, sy, w):
        return slice_stencil(t, k, sx, sy, w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7],
                             w[8])

    rng = np.random.default_rng(5)
    t = rng.normal(size=6000)
    for _ in range(20):
        k, sx, sy = int(rng.integers(0, 100)), int(rng.integers(200, 400)), 4 * 7
        w = tuple(float(v) for v in rng.uniform(size=9))
        got = compiled(t, k, sx, sy, w)
        ref = slice_stencil(t, k, sx, sy, *w)
        assert got == pytest.approx(ref, rel=1e-13, abs=1e-13)


def test_the_table_is_skipped_smoothly_at_small_creepage():
    """Below rho = 0.005 the law is the saturated linear law exactly; its first derivative
    is continuous across the blend (rho 0.005 and 0.01: one-sided difference quotients
    agree to 1e-4 of the slope)."""
    from railhunt.contact.creep_table import shipped_creep_table
    from railhunt.kernel.creep_table import table_creep

    arr = shipped_creep_table().kernel_array
    my, ms = 0.35, 0.6
    ux, uy, us = 0.6, 0.5, 0.3  # a direction; rho scales with the factor s below
    rho1 = math.sqrt(ux**2 + uy**2 + us**2 + (my * uy - ms * us) ** 2)
    s = 0.004 / rho1
    lin = 1.0 / math.sqrt(1.0 + 0.004**2)
    got = table_creep(s * ux, s * uy, s * us, my, ms, 4.5, arr)
    assert got == pytest.approx((-s * ux * lin, -s * (uy + us) * lin,
                                 s * (my * uy - ms * us) * lin), rel=1e-14)
    h = 1e-9
    for rho in (0.005, 0.01):
        s = rho / rho1
        f = [np.array(table_creep((s + d) * ux, (s + d) * uy, (s + d) * us, my, ms, 4.5,
                                  arr)) for d in (-h, 0.0, h)]  # fmt: skip
        left, right = (f[1] - f[0]) / h, (f[2] - f[1]) / h
        assert np.allclose(left, right, rtol=0, atol=1e-4 * np.abs(left).max()), rho


def test_a_built_table_has_the_exact_symmetries():
    """Whatever the solver's noise: D_x = 0 at s_x = 0 (F_x odd in xi, so F_x = 0 at
    xi = 0 exactly) and the plane s_y = 0 mirrored into itself (D_y, D_m odd in s_s
    there): a solver with an asymmetric perturbation of 1e-3 still gives both to 1e-15."""
    from railhunt.contact.creep_table import build_creep_table
    from railhunt.kernel.creep_table import table_creep

    k11, k22, k23, k33 = 4.0, 3.5, 1.5, 1.2

    def solver(xi, eta, phi, a, b, mu, n_load, g, nu):
        c = math.sqrt(a * b)
        lin = np.array([-g * c * c * k11 * xi, -g * c * c * (k22 * eta + c * k23 * phi),
                        g * c**3 * (k23 * eta - c * k33 * phi)])  # fmt: skip
        r2 = (lin[0] ** 2 + lin[1] ** 2) / (mu * n_load) ** 2
        noise = 1e-3 * mu * n_load * np.array([1.0, 0.7, 0.3 * c]) * math.tanh(eta * 1e3 + 1)
        return tuple(lin / math.sqrt(1.0 + r2) + noise)

    table = build_creep_table(solver, a_over_b=np.array([1.0]), n_x=5, n_y=7, n_s=7)
    assert np.all(table.values[:, 0, ..., 0] == 0.0)
    mid = table.values[:, :, 3]
    assert np.allclose(mid, mid[:, :, ::-1] * np.array([1.0, -1.0, -1.0]), rtol=0, atol=1e-15)
    arr = table.kernel_array
    my, ms = k23 / k22, k33 / k23
    for uy, us in ((0.3, 0.2), (2.0, -1.0), (0.0, 5.0)):
        assert table_creep(0.0, uy, us, my, ms, 0.0, arr)[0] == 0.0
