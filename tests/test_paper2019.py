"""Tests of the paper's home (railhunt.paper2019) and of the studies modules' layout."""

from __future__ import annotations

import ast
import subprocess
import sys
from importlib import resources
from pathlib import Path

import pytest

import railhunt
from railhunt import paper2019
from railhunt.paper2019.expected import KINDS, OUTPUTS, _parse_row

SRC = Path(railhunt.__file__).resolve().parent
PAPER_HOME = SRC / "paper2019"
#: The modules that hold the reproduction's steps (what to compute, how to plot).
STEP_MODULES = ("reproduce.py", "reproduce_fig6_8.py", "reproduce_fig10_12.py",
                "reproduce_fig13.py")  # fmt: skip


# --------------------------------------------------------------------------- the paper home


def test_the_paper_home_holds_the_paper():
    assert paper2019.CITATION == (
        "Numerical Investigation into the Critical Speed and Frequency of the Hunting Motion "
        "in Railway Vehicle System (Mathematical Problems in Engineering, 2019)"
    )
    assert paper2019.vehicle().name == "paper2019"
    assert paper2019.vehicle() == railhunt.Vehicle.paper2019()
    assert list(paper2019.TABLE1) == ["C_d1", "K_d", "C_d2", "mu", "K_px", "f11", "C_sy"]
    assert paper2019.TABLE1 is paper2019.load_table1()
    assert set(paper2019.CAPTIONS) == {f"fig{n}" for n in (6, 7, 8, 10, 11, 12, 13)}
    assert paper2019.NO_BLOWOFF == 1e12
    # The compatible names are the paper home's own objects.
    from railhunt.studies import sections

    assert railhunt.load_table1 is sections.load_table1 is paper2019.load_table1
    assert sections.Table1Parameter is paper2019.Table1Parameter


def test_every_expected_row_quotes_the_paper():
    expected = paper2019.EXPECTED
    quotations = set(paper2019.QUOTATIONS.values())
    notes = set(paper2019.NOTES.values())
    assert len(expected) == 36
    for key, row in expected.items():
        assert row.key == key and row.kind in KINDS
        assert row.quote in quotations, key
        assert row.note == "" or row.note in notes, key
        if row.kind == "number":
            assert isinstance(row.paper, float) and 0 < row.rel_tol <= 0.05, key
        if row.kind in ("trend", "bound"):
            assert row.line in paper2019.TABLE1 and row.output in OUTPUTS, key
    # Every quotation and note is used by a row.
    assert quotations == {row.quote for row in expected.values()}
    assert notes == {row.note for row in expected.values()} - {""}
    # The headline numbers of Sec. 4, as the paper prints them.
    assert {k: expected[k].paper for k in ("nonlinear_critical_speed_kmh",
                                           "linear_critical_speed_kmh", "point_p_kmh",
                                           "frequency_q1_hz", "frequency_q2_hz",
                                           "period_below_blowoff_s", "period_above_blowoff_s")} \
        == {"nonlinear_critical_speed_kmh": 321.0, "linear_critical_speed_kmh": 440.0,
            "point_p_kmh": 375.0, "frequency_q1_hz": 4.0, "frequency_q2_hz": 5.3,
            "period_below_blowoff_s": 0.25, "period_above_blowoff_s": 0.19}  # fmt: skip
    assert expected["fig12a_dvcr_K_px_kmh"].bound == ("<", 50.0)
    for key in ("nonlinear_critical_speed_kmh", "point_p_kmh", "fig10a_jump_cd1"):
        assert f"{expected[key].paper:g}" in expected[key].quote, key


def test_a_broken_row_is_an_installation_error():
    good = {"kind": "number", "quantity": "q", "where": "Fig. 6", "unit": "km/h",
            "paper": 321.0, "quote": "fig6_critical_speed", "rel_tol": 0.03, "digits": 0}
    assert _parse_row("k", good).paper == 321.0
    for change, why in (({"quote": "nowhere"}, "quote"), ({"kind": "guess"}, "kind"),
                        ({"paper": "321"}, "number"), ({"colour": "red"}, "unknown"),
                        ({"note": "nowhere"}, "note")):  # fmt: skip
        with pytest.raises(RuntimeError, match=f"installation error: expected.toml.*{why}"):
            _parse_row("k", {**good, **change})


