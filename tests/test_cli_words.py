"""What a user reads: the first screen of ``railhunt critical-speed``, one summary per kind
of limit, Python's warnings as one line each, helps that take vehicles and counts from the
code, the parameters' sources, and the smaller messages (each one line naming the culprit).
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

import railhunt
from railhunt import Vehicle
from railhunt.cli import main
from railhunt.vehicle import shipped_vehicles

ROOT = Path(__file__).resolve().parents[1]
PAPER = Vehicle.paper2019()
SCREEN_LINES, SCREEN_COLUMNS = 24, 80


def run(*args: str, columns: int = SCREEN_COLUMNS):
    return CliRunner(env={"COLUMNS": str(columns)}).invoke(main, list(args))


# ------------------------------------------------- the first screen of critical-speed


@pytest.fixture(scope="module")
def first_run() -> list[str]:
    result = run("critical-speed")
    assert result.exit_code == 0, result.output
    return result.output.splitlines()


def test_the_default_search_shows_both_answers_on_its_first_screen(first_run):
    # main: six "warning: ... limit reached: ..." lines (12 on 80 columns) before the
    # linear critical speed, on lines 17-30.
    screen = first_run[:SCREEN_LINES]
    assert all(len(line) <= SCREEN_COLUMNS for line in first_run)
    text = " ".join(" ".join(screen).split())
    assert "nonlinear critical speed: 301 km/h" in text
    assert "linear critical speed: 441.3 km/h" in text
    limits = [line for line in first_run if "changes no verdict" in line]
    assert 1 <= len(limits) <= 2 and all(line in screen for line in limits)
    # no verdict word for what decides nothing, no warning wall
    assert not any("limit reached" in line or line.startswith("warning:") for line in first_run)
    summary = {line.split()[0]: line for line in limits}
    assert summary["ΣY"].startswith("ΣY 48.8 kN > 45.6 kN (EN 14363) at 301–310 km/h")
    assert summary["Y/Q"].startswith("Y/Q 0.829 > 0.8 (EN 14363) at 305–310 km/h")


def test_getting_started_shows_the_output_as_the_tool_prints_it(first_run):
    page = (ROOT / "docs" / "getting-started.md").read_text(encoding="utf-8")
    block = page.split("```bash\nrailhunt critical-speed\n```", 1)[1].split("```\n", 2)[1]
    printed = " ".join(" ".join(first_run).split())
    for line in block.strip().splitlines():
        assert " ".join(line.split()) in printed, line


def test_verbose_lists_every_trial_s_limits():
    result = run("critical-speed", "--start", "300", "--step", "10", "--tol", "10",
                 "--verbose", columns=200)  # fmt: skip
    assert result.exit_code == 0, result.output
    lines = [line.strip() for line in result.output.splitlines()]
    assert "310 km/h: Y/Q 0.829 beyond 0.8 (EN 14363) at wheelset 1 right, t = 0.308 s" in lines
    assert "310 km/h: ΣY 48.8 kN beyond 45.6 kN (EN 14363) at wheelset 2, t = 0.240 s" in lines


def test_one_summary_per_kind_of_limit():
    """The largest value, where, at which speeds, whether it decided anything."""
    from railhunt.validity import Limit, summarize_limits

    def lim(name, value, place):
        return Limit(name, 0.8 if name == "Y/Q" else 45.6e3, value,
                     "1" if name == "Y/Q" else "N", place, "EN 14363")  # fmt: skip

    reached = [(310.0, lim("ΣY", 48.8e3, "wheelset 2, t = 0.240 s")),
               (301.0, lim("ΣY", 45.9e3, "wheelset 2, t = 0.246 s")),
               (305.0, lim("Y/Q", 0.802, "wheelset 1 right, t = 0.312 s")),
               (305.0, lim("ΣY", 47.2e3, "wheelset 2, t = 0.244 s"))]  # fmt: skip
    yq, sy = summarize_limits(reached)  # in the order of validity.LIMIT_NAMES
    assert (sy.name, sy.value, sy.speed_kmh, sy.speeds_kmh) == ("ΣY", 48.8e3, 310.0,
                                                                (301.0, 305.0, 310.0))
    assert sy.place == "wheelset 2, t = 0.240 s" and not sy.decided
    assert sy.line == ("ΣY 48.8 kN > 45.6 kN (EN 14363) at 301–310 km/h, wheelset 2: "
                       "changes no verdict")  # fmt: skip
    assert sy.text == ("ΣY beyond 45.6 kN (EN 14363) at 301, 305 and 310 km/h; largest "
                       "48.8 kN at wheelset 2, t = 0.240 s, 310 km/h; changes no verdict")
    assert yq.speeds_kmh == (305.0,) and "at 305 km/h" in yq.line
    assert summarize_limits(reached, decided=True)[0].effect == "the answer stops there"
    assert sy.to_dict()["speeds_kmh"] == [301.0, 305.0, 310.0]


def test_many_undecided_trials_are_one_line():
    """``--set W=100`` printed 29 lines of undecided trials, one per speed."""
    from railhunt.verdicts import trial_summaries

    class T:
        def __init__(self, speed: float) -> None:
            self.speed_kmh, self.verdict = speed, "undecided"
            self.reason = "after 60 s the motion is 9 mm and neither died out nor settled"

    lines = trial_summaries([T(s) for s in range(300, 20, -10)])
    assert len(lines) == 1
    assert lines[0].startswith("undecided at 28 trial speeds, 30–300 km/h")
    assert "counted as not stable" in lines[0]
    assert trial_summaries([T(300)])[0].startswith("300 km/h: undecided (after 60 s")


# ------------------------------------------------------------- Python's warnings


def test_python_warnings_are_one_line_each_never_a_source_path():
    """A central mechanism: every command's warnings, however many times raised."""
    from railhunt.cli.app import Group

    group = Group("railhunt")

    @group.command("warns")
    def warns() -> None:
        for _ in range(3):
            warnings.warn("a measuring spike?\n  It is kept", UserWarning, stacklevel=1)
        warnings.warn("another", RuntimeWarning, stacklevel=1)

    result = CliRunner().invoke(group, ["warns"])
    assert result.exit_code == 0
    assert result.output.splitlines() == ["warning: a measuring spike? It is kept",
                                          "warning: another"]  # fmt: skip


