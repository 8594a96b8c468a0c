"""MkDocs hook: the worked examples become pages of the site, with their outputs.

Each ``examples/NN_name.py`` is a notebook in jupytext's percent format. Its Markdown cells
become the page's text, its code cells Python code blocks, and below each code cell come
the outputs that cell produced when the notebook was executed: printed text, HTML tables
(results, DataFrames) and figures (PNG files written beside the page). The executed
notebooks come from ``docs/_hooks/notebooks.py``: reused from its build folder when their
fingerprint matches (``.ci/run`` executes them once, before the build), executed here
otherwise. A page without a single table or figure is a warning, so ``mkdocs build
--strict`` fails on it. The ``.py`` file and the executed ``.ipynb`` are copied beside the
page for download; ``examples/README.md`` is the section's index page.

Every ``examples/NN_name.py`` is picked up: the navigation's "Examples" section gets an
entry for each example it does not list yet, titled by the example's link text in
``examples/README.md``.
"""

from __future__ import annotations

import base64
import html
import logging
import re
import sys
from pathlib import Path
from typing import Any

import jupytext
import nbformat
from mkdocs.structure.files import File, Files

sys.path.insert(0, str(Path(__file__).resolve().parent))
import notebooks  # noqa: E402

log = logging.getLogger("mkdocs.hooks.examples")

ROOT = notebooks.ROOT
EXAMPLES = notebooks.EXAMPLES
example_paths = notebooks.example_paths
#: The navigation section that lists the examples.
NAV_SECTION = "Examples"

_RUN = """\
!!! note "Run this example"
    This page is the notebook [`examples/{name}`]({name}) (jupytext percent format:
    plain Python with `# %%` cells); the outputs below are the ones it produced when this
    site was built ([`{stem}.ipynb`]({stem}.ipynb): the executed notebook). From the
    repository's root:

    ```bash
    pip install -e '.[notebooks]' jupyterlab   # railhunt, jupytext, pandas, xarray
    cd examples && jupytext --to ipynb {name}   # or open {name} in JupyterLab directly
    ```

    Its input files are in `examples/data/`. Every number the text quotes is checked by
    an `assert` in the notebook, and the test suite checks the executed notebook.
"""

#: The rendered outputs of each page, by its source path, until on_page_content puts them in.
_OUTPUTS: dict[str, list[str]] = {}
_MARK = "<!-- railhunt-output {} -->"
_MARK_RE = re.compile(r"(?:<p>)?<!-- railhunt-output (\d+) -->(?:</p>)?")


def _text(value: str | list[str]) -> str:
    return "".join(value) if isinstance(value, list) else value


def render_output(output: dict, figure: str | None) -> str:
    """The HTML of one notebook output; ``figure`` is the image's URL when it is a figure."""
    kind = output.get("output_type")
    if kind == "stream":
        name = "nb-stderr" if output.get("name") == "stderr" else "nb-stream"
        return f'<pre class="{name}"><code>{html.escape(_text(output["text"]))}</code></pre>'
    if kind == "error":
        return f'<pre class="nb-error"><code>{html.escape(output.get("ename", ""))}: ' \
               f'{html.escape(output.get("evalue", ""))}</code></pre>'
    data = output.get("data", {})
    if figure is not None:
        return f'<img class="nb-figure" src="{figure}" alt="figure drawn by the cell above">'
    if "text/html" in data:
        return f'<div class="nb-html">{_text(data["text/html"])}</div>'
    if "text/plain" in data:
        return f'<pre class="nb-result"><code>{html.escape(_text(data["text/plain"]))}</code></pre>'
    return ""


def _merged_streams(outputs: list[dict]) -> list[dict]:
    """The outputs with consecutive pieces of the same stream joined (as Jupyter shows them)."""
    merged: list[dict] = []
    for output in outputs:
        previous = merged[-1] if merged else {}
        if (output.get("output_type") == "stream" and previous.get("output_type") == "stream"
                and previous.get("name") == output.get("name")):
            merged[-1] = {**previous, "text": _text(previous["text"]) + _text(output["text"])}
        else:
            merged.append(output)
    return merged


