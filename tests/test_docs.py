"""The documentation site, the citation file and ``railhunt --version``.

The site's structure is checked without building it (every page in the navigation, every
example and every exported name documented), and one slow test builds it with
``mkdocs build --strict`` into a scratch folder, as ``.ci/run`` does: a warning, a broken
link or a page that would load something from the internet fails it.
"""

from __future__ import annotations

import importlib.metadata
import re
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
    nav = _nav_files(_config()["nav"])
    pages = {str(p.relative_to(DOCS)) for p in DOCS.rglob("*.md") if "_hooks" not in p.parts}
    assert pages - set(nav) == set(), "pages missing from the nav of mkdocs.yml"
    examples = {f"examples/{p.stem}.md" for p in (ROOT / "examples").glob("[0-9][0-9]_*.py")}
    assert examples <= set(nav), "an example is missing from the nav of mkdocs.yml"
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
