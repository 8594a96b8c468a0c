"""The documentation site, the citation file and ``railhunt --version``.

The site's structure is checked without building it (every page in the navigation, every
example and every exported name documented), and one slow test builds it with
``mkdocs build --strict`` into a scratch folder, as ``.ci/run`` does: a warning, a broken
link or a page that would load something from the internet fails it.
"""

from __future__ import annotations

import importlib.metadata
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

import railhunt
from railhunt.cli import main

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS / "_hooks"))

import counts  # noqa: E402
import examples as examples_hook  # noqa: E402
import nbformat  # noqa: E402
import offline  # noqa: E402
import sphinx_roles  # noqa: E402


def _nav_files(node: object) -> list[str]:
    if isinstance(node, str):
        return [node]
    if isinstance(node, dict):
        return [f for v in node.values() for f in _nav_files(v)]
    if isinstance(node, list):
        return [f for v in node for f in _nav_files(v)]
    return []


def _config() -> dict:
    # mkdocs.yml has no custom YAML tags, so the plain loader reads it.
    return yaml.safe_load((ROOT / "mkdocs.yml").read_text(encoding="utf-8"))


def test_every_page_is_in_the_navigation_and_every_navigation_entry_exists() -> None:
    nav = _nav_files(examples_hook.complete_nav(_config()["nav"]))
    pages = {str(p.relative_to(DOCS)) for p in DOCS.rglob("*.md") if "_hooks" not in p.parts}
    assert pages - set(nav) == set(), "pages missing from the nav of mkdocs.yml"
    examples = {f"examples/{p.stem}.md" for p in (ROOT / "examples").glob("[0-9][0-9]_*.py")}
    assert examples <= set(nav), "an example is missing from the navigation"
    assert len(nav) == len(set(nav)), "a page is listed twice in the navigation"
    generated = examples | {"examples/index.md"}
    assert [f for f in nav if f not in pages | generated] == []


def test_the_user_guide_has_a_page_per_topic() -> None:
    guide = next(item["User guide"] for item in _config()["nav"] if "User guide" in item)
    titles = [next(iter(entry)) for entry in guide]
    for topic in ("The model", "Contact and conicity", "Critical speeds",
                  "Bifurcation and frequency", "Hunting frequency",
                  "Track irregularities and the stability criterion", "Sweeps and clusters",
                  "Curved track", "Reproducing the paper"):  # fmt: skip
        assert topic in titles


def test_every_exported_name_is_in_the_api_index_and_its_module_documented() -> None:
    index = (DOCS / "api" / "index.md").read_text(encoding="utf-8")
    documented = set(re.findall(r"^::: ([\w.]+)", "\n".join(
        p.read_text(encoding="utf-8") for p in (DOCS / "api").glob("*.md")), flags=re.M))
    for name in railhunt.__all__:
        assert f"`{name}`" in index, f"{name} is not in docs/api/index.md"
        module = getattr(railhunt, name).__module__  # where it is defined
        assert any(module == d or module.startswith(d + ".") for d in documented), (
            f"{name} ({module}) is documented on no API page")


def test_the_examples_section_lists_every_example_without_a_list_to_maintain() -> None:
    nav = [{"Home": "index.md"}, {"Examples": ["examples/index.md",
                                               {"Own title": "examples/02_worn_wheel.md"}]}]
    section = examples_hook.complete_nav(nav)[1]["Examples"]
    uris = [next(iter(e.values())) if isinstance(e, dict) else e for e in section]
    expected = [f"examples/{p.stem}.md" for p in examples_hook.example_paths()]
    assert sorted(uris[1:]) == sorted(expected) and uris.count("examples/02_worn_wheel.md") == 1
    assert {"A bifurcation diagram": "examples/03_bifurcation_diagram.md"} in section


def _fake_executed(outputs: list[dict]) -> nbformat.NotebookNode:
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# Title"), nbformat.v4.new_code_cell("x = 1")]
    nb.cells[1].outputs = [nbformat.from_dict(o) for o in outputs]
    return nb


def test_an_example_page_shows_the_outputs_of_its_cells() -> None:
    png = ("iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGNgYGD4DwABBAEAwS2OUAAAAABJ"
           "RU5ErkJggg==")  # a 1x1 PNG
    nb = _fake_executed([
        {"output_type": "stream", "name": "stdout", "text": "a < b\n"},
        {"output_type": "stream", "name": "stdout", "text": "c\n"},
        {"output_type": "display_data", "metadata": {},
         "data": {"image/png": png, "text/plain": "<Figure>"}},
        {"output_type": "execute_result", "execution_count": 1, "metadata": {},
         "data": {"text/html": "<table><tr><td>1</td></tr></table>", "text/plain": "1"}},
    ])
    path = examples_hook.example_paths()[0]
    text, blocks, figures = examples_hook.page(path, nb)
    assert len(blocks) == 1 and "<!-- railhunt-output 0 -->" in text
    assert "a &lt; b\nc\n</code></pre>" in blocks[0] and "<table>" in blocks[0]
    assert blocks[0].count("<pre") == 1  # consecutive pieces of one stream are one block
    name = f"examples/{path.stem}/figure-1.png"
    assert list(figures) == [name] and figures[name].startswith(b"\x89PNG")
    assert f'src="{path.stem}/figure-1.png"' in blocks[0]
    assert examples_hook.missing_outputs(figures, blocks) is None
    page = type("Page", (), {"file": type("F", (), {"src_uri": f"examples/{path.stem}.md"})})
    examples_hook._OUTPUTS[page.file.src_uri] = blocks
    html = examples_hook.on_page_content("<p><!-- railhunt-output 0 --></p>", page, {}, None)
    assert html == blocks[0]


