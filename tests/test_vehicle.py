"""Tests of railhunt.vehicle: parameter set, validation, TOML input/output."""

import dataclasses
import math
import pickle

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from railhunt.vehicle import (
    DERIVED,
    PARAMETERS,
    DerivedParameterError,
    MissingParametersError,
    ParameterError,
    UnknownParameterError,
    Vehicle,
    VehicleFileError,
    load_vehicle,
    validate_all,
    validate_value,
)

PAPER = Vehicle.paper2019()
POSITIVE = [n for n, s in PARAMETERS.items() if s.rule.lower == 0.0 and s.rule.lower_strict] + [
    "r0",
    "a",
]
NONNEGATIVE = [n for n, s in PARAMETERS.items() if s.rule.lower == 0.0 and not s.rule.lower_strict]
FINITE_ONLY = [n for n, s in PARAMETERS.items() if s.rule.lower is None and s.rule.upper is None]
NON_FINITE = [math.nan, math.inf, -math.inf]


def value_texts(value: float) -> set[str]:
    """Ways a float may be printed in an error message."""
    texts = {repr(value), str(value)}
    if math.isfinite(value) and value.is_integer():
        texts.add(str(int(value)))
    return texts


def write(tmp_path, text: str, name: str = "vehicle.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


# --------------------------------------------------------------------------- parameter set


def test_parameter_set_matches_rule_categories():
    # The paper's 53 and the secondary lateral bump stop's three (curved track, issue 14).
    assert len(PARAMETERS) == 56
    # The paper's vehicle is a layout file whose parameter table is this one (issue 18).
    assert list(PARAMETERS) == list(Vehicle.paper2019().values)
    assert dict(PARAMETERS) == Vehicle.paper2019().parameters
    for name in ["M_c", "J_wz", "K_d", "C_d1", "C_d2", "F_u", "h4", "l", "l1", "W", "g"]:
        assert name in POSITIVE
    for name in ["C_px", "C_py", "C_pz", "C_sy", "C_sz", "f23", "f33", "h1", "h2", "h3", "h5",
                 "y_bs", "K_bs", "K_bs3"]:
        assert name in NONNEGATIVE
    expected_finite = [f"lambda{i}" for i in range(1, 6)] + ["d0", "d1", "d4", "d5"]
    assert sorted(FINITE_ONLY) == sorted(expected_finite)
    assert len(set(POSITIVE) | set(NONNEGATIVE) | set(FINITE_ONLY)) == 56
    assert PARAMETERS["C_d1"].unit == "N*s/m"
    assert PARAMETERS["mu"].unit == "1"


def test_paper_values():
    v = Vehicle.paper2019()
    assert v.name == "paper2019"
    assert v.description
    assert v.M_c == 28000.0
    assert v.C_d1 == 300e3
    assert v.F_u == 3000.0
    assert v.l == 8.75 and v.l1 == 1.25
    assert v.d5 == -3.58e9
    assert abs(v.v_u - 0.01) <= 1e-12
    assert math.isclose(v.N, 53410.0, rel_tol=1e-9)
    assert all(isinstance(x, float) for x in v.as_dict().values())


def test_paper2019_is_cached_and_equal():
    assert Vehicle.paper2019() == PAPER
    assert hash(Vehicle.paper2019()) == hash(PAPER)


def test_immutable():
    with pytest.raises(dataclasses.FrozenInstanceError):
        PAPER.M_c = 1.0  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        PAPER.new_attribute = 1.0  # type: ignore[attr-defined]


def test_repr_short():
    assert repr(PAPER) == "Vehicle('paper2019', 56 parameters)"


def test_constructor_validates():
    params = PAPER.as_dict()
    params["K_d"] = 0.0
    with pytest.raises(ParameterError) as info:
        Vehicle(name="x", **params)
    assert info.value.parameter == "K_d"
    with pytest.raises(TypeError):
        Vehicle(name="x", **{k: v for k, v in PAPER.as_dict().items() if k != "M_c"})
    with pytest.raises(ParameterError):
        dataclasses.replace(PAPER, M_c=-1.0)
    with pytest.raises(ValueError, match="name"):
        PAPER.replace(name="")


def test_constructor_converts_ints():
    params = PAPER.as_dict()
    params["M_c"] = 28000
    v = Vehicle(name="paper2019", **params)
    assert isinstance(v.M_c, float)
    assert v == PAPER


def test_equality_and_hash():
    copy = Vehicle(name=PAPER.name, description="other text", **PAPER.as_dict())
    assert copy == PAPER and hash(copy) == hash(PAPER)
    assert PAPER.replace(name="other") != PAPER
    assert PAPER.replace(M_c=28001.0) != PAPER
    assert len({PAPER, copy, PAPER.replace(M_c=28001.0)}) == 2


def test_pickle():
    assert pickle.loads(pickle.dumps(PAPER)) == PAPER
    err = pickle.loads(pickle.dumps(ParameterError("C_d1", -5.0, "finite and > 0", "N*s/m")))
    assert err.parameter == "C_d1" and err.value == -5.0 and err.unit == "N*s/m"
    assert str(err).startswith("C_d1 = -5 N*s/m is invalid")


# --------------------------------------------------------------------------- replace


def test_replace_returns_copy():
    changed = PAPER.replace(M_c=30000.0, K_d=2e7)
    assert changed is not PAPER
    assert changed.M_c == 30000.0 and changed.K_d == 2e7
    assert PAPER.M_c == 28000.0 and PAPER.K_d == 1e7
    assert changed.name == PAPER.name
    assert {k: v for k, v in changed.as_dict().items() if k not in ("M_c", "K_d")} == {
        k: v for k, v in PAPER.as_dict().items() if k not in ("M_c", "K_d")
    }


def test_replace_c_d1_keeps_f_u_changes_v_u():
    changed = PAPER.replace(C_d1=600e3)
    assert changed.F_u == PAPER.F_u
    assert changed.v_u == pytest.approx(0.005, rel=1e-12)
    assert PAPER.v_u == pytest.approx(0.01, rel=1e-12)


def test_replace_w_changes_n():
    assert PAPER.replace(W=11000.0).N == pytest.approx(11000.0 * 9.8 / 2)


@pytest.mark.parametrize(("name", "hint"), [("v_u", "F_u"), ("N", "W")])
def test_replace_derived_raises(name, hint):
    with pytest.raises(DerivedParameterError) as info:
        PAPER.replace(**{name: 1.0})
    msg = str(info.value)
    assert isinstance(info.value, ValueError)
    assert "derived" in msg and hint in msg and DERIVED[name].formula in msg


def test_replace_unknown_name_suggests():
    with pytest.raises(UnknownParameterError) as info:
        PAPER.replace(C_d3=1.0)
    assert "did you mean" in str(info.value) and "'C_d1'" in str(info.value)
    assert info.value.parameter == "C_d3"
    with pytest.raises(UnknownParameterError, match="'M_c'"):
        PAPER.replace(m_c=1.0)


def test_consistency_l_greater_than_l1():
    with pytest.raises(ParameterError, match=r"l1") as info:
        PAPER.replace(l=1.0)
    assert info.value.parameter == "l"
    with pytest.raises(ParameterError):
        PAPER.replace(l1=9.0)
    assert PAPER.replace(l=2.0, l1=1.0).l == 2.0
    # C_d2 > C_d1 is allowed
    assert PAPER.replace(C_d2=400e3).C_d2 == 400e3


# --------------------------------------------------------------------------- error messages


def test_error_message_format():
    with pytest.raises(ParameterError) as info:
        PAPER.replace(C_d1=-5)
    err = info.value
    assert str(err) == (
        "C_d1 = -5 N*s/m is invalid: must be finite and > 0 "
        "(First stage damping of yaw damper (below blow-off))"
    )
    assert (err.parameter, err.value, err.rule, err.unit) == (
        "C_d1",
        -5,
        "finite and > 0",
        "N*s/m",
    )


@pytest.mark.parametrize("bad", [True, False, "28000", None, [1.0], {"value": 1.0}])
def test_non_numbers_rejected(bad):
    with pytest.raises(ParameterError) as info:
        validate_value("M_c", bad)
    assert info.value.parameter == "M_c"
    assert "real number" in str(info.value)


def test_huge_int_rejected():
    with pytest.raises(ParameterError):
        validate_value("M_c", 10**400)


@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("mu", 1.6),
        ("mu", 0.0),
        ("delta_max", math.pi / 2),
        ("delta_max", 0.0),
        ("r0", 430.0),
        ("r0", 0.2),
        ("a", 1.435),
        ("a", 0.5),
    ],
)
def test_range_rules(name, value):
    with pytest.raises(ParameterError) as info:
        validate_value(name, value)
    assert info.value.parameter == name


