"""Layouts judged whole: every force of the rails in the guiding forces, every wheelset and
bogie frame watched, derived parameters that follow their inputs, every value checked by
its meaning, no doubled mirror, linear models without limit cycles, and the small ones
(expression functions, bump stops in curves, trivial orbits, cant excess, empty files).

Each test failed before (the comment says how) and is cheap: static states, short runs of
small layouts, one run shared per module.
"""

from __future__ import annotations

import dataclasses
import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

import railhunt
from railhunt import Model, SingleDefect, Vehicle
from railhunt.channels import derived_channels
from railhunt.cli import main
from railhunt.layout.spec import LayoutError
from railhunt.vehicle import ParameterError, VehicleFileError
from railhunt.vehicle.errors import DerivedOverrideWarning
from railhunt.vehicle.files import load_vehicle, shipped_path

ROOT = Path(__file__).resolve().parents[1]
COOP = Vehicle.shipped("cooperrider_bogie")
COOP_TEXT = Path(str(shipped_path("cooperrider_bogie"))).read_text(encoding="utf-8")
_DOCS = (ROOT / "docs" / "layouts.md").read_text(encoding="utf-8")
#: The docs' sprung wheelset (f11 = "GPIAB / 0.60252"): linear creep, no flange.
SPRUNG_TEXT = _DOCS.split("```toml\n", 1)[1].split("```", 1)[0]


def run(*args: str):
    return CliRunner().invoke(main, list(args))