def test_an_example_page_without_a_table_or_figure_is_a_warning() -> None:
    path = examples_hook.example_paths()[0]
    text_only = _fake_executed([{"output_type": "stream", "name": "stdout", "text": "hi"}])
    _, blocks, figures = examples_hook.page(path, text_only)
    assert examples_hook.missing_outputs(figures, blocks) is not None
    _, blocks, figures = examples_hook.page(path, _fake_executed([]))
    assert blocks == [] and examples_hook.missing_outputs(figures, blocks) is not None
    figure_as_text = _fake_executed([
        {"output_type": "execute_result", "execution_count": 1, "metadata": {},
         "data": {"text/plain": "<Figure size 800x650 with 2 Axes>"}},
        {"output_type": "execute_result", "execution_count": 2, "metadata": {},
         "data": {"text/html": "<table></table>", "text/plain": "t"}}])
    _, blocks, figures = examples_hook.page(path, figure_as_text)
    assert "<Figure size 800x650" in examples_hook.missing_outputs(figures, blocks)


def test_the_build_warns_on_an_example_page_without_outputs(
        monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture) -> None:
    from mkdocs.config import load_config
    from mkdocs.structure.files import Files

    # Every example "executed" without a single output: each page is a warning (strict: fails).
    monkeypatch.setattr(examples_hook.notebooks, "executed",
                        lambda path: _fake_executed([]))  # fmt: skip
    config = load_config(str(ROOT / "mkdocs.yml"))
    config.plugins._current_plugin = None  # as outside a plugin event of a build
    files = examples_hook.on_files(Files([]), config)
    assert len(files) == 3 * len(examples_hook.example_paths()) + 1  # page, .py, .ipynb; index
    warned = [r.getMessage() for r in caplog.records if r.levelname == "WARNING"]
    for path in examples_hook.example_paths():
        assert any(f"examples/{path.stem}.md shows no output" in w for w in warned), warned


def test_the_math_renderer_ships_with_the_site() -> None:
    config = _config()
    arithmatex = [e for e in config["markdown_extensions"]
                  if isinstance(e, dict) and "pymdownx.arithmatex" in e]
    assert arithmatex and arithmatex[0]["pymdownx.arithmatex"]["generic"] is True
    for asset in (*config["extra_javascript"], *config["extra_css"]):
        assert "//" not in asset and (DOCS / asset).is_file(), asset
    katex = DOCS / "assets" / "katex"
    assert "assets/katex/katex.min.js" in config["extra_javascript"]
    assert "assets/katex/katex.min.css" in config["extra_css"]
    assert (katex / "LICENSE").read_text(encoding="utf-8").startswith("The MIT License")
    css = (katex / "katex.min.css").read_text(encoding="utf-8")
    fonts = set(re.findall(r"url\((fonts/[\w.-]+)\)", css))
    assert fonts and all((katex / f).is_file() for f in fonts)


def test_the_counts_the_pages_state_are_current_and_generated() -> None:
    from railhunt.vehicle.parameters import DERIVED, PARAMETERS

    expected = {"parameters": len(PARAMETERS), "derived": len(DERIVED),
                "examples": len(examples_hook.example_paths())}
    assert {name: f() for name, f in counts.COUNTS.items()} == expected
    found = []
    for page in DOCS.rglob("*.md"):
        for name, written in counts.COUNT.findall(page.read_text(encoding="utf-8")):
            found.append(name)
            assert int(written) == expected[name], f"{page.name} says {written} {name}"
    assert {"parameters", "derived", "examples"} <= set(found)
    text = "The <!--count:parameters-->53<!--/count--> parameters"
    assert counts.fill(text) == f"The {len(PARAMETERS)} parameters"
    parameters_page = (DOCS / "parameters.md").read_text(encoding="utf-8")
    assert f"<!--count:parameters-->{len(PARAMETERS)}<!--/count--> parameters" in parameters_page


def test_an_unknown_count_is_a_warning(caplog: pytest.LogCaptureFixture) -> None:
    assert counts.fill("<!--count:nonsense-->3<!--/count-->", "x.md") == "3"
    assert "unknown count 'nonsense'" in caplog.text


