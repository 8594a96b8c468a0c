"""CHANGELOG.md and the version: Keep a Changelog's form, one version everywhere, pages that
speak of versions (never of the tracker's issue numbers), results that carry the version.
"""

from __future__ import annotations

import datetime
import json
import re
from pathlib import Path

from click.testing import CliRunner

import railhunt
from railhunt.cli import main

ROOT = Path(__file__).resolve().parents[1]
CHANGELOG = ROOT / "CHANGELOG.md"
#: Keep a Changelog 1.1.0's types of changes.
TYPES = ("Added", "Changed", "Deprecated", "Removed", "Fixed", "Security")
VERSION_HEAD = re.compile(r"^## \[(\d+)\.(\d+)\.(\d+)\] - (\d{4}-\d{2}-\d{2})$")


def _versions() -> list[tuple[str, list[str]]]:
    """(heading, lines) of every ``## `` section of the changelog, in order."""
    sections: list[tuple[str, list[str]]] = []
    for line in CHANGELOG.read_text(encoding="utf-8").splitlines():
        if line.startswith("## "):
            sections.append((line, []))
        elif sections:
            sections[-1][1].append(line)
    return sections


def test_the_changelog_keeps_a_changelog() -> None:
    text = CHANGELOG.read_text(encoding="utf-8")
    assert text.startswith("# Changelog\n")
    assert "https://keepachangelog.com/en/1.1.0/" in text
    sections = _versions()
    assert sections[0][0] == "## [Unreleased]", "the first section is [Unreleased]"
    released = [(VERSION_HEAD.match(head), lines) for head, lines in sections[1:]]
    assert all(m for m, _ in released), [h for h, _ in sections[1:] if not VERSION_HEAD.match(h)]
    numbers = [tuple(int(m.group(i)) for i in (1, 2, 3)) for m, _ in released]
    dates = [datetime.date.fromisoformat(m.group(4)) for m, _ in released]
    assert numbers == sorted(numbers, reverse=True) and len(set(numbers)) == len(numbers)
    assert dates == sorted(dates, reverse=True)
    assert numbers[-1] == (0, 1, 0)
    for (_, lines), number in zip(released, numbers, strict=True):
        kinds = [ln[4:] for ln in lines if ln.startswith("### ")]
        assert kinds, f"{number}: no changes listed"
        assert set(kinds) <= set(TYPES), f"{number}: {kinds} (Keep a Changelog: {TYPES})"
        assert kinds == sorted(kinds, key=TYPES.index), f"{number}: types out of order"
        assert any(ln.startswith("- ") for ln in lines), f"{number}: no entries"
    # every minor version from 0.1.0 up: a capability per version, none left out
    minors = sorted(n[1] for n in numbers if n[0] == 0 and n[2] == 0)
    assert minors == list(range(1, minors[-1] + 1))


def test_the_version_is_the_changelogs_latest_and_every_page_names_it() -> None:
    latest = VERSION_HEAD.match(_versions()[1][0])
    assert latest and ".".join(latest.groups()[:3]) == railhunt.__version__
    result = CliRunner().invoke(main, ["--version"])
    assert result.output.strip() == f"railhunt, version {railhunt.__version__}"
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    stale = [(p.name, v) for p in pages
             for v in re.findall(r"\bversion (\d+\.\d+\.\d+)", p.read_text(encoding="utf-8"))
             if v != railhunt.__version__]  # fmt: skip
    assert stale == [], "pages naming another version than the package's"


def test_pages_speak_of_versions_never_of_issue_numbers() -> None:
    """The docs, the README, the examples and the benchmarks' README name versions that
    the changelog lists; no page names a tracker's issue (``issue 13``, ``the issue``)."""
    known = {".".join(m.groups()[:3]) for h, _ in _versions()[1:]
             if (m := VERSION_HEAD.match(h))}  # fmt: skip
    pages = [ROOT / "README.md", ROOT / "benchmarks" / "README.md",
             ROOT / "examples" / "README.md", *sorted((ROOT / "docs").rglob("*.md")),
             *sorted((ROOT / "examples").glob("*.py"))]  # fmt: skip
    issue = re.compile(r"\bissues? \d+|\bthe issue\b|\bissue's\b", re.IGNORECASE)
    found, unknown = [], []
    for page in pages:
        text = page.read_text(encoding="utf-8")
        found += [(page.name, m.group(0)) for m in issue.finditer(text)]
        unknown += [(page.name, v) for v in re.findall(r"(?<![\d.])(0\.\d+\.\d+)(?![\d.])", text)
                    if v not in known and not v.startswith("0.0")]  # fmt: skip
    assert found == [], "pages naming the tracker's issues: speak of versions"
    assert unknown == [], "versions the changelog does not list"


def test_result_files_carry_the_version(tmp_path: Path) -> None:
    """A CSV's metadata file and a figure (PNG, PDF, SVG) name the version; JSON outputs
    carry it through the same provenance keys (``railhunt.cli.output.traced``)."""
    from PIL import Image

    from railhunt.cli.files import write_sidecar
    from railhunt.cli.output import traced
    from railhunt.plots.figure import new_figure, save_figure
    from railhunt.provenance import provenance

    assert traced({})["railhunt_version"] == railhunt.__version__
    side = write_sidecar(tmp_path / "run.csv", provenance())
    assert json.loads(side.read_text(encoding="utf-8"))["railhunt_version"] == railhunt.__version__
    fig = new_figure(1.0, 1.0)
    fig.add_subplot().plot([0, 1])
    creator = f"railhunt {railhunt.__version__} "
    assert Image.open(save_figure(fig, tmp_path / "a.png")).info["Software"].startswith(creator)
    for suffix in ("pdf", "svg"):
        assert creator.encode() in save_figure(fig, tmp_path / f"a.{suffix}").read_bytes()
