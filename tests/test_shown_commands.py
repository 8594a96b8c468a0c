"""Every ``railhunt`` command a page or a help text shows works as shown.

The commands are read from the README, the documentation pages, the examples (their
README, the notebooks' text and the data files' comments) and every ``--help`` text.
Running them all would take the whole CI budget (studies, diagrams, the reproduction), so
the checks come in three depths:

1. every command shown, also a mention with placeholders (``railhunt vehicle NAME --png
   FILE``): the command exists and each flag it names is one of its options;
2. every complete command (no placeholder): click parses it as written and the command's
   declared option rules hold; an input file it names ships, or another shown command
   writes it;
3. the cheap complete commands run to the end: ``--help``, ``--version`` and the commands
   in :data:`RUN` (they list, describe or draw a vehicle; no simulation).

The README's commands that read shipped files are also run by tests/test_readme.py.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from railhunt.cli import main
from railhunt.vehicle import shipped_vehicles

ROOT = Path(__file__).resolve().parents[1]
#: Commands cheap enough to run in full (well under a second each, no simulation).
RUN = {"vehicles", "parameters", "vehicle"}
#: Options whose value is a file the command writes.
OUTPUTS = {"--csv", "--png", "--out", "--damper-png", "--family-png", "--mode-png"}
#: A placeholder: NAME, FILE, KMH, NAME|FILE, NAME=VALUE, ..., [--seed N], <x>.
PLACEHOLDER = re.compile(r"^(?:\[.*|.*\]|\.\.\.|<.*>|[A-Z][A-Z0-9_|]*(?:=[A-Z_]+)?|X)$")


def _pages() -> list[Path]:
    pages = [ROOT / "README.md", ROOT / "examples" / "README.md",
             *sorted((ROOT / "docs").glob("*.md"))]  # fmt: skip
    # the changelog is history (docs/changelog.md shows it); cli.md is generated from click
    return [p for p in pages if p.name not in ("changelog.md", "cli.md")]


def _shell_lines(text: str) -> list[str]:
    """The ``railhunt`` lines of a text's shell blocks (continuations joined, comments cut)."""
    out = []
    for block in re.findall(r"```(?:bash|sh|shell|console)\n(.*?)```", text, flags=re.S):
        for line in block.replace("\\\n", " ").splitlines():
            line = line.split("  #")[0].strip()
            if line.startswith("railhunt"):
                out.append(line)
    return out


def _mentions(text: str) -> list[str]:
    """``railhunt ...`` in backticks or single quotes (a help text's mentions)."""
    found = re.findall(r"`(railhunt(?: [^`]*)?)`", text)
    found += re.findall(r"'(railhunt [^']*)'", text)
    return [" ".join(m.split()) for m in found]


def _help_texts() -> dict[str, str]:
    ctx = click.Context(main, info_name="railhunt", terminal_width=200)
    texts = {"railhunt --help": main.get_help(ctx)}
    for name, command in main.commands.items():
        sub = click.Context(command, info_name=name, parent=ctx, terminal_width=200)
        texts[f"railhunt {name} --help"] = command.get_help(sub)
    return texts


def _command_like(line: str) -> bool:
    """A help text's line that is a command, not a sentence starting with 'railhunt'."""
    words = line.split()
    return (len(words) > 1 and words[0] == "railhunt"
            and (words[1] in main.commands or words[1].startswith("-") or " --" in line))


def shown_commands() -> list[tuple[str, str, bool]]:
    """``(where, command line, complete)`` for every command shown: ``complete`` when it
    is written to be run as it stands (a shell block, a help's example line)."""
    shown: list[tuple[str, str, bool]] = []
    for page in _pages():
        text = page.read_text(encoding="utf-8")
        shown += [(page.name, line, True) for line in _shell_lines(text)]
        shown += [(page.name, m, False) for m in _mentions(text)]
    for path in sorted((ROOT / "examples").glob("*.py")):
        shown += [(path.name, m, False) for m in _mentions(path.read_text(encoding="utf-8"))]
    for path in sorted((ROOT / "examples" / "data").glob("*.toml")):
        comments = " ".join(line.lstrip("# ") for line in path.read_text(encoding="utf-8")
                            .splitlines() if line.startswith("#"))  # fmt: skip
        shown += [(path.name, m, False) for m in _mentions(comments)]
    for where, text in _help_texts().items():
        joined = re.sub(r"\\\n\s*", " ", text)  # an example's continuation lines
        lines = [line.split("  #")[0].strip() for line in joined.splitlines()]
        shown += [(where, line, True) for line in lines if _command_like(line)]
        shown += [(where, m, False) for m in _mentions(" ".join(text.split()))]
    return shown