def test_the_site_loads_no_web_fonts() -> None:
    theme = _config()["theme"]
    assert theme["name"] == "material" and theme["font"] is False
    assert "repo_url" not in _config()  # the theme would fetch the repository's stars


def test_the_offline_check_finds_remote_loads() -> None:
    page = ('<a href="https://example.org">a link is fine</a>'
            '<script src="https://cdn.example.org/x.js"></script>'
            '<link rel="stylesheet" href="//fonts.example.org/css">'
            '<img src="img/local.png"><style>@import url("https://x.org/y.css");</style>')
    found = offline.remote_loads(page)
    assert len(found) == 3
    assert offline.remote_loads('<script src="assets/javascripts/bundle.js"></script>') == []


def test_sphinx_roles_become_code_spans_and_grouped_parameters_split() -> None:
    text = "See :class:`~railhunt.vehicle.Vehicle`, :func:`railhunt.sweep`, :data:`t <a.b>`."
    assert sphinx_roles.convert(text) == "See `Vehicle`, `railhunt.sweep`, `t`."
    doc = ("Parameters\n----------\na, b : float\n    Both.\nc : int\n    C.\n\n"
           "Returns\n-------\nx, y : float\n    Kept.")
    assert sphinx_roles.split_grouped_parameters(doc) == (
        "Parameters\n----------\na : float\n    Both.\nb : float\n    Both.\nc : int\n    C.\n\n"
        "Returns\n-------\nx, y : float\n    Kept.")


def test_version_is_one_number_everywhere() -> None:
    result = CliRunner().invoke(main, ["--version"])
    assert result.exit_code == 0
    assert result.output.strip() == f"railhunt, version {railhunt.__version__}"
    assert importlib.metadata.version("railhunt") == railhunt.__version__
    citation = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert str(citation["version"]) == railhunt.__version__
    assert citation["cff-version"] == "1.2.0" and citation["authors"] and citation["message"]
    paper = citation["references"][0]
    assert paper["title"].startswith("Numerical Investigation into the Critical Speed")
    assert paper["journal"] == "Mathematical Problems in Engineering" and paper["year"] == 2019
    assert paper["doi"] == "10.1155/2019/7163732"  # CFF 1.2.0: a DOI is "10.<registrant>/<suffix>"
    assert re.fullmatch(r"10\.\d{4,9}/[-._;()/:A-Za-z0-9]+", paper["doi"])


def test_the_readme_has_a_cite_section_and_says_how_to_build_the_site() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "\n## Cite\n" in readme and "CITATION.cff" in readme
    assert "mkdocs build --strict" in readme and "mkdocs serve" in readme


@pytest.mark.slow
def test_the_site_builds_strictly(tmp_path: Path) -> None:
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path)],
        cwd=ROOT, capture_output=True, text=True, timeout=600,
        env={**__import__("os").environ, "NO_MKDOCS_2_WARNING": "1"},
    )
    assert done.returncode == 0, done.stderr[-3000:]
    for page in ("index.html", "cli.html", "api/analysis.html",
                 "examples/01_your_own_vehicle.html", "examples/01_your_own_vehicle.py"):
        assert (tmp_path / page).is_file(), page
    cli = (tmp_path / "cli.html").read_text(encoding="utf-8")
    for command in main.commands:  # generated from the commands themselves
        assert f"railhunt {command}" in cli
    for path in examples_hook.example_paths():  # every example shows its outputs
        html = (tmp_path / "examples" / f"{path.stem}.html").read_text(encoding="utf-8")
        shown = re.findall(r'<div class="nb-output">(.*?)</div>\n', html, flags=re.S)
        assert shown, f"{path.stem}: no outputs on the page"
        assert any("<table" in block for block in shown), f"{path.stem}: no table"
        figures = re.findall(r'<img class="nb-figure" src="([^"]+)"', html)
        assert figures, f"{path.stem}: no figure"
        for src in figures:
            assert (tmp_path / "examples" / src).read_bytes().startswith(b"\x89PNG"), src
        assert (tmp_path / "examples" / f"{path.stem}.ipynb").is_file()
    model = (tmp_path / "model.html").read_text(encoding="utf-8")  # equations: KaTeX, local
    assert model.count('class="arithmatex"') >= 10
    for asset in ("assets/katex/katex.min.js", "assets/katex/katex.min.css",
                  "assets/javascripts/katex.js"):
        assert f'"{asset}' in model and (tmp_path / asset).is_file(), asset
    assert (tmp_path / "assets/katex/fonts/KaTeX_Main-Regular.woff2").is_file()
    node = shutil.which("node")
    if node is not None:  # every formula parses with the shipped KaTeX, as in the browser
        done = subprocess.run([node, str(ROOT / "tests" / "katex_check.js"), str(tmp_path)],
                              capture_output=True, text=True, timeout=120, check=True)
        checked = json.loads(done.stdout)
        assert checked["formulas"] >= 50 and checked["failed"] == [], checked