@pytest.mark.parametrize(
    ("name", "value"), [("mu", 1.5), ("r0", 0.7), ("a", 1.0), ("delta_max", 1.57), ("h1", 0.0)]
)
def test_range_bounds_accepted(name, value):
    assert validate_value(name, value) == value


def test_mu_message_explains():
    with pytest.raises(ParameterError, match="not physical"):
        PAPER.replace(mu=2.0)


def test_validate_value_names():
    with pytest.raises(UnknownParameterError):
        validate_value("nope", 1.0)
    with pytest.raises(DerivedParameterError):
        validate_value("v_u", 0.01)


def test_validate_all():
    assert validate_all(PAPER.as_dict()) == PAPER.as_dict()
    partial = PAPER.as_dict()
    del partial["M_c"], partial["d5"]
    with pytest.raises(MissingParametersError) as info:
        validate_all(partial)
    assert info.value.missing == ("M_c", "d5")
    with pytest.raises(UnknownParameterError):
        validate_all({**PAPER.as_dict(), "Mc": 1.0})


# --------------------------------------------------------------------------- hypothesis

bad_positive = st.one_of(st.floats(max_value=0.0), st.sampled_from(NON_FINITE))
bad_nonnegative = st.one_of(
    st.floats(max_value=0.0, exclude_max=True).filter(lambda x: x < 0),
    st.sampled_from(NON_FINITE),
)