def test_a_free_wheelset_warns_in_one_line(tmp_path):
    # main: ".../vehicle/core.py:247: FreeWheelsetWarning: ..." and the source line
    rig = (ROOT / "tests" / "data" / "layout_wheelset.toml").read_text(encoding="utf-8")
    path = tmp_path / "alone.toml"
    path.write_text(rig[:rig.index("[[element]]")], encoding="utf-8")
    result = run("vehicle", str(path))
    assert result.exit_code == 0, result.output
    said = [line for line in result.output.splitlines() if "free wheelset" in line]
    assert said == [f"warning: {path}: wheelset 'wheelset' is joined to no body: only the "
                    "rails hold it (a free wheelset)"]  # fmt: skip
    assert ".py:" not in result.output and "Warning:" not in result.output


# ------------------------------------------------------ helps that read the code


def _help(command: click.Command, name: str) -> str:
    ctx = click.Context(command, info_name=name, parent=click.Context(main), terminal_width=300)
    return " ".join(command.get_help(ctx).split())


def test_every_vehicle_help_lists_every_shipped_vehicle(monkeypatch):
    # main: paper2019, s1002_uic60 and s1002_uic60_table only
    with_vehicle = [n for n, c in main.commands.items()
                    if any("--vehicle" in p.opts for p in c.params)]  # fmt: skip
    assert len(with_vehicle) >= 10
    for name in with_vehicle:
        text = _help(main.commands[name], name)
        assert all(v in text for v in shipped_vehicles()), name
    # read from the data directory when shown: a vehicle added there is listed
    import railhunt.vehicle

    monkeypatch.setattr(railhunt.vehicle, "shipped_vehicles", lambda: ("paper2019", "new_car"))
    assert "paper2019, new_car" in _help(main.commands["eigen"], "eigen")


def test_the_docs_list_every_shipped_vehicle():
    page = (ROOT / "docs" / "layouts.md").read_text(encoding="utf-8")
    table = page.split("## Shipped vehicles", 1)[1].split("What they give", 1)[0]
    assert set(re.findall(r"`(\w+)`", table)) >= set(shipped_vehicles())


def test_helps_count_from_the_vehicle_not_the_paper():
    # main: "computes its 38 eigenvalues", "all four wheelsets"
    eigen, simulate = _help(main.commands["eigen"], "eigen"), _help(main.commands["simulate"],
                                                                    "simulate")  # fmt: skip
    assert "38" not in eigen and "two per coordinate and one per yaw damper force" in eigen
    assert "four wheelsets" not in simulate and "every wheelset displaced" in simulate
    assert "four wheelsets" not in _help(main.commands["bifurcation"], "bifurcation")