def test_the_data_files_are_package_data():
    names = {p.name for p in resources.files("railhunt.paper2019").iterdir()}
    assert {"table1.toml", "paper.toml", "expected.toml"} <= names
    import tomllib

    pyproject = tomllib.loads((SRC.parents[1] / "pyproject.toml").read_text(encoding="utf-8"))
    assert "paper2019/*.toml" in pyproject["tool"]["setuptools"]["package-data"]["railhunt"]


# --------------------------------------------------------------------------- one home only


def _string_constants(path: Path) -> list[str]:
    """Every string literal of a source file (implicitly joined pieces as one)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return [n.value for n in ast.walk(tree) if isinstance(n, ast.Constant)
            and isinstance(n.value, str)]  # fmt: skip


def _numbers(path: Path) -> set[float]:
    """Every float literal of a source file, and every integer from 10 up (not small counts)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    values = [n.value for n in ast.walk(tree) if isinstance(n, ast.Constant)]
    return {float(v) for v in values if isinstance(v, float)
            or (isinstance(v, int) and not isinstance(v, bool) and v >= 10)}  # fmt: skip


def test_only_the_paper_home_holds_the_papers_words():
    """No source outside railhunt/paper2019 quotes the paper (sentences, captions, title)
    or repeats railhunt's notes on the differences."""
    texts = [*paper2019.QUOTATIONS.values(), *paper2019.CAPTIONS.values(),
             *paper2019.NOTES.values(), paper2019.CITATION]  # fmt: skip
    offenders = []
    for path in sorted(SRC.rglob("*.py")):
        if PAPER_HOME in path.parents:
            continue
        for literal in _string_constants(path):
            if len(literal) >= 25 and any(literal in text for text in texts):
                offenders.append((path.relative_to(SRC).as_posix(), literal[:60]))
    assert not offenders, offenders


def test_the_steps_hold_no_expected_number():
    """The paper's numbers (321 km/h, 5.3 Hz, 0.19 s ...) come from the paper home."""
    paper_numbers = {row.paper for row in paper2019.EXPECTED.values() if row.kind == "number"}
    for name in STEP_MODULES:
        path = SRC / "studies" / name
        clash = _numbers(path) & paper_numbers
        assert not clash, f"{name} writes the paper's number(s) {sorted(clash)} as literals"


def test_no_blowoff_is_defined_once():
    holders = []
    for path in sorted(SRC.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if (isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant)
                    and node.value.value == 1e12):  # fmt: skip
                holders.append(path.relative_to(SRC).as_posix())
    assert holders == ["paper2019/__init__.py"]


# --------------------------------------------------------------------------- no import cycle


def _studies_modules() -> dict[str, Path]:
    modules = {}
    for folder in ("studies", "paper2019"):
        for path in sorted((SRC / folder).glob("*.py")):
            name = f"railhunt.{folder}"
            modules[name if path.stem == "__init__" else f"{name}.{path.stem}"] = path
    return modules


def _imports(path: Path) -> set[str]:
    """Every module a file imports, wherever the import stands (functions, TYPE_CHECKING)."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            out.add(node.module)
            out.update(f"{node.module}.{alias.name}" for alias in node.names)
    return out


def test_no_import_cycle_between_studies_modules():
    modules = _studies_modules()
    graph = {name: sorted(_imports(path) & set(modules) - {name})
             for name, path in modules.items()}  # fmt: skip
    # report.py writes HTML and knows nothing of the steps.
    assert not any(m.startswith("railhunt.studies.reproduce")
                   for m in graph["railhunt.studies.report"])  # fmt: skip
    state: dict[str, int] = {}

    def visit(name: str, path: list[str]) -> None:
        state[name] = 1
        for nxt in graph[name]:
            if state.get(nxt) == 1:
                raise AssertionError("import cycle: " + " -> ".join([*path, name, nxt]))
            if nxt not in state:
                visit(nxt, [*path, name])
        state[name] = 2

    for name in graph:
        if name not in state:
            visit(name, [])


def test_each_studies_module_imports_alone():
    """In a fresh interpreter each module imports on its own (no order dependence)."""
    for name in _studies_modules():
        result = subprocess.run([sys.executable, "-c", f"import {name}"], capture_output=True,
                                text=True, check=False)  # fmt: skip
        assert result.returncode == 0, (name, result.stderr[-2000:])