def check_rejected(name: str, value: float) -> None:
    spec = PARAMETERS[name]
    for call in (lambda: validate_value(name, value), lambda: PAPER.replace(**{name: value})):
        with pytest.raises(ParameterError) as info:
            call()
        err = info.value
        msg = str(err)
        assert err.parameter == name
        assert msg.startswith(f"{name} = ")
        assert any(text in msg for text in value_texts(value)), msg
        if spec.unit != "1":  # dimensionless values are printed without a unit
            assert spec.unit in msg
        assert err.unit == spec.unit


@given(name=st.sampled_from(POSITIVE), value=bad_positive)
def test_positive_parameters_reject_nonpositive_and_nonfinite(name, value):
    check_rejected(name, value)


@given(name=st.sampled_from(NONNEGATIVE), value=bad_nonnegative)
def test_nonnegative_parameters_reject_negative_and_nonfinite(name, value):
    check_rejected(name, value)


@given(name=st.sampled_from(FINITE_ONLY), value=st.sampled_from(NON_FINITE))
def test_finite_parameters_reject_nonfinite(name, value):
    check_rejected(name, value)


@st.composite
def valid_value(draw):
    name = draw(st.sampled_from(list(PARAMETERS)))
    rule = PARAMETERS[name].rule
    value = draw(
        st.floats(
            min_value=rule.lower,
            max_value=rule.upper,
            exclude_min=rule.lower is not None and rule.lower_strict,
            exclude_max=rule.upper is not None and rule.upper_strict,
            allow_nan=False,
            allow_infinity=False,
        )
    )
    return name, value