def test_parameters_have_a_source_column():
    result = run("parameters", "--vehicle", "cooperrider_bogie", "--set", "mu=0.2",
                 columns=200)  # fmt: skip
    assert result.exit_code == 0, result.output
    header = next(line for line in result.output.splitlines() if "meaning" in line)
    assert "source" in header
    rows = {line.split("│")[1].strip(): line for line in result.output.splitlines()
            if line.startswith("│")}  # fmt: skip
    assert "code (DYTSI)" in rows["m_w"] and "--set" in rows["mu"]
    paper = run("parameters", columns=200).output
    assert "Table 2" in next(line for line in paper.splitlines() if line.startswith("│ M_c "))


def test_the_articulated_pair_names_a_command_that_exists():
    text = (ROOT / "examples" / "data" / "articulated_pair.toml").read_text(encoding="utf-8")
    named = re.findall(r"`railhunt ([a-z-]+)", text)
    assert named and all(n in main.commands for n in named)


# --------------------------------------------------------------- smaller messages


def _one_line(result) -> str:
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2 and len(lines) == 1, result.output
    return lines[0]


def test_a_toml_file_with_a_byte_order_mark_loads(tmp_path):
    # main: "not a valid TOML file: Invalid statement (at line 1, column 1)"
    path = tmp_path / "bom.toml"
    path.write_bytes(b'\xef\xbb\xbf[vehicle]\nbase = "paper2019"\n[parameters]\nC_d1 = 2e5\n')
    assert railhunt.load_vehicle(path).C_d1 == 2e5


def test_a_negative_seed_names_the_seed():
    # main: numpy's "expected non-negative integer"
    with pytest.raises(ValueError, match=r"^seed = -1 is invalid: must be an integer >= 0"):
        railhunt.track_irregularity("german-low", length=500.0, seed=-1)


def test_a_sweep_value_that_is_no_number_names_the_parameter():
    # main: "could not convert string to float: 'abc'"
    with pytest.raises(ValueError, match=r"^C_d1 = 'abc' is invalid: the values of a sweep "
                                         r"are numbers in N\*s/m"):  # fmt: skip
        railhunt.sweep(PAPER, {"C_d1": "abc"})


def test_a_light_body_s_step_names_its_mass():
    # main: "set by the model's fastest mode (...: a stiff spring or a light body)"
    # (a 1 g wheelset is implausible: it must be allowed on purpose to reach the step)
    refused = _one_line(run("critical-speed", "--set", "M_w=0.001"))
    assert "implausible" in refused and "`--allow M_w` on the command line" in refused
    line = _one_line(run("critical-speed", "--set", "M_w=0.001", "--allow", "M_w"))
    assert re.search(r"y_w\d of wheelset\d moves most in it", line), line
    assert "its mass M_w = 0.001 kg is light" in line
    from railhunt.model import Model
    from railhunt.simulation import step_cause

    # a vehicle without yaw dampers (main: a ValueError of numpy's empty max)
    assert step_cause(Model(railhunt.Vehicle.shipped("cooperrider_bogie")), 30.0).startswith(
        "the step of 0.00076 s is set by the model's fastest mode")


def test_a_model_function_returning_a_float_is_named():
    # main: "only 0 of 8 base samples have every point's value: too few for the indices"
    import numpy as np

    from railhunt.studies.factors import function_task, parse_factors
    from railhunt.studies.sensitivity import analyse_study
    from railhunt.studies.store import SweepResults

    def model(a: float, b: float) -> float:
        return a + b

    rows = [function_task((i, {"a": 0.5, "b": 0.5}), model, ("y",)) for i in range(8)]
    assert rows[0]["status"] == "failed"
    assert re.search(r"the model function .*model returned 1.0 \(float\), not a mapping of "
                     r"the outputs to their values, e.g. \{'y': 1.0\}", rows[0]["message"])
    factors = parse_factors(model, {"a": (0.0, 1.0), "b": (0.0, 1.0)})
    with pytest.raises(ValueError, match=r"too few for the indices \(point 0 failed: "
                                         r"TypeError: the model function"):  # fmt: skip
        analyse_study(SweepResults(rows), "sobol", factors, np.zeros((8, 2)), ("y",), 0)
    missing = function_task((0, {"a": 0.5, "b": 0.5}), lambda a, b: {"z": 1.0}, ("y",))
    assert "returned no 'y' (it returned 'z')" in missing["message"]