def page(path: Path, nb: Any = None) -> tuple[str, list[str], dict[str, bytes]]:
    """The Markdown page of one example, its outputs' HTML and its figures.

    Parameters
    ----------
    path : Path
        The example, ``examples/NN_name.py``.
    nb : NotebookNode, optional
        The executed notebook; without it the page has the code only.

    Returns
    -------
    tuple
        The Markdown (with a placeholder comment per output block), the HTML of each
        output block in order, and the figures as ``{site path: PNG bytes}``.
    """
    nb = jupytext.read(path) if nb is None else nb
    parts = [f"<!-- generated from examples/{path.name} by docs/_hooks/examples.py -->"]
    blocks: list[str] = []
    figures: dict[str, bytes] = {}
    for i, cell in enumerate(nb.cells):
        source = cell.source.strip("\n")
        if cell.cell_type == "markdown":
            parts.append(source)
        elif source:
            parts.append(f"```python\n{source}\n```")
            rendered = []
            for output in _merged_streams(cell.get("outputs", [])):
                figure = None
                png = output.get("data", {}).get("image/png")
                if png is not None:
                    name = f"{path.stem}/figure-{len(figures) + 1}.png"
                    figures[f"examples/{name}"] = base64.b64decode(_text(png))
                    figure = name
                rendered.append(render_output(output, figure))
            if any(rendered):
                parts.append(_MARK.format(len(blocks)))
                blocks.append('<div class="nb-output">' + "".join(rendered) + "</div>")
        if i == 0:
            parts.append(_RUN.format(name=path.name, stem=path.stem))
    return "\n\n".join(parts) + "\n", blocks, figures


_FIGURE_AS_TEXT = re.compile(r"&lt;(?:Figure|matplotlib\.figure\.Figure) size [^&]*&gt;")


def missing_outputs(figures: dict[str, bytes], blocks: list[str]) -> str | None:
    """What an example page lacks (None: it shows at least one table or figure, and no
    figure as the text ``<Figure size ...>``)."""
    as_text = [m.group(0) for block in blocks for m in _FIGURE_AS_TEXT.finditer(block)]
    if as_text:
        return (f"shows a figure as text, {html.unescape(as_text[0])!r}: its cell's output "
                "has no image")
    if figures or any("<table" in block for block in blocks):
        return None
    return "shows no output: not a single table or figure (did the notebook run?)"


def index() -> str:
    """The section's index: examples/README.md with its links pointing at the pages."""
    text = (EXAMPLES / "README.md").read_text(encoding="utf-8")
    return re.sub(r"\]\((\d\d_[\w]+)\.py\)", r"](\1.md)", text)


def title(path: Path) -> str:
    """The example's title in the navigation: its link text in examples/README.md."""
    readme = (EXAMPLES / "README.md").read_text(encoding="utf-8")
    found = re.search(r"\[(?:\d\d\s+)?([^\]]+)\]\(" + re.escape(path.name) + r"\)", readme)
    if found:
        return found.group(1).strip()
    return jupytext.read(path).cells[0].source.lstrip("# ").splitlines()[0]


def _nav_files(node: Any) -> set[str]:
    if isinstance(node, str):
        return {node}
    if isinstance(node, dict):
        return {f for v in node.values() for f in _nav_files(v)}
    if isinstance(node, list):
        return {f for v in node for f in _nav_files(v)}
    return set()


def complete_nav(nav: list) -> list:
    """The navigation with every example listed in its section (in place, and returned)."""
    section = next(item[NAV_SECTION] for item in nav
                   if isinstance(item, dict) and NAV_SECTION in item)  # fmt: skip
    listed = _nav_files(nav)
    for path in example_paths():
        uri = f"examples/{path.stem}.md"
        if uri not in listed:
            section.append({title(path): uri})
    return nav


def on_config(config: Any) -> Any:
    """List every example in the navigation."""
    if config["nav"] is not None:
        complete_nav(config["nav"])
    return config


def on_files(files: Files, config: Any) -> Files:
    """Add one page, its figures and two downloads per example, and the index page."""
    _OUTPUTS.clear()
    for path in example_paths():
        try:
            nb = notebooks.executed(path)
        except Exception as error:  # the build goes on and fails in strict mode
            log.error("examples/%s does not run: %s", path.name, error)
            nb = None
        text, blocks, figures = page(path, nb)
        uri = f"examples/{path.stem}.md"
        _OUTPUTS[uri] = blocks
        problem = None if nb is None else missing_outputs(figures, blocks)
        if problem:
            log.warning("%s %s", uri, problem)
        files.append(File.generated(config, uri, content=text))
        for name, png in figures.items():
            files.append(File.generated(config, name, content=png))
        files.append(File.generated(config, f"examples/{path.name}",
                                    content=path.read_text(encoding="utf-8")))  # fmt: skip
        if nb is not None:
            files.append(File.generated(config, f"examples/{path.stem}.ipynb",
                                        content=nbformat.writes(nb)))  # fmt: skip
    files.append(File.generated(config, "examples/index.md", content=index()))
    return files


def on_page_content(html_text: str, page: Any, config: Any, files: Files) -> str:
    """Put each example's outputs below the code cells that produced them."""
    blocks = _OUTPUTS.get(page.file.src_uri)
    if blocks is None:
        return html_text
    return _MARK_RE.sub(lambda m: blocks[int(m.group(1))], html_text)