@settings(suppress_health_check=[HealthCheck.filter_too_much])
@given(valid_value())
def test_valid_values_accepted(name_value):
    """A value its parameter's rule accepts is accepted, unless a use of the parameter in
    the layout finds it implausible (a 1 kg car body, a 1e300 m bogie distance): then it is
    refused naming the range and how to take it on purpose, and taken with ``allow``. Two
    wheelsets closer than their wheels, or a load that overflows, are refused either way."""
    import dataclasses

    from railhunt.layout.spec import LayoutError

    name, value = name_value
    assert validate_value(name, value) == value
    if name == "l":
        assume(value > PAPER.l1)
    if name == "l1":
        assume(value < PAPER.l)
    physical = ("would overlap", "= inf is invalid")  # refused with or without allow
    try:
        changed = PAPER.replace(**{name: value})
    except LayoutError as exc:
        if any(text in str(exc) for text in physical):
            return
        assert "is implausible" in str(exc) and "allow = true" in str(exc), str(exc)
        allowed = dataclasses.replace(PAPER.layout, allowed=frozenset({name}))
        try:
            changed = PAPER.replace(layout=allowed, **{name: value})
        except LayoutError as again:
            assert any(text in str(again) for text in physical), str(again)
            return
    assert getattr(changed, name) == value


@given(st.floats(min_value=1e-3, max_value=1e9), st.floats(min_value=1e-3, max_value=1e9))
def test_v_u_follows_f_u_and_c_d1(f_u, c_d1):
    v = PAPER.replace(F_u=f_u, C_d1=c_d1)
    assert v.v_u == f_u / c_d1


# --------------------------------------------------------------------------- TOML files


def test_round_trip(tmp_path):
    path = PAPER.to_toml(tmp_path / "out.toml")
    back = load_vehicle(path)
    assert back == PAPER
    assert back.description == PAPER.description
    assert back.as_dict() == PAPER.as_dict()


def test_round_trip_awkward_values_and_text(tmp_path):
    v = PAPER.replace(
        name='odd "name" \\ ü',
        description="line1\nline2\ttab \x7f end",
        C_px=1e-300,
        d0=-0.0,
        d5=0.1 + 0.2,
        lambda3=1e16,
    )
    back = load_vehicle(v.to_toml(tmp_path / "odd.toml"))
    assert back == v and back.description == v.description
    assert all(getattr(back, k) == getattr(v, k) for k in PARAMETERS)


def test_shipped_file_loads_through_load_vehicle():
    from importlib import resources

    path = resources.files("railhunt") / "data" / "vehicles" / "paper2019.toml"
    assert load_vehicle(str(path)) == PAPER


def test_base_partial_file(tmp_path):
    path = write(
        tmp_path,
        """
[vehicle]
name = "stiff"
base = "paper2019"

[parameters]
C_d1 = 600000.0
K_d = 20000000

[parameters.mu]
value = 0.2
unit = "1"
""",
    )
    v = load_vehicle(path)
    assert v.name == "stiff"
    assert v.C_d1 == 600e3 and v.K_d == 2e7 and v.mu == 0.2
    assert v.M_c == PAPER.M_c
    assert v == PAPER.replace(name="stiff", C_d1=600e3, K_d=2e7, mu=0.2)


def test_base_only_and_default_name(tmp_path):
    v = load_vehicle(write(tmp_path, '[vehicle]\nbase = "paper2019"\n', "mycar.toml"))
    assert v.name == "mycar"
    assert v.as_dict() == PAPER.as_dict()


def test_unknown_base(tmp_path):
    with pytest.raises(VehicleFileError, match="paper2019"):
        load_vehicle(write(tmp_path, '[vehicle]\nbase = "paper2020"\n'))


def test_missing_parameters_listed(tmp_path):
    path = write(tmp_path, '[vehicle]\nname = "x"\n[parameters]\nM_c = 28000.0\nM_t = 3000.0\n')
    with pytest.raises(MissingParametersError) as info:
        load_vehicle(path)
    err = info.value
    assert len(err.missing) == 51
    assert "M_w" in err.missing and "M_c" not in err.missing
    msg = str(err)
    assert str(path) in msg
    for name in err.missing:
        assert name in msg
    assert "base" in msg


