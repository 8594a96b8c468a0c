"""Verdicts a user can trust (issue 20): every answer inside the model's validity, or it
says why not. Each case is one the user trial of main 80c2b49 found wrong or meaningless."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import railhunt
from railhunt import Curve, Model, SingleDefect, Vehicle
from railhunt.analysis.critical import Judgement, critical_speed, run_trial
from railhunt.analysis.verdicts import BLOW_UP, DERAILED, VERDICTS, ending
from railhunt.cli import main
from railhunt.kernel.integrators import STATUS_NAMES
from railhunt.kernel.layout import N_STATE, WHEELSET_Y
from railhunt.simulation import integrate_model
from railhunt.stepsize import stable_step, stable_step_for

PAPER = Vehicle.paper2019()
DOCS = Path(__file__).resolve().parents[1] / "docs"


def run(*args: str):
    return CliRunner().invoke(main, list(args))


# ---------------------------------------------------------------- 3. blow-up is not physics


def test_rk4_stable_step_matches_the_stability_region_on_both_axes():
    # RK4's region of absolute stability: 2.785 on the negative real axis, 2 sqrt(2) on
    # the imaginary axis (a slightly damped pair stands for it).
    assert stable_step_for(np.array([-1.0 + 0j])) == pytest.approx(2.785, abs=2e-3)
    assert stable_step_for(np.array([-1e-6 + 10j])) == pytest.approx(0.2828, abs=3e-4)
    assert math.isinf(stable_step_for(np.array([0.5 + 3j])))  # growth: no step decays it


def test_a_step_above_the_stable_one_blows_up_and_one_below_does_not():
    model = Model(PAPER)
    speed = 300 / 3.6
    h = stable_step(model, speed)
    assert 4e-3 < h < 6e-3  # |lambda| = 565 1/s at 300 km/h
    x0 = np.zeros(N_STATE)
    x0[list(WHEELSET_Y)] = 1e-3
    for factor in (1.05, 1.3):  # main called each of these runs "derailed"
        t, x, code, _ = integrate_model(model, speed, 2.0, x0, dt=factor * h)
        assert ending(STATUS_NAMES[code], x) == BLOW_UP, factor
    t, x, code, _ = integrate_model(model, speed, 2.0, x0, dt=0.95 * h)
    assert STATUS_NAMES[code] == "ok"


def test_a_physical_derailment_stays_a_derailment():
    run_ = railhunt.simulate(PAPER, 250.0, duration=10.0, curve=Curve(300.0, 0.0, start=10.0))
    assert run_.status == "derailed" and run_.ending == DERAILED


def test_a_dt_above_the_stable_step_is_refused_with_the_number():
    # main: simulate(dt=0.008) "derailed" at 0.072 s; critical_speed(dt=0.01) returned NaN.
    with pytest.raises(ValueError, match=r"dt = 0.008 s is invalid: RK4 blows up above 0.005"):
        railhunt.simulate(PAPER, 300.0, dt=0.008)
    with pytest.raises(ValueError, match=r"RK4 blows up above"):
        critical_speed(PAPER, dt=0.01)
    result = run("critical-speed", "--dt", "0.008", "--json")
    assert result.exit_code == 2 and "RK4 blows up above 0.00523 s" in result.output


def test_ending_tells_a_blow_up_from_a_derailment():
    slow = np.linspace(0.0, 0.026, 200)[:, None]  # drifts past 25 mm: physics
    fast = np.concatenate([np.full(190, 1e-3), 1e-3 * 10.0 ** np.arange(1, 11)])[:, None]
    assert ending("derailed", slow) == DERAILED
    assert ending("derailed", fast) == BLOW_UP
    assert ending("diverged", slow) == BLOW_UP
    assert ending("ok", slow) == "ok"


# -------------------------------------------------------- 4. what the linear speed crosses


def test_without_yaw_damper_the_crossing_pair_is_the_hunting_mode():
    # main: "219.2 km/h (Hopf point; not the hunting mode at 0.00 Hz)": it picked the
    # damper's relaxation eigenvalue (-K_d/C_d1, ~0) instead of the pair that crosses.
    lin = railhunt.linear_critical_speed(PAPER.replace(K_d=1.0))
    assert lin.speed_kmh == pytest.approx(219.2, abs=0.1)
    assert lin.crossing == "hopf" and lin.is_hunting_mode
    assert lin.frequency_hz == pytest.approx(3.37, abs=0.05)
    assert abs(lin.eigenvalue.real) < 1e-3


def test_an_equilibrium_unstable_at_the_lowest_speed_is_divergence_not_a_hopf_point():
    # main: "20.0 km/h (Hopf point; not the hunting mode at 0.00 Hz)".
    lin = railhunt.linear_critical_speed(PAPER.replace(lambda1=-0.16))
    assert math.isnan(lin.speed_kmh) and lin.unstable_from_kmh == 20.0
    assert lin.crossing == "divergence" and lin.eigenvalue.imag == 0.0
    assert lin.text == "unstable at every speed from 20 km/h (real eigenvalue: divergence)"
    result = run("critical-speed", "--set", "lambda1=-0.16", "--start", "350", "--step",
                 "10", "--tol", "10")  # fmt: skip
    assert "linear critical speed: unstable at every speed from 20 km/h (real eigenvalue: " \
           "divergence)" in " ".join(result.output.split())  # fmt: skip


# ------------------------------------------------- 5. "stable" only for motion that died out


def test_a_motion_that_does_not_decay_is_undecided_not_stable():
    # main: with W = 100 kg every trial stayed at 10.1 mm and was called stable up to
    # 800 km/h, although the linear critical speed is 52.9 km/h.
    res = critical_speed(PAPER.replace(W=100.0), start_kmh=300.0, step_kmh=10.0,
                         tol_kmh=10.0, max_kmh=310.0)  # fmt: skip
    assert res.trials and all(t.verdict != "stable" for t in res.trials)
    assert res.undecided and "neither died out" in res.undecided[0].reason
    assert any("undecided" in w for w in res.warnings)


def test_an_excitation_of_zero_size_is_refused():
    # main: --amplitude 0 excited nothing and reported "stable up to 800 km/h".
    with pytest.raises(ValueError, match="zero size"):
        critical_speed(PAPER, SingleDefect(amplitude=0.0))
    result = run("critical-speed", "--amplitude", "0")
    assert result.exit_code == 2 and "--amplitude 0 mm is invalid" in result.output


def test_a_slow_growth_near_the_hopf_point_is_not_a_steady_cycle():
    # main: a 0.01 mm defect at 441 km/h (Hopf point 441.3 km/h) grew at +0.003 1/s and
    # passed the steady-cycle test after 9 s ("hunting", decided).
    trial = run_trial(Model(PAPER), 441.0, SingleDefect(amplitude=1e-5), Judgement(), dt=1e-3)
    assert not (trial.verdict == "hunting" and trial.decided)
    assert trial.duration > 60.0


def test_a_start_beyond_20_mm_is_refused():
    # main: --initial-displacement 30 ran and "derailed" after one step.
    with pytest.raises(ValueError, match="amplitude"):
        railhunt.InitialDisplacement(0.03)
    result = run("simulate", "--speed", "300", "--initial-displacement", "30")
    assert result.exit_code == 2 and "[-20, 20] mm" in result.output


# ---------------------------------------------------------------- 6. the words, defined once


def test_every_verdict_word_is_defined_in_the_docs_and_in_help():
    page = " ".join((DOCS / "critical-speeds.md").read_text().split())
    for word, meaning in VERDICTS.items():
        assert f"**{word}**: {meaning}" in page, word
    for command in ("critical-speed", "simulate", "stability-map", "bifurcation"):
        text = " ".join(run(command, "--help").output.split())
        for word, meaning in VERDICTS.items():
            assert f"{word}: {' '.join(meaning.split())}" in text, (command, word)


def test_the_critical_speed_json_carries_warnings_and_limits():
    result = run("critical-speed", "--set", "W=100", "--start", "300", "--step", "10",
                 "--tol", "10", "--curve-radius", "8000", "--json")  # fmt: skip
    data = json.loads(result.stdout)
    assert isinstance(data["warnings"], list) and data["warnings"]
    assert isinstance(data["limits"], list)
    assert re.search(r"undecided|limit reached", " ".join(data["warnings"]))