def _argv(line: str) -> list[str]:
    line = re.split(r" [>|] ", line)[0]
    return shlex.split(line)[1:]


def _written() -> set[str]:
    """Every file a complete shown command writes (an output option's value, a ``>``)."""
    out = set()
    for _, line, complete in shown_commands():
        if not complete:
            continue
        argv = shlex.split(line)
        out.update(argv[i + 1] for i, a in enumerate(argv[:-1]) if a in OUTPUTS)
        if " > " in line:
            out.add(line.split(" > ")[1].split()[0])
    return out


SHOWN = shown_commands()
COMPLETE = sorted({line for _, line, complete in SHOWN
                   if complete and not any(PLACEHOLDER.match(a) for a in _argv(line))})


def test_the_pages_and_helps_show_many_commands() -> None:
    wheres = {where for where, _, _ in SHOWN}
    assert len(SHOWN) > 150 and len(COMPLETE) > 50
    assert {"README.md", "getting-started.md", "railhunt --help"} <= wheres
    assert "articulated_pair.toml" in wheres  # the data files' comments are read too


def test_every_command_shown_exists_with_the_flags_it_names() -> None:
    bad = []
    for where, line, _ in SHOWN:
        argv = _argv(line)
        if not argv or argv[0].startswith("-") or PLACEHOLDER.match(argv[0]):
            unknown = [a for a in argv if a.startswith("--") and a.split("=")[0] not in
                       {"--help", "--version", "--debug"}]  # fmt: skip
            if unknown:
                bad.append(f"{where}: {line}: {unknown}")
            continue
        command = main.commands.get(argv[0])
        if command is None:
            bad.append(f"{where}: {line}: no command {argv[0]!r}")
            continue
        flags = {o for p in command.params for o in p.opts} | {"--help", "-h"}
        unknown = [a for a in argv[1:] if a.startswith("--") and a.split("=")[0] not in flags]
        if unknown:
            bad.append(f"{where}: {line}: {argv[0]} has no {', '.join(unknown)}")
    assert bad == []


def _parse(argv: list[str]) -> str | None:
    """Why click (or the command's declared rules) refuses ``argv``; None when it parses."""
    from railhunt.cli.errors import CliError

    group = click.Context(main, info_name="railhunt")
    if not argv or argv[0].startswith("-"):
        try:
            main.make_context("railhunt", list(argv), resilient_parsing=False)
        except click.exceptions.Exit:
            return None
        except click.ClickException as exc:
            return exc.format_message()
        return None
    command = main.commands[argv[0]]
    try:
        ctx = command.make_context(argv[0], list(argv[1:]), parent=group)
        for rule in getattr(command, "rules", ()):
            message = rule.broken(ctx, command._names)
            if message is not None:
                raise CliError(message)
    except click.exceptions.Exit:
        return None
    except click.ClickException as exc:
        return exc.format_message()
    return None


@pytest.mark.parametrize("line", COMPLETE)
def test_every_complete_command_shown_parses_as_written(line: str, monkeypatch) -> None:
    monkeypatch.chdir(ROOT)  # the pages' relative paths are the repository's
    why = _parse(_argv(line))
    if why is not None and "does not exist" in why:
        written = _written()
        if any(name in why for name in written):
            return  # a file another shown command writes (run.csv, table1.csv, ...)
    assert why is None, f"{line}: {why}"


def _cheap(line: str) -> bool:
    argv = _argv(line)
    return bool(argv) and ("--help" in argv or "--version" in argv or argv[0] in RUN)


@pytest.mark.parametrize("line", [c for c in COMPLETE if _cheap(c)])
def test_every_cheap_command_shown_runs(line: str, tmp_path: Path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    argv = [str(ROOT / a) if (ROOT / a).is_file() and "/" in a else a for a in _argv(line)]
    result = CliRunner().invoke(main, argv)
    assert result.exit_code == 0, f"{line}: {result.output}"


def test_the_shipped_vehicles_are_those_of_the_data_directory() -> None:
    """What the --vehicle helps list (tests/test_cli_words.py) is the data directory."""
    folder = ROOT / "src" / "railhunt" / "data" / "vehicles"
    assert set(shipped_vehicles()) == {p.stem for p in folder.glob("*.toml")}