def test_unit_mismatch(tmp_path):
    """A unit of the parameter's dimension is converted (300 kN*s/m is 3e5 N*s/m); one of
    another dimension, or an unknown one, is refused naming both units."""
    path = write(
        tmp_path,
        '[vehicle]\nbase = "paper2019"\n[parameters.C_d1]\nvalue = 300.0\nunit = "kN*s/m"\n',
    )
    assert load_vehicle(path).C_d1 == 3e5
    for unit in ("kN/m", "lbf*s/in"):
        path = write(
            tmp_path,
            f'[vehicle]\nbase = "paper2019"\n[parameters.C_d1]\nvalue = 300.0\nunit = "{unit}"\n',
        )
        with pytest.raises(ParameterError) as info:
            load_vehicle(path)
        msg = str(info.value)
        assert info.value.parameter == "C_d1"
        assert unit in msg and ("'N*s/m'" in msg or "not a unit railhunt knows" in msg)


def test_matching_unit_accepted(tmp_path):
    path = write(
        tmp_path,
        '[vehicle]\nbase = "paper2019"\n[parameters.C_d1]\nvalue = 3e5\nunit = "N*s/m"\n'
        'meaning = "x"\nsource = "me"\n',
    )
    assert load_vehicle(path).C_d1 == 3e5


def test_table_without_value_or_with_unknown_key(tmp_path):
    with pytest.raises(ParameterError, match="value"):
        load_vehicle(
            write(tmp_path, '[vehicle]\nbase = "paper2019"\n[parameters.M_c]\nunit = "kg"\n')
        )
    with pytest.raises(ParameterError, match="valeu"):
        load_vehicle(
            write(tmp_path, '[vehicle]\nbase = "paper2019"\n[parameters.M_c]\nvaleu = 1.0\n')
        )


def test_derived_values_checked(tmp_path):
    ok = write(tmp_path, '[vehicle]\nbase = "paper2019"\n[parameters]\nv_u = 0.01\nN = 53410\n')
    assert load_vehicle(ok) == PAPER.replace(name="vehicle")

    bad = write(tmp_path, '[vehicle]\nbase = "paper2019"\n[parameters]\nv_u = 0.02\n', "bad.toml")
    with pytest.raises(ParameterError) as info:
        load_vehicle(bad)
    msg = str(info.value)
    assert info.value.parameter == "v_u"
    assert "0.02" in msg and "0.01" in msg and "F_u / C_d1" in msg

    # the paper's rounding of N is within the 1e-3 tolerance; 1 % off is not
    near = write(tmp_path, '[vehicle]\nbase = "paper2019"\n[parameters]\nN = 53400.0\n', "n.toml")
    assert load_vehicle(near).N == pytest.approx(53410.0)
    far = write(tmp_path, '[vehicle]\nbase = "paper2019"\n[parameters]\nN = 54000.0\n', "f.toml")
    with pytest.raises(ParameterError, match="54000") as info:
        load_vehicle(far)
    assert "53410" in str(info.value)


def test_derived_checked_against_overridden_values(tmp_path):
    path = write(
        tmp_path,
        '[vehicle]\nbase = "paper2019"\n[parameters]\nC_d1 = 600000.0\n'
        '[parameters.v_u]\nvalue = 0.005\nunit = "m/s"\n',
    )
    assert load_vehicle(path).v_u == pytest.approx(0.005)


def test_unknown_name_suggestion_in_file(tmp_path):
    path = write(tmp_path, '[vehicle]\nbase = "paper2019"\n[parameters]\nC_dl = 3e5\n')
    with pytest.raises(UnknownParameterError) as info:
        load_vehicle(path)
    assert "C_d1" in info.value.suggestions
    assert "did you mean" in str(info.value) and "'C_d1'" in str(info.value)


