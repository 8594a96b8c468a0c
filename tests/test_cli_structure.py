"""The command line's structure: every command in the help, no shadowed library names,
no private imports across modules, lazy library imports, and the declared option rules."""

import ast
import importlib
import inspect
import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

import railhunt
import railhunt.cli
from railhunt.cli import main
from railhunt.cli.rules import Excludes, Ordered, Requires, command

CLI_DIR = Path(railhunt.cli.__file__).parent


def cli_modules() -> list:
    """railhunt.cli and every module below it."""
    names = [info.name for info in pkgutil.walk_packages(railhunt.cli.__path__, "railhunt.cli.")]
    return [railhunt.cli] + [importlib.import_module(name) for name in names]


def invoke(cmd: click.Command, *args: str):
    try:
        runner = CliRunner(mix_stderr=False)
    except TypeError:  # click >= 8.2 always separates them
        runner = CliRunner()
    return runner.invoke(cmd, list(args))


# --------------------------------------------------------------------------- the group


def test_main_help_lists_every_registered_command():
    """The list in 'railhunt --help' is generated: each command once, with its short help."""
    text = invoke(main, "--help").stdout
    section = text.split("\nCommands:\n", 1)[1].split("\n\n", 1)[0]
    listed = re.findall(r"^  (\S+)  ", section, flags=re.MULTILINE)
    assert listed == list(main.commands)
    assert len(listed) >= 12
    for name, cmd in main.commands.items():
        assert cmd.short_help, name
        first_words = " ".join(cmd.short_help.split()[:3])
        assert first_words in " ".join(section.split()), name
    for paragraph in ("limit cycle", "Units:", "Examples:", "railhunt: error:"):
        assert paragraph in text


def test_no_cli_function_shadows_a_library_name():
    """``railhunt.simulate`` is the library's; the function behind ``railhunt simulate``
    has its own name (``simulate_command``)."""
    exported = set(railhunt.__all__)
    clashes = []
    for module in cli_modules():
        for name, obj in vars(module).items():
            func = obj.callback if isinstance(obj, click.Command) else obj
            if not inspect.isfunction(func) or func.__module__ != module.__name__:
                continue
            for public in {name, func.__name__}:
                if not public.startswith("_") and public in exported:
                    clashes.append(f"{module.__name__}.{public}")
    assert not clashes


def test_no_private_names_are_imported_across_modules():
    """What the commands share is public: no ``from railhunt... import _name``."""
    private = []
    for path in sorted(CLI_DIR.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("railhunt"):
                private += [f"{path.name}: {node.module}.{alias.name}" for alias in node.names
                            if alias.name.startswith("_")]  # fmt: skip
    assert not private


def test_help_imports_no_numerics():
    """The library is imported inside the commands: 'railhunt --help' stays fast."""
    code = ("import sys\nfrom railhunt.cli import main\n"
            "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in ('numpy', 'numba', 'scipy', 'matplotlib', 'dask')"
            " if m in sys.modules))")  # fmt: skip
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout  # fmt: skip
    assert out.strip().splitlines()[-1] == "[]"


# --------------------------------------------------------------------------- rules


@command("toy", rules=(
    Excludes("--resume", "--overwrite", "{a} and {b} exclude each other"),
    Excludes("--method=fancy", ("--amplitude", "--shape!=bump"), "{b} makes no sense with {a}"),
    Requires(("--seed", "--spectrum"), "--method=random|fancy",
             "{a} only applies with {b} (not {method!r})"),
    Ordered("--low", "--high", "--low {low:g} must be below --high {high:g}", strict=True),
))  # fmt: skip
@click.option("--resume", is_flag=True)
@click.option("--overwrite", is_flag=True)
@click.option("--method", type=click.Choice(["plain", "random", "fancy"]), default="plain")
@click.option("--amplitude", type=float, default=1.0)
@click.option("--shape", type=click.Choice(["bump", "sine"]), default="bump")
@click.option("--seed", type=int, default=0)
@click.option("--spectrum")
@click.option("--low", type=float)
@click.option("--high", type=float, default=2.0)
def toy_command(**kwargs):
    click.echo("ran")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ([], None),
        (["--resume"], None),
        (["--resume", "--overwrite"], "--resume and --overwrite exclude each other"),
        (["--method", "fancy", "--shape", "bump"], None),
        (["--method", "fancy", "--amplitude", "1"], "--amplitude makes no sense with --method"),
        (["--method", "fancy", "--shape", "sine"], "--shape makes no sense with --method"),
        (["--amplitude", "3"], None),
        (["--seed", "0"], "--seed only applies with --method (not 'plain')"),
        (["--spectrum", "x", "--seed", "2"], "--seed only applies with --method (not 'plain')"),
        (["--method", "random", "--spectrum", "x"], None),
        (["--low", "1"], None),
        (["--low", "2"], "--low 2 must be below --high 2"),
        (["--high", "0"], None),  # --low not set
    ],
)
def test_declared_rules(args, message):
    result = invoke(toy_command, *args)
    if message is None:
        assert result.exit_code == 0, result.stderr
        assert result.stdout == "ran\n"
    else:
        assert result.exit_code == 2
        assert result.stderr == f"railhunt: error: {message}\n"
        assert result.stdout == ""


def test_a_rule_must_name_an_option():
    with pytest.raises(ValueError, match="--nope"):
        command("bad", rules=(Requires("--seed", "--nope", "{a} needs {b}"),))(
            click.option("--seed")(lambda seed: None)
        )