def write(tmp_path: Path, text: str, name: str = "layout.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def coop_with(tmp_path: Path, old: str, new: str) -> Path:
    assert old in COOP_TEXT, old
    return write(tmp_path, COOP_TEXT.replace(old, new, 1))


# --------------------------------------------------------------- 1. flanges in Y and ΣY


def test_a_flange_force_is_in_sum_y_y_and_y_over_q():
    """A static state 4.8 mm into the leading wheelset's flange and 1 mm into the trailing
    one's (no creep: centred yaw, no velocity): ΣY is k0 (y - delta) of each, on the wheel
    whose flange touches (before: 0 N, Y/Q 0)."""
    model = Model(COOP)
    x = np.zeros(model.layout.n_state)
    x[model.layout.dof("y_w1")] = COOP.delta + 4.8e-3
    x[model.layout.dof("y_w2")] = -(COOP.delta + 1e-3)
    d = derived_channels(np.zeros(1), x[None, :], 280 / 3.6, model.system(), model.layout)
    assert d["SY_w1"][0] == pytest.approx(COOP.k0 * 4.8e-3, rel=1e-12)  # 70.2 kN
    assert d["Y_w1L"][0] == pytest.approx(COOP.k0 * 4.8e-3, rel=1e-12) and d["Y_w1R"][0] == 0
    assert d["SY_w2"][0] == pytest.approx(-COOP.k0 * 1e-3, rel=1e-12)
    assert d["Y_w2R"][0] == pytest.approx(COOP.k0 * 1e-3, rel=1e-12) and d["Y_w2L"][0] == 0
    assert d["YQ_w1L"][0] == pytest.approx(COOP.k0 * 4.8e-3 / COOP.N_w)  # 1.12 > 0.8
    # Action and reaction: the force the derived channels put on the track is the one the
    # equations of motion put on the wheelset (its acceleration without the flange less
    # with it, times its mass).
    free = Model(COOP.replace(k0=0.0))
    acc = model.derivative(x, 280 / 3.6)[model.layout.rate("y_w1")]
    acc_free = free.derivative(x, 280 / 3.6)[model.layout.rate("y_w1")]
    assert COOP.m_w * (acc_free - acc) == pytest.approx(d["SY_w1"][0], rel=1e-9)


@pytest.fixture(scope="module")
def hunting_bogie():
    """The Cooperrider bogie hunting on its flanges after the defect at 280 km/h, 10 s."""
    return railhunt.simulate(COOP, 280.0, duration=10.0, excitation=SingleDefect())


def test_a_hunting_run_carries_its_flange_forces(hunting_bogie):
    """Along the run, ΣY and Y less their creep and normal part (the same states through a
    model without flange stiffness) are the flanges' k0 (|y - y_rail| - delta); the
    stochastic criterion reads the same ΣY. Before: no difference, and the criterion saw
    a ΣY rms of 8.0 kN ("stable"); now 15.6 kN ("unstable") against its 25.8 kN limit."""
    r = hunting_bogie
    model = Model(COOP)
    creep_only = derived_channels(r.t, r.x, r.speed, Model(COOP.replace(k0=0.0)).system(
        SingleDefect()), model.layout, accelerations=False)  # fmt: skip
    from railhunt.kernel.track import rail_offsets

    sysm = model.system(SingleDefect())
    rails = rail_offsets(r.t, r.speed, sysm.wheelset_delay, sysm.track, sysm.track_samples)
    for j, w in enumerate(("w1", "w2")):
        u = r[f"y_{w}"] - rails[:, j]
        flange = COOP.k0 * np.sign(u) * np.maximum(np.abs(u) - COOP.delta, 0.0)
        assert np.max(np.abs(flange)) > 20e3  # the flange is hit
        assert np.allclose(r[f"SY_{w}"] - creep_only[f"SY_{w}"], flange, rtol=0, atol=1e-6)
        assert np.allclose(r[f"Y_{w}L"] - creep_only[f"Y_{w}L"], np.maximum(flange, 0),
                           rtol=0, atol=1e-6)  # fmt: skip
    a = railhunt.assess_stability(r, COOP)
    assert a.sum_y_rms.max() == pytest.approx(15.58e3, rel=0.02)


# --------------------------------------------------------- 2. every wheelset is watched


def _free_trailing_wheelset(tmp_path: Path) -> Vehicle:
    """The Cooperrider bogie whose trailing wheelset has no primary suspension (only its
    rails and flanges hold it): it hunts while the leading one runs quietly."""
    text = COOP_TEXT
    start = text.index('[[element]]\nname = "primary lateral spring, wheelset 2"')
    end = text.index("# ---- secondary suspension")
    return load_vehicle(write(tmp_path, text[:start] + text[end:]))


def test_a_trailing_wheelset_that_hunts_is_not_stable(tmp_path):
    """Before: "stable" at 93 km/h (the leading wheelset's motion died out) while the free
    trailing wheelset left the track. Now the trailing wheelset decides, and says so."""
    from railhunt.analysis.critical import run_trial
    from railhunt.analysis.judgement import Judgement

    vehicle = _free_trailing_wheelset(tmp_path)
    trial = run_trial(Model(vehicle), 93.0, SingleDefect(), Judgement(max_duration=30.0),
                      dt=1e-3)  # fmt: skip
    assert trial.verdict != "stable" and trial.body == "wheelset2", trial
    run_ = railhunt.simulate(vehicle, 93.0, duration=30.0, excitation=SingleDefect())
    verdict = railhunt.analysis.critical.judge_run(run_)
    assert verdict.verdict != "decays" and verdict.body == "wheelset2"


def test_the_worst_body_decides():
    """judge_bodies: a decaying leading column and a steady cycle behind it is hunting,
    decided by the second; all decaying is stable (the last to decay named)."""
    from railhunt.analysis.judgement import Judgement, judge_bodies

    t = np.arange(0.0, 12.0, 2e-3)
    lead = 5e-3 * np.exp(-2.0 * t) * np.sin(2 * np.pi * 4 * t)
    rear = 6e-3 * np.sin(2 * np.pi * 4 * t)
    assert judge_bodies(t, np.column_stack([lead, rear]), 1.0, Judgement())[0::3] == (
        "hunting", 1)
    slow = 5e-3 * np.exp(-1.5 * t) * np.sin(2 * np.pi * 4 * t)
    verdict, _, _, k = judge_bodies(t, np.column_stack([lead, slow]), 1.0, Judgement())
    assert (verdict, k) == ("stable", 1)


def test_the_critical_speed_json_names_the_deciding_body():
    """The JSON gains deciding_body and each trial's body (existing keys kept)."""
    result = run("critical-speed", "--vehicle", "two_axle_wagon", "--start", "300",
                 "--step", "10", "--tol", "10", "--json")  # fmt: skip
    data = json.loads(result.stdout)
    assert data["deciding_body"].startswith("wheelset")
    assert all(t["body"].startswith("wheelset") for t in data["trials"])
    assert {"first_hunting_speed_kmh", "nonlinear_critical_speed_kmh"} <= set(data)


# ------------------------------------------------------ 3. derived parameters follow


def test_a_derived_parameter_follows_its_input(tmp_path):
    """f11 = "GPIAB / 0.60252": replace, --set and the critical speed follow GPIAB (before:
    f11 and the linear critical speed stayed as read)."""
    v = load_vehicle(write(tmp_path, SPRUNG_TEXT))
    low = v.replace(GPIAB=1e5)
    assert low.f11 == 1e5 / 0.60252 and low.f22 == 1e5 / 0.54219
    base = railhunt.linear_critical_speed(v).speed_kmh
    assert railhunt.linear_critical_speed(low).speed_kmh != pytest.approx(base, rel=1e-3)
    shown = run("parameters", "--vehicle", str(tmp_path / "layout.toml"), "--set",
                "GPIAB=1e5").stdout  # fmt: skip
    f11_row = next(line for line in shown.splitlines() if "│ f11" in line)
    assert "165970" in f11_row  # 1e5 / 0.60252 N
    # A file written from it keeps the formula.
    back = load_vehicle(low.to_toml(tmp_path / "back.toml"))
    assert back.replace(GPIAB=2e5).f11 == 2e5 / 0.60252


def test_setting_a_derived_parameter_overrides_it_and_says_so(tmp_path):
    v = load_vehicle(write(tmp_path, SPRUNG_TEXT))
    with pytest.warns(DerivedOverrideWarning, match="f11 is derived .* no longer follows GPIAB"):
        own = v.replace(f11=1e7)
    assert own.f11 == 1e7 and own.replace(GPIAB=1e5).f11 == 1e7  # no longer follows
    result = run("parameters", "--vehicle", str(tmp_path / "layout.toml"), "--set", "f11=1e7")
    assert result.exit_code == 0 and "note: f11 is derived" in result.stderr


def test_a_study_sees_a_parameter_through_its_formula(tmp_path):
    """A sweep of GPIAB: the linear critical speed follows through f11 and f22 (before:
    the same at every point, the formula frozen when the file was read; a Sobol' study
    gave ST(GPIAB) = 0)."""
    v = load_vehicle(write(tmp_path, SPRUNG_TEXT))
    res = railhunt.sweep(v, {"GPIAB": [3e6, 9e6]}, ("linear_critical_speed",), workers=1)
    speeds = [row["linear_critical_speed_kmh"] for row in res.rows]
    assert speeds[0] != pytest.approx(speeds[1], rel=1e-3)


# ------------------------------------------------------------ 4. values by meaning


BAD_COOP = [
    # (old, new, words the one-line refusal must contain); before, all were accepted
    ("value = 1.823e6", "value = -1.823e6", ["k1", "must be finite and >= 0"]),
    ("value = 2.92e4", "value = -2.92e4", ["D2", ">= 0"]),
    ("[parameters.mu]\nvalue = 0.15", "[parameters.mu]\nvalue = -0.15", ["mu", "(0, 1.5]"]),
    ("[parameters.mu]\nvalue = 0.15", "[parameters.mu]\nvalue = 0.0", ["mu", "(0, 1.5]"]),
    ("value = 6.24e4", "value = -6.24e4", ["N_w", "[1000, 300000]"]),
    ("value = 0.0091", "value = -0.0091", ["delta", "[0, 0.2]"]),
    ('height = "r0 + h1"', 'height = "-0.5"', ["height", "above the top of rail"]),
    ("value = 0.4572", "value = 457.2", ["r0", "(0.2, 0.7]", "allow = true"]),
    ("[parameters.b]\nvalue = 1.074", "[parameters.b]\nvalue = 1000.0",
     ["b", "[-200, 200]", "allow = true"]),
    ('x = "-b"', 'x = "b"', ["wheelsets 'wheelset1'", "would overlap"]),
    ("value = 2918.9", "value = 2.9189", ["m_f", "[50, 50000]", "allow = true"]),
    ("[parameters.a]\nvalue = 0.7163", "[parameters.a]\nvalue = 716.3",
     ["a", "[0.3, 1]", "allow = true"]),
    ('unit = "N/m"\nmeaning = "Primary lateral', 'unit = "lbf/in"\nmeaning = "Primary lateral',
     ["'lbf' is not a unit railhunt knows"]),
    ('unit = "N/m"\nmeaning = "Primary lateral', 'unit = "N*s/m"\nmeaning = "Primary lateral',
     ["'k1' is given in N*s/m", "stiffness", "N/m"]),
]


@pytest.mark.parametrize(("old", "new", "words"), BAD_COOP, ids=[w[0] for *_, w in BAD_COOP])
def test_a_value_against_its_meaning_is_refused_naming_it(tmp_path, old, new, words):
    path = coop_with(tmp_path, old, new)
    with pytest.raises(ValueError) as info:
        load_vehicle(path)
    assert all(w in str(info.value) for w in words), str(info.value)
    result = run("critical-speed", "--vehicle", str(path))  # one line, before any work
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2 and len(lines) == 1 and lines[0].startswith("railhunt: error:")


def test_a_unit_beside_a_value_is_converted(tmp_path):
    """unit = "kN/m" beside 1823: 1.823e6 N/m (before: 1823 N/m used)."""
    path = coop_with(tmp_path, 'value = 1.823e6\nunit = "N/m"', 'value = 1823\nunit = "kN/m"')
    v = load_vehicle(path)
    assert v.k1 == 1.823e6 and v.parameters["k1"].unit == "N/m"
    assert v == COOP.replace(name=v.name)
    gap = coop_with(tmp_path, 'value = 0.0091\nunit = "m"', 'value = 9.1\nunit = "mm"')
    assert load_vehicle(gap).delta == 0.0091


def test_set_and_replace_obey_the_same_rules():
    """--set k1=-1e6 and a 28 kg car body are refused before any work (before: answers)."""
    with pytest.raises(ParameterError, match=r"k1 = -1000000 N/m is invalid: must be finite "
                                             r"and >= 0"):  # fmt: skip
        COOP.replace(k1=-1e6)
    result = run("critical-speed", "--vehicle", "cooperrider_bogie", "--set", "k1=-1e6")
    assert result.exit_code == 2 and "k1 = -1000000 N/m is invalid" in result.output
    for vehicle in (Vehicle.shipped("two_axle_wagon"), Vehicle.paper2019()):
        with pytest.raises(LayoutError, match=r"body 'car': mass = 28.0 is implausible: must "
                                              r"be in \[1000, 500000\] kg .*`allow = true`"):
            vehicle.replace(M_c=28.0)
    result = run("critical-speed", "--set", "M_c=28")
    assert result.exit_code == 2 and "is implausible" in result.output


def test_an_implausible_value_is_taken_on_purpose_with_allow(tmp_path):
    """A 1:5 scale model's wheels (r0 = 0.09 m): allow = true in the file, --allow NAME or
    Vehicle.allowing; the rule of sign still holds."""
    path = coop_with(tmp_path, 'meaning = "Nominal rolling radius (18 in)"',
                     'meaning = "Nominal rolling radius (18 in)"\nallow = true')
    v = load_vehicle(path)
    assert v.replace(r0=0.09).r0 == 0.09
    with pytest.raises(ParameterError, match="r0 = -0.09 m is invalid"):
        v.replace(r0=-0.09)
    assert COOP.allowing("r0").replace(r0=0.09).r0 == 0.09
    result = run("parameters", "--vehicle", "cooperrider_bogie", "--set", "r0=0.09",
                 "--allow", "r0")  # fmt: skip
    assert result.exit_code == 0, result.output
    assert run("parameters", "--vehicle", "cooperrider_bogie", "--set", "r0=0.09").exit_code == 2


def test_a_sweep_outside_a_rule_is_refused_before_any_work():
    with pytest.raises(ValueError, match="k1"):
        railhunt.sweep(COOP, {"k1": [-1e6, 1e6]}, ("linear_critical_speed",), workers=1)


def test_base_files_that_name_each_other_are_refused(tmp_path):
    """Before: RecursionError."""
    write(tmp_path, '[vehicle]\nbase = "b.toml"\n[parameters]\nk1 = 1.9e6\n', "a.toml")
    write(tmp_path, '[vehicle]\nbase = "a.toml"\n[parameters]\nk1 = 2.0e6\n', "b.toml")
    with pytest.raises(VehicleFileError, match="circle of base files"):
        load_vehicle(tmp_path / "a.toml")


def test_a_base_file_converts_and_allows(tmp_path):
    base = write(tmp_path, COOP_TEXT, "coop.toml")
    child = write(tmp_path, f'[vehicle]\nbase = "{base.name}"\n[parameters.k1]\nvalue = 1.9\n'
                  'unit = "MN/m"\n[parameters.r0]\nvalue = 0.09\nallow = true\n', "child.toml")
    v = load_vehicle(child)
    assert v.k1 == 1.9e6 and v.r0 == 0.09


@settings(max_examples=25, deadline=None)
@given(name=st.sampled_from(["k1", "k2", "k4", "k6", "D1", "D2", "k0"]),
       value=st.floats(max_value=-1e-9, min_value=-1e12))
def test_no_negative_stiffness_or_damping_is_accepted(name, value):
    with pytest.raises(ParameterError, match=f"{name} = .* is invalid: must be finite and >= 0"):
        COOP.replace(**{name: value})


# ----------------------------------------------------------- 5. mirror at y = 0


def test_mirror_at_y_0_is_refused_naming_the_element(tmp_path):
    """Cooperrider's yaw spring mirrored at y = 0 doubled it (Hopf 247.1 -> 271.6 km/h)."""
    old = 'axis = "yaw"\nat = [0.0, 0.0, "r0 + h1"]\n'
    path = coop_with(tmp_path, old, old + "mirror = true\n")
    with pytest.raises(LayoutError, match="'secondary yaw stiffness': mirror = true at y = 0"):
        load_vehicle(path)
    # at y = a parameter that is 0
    text = COOP_TEXT.replace(old, 'axis = "yaw"\nat = [0.0, "y0", "r0 + h1"]\nmirror = true\n')
    text = text.replace("[parameters.g]", "[parameters.y0]\nvalue = 0.0\nunit = \"m\"\n\n"
                        "[parameters.g]")  # fmt: skip
    with pytest.raises(LayoutError, match="'secondary yaw stiffness': mirror = true at y = 0"):
        load_vehicle(write(tmp_path, text, "y0.toml"))


# -------------------------------------------------------------- 6. linear models


def test_a_linear_model_has_no_limit_cycle(tmp_path):
    """The sprung wheelset (linear creep, no flange) at its Hopf speed: "neutral", not a
    limit cycle (before: "limit cycle of 7.2 mm"); the bifurcation diagram is the vertical
    line of its neutral orbits, type "linear", no fold (before: "supercritical-b", three
    folds of 0.07-0.23 mm)."""
    from railhunt.analysis.critical import judge_run
    from railhunt.analysis.linearity import is_linear

    v = load_vehicle(write(tmp_path, SPRUNG_TEXT))
    assert is_linear(Model(v)) and not is_linear(Model(COOP))
    hopf = railhunt.linear_critical_speed(v).speed_kmh
    r = railhunt.simulate(v, round(hopf, 1), duration=10.0, excitation=SingleDefect())
    verdict = judge_run(r, linear_model=True)
    assert verdict.verdict == "undecided" and verdict.text.startswith("neutral")
    out = run("simulate", "--vehicle", str(tmp_path / "layout.toml"), "--speed",
              f"{hopf:.1f}", "--duration", "10").stdout  # fmt: skip
    assert out.split("verdict:")[1].split()[0] == "neutral:"
    d = railhunt.bifurcation_diagram(v, (hopf - 50, hopf + 50))
    assert d.hopf_type == "linear" and d.folds == [] and d.fold_speed_kmh == d.hopf_speed_kmh
    assert np.all(d.branches[0].speed_kmh == d.hopf_speed_kmh)


# ------------------------------------------------------------------ 7. the small ones


def test_expression_functions_are_not_parameters(tmp_path):
    """sqrt, abs, min, max were refused as unknown parameters."""
    path = coop_with(tmp_path, 'stiffness = "k1"', 'stiffness = "max(k1, abs(-k1)) * '
                     'sqrt(min(4.0, 9.0)) / 2"')  # fmt: skip
    v = load_vehicle(path)
    assert np.array_equal(Model(v).system().linear, Model(COOP).system().linear)


def test_a_run_in_a_curve_checks_its_bump_stops_with_the_curve():
    """At 80 km/h in a 400 m curve (100 mm cant) the car body to bogie travel is 21 mm
    with the curve's offsets (no contact; `railhunt curve` finds none); without them, as
    before, 80 mm, "beyond its travel"."""
    from railhunt import Curve

    paper = Vehicle.paper2019()
    curve = Curve(400.0, cant=0.1, transition=40.0)
    r = railhunt.simulate(paper, 80.0, duration=4.0, curve=curve, excitation=SingleDefect())
    assert not [lim for lim in r.limits if lim.name == "bump stop"]
    from railhunt.validity import curve_offsets_along

    s = Model(paper).system()
    q = r.x[:, :s.linear.shape[0]]
    geo = curve_offsets_along(Model(paper), r.speed, r.t, curve.route())
    assert np.abs(q @ s.stop_rows.T).max() > 0.07 > np.abs((q + geo) @ s.stop_rows.T).max()


def test_a_release_that_slides_to_the_equilibrium_is_no_branch():
    """Cooperrider at 350 km/h: shooting from a flange-bound run slid to the unstable
    equilibrium, and the diagram listed one-orbit "branches" of 0.00 mm."""
    from railhunt.analysis.continuation import _release
    from railhunt.analysis.hopf_start import hopf_mode_shape, measure_coordinate
    from railhunt.analysis.periodic import Shooting

    model = Model(COOP)
    shape, period = hopf_mode_shape(model, 247.1)
    shoot = Shooting(model, dt_speed=350 / 3.6, phase_coordinate=measure_coordinate(model, shape))
    shoot.set_period_hint(period)
    outcome, found = _release(model, shoot, 350.0, 0.008)
    assert found is None or found[1].amplitude > 1e-3
    if found is None:
        assert "slid to the equilibrium" in outcome


def test_a_cant_excess_is_named_so_in_mm():
    from railhunt.validity import check_cant_deficiency

    (excess,) = check_cant_deficiency(-0.2, "30 km/h in the 500 m curve")
    assert excess.name == "cant excess"
    assert excess.text.startswith("cant excess 200 mm beyond 165 mm")
    (deficit,) = check_cant_deficiency(0.2, "here")
    assert deficit.name == "cant deficiency"


def test_an_empty_file_says_so(tmp_path):
    """Before: "53 missing parameters" of the paper's vehicle."""
    with pytest.raises(VehicleFileError, match="the file is empty") as info:
        load_vehicle(write(tmp_path, ""))
    assert "M_c" not in str(info.value)
    warnings.simplefilter("ignore")  # (nothing else of this module warns)


def test_the_docs_example_is_still_the_closed_form(tmp_path):
    """The sprung wheelset of docs/layouts.md loads with its parameters' units filled in
    from their uses, its rules and its formulas, and its numbers unchanged."""
    v = load_vehicle(write(tmp_path, SPRUNG_TEXT))
    assert dict(v.layout.formulas) == {"f11": "GPIAB / 0.60252", "f22": "GPIAB / 0.54219"}
    assert v.parameters["k_y"].rule.lower == 0.0
    assert math.isclose(v.f11, 6.563e6 / 0.60252)
    assert dataclasses.replace(v.layout, formulas=()) != v.layout