@pytest.mark.parametrize("text", ['"28000"', "true", "[1.0]", "1979-05-27", "nan", "inf"])
def test_non_numeric_or_nonfinite_in_file(tmp_path, text):
    path = write(tmp_path, f'[vehicle]\nbase = "paper2019"\n[parameters]\nM_c = {text}\n')
    with pytest.raises(ParameterError) as info:
        load_vehicle(path)
    assert info.value.parameter == "M_c"
    assert str(info.value).startswith(f"{path}: M_c = ")


def test_out_of_range_in_file(tmp_path):
    path = write(tmp_path, '[vehicle]\nbase = "paper2019"\n[parameters]\nr0 = 430\n')
    with pytest.raises(ParameterError, match="r0 = 430 m is invalid"):
        load_vehicle(path)


def test_file_structure_errors(tmp_path):
    with pytest.raises(VehicleFileError, match="TOML"):
        load_vehicle(write(tmp_path, "[vehicle\n"))
    with pytest.raises(VehicleFileError, match="extra"):
        load_vehicle(write(tmp_path, '[vehicle]\nbase = "paper2019"\n[extra]\nx = 1\n'))
    with pytest.raises(VehicleFileError, match="colour"):
        load_vehicle(write(tmp_path, '[vehicle]\nbase = "paper2019"\ncolour = "red"\n'))
    with pytest.raises(VehicleFileError, match="string"):
        load_vehicle(write(tmp_path, "[vehicle]\nname = 3\n"))


def test_parameter_table():
    rows = PAPER.parameter_table()
    assert len(rows) == 56
    assert rows[0] == ("M_c", 28000.0, "kg", "Car body mass")
    names = [r[0] for r in PAPER.parameter_table(include_derived=True)]
    assert names[-2:] == ["v_u", "N"]


def test_as_dict_is_a_copy():
    d = PAPER.as_dict()
    d["M_c"] = -1.0
    assert PAPER.M_c == 28000.0
    assert list(d) == list(PARAMETERS)


# --------------------------------------------------------------------------- the table


def test_shipped_files_agree_with_the_table():
    """Every shipped file of the paper's layout lists every parameter in table order, in
    the table's units; paper2019.toml also repeats the table's meanings (the s1002 files
    refine some). Other layouts have their own tables (tests/test_layouts.py)."""
    import tomllib
    from importlib import resources

    from railhunt.vehicle import shipped_vehicles

    folder = resources.files("railhunt") / "data" / "vehicles"
    assert "paper2019" in shipped_vehicles()
    paper = [n for n in shipped_vehicles() if Vehicle.shipped(n).layout == PAPER.layout]
    assert {"paper2019", "s1002_uic60", "s1002_uic60_table"} <= set(paper)
    for name in paper:
        entries = tomllib.loads((folder / f"{name}.toml").read_text(encoding="utf-8"))[
            "parameters"
        ]
        assert list(entries) == list(PARAMETERS), name
        for key, spec in PARAMETERS.items():
            assert entries[key]["unit"] == spec.unit, (name, key)
            if name == "paper2019":
                assert entries[key]["meaning"] == spec.meaning, key
        assert Vehicle.shipped(name).as_dict() == {k: float(e["value"]) for k, e in
                                                  entries.items()}  # fmt: skip


def test_parameter_table_is_the_vehicle_fields():
    from railhunt.vehicle.parameters import VehicleFields

    names = [f.name for f in dataclasses.fields(VehicleFields)]
    assert names[3:] == list(Vehicle.paper2019().values)
    assert names[:3] == ["name", "description", "contact"] and names[3:] == list(PARAMETERS)
    # The paper's parameters are required; those added later (the bump stop) have defaults,
    # so vehicle files written before them still load.
    later = {"y_bs": 0.03, "K_bs": 1.0e6, "K_bs3": 5.0e9}
    assert {n: s.default for n, s in PARAMETERS.items() if s.default is not None} == later
    with pytest.raises(TypeError, match="build a Vehicle"):
        VehicleFields(**PAPER.as_dict())