def test_two_objectives_of_one_column_are_refused():
    # main: a "front" of y against itself
    def model(a: float, b: float) -> dict:
        return {"y": a + b}

    with pytest.raises(ValueError, match=r"^objective 'max y' is about y, as 'max y' is"):
        railhunt.optimize(model, {"a": (0.0, 1.0), "b": (0.0, 1.0)},
                          objectives=("max y", "max y"), population=4, generations=1)


@pytest.mark.parametrize("args", [
    ["critical-speed", "--set", "C_d1"],
    ["sweep", "--tie", "f22", "C_d1", "--from", "1e5", "--to", "2e5"],
    ["optimize", "C_d1", "--tolerance", "0.2", "--objective", "max critical_speed_kmh",
     "--out", "OUT"],
    ["simulate", "--speed", "300", "--spectrum", "bad"],
])  # fmt: skip
def test_no_message_names_a_flag_twice(args, tmp_path):
    # main: "Invalid value for '--set': 'C_d1' is not of the form NAME=VALUE (SI units),
    # e.g. --set C_d1=150e3" (and --tie, --objective alike)
    args = [str(tmp_path / "o.csv") if a == "OUT" else a for a in args]
    line = _one_line(run(*args, columns=300))
    flags = re.findall(r"--[a-z][\w-]*", line)
    assert flags and len(flags) == len(set(flags)), line


def test_simulate_prints_verdict_words():
    # main: "verdict:    decays (below 0.02 mm at the end)", a word no page defines
    from railhunt.analysis.judgement import judge_run
    from railhunt.verdicts import VERDICTS

    for speed, duration in ((250.0, 10.0), (300.0, 4.0), (350.0, 0.2)):
        verdict = judge_run(railhunt.simulate(PAPER, speed, duration=duration,
                                              excitation=railhunt.SingleDefect()))  # fmt: skip
        assert verdict.verdict in VERDICTS and verdict.text.startswith(verdict.verdict)


def test_a_wheelset_the_vehicle_lacks_is_refused():
    # main: InitialDisplacement(wheelsets=(5,)) on four wheelsets ran with nothing displaced
    with pytest.raises(ValueError, match=r"wheelset 5 is not one of the vehicle's 4 wheelsets"):
        railhunt.simulate(PAPER, 300.0, duration=0.1,
                          excitation=railhunt.InitialDisplacement(wheelsets=(5,)))
    wagon = railhunt.Vehicle.shipped("two_axle_wagon")  # the default: the first four
    railhunt.simulate(wagon, 60.0, duration=0.05, excitation=railhunt.InitialDisplacement())


def test_a_curve_entry_without_a_transition_warns():
    # main: "peak Y/Q of the leading wheelset 2.759" beside "ok", and no warning
    from railhunt.cli.commands.curve import entry_warnings

    said = entry_warnings(railhunt.Curve(300.0, cant=0.15, transition=0.0), 2.759)
    assert said[0].startswith("--transition 0: the curvature and the cant jump")
    assert said[1].startswith("peak Y/Q 2.76 beyond 0.8")
    assert entry_warnings(railhunt.Curve(300.0, cant=0.15, transition=40.0), 0.5) == []


def test_a_study_resumed_with_new_points_is_written_in_point_order(tmp_path):
    # main: optimize's generations after the first stayed in the order they finished
    from railhunt.studies.runner import run_study
    from railhunt.studies.store import read_results

    def task(index: int) -> dict:
        return {"point": index, "line": "function", "y": float(index), "status": "ok",
                "message": ""}  # fmt: skip

    out = tmp_path / "study.csv"
    meta = {"study": "test", "columns": ["point", "line", "y", "status", "message"]}
    run_study([(0, 0), (1, 1)], task, meta, label="first", out=out, workers=1)
    run_study([(3, 3), (2, 2)], task, meta, label="second", out=out, resume=True, workers=1)
    assert [r["point"] for r in read_results(out).rows] == [0, 1, 2, 3]
    lines = out.read_text(encoding="utf-8").splitlines()
    assert [line.split(",")[0] for line in lines[1:]] == ["0", "1", "2", "3"]
    assert not math.isnan(float(lines[-1].split(",")[2]))
