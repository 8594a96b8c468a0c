"""MkDocs hook: the worked examples become pages of the site.

Each ``examples/NN_name.py`` is a notebook in jupytext's percent format. Its Markdown cells
become the page's text and its code cells Python code blocks; the ``.py`` file itself is
copied beside the page for download. ``examples/README.md`` is the section's index page.
Nothing is executed here (the build stays fast and offline): the test suite runs every
notebook (``tests/test_examples.py``).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import jupytext
from mkdocs.structure.files import File, Files

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

_RUN = """\
!!! note "Run this example"
    This page is the notebook [`examples/{name}`]({name}) (jupytext percent format:
    plain Python with `# %%` cells). From the repository's root:

    ```bash
    pip install -e '.[notebooks]' jupyterlab   # railhunt, jupytext, pandas, xarray
    cd examples && jupytext --to ipynb {name}   # or open {name} in JupyterLab directly
    ```

    Its input files are in `examples/data/`. The outputs (tables, figures) appear when you
    run it; every number the text quotes is checked by an `assert` in the notebook, and
    the test suite runs it.
"""


def example_paths() -> list[Path]:
    """The example notebooks, in order."""
    return sorted(EXAMPLES.glob("[0-9][0-9]_*.py"))


def page(path: Path) -> str:
    """The Markdown page of one example notebook."""
    nb = jupytext.read(path)
    parts = [f"<!-- generated from examples/{path.name} by docs/_hooks/examples.py -->"]
    for i, cell in enumerate(nb.cells):
        source = cell.source.strip("\n")
        if cell.cell_type == "markdown":
            parts.append(source)
        elif source:
            parts.append(f"```python\n{source}\n```")
        if i == 0:
            parts.append(_RUN.format(name=path.name))
    return "\n\n".join(parts) + "\n"


def index() -> str:
    """The section's index: examples/README.md with its links pointing at the pages."""
    text = (EXAMPLES / "README.md").read_text(encoding="utf-8")
    return re.sub(r"\]\((\d\d_[\w]+)\.py\)", r"](\1.md)", text)


def on_files(files: Files, config: Any) -> Files:
    """Add one page and one download per example, and the index page."""
    for path in example_paths():
        files.append(File.generated(config, f"examples/{path.stem}.md", content=page(path)))
        files.append(File.generated(config, f"examples/{path.name}",
                                    content=path.read_text(encoding="utf-8")))  # fmt: skip
    files.append(File.generated(config, "examples/index.md", content=index()))
    return files