def test_docs_page_holds_the_markdown_table():
    from pathlib import Path

    from railhunt.vehicle import parameter_markdown

    table = parameter_markdown()
    lines = table.splitlines()
    assert len(lines) == 2 + len(PARAMETERS) + len(DERIVED)
    assert lines[0] == "| name | unit | meaning | rule | paper2019 |"
    assert lines[2] == "| `M_c` | kg | Car body mass | finite and > 0 | 28000 |"
    assert lines[-2].startswith("| `v_u` | m/s | blow-off velocity of the yaw damper |")
    page = Path(__file__).parent.parent / "docs" / "parameters.md"
    text = page.read_text(encoding="utf-8")
    begin = "<!-- BEGIN parameter table: railhunt.vehicle.parameter_markdown() -->\n"
    end = "<!-- END parameter table -->"
    assert text[text.index(begin) + len(begin):text.index(end)] == table, (
        "docs/parameters.md is out of date: paste the output of "
        "python -c 'from railhunt.vehicle import parameter_markdown as m; print(m(), end=\"\")'"
    )


def test_a_parameter_with_a_default_is_optional():
    """The mechanism for parameters added later, on a test-only table."""
    from railhunt.vehicle import NONNEGATIVE as AT_LEAST_ZERO
    from railhunt.vehicle import POSITIVE as ABOVE_ZERO
    from railhunt.vehicle import parameter
    from railhunt.vehicle.rules import parameter_specs

    @dataclasses.dataclass(frozen=True, kw_only=True)
    class Table:
        name: str = "t"
        old: float = parameter("kg", ABOVE_ZERO, "A parameter from the start")
        new: float = parameter("m", AT_LEAST_ZERO, "Added later", default=0)

    specs = parameter_specs(Table)
    assert list(specs) == ["old", "new"]
    assert specs["old"].default is None
    assert specs["new"].default == 0.0 and isinstance(specs["new"].default, float)
    assert specs["new"] == ("new", "m", "Added later", AT_LEAST_ZERO, 0.0)
    assert Table(old=1.0).new == 0.0
    with pytest.raises(TypeError):
        Table(new=1.0)  # old has no default
    with pytest.raises(ValueError, match="breaks the rule"):
        parameter("m", ABOVE_ZERO, "x", default=0.0)


@pytest.fixture
def delta_max_with_default(monkeypatch):
    """PARAMETERS as if delta_max had been added with a default after files existed."""
    import sys
    from types import MappingProxyType

    table = dict(PARAMETERS)
    table["delta_max"] = table["delta_max"]._replace(default=1.2)
    patched = MappingProxyType(table)
    for module in list(sys.modules.values()):
        if module.__name__.startswith("railhunt.vehicle") and hasattr(module, "PARAMETERS"):
            monkeypatch.setattr(module, "PARAMETERS", patched)
    return patched


def test_files_written_before_a_parameter_existed_still_load(tmp_path, delta_max_with_default):
    text = PAPER.to_toml(tmp_path / "full.toml").read_text(encoding="utf-8")
    old = text[: text.index("[parameters.delta_max]")]  # a complete file of an older version
    v = load_vehicle(write(tmp_path, old, "old.toml"))
    assert v.delta_max == 1.2
    assert v == PAPER.replace(delta_max=1.2)
    params = PAPER.as_dict()
    del params["delta_max"]
    assert validate_all(params)["delta_max"] == 1.2
    del params["d5"]
    with pytest.raises(MissingParametersError) as info:
        validate_all(params)
    assert info.value.missing == ("d5",)
    no_d5 = old[: old.index("[parameters.d5]")]
    with pytest.raises(MissingParametersError) as info:
        load_vehicle(write(tmp_path, no_d5, "older.toml"))
    assert info.value.missing == ("d5",)
    # a file with a base still takes the base's value
    based = load_vehicle(write(tmp_path, '[vehicle]\nbase = "paper2019"\n', "based.toml"))
    assert based.delta_max == PAPER.delta_max
