"""The worked examples in examples/ run as notebooks, the way a reader runs them.

Each ``examples/NN_name.py`` is a Jupyter notebook in jupytext's percent format. Here it is
converted (jupytext) and executed cell by cell in a fresh Jupyter kernel (nbclient), with
the examples folder as the working directory, as ``jupyter lab`` would. Every number an
example's text quotes is asserted in its own cells, so an example whose results drift
fails here. Measured on this 2-core machine (shared with other jobs; two runs): 01 5-10 s,
02 8-17 s, 03 14-25 s, 04 4-5 s, 05 29-39 s (Dask start-up and numba warm-up), 06 7-10 s,
07 6-8 s; 73-114 s in all.
"""

from __future__ import annotations

import re
from pathlib import Path

import jupytext
import nbclient
import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES_DIR = ROOT / "examples"
EXAMPLES = sorted(EXAMPLES_DIR.glob("[0-9][0-9]_*.py"))
#: The examples that take longer than 20 s (still part of the default run).
SLOW = {"03_bifurcation_diagram", "05_parameter_study_dask"}


def _files_in(folder: Path) -> set[Path]:
    return {p for p in folder.rglob("*") if "__pycache__" not in p.parts
            and ".ipynb_checkpoints" not in p.parts}  # fmt: skip


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
    nb = jupytext.read(path)
    before = _files_in(EXAMPLES_DIR)
    client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(EXAMPLES_DIR)}})
    client.execute()  # raises CellExecutionError with the failing cell and its traceback
    shown = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert any("text/html" in o.get("data", {}) for o in shown), (
        "the notebook shows no HTML table (a result's or a DataFrame's)")
    assert _files_in(EXAMPLES_DIR) == before, "the example wrote into examples/"


def test_the_examples_readme_lists_every_example() -> None:
    readme = (EXAMPLES_DIR / "README.md").read_text(encoding="utf-8")
    for path in EXAMPLES:
        assert f"]({path.name})" in readme, f"examples/README.md does not link {path.name}"
