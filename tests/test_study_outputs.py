"""The outputs studies need: fold speed, least damping ratio, curving Y/Q, ΣY, wear number."""

from __future__ import annotations

import math

import numpy as np
import pytest

from railhunt import Curve, Vehicle, curving, linear_critical_speed
from railhunt.analysis.fold import fold_speed
from railhunt.analysis.wear import wheel_wear_numbers, wheelset_creep
from railhunt.kernel.contact import wheel_geometry
from railhunt.model import Model
from railhunt.studies.outputs import OutputOptions, evaluate_output, least_damping_ratio
from railhunt.units import kmh_to_ms

CURVE = {"curve_radius": 600.0, "curve_cant": 0.15, "curve_speed_kmh": 120.0}


def test_fold_speed_is_the_hopf_branch_fold():
    # docs/bifurcation.md: the whole diagram's Hopf branch folds at 302.0 km/h.
    r = fold_speed(Vehicle.paper2019())
    assert r.turned and r.speed_kmh == pytest.approx(302.0, abs=0.2)
    assert r.hopf_speed_kmh == pytest.approx(441.318, abs=1e-3)


def test_fold_speed_refinement_converged():
    v = Vehicle.paper2019().replace(K_px=40e6)
    fine = fold_speed(v)
    finer = fold_speed(v, fine_step_kmh=0.5, fine_step_amplitude=3e-5)
    assert fine.turned and abs(fine.speed_kmh - finer.speed_kmh) < 0.1


def test_least_damping_ratio_changes_sign_at_the_hopf_point():
    v = Vehicle.paper2019()
    hopf = linear_critical_speed(v).speed_kmh
    assert least_damping_ratio(v, np.linspace(100.0, hopf - 5.0, 5)) > 0
    assert least_damping_ratio(v, np.array([hopf + 5.0])) < 0
    assert evaluate_output("least_damping_ratio", v, OutputOptions())["least_damping_ratio"] > 0


def test_wear_number_zero_when_centred_on_straight_track():
    # Centred, only the conical wheels' spin creepage is left, which T-gamma leaves out;
    # the longitudinal creepage is round-off (1e-16).
    m = Model(Vehicle.paper2019())
    assert np.all(wheel_wear_numbers(m, 60.0, np.zeros(m.layout.n_state)) < 1e-9)


@pytest.mark.parametrize("direction", ["left", "right"])
def test_creep_forces_rebuild_the_guiding_forces(direction):
    """The creep forces and loads of wheelset_creep give the kernel's Y and ΣY back."""
    v = Vehicle.paper2019()
    m = Model(v)
    curve = Curve(radius=600.0, cant=0.15, direction=direction)
    res = curving(v, 120.0, curve)
    route = curve.steady_route()
    c = wheelset_creep(m, kmh_to_ms(120.0), res.state, 0, route)
    s = m.system(route=route)
    y, psi = res.state[s.wheelsets[0, 0]], res.state[s.wheelsets[0, 1]]
    _, _, d_l, d_r = wheel_geometry(y, s.wheel_rail[0])
    f_l = c[0, 1] * math.cos(d_l) * math.cos(psi) + c[0, 0] * math.sin(psi) \
        - res.Q[0, 0] * math.tan(d_l)
    f_r = c[1, 1] * math.cos(d_r) * math.cos(psi) + c[1, 0] * math.sin(psi) \
        + res.Q[0, 1] * math.tan(d_r)
    assert abs(f_l + f_r + res.sum_Y[0]) < 1e-6 * abs(res.sum_Y[0])
    assert sorted(np.abs([f_l, f_r])) == pytest.approx(sorted(np.abs(res.Y[0])), rel=1e-9)


def test_wear_numbers_mirror_symmetric():
    v = Vehicle.paper2019()
    m = Model(v)
    wear = {}
    for direction in ("left", "right"):
        curve = Curve(radius=600.0, cant=0.15, direction=direction)
        res = curving(v, 120.0, curve)
        wear[direction] = wheel_wear_numbers(m, kmh_to_ms(120.0), res.state, 0,
                                             curve.steady_route())
    assert wear["left"] == pytest.approx(wear["right"][::-1], rel=1e-9)
    out = evaluate_output("curving", v, OutputOptions(**CURVE))
    assert out["wear_number"] == pytest.approx(float(np.sum(wear["left"])), rel=1e-12)
    assert 0 < out["max_YQ"] < 1 and out["sum_Y_leading"] > 0
    assert 50.0 < out["wear_number"] < 500.0


def test_sweep_with_new_outputs(tmp_path):
    from railhunt import read_results, sweep

    r = sweep(Vehicle.paper2019(), {"K_px": [40e6, 85e6]}, ["least_damping_ratio", "curving"],
              workers=1, out=tmp_path / "s.csv", output_options=CURVE)
    back = read_results(tmp_path / "s.csv")
    assert back.column("wear_number").tolist() == r.column("wear_number").tolist()
    assert r.column("wear_number")[0] < r.column("wear_number")[1]  # softer K_px steers
    assert back.meta["curve_radius"] == 600.0


def test_curving_needs_its_curve():
    from railhunt import sweep

    with pytest.raises(ValueError, match="curve_radius and curve_speed_kmh"):
        sweep(Vehicle.paper2019(), {"K_px": [40e6]}, ["curving"], workers=1)
    with pytest.raises(ValueError, match="curve_radius"):
        OutputOptions(curve_radius=10.0)


def test_study_outputs_use_the_layouts_own_creep_law_by_default():
    """The Cooperrider bogie's layout uses Vermeulen-Johnson: the fold speed without a
    creep_law is that law's, not the paper's heuristic (which moves it by ~1e-3 km/h)."""
    import inspect

    from railhunt import Vehicle
    from railhunt.analysis.fold import fold_speed
    from railhunt.studies import optimize, sensitivity

    bogie = Vehicle.shipped("cooperrider_bogie")
    default = fold_speed(bogie).speed_kmh
    assert default == fold_speed(bogie, creep_law="vermeulen-johnson").speed_kmh
    assert default != fold_speed(bogie, creep_law="heuristic").speed_kmh
    for study in (sensitivity.sensitivity, optimize.optimize):
        assert inspect.signature(study).parameters["creep_law"].default is None


def test_fold_speed_where_the_two_bogies_hunting_modes_nearly_coincide():
    """A Table 1 sample (a Sobol study's point) whose front- and rear-bogie hunting modes
    lie within 0.1 rad/s of each other at the Hopf point: the second small orbit's Newton
    failed from the first orbit with only y_w1 moved and starts again from the first orbit
    scaled to the new size; the fold is then found, below the Hopf point, and converged
    (a finer trace agrees within 0.1 km/h)."""
    v = Vehicle.paper2019().replace(C_d1=877830.7957574725, K_d=968745.8178028464,
                                    C_d2=91832.75837730616, mu=0.20803257715888324,
                                    K_px=36341750.6031692, f11=10652708.549052477,
                                    f22=10652708.549052477, C_sy=52897.47644215822)  # fmt: skip
    fine = fold_speed(v)
    finer = fold_speed(v, fine_step_kmh=0.5, fine_step_amplitude=3e-5)
    assert fine.turned and fine.speed_kmh < fine.hopf_speed_kmh - 5.0
    assert abs(fine.speed_kmh - finer.speed_kmh) < 0.1
