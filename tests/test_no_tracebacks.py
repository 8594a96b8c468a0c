"""No traceback reaches a user: the command line's errors are one line, the API's wrong
types are TypeErrors naming the argument, and a run that stops early says why."""

from __future__ import annotations

import pytest

import railhunt
from test_cli import assert_input_error, run

PAPER = railhunt.Vehicle.paper2019()


@pytest.fixture()
def radius_mismatch(tmp_path):
    """A vehicle whose [contact] wheel radius is not its r0."""
    path = tmp_path / "r0.toml"
    path.write_text('[vehicle]\nbase = "paper2019"\nname = "r0"\n[contact]\n'
                    "wheel_radius = 0.46\n")  # fmt: skip
    return path


@pytest.mark.parametrize("command", [["critical-speed"], ["frequency"], ["eigen"],
                                     ["sweep", "C_d1", "--from", "1e5", "--to", "2e5",
                                      "--num", "2", "--workers", "1", "--out", "OUT"]])  # fmt: skip
def test_a_contact_section_that_does_not_fit_is_one_line(radius_mismatch, tmp_path, command):
    argv = [str(tmp_path / "s.csv") if a == "OUT" else a for a in command]
    result = run(*argv, "--vehicle", str(radius_mismatch))
    assert_input_error(result, f"--vehicle {radius_mismatch}: [contact]", "r0 = 0.43 m",
                       "centred rolling radius")  # fmt: skip
    assert not (tmp_path / "s.csv").exists()


def test_a_curve_too_tight_for_the_speed_is_one_line():
    assert_input_error(run("critical-speed", "--curve-radius", "50"), "steady-curving")


def test_an_unexpected_error_is_one_line_with_a_hint(monkeypatch):
    import railhunt.analysis.linear as linear

    def broken(*args, **kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(linear, "linear_critical_speed", broken)
    monkeypatch.setattr(railhunt, "linear_critical_speed", broken)
    result = run("eigen")
    assert result.exit_code == 1 and "Traceback" not in result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "unexpected RuntimeError: boom" in lines[0]
    assert "RAILHUNT_DEBUG=1" in lines[0] and "--debug" in lines[0]
    debug = run("--debug", "eigen")
    assert isinstance(debug.exception, RuntimeError)
    monkeypatch.setenv("RAILHUNT_DEBUG", "1")
    assert isinstance(run("eigen").exception, RuntimeError)


def test_a_study_whose_every_point_failed_exits_non_zero(tmp_path, monkeypatch):
    import railhunt.analysis.linear as linear

    def broken(*args, **kwargs):
        raise ValueError("no Hopf point (a test's broken analysis)")

    monkeypatch.setattr(linear, "linear_critical_speed", broken)
    result = run("sweep", "C_d1", "--from", "1e5", "--to", "2e5", "--num", "2", "--outputs",
                 "linear_critical_speed", "--workers", "1", "--out", str(tmp_path / "s.csv"))
    assert result.exit_code == 1, (result.exit_code, result.stderr)
    assert "every one of the 2 points failed" in result.stderr
    assert "no Hopf point" in result.stderr


@pytest.mark.parametrize(("call", "argument"), [
    (lambda: railhunt.simulate(PAPER, 300, duration="1"), "duration = '1'"),
    (lambda: railhunt.simulate(PAPER, "fast"), "speed_kmh = 'fast'"),
    (lambda: railhunt.simulate(None, 300), "vehicle = None"),
    (lambda: railhunt.critical_speed("paper2019"), "vehicle = 'paper2019'"),
    (lambda: railhunt.linear_critical_speed("paper2019"), "vehicle = 'paper2019'"),
    (lambda: railhunt.critical_speed(PAPER, curve="4000"), "curve = '4000'"),
    (lambda: railhunt.simulate(PAPER, 300, curve=4000.0), "curve = 4000.0"),
    (lambda: railhunt.critical_speed(PAPER, start_kmh="300"), "start_kmh = '300'"),
    (lambda: railhunt.stochastic_critical_speed(PAPER, irregularity="german-high"),
     "irregularity = 'german-high'"),
])  # fmt: skip
def test_a_wrong_type_is_a_type_error_naming_the_argument(call, argument):
    with pytest.raises(TypeError) as info:
        call()
    from railhunt.arguments import ArgumentTypeError

    assert isinstance(info.value, ArgumentTypeError)
    assert str(info.value).startswith(argument)


def test_a_radius_given_for_a_curve_says_how_to_make_one():
    with pytest.raises(TypeError, match=r"railhunt.Curve\(radius=4000.0\)"):
        railhunt.critical_speed(PAPER, curve="4000")


def test_dopri5_says_when_it_used_up_its_step_budget():
    # A yaw damper so stiff (K_d = 1e11 N/m: time constant C_d1/K_d = 3 us) that the
    # adaptive method needs steps of microseconds: it stops early and says so.
    stiff = PAPER.replace(K_d=1e11)
    result = railhunt.simulate(stiff, 300, duration=0.2, method="dopri5", dt=1e-3,
                               excitation=railhunt.SingleDefect())  # fmt: skip
    assert result.status == "step-limit" and not result.ok
    assert result.t[-1] < 0.2
    assert "before the end" in result.message and "budget" in result.message
    done = railhunt.simulate(PAPER, 300, duration=0.2, method="dopri5")
    assert done.status == "ok" and done.t[-1] == pytest.approx(0.2)
