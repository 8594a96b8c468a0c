"""The package's structure: kernel boundary, named state slots, file sizes.

These checks read the sources (no physics): the compiled kernel imports nothing from the
object layer above it, no module outside the state layout indexes the state with literal
offsets, and no source file grows past 600 lines.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "railhunt"
KERNEL = SRC / "kernel"
MAX_LINES = 600


def _sources(root: Path) -> list[Path]:
    return sorted(p for p in root.rglob("*.py") if "__pycache__" not in p.parts)


def _imported_modules(path: Path) -> list[tuple[int, str]]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:  # relative import: resolve against the kernel package
                out.append((node.lineno, "railhunt.kernel." + (node.module or "")))
            else:
                out.append((node.lineno, node.module or ""))
    return out


@pytest.mark.parametrize("path", _sources(KERNEL), ids=lambda p: p.name)
def test_the_kernel_imports_nothing_above_it(path: Path) -> None:
    allowed_third_party = {"numpy", "numba"}
    for line, module in _imported_modules(path):
        top = module.split(".")[0]
        if top == "railhunt":
            assert module == "railhunt.kernel" or module.startswith("railhunt.kernel."), (
                f"{path.relative_to(SRC)}:{line} imports {module}: the kernel may import only "
                "railhunt.kernel.*"
            )
        else:
            assert top in allowed_third_party or top in sys.stdlib_module_names or (
                top == "__future__"
            ), f"{path.relative_to(SRC)}:{line} imports {module}"


def test_importing_the_kernel_loads_no_object_layer_module() -> None:
    import subprocess

    code = (
        "import sys, railhunt.kernel.rhs, railhunt.kernel.integrators, railhunt.kernel.flow; "
        "print(sorted(m for m in sys.modules if m.startswith('railhunt')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded = eval(out.stdout)  # a list literal of module names
    outside = [m for m in loaded if not m.startswith("railhunt.kernel")
               and m not in ("railhunt", "railhunt._cache", "railhunt._version")]  # fmt: skip
    assert outside == []


# Literal indices of the 17-DOF state: 9 (y_w1), 17 (first rate), 34 (first damper force),
# 38 (state length). Inside a subscript they mean a state slot, which only the layout
# module may spell out.
_STATE_LITERALS = {9, 17, 34, 38}
_EXEMPT = {KERNEL / "layout.py"}


def _literal_subscripts(path: Path) -> list[tuple[int, int]]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    hits = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Subscript):
            for sub in ast.walk(node.slice):
                if (isinstance(sub, ast.Constant) and type(sub.value) is int
                        and sub.value in _STATE_LITERALS):  # fmt: skip
                    hits.append((sub.lineno, sub.value))
    return hits


@pytest.mark.parametrize("path", [p for p in _sources(SRC) if p not in _EXEMPT],
                         ids=lambda p: str(p.relative_to(SRC)))  # fmt: skip
def test_no_literal_state_offsets_outside_the_layout(path: Path) -> None:
    assert _literal_subscripts(path) == [], (
        f"{path.relative_to(SRC)} indexes with literal state offsets; use the names in "
        "railhunt.kernel.layout"
    )


def test_the_offset_check_can_fail(tmp_path: Path) -> None:
    bad = tmp_path / "bad.py"
    bad.write_text("x = [0] * 40\ny = x[34:38]\nz = x[9 + 2 * 1]\n")
    assert sorted(v for _, v in _literal_subscripts(bad)) == [9, 34, 38]


@pytest.mark.parametrize("path", _sources(SRC), ids=lambda p: str(p.relative_to(SRC)))
def test_no_source_file_over_600_lines(path: Path) -> None:
    n = len(path.read_text(encoding="utf-8").splitlines())
    assert n <= MAX_LINES, f"{path.relative_to(SRC)} has {n} lines: split it by theme"


def test_every_package_folder_says_what_lives_there() -> None:
    for init in SRC.rglob("__init__.py"):
        doc = ast.get_docstring(ast.parse(init.read_text(encoding="utf-8")))
        assert doc, f"{init.relative_to(SRC)} has no docstring"


# The floors of the object layer, lowest first. A module may import modules of its own
# floor or below; the command line is the top floor and reads the package's public names.
_FLOORS = {"analysis": 1, "studies": 2, "plots": 2, "cli": 3}


def _floor(module: str) -> int | None:
    parts = module.split(".")
    return _FLOORS.get(parts[1]) if len(parts) > 1 and parts[0] == "railhunt" else None


def _absolute_imports(path: Path) -> list[tuple[int, str, list[str]]]:
    """(line, module, imported names) of every import of ``path``, relative ones resolved."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = ["railhunt", *path.relative_to(SRC).parts[:-1]]
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, alias.name, []) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            module = ".".join([*base, node.module] if node.module else base)
            out.append((node.lineno, module, [a.name for a in node.names]))
    return out


def _is_submodule(name: str) -> bool:
    return (SRC / f"{name}.py").exists() or (SRC / name / "__init__.py").exists()


def _upstream_imports(path: Path) -> list[str]:
    """The imports of ``path`` that climb: the package's top level from inside it, or a
    module on a higher floor of the object layer."""
    rel = path.relative_to(SRC)
    if rel.parts[0] == "cli" or rel == Path("__init__.py"):
        return []
    own = _FLOORS.get(rel.parts[0], 0) if len(rel.parts) > 1 else 0
    bad = []
    for line, module, names in _absolute_imports(path):
        if module == "railhunt":
            top = [n for n in names if not _is_submodule(n)] if names else ["railhunt"]
            if top or (rel.parts[0] == "studies" and names):
                names_ = ', '.join(names or top)
                bad.append(f"{rel}:{line} imports the package's top level ({names_})")
        floor = _floor(module)
        if floor is not None and floor > own and module.split(".")[1] != rel.parts[0]:
            bad.append(f"{rel}:{line} imports {module}, a floor above it")
    return bad


@pytest.mark.parametrize("path", _sources(SRC), ids=lambda p: str(p.relative_to(SRC)))
def test_imports_run_downhill(path: Path) -> None:
    assert _upstream_imports(path) == []


def test_analysis_and_plots_of_one_theme_do_not_import_each_other() -> None:
    analysis = {m for _, m, _ in _absolute_imports(SRC / "analysis" / "spectrogram.py")}
    assert "railhunt.plots.spectrogram" not in analysis


def test_the_downhill_check_can_fail(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    fake = tmp_path / "railhunt"
    for folder, text in {
        "studies": "import railhunt\nfrom railhunt import paper2019\n",
        "analysis": "from railhunt.plots.figure import new_figure\nfrom ..cli import app\n",
    }.items():
        (fake / folder).mkdir(parents=True)
        (fake / folder / "x.py").write_text(text)
    (fake / "paper2019").mkdir()
    (fake / "paper2019" / "__init__.py").write_text("")
    monkeypatch.setattr(sys.modules[__name__], "SRC", fake)
    assert len(_upstream_imports(fake / "studies" / "x.py")) == 2
    assert len(_upstream_imports(fake / "analysis" / "x.py")) == 2
