"""The worked examples in examples/ run as notebooks, the way a reader runs them.

Each ``examples/NN_name.py`` is a Jupyter notebook in jupytext's percent format. It is
converted (jupytext) and executed cell by cell in a fresh Jupyter kernel (nbclient), with
the examples folder as the working directory, as ``jupyter lab`` would
(``docs/_hooks/notebooks.py``). Every number an example's text quotes is asserted in its own
cells, so an example whose results drift fails here. The executed notebooks are kept in
``$RAILHUNT_EXECUTED_EXAMPLES`` (``build/examples`` when unset) with a fingerprint of the
example, its data, the package's source and the installed versions: ``.ci/run`` executes
every example once, before the documentation build, and this test and the site reuse that
run; a notebook whose fingerprint no longer matches is executed again here.
``python docs/_hooks/notebooks.py`` prints each example's time.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import jupytext
import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES_DIR = ROOT / "examples"
EXAMPLES = sorted(EXAMPLES_DIR.glob("[0-9][0-9]_*.py"))
sys.path.insert(0, str(ROOT / "docs" / "_hooks"))

import notebooks  # noqa: E402

#: The examples that take longer than 20 s (still part of the default run).
SLOW = {"03_bifurcation_diagram", "05_parameter_study_dask"}


def test_there_are_at_least_seven_examples() -> None:
    names = [p.stem for p in EXAMPLES]
    assert len(names) >= 7, names
    assert len({n[:2] for n in names}) == len(names), "two examples share a number"


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_is_a_percent_notebook_with_a_title(path: Path) -> None:
    nb = jupytext.read(path)
    assert nb.metadata["jupytext"]["formats"] == "py:percent"
    first = nb.cells[0]
    assert first.cell_type == "markdown" and first.source.startswith("# "), first.source[:80]
    assert sum(c.cell_type == "code" for c in nb.cells) >= 3


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_data_file_an_example_names_ships(path: Path) -> None:
    names = set(re.findall(r"""["'](data/[\w./-]+)["']""", path.read_text(encoding="utf-8")))
    for name in names:
        assert (EXAMPLES_DIR / name).is_file(), f"{path.name} reads {name}, which does not exist"


@pytest.mark.parametrize(
    "path",
    [pytest.param(p, marks=pytest.mark.slow) if p.stem in SLOW else p for p in EXAMPLES],
    ids=lambda p: p.stem,
)
def test_example_runs_as_a_notebook(path: Path) -> None:
    # Raises CellExecutionError with the failing cell and its traceback.
    nb = notebooks.executed(path)
    assert nb.metadata["railhunt"]["fingerprint"] == notebooks.fingerprint(path)
    shown = notebooks.outputs(nb)
    assert not [o for o in shown if o["output_type"] == "error"]
    assert any("text/html" in o.get("data", {}) for o in shown), (
        "the notebook shows no HTML table (a result's or a DataFrame's)")
    assert any("image/png" in o.get("data", {}) for o in shown), (
        "the notebook shows no figure (is the kernel's matplotlib backend inline?)")
    assert nb.metadata["railhunt"]["wrote"] == [], "the example wrote into examples/"


def test_the_examples_are_found_without_a_list() -> None:
    assert notebooks.example_paths() == EXAMPLES


def test_the_examples_readme_lists_every_example() -> None:
    readme = (EXAMPLES_DIR / "README.md").read_text(encoding="utf-8")
    for path in EXAMPLES:
        assert f"]({path.name})" in readme, f"examples/README.md does not link {path.name}"
