"""The README's commands work as written in a fresh clone, including those that name files.

Every ``railhunt`` command in the README's bash blocks is read; each input file it names
(a vehicle file, a profile, a measured track, a results file, a CSV to analyse) must either
ship in the repository or be written by a README command before it. The files that ship
are loaded, and the commands that read them are run (from the repository's root, as a
reader would); so is the simulate → spectrogram chain, in a scratch folder.
"""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

import railhunt
from railhunt.vehicle.files import shipped_vehicles

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"

#: Options whose value is a file the command reads / writes.
INPUT_OPTIONS = {"--vehicle", "--wheel", "--rail", "--irregularity"}
OUTPUT_OPTIONS = {"--csv", "--png", "--out", "--damper-png", "--family-png"}
#: Commands whose positional arguments are files they read.
READS_POSITIONAL = {"spectrogram", "plot", "sections"}
#: Names that are not files: shipped vehicles and the analytic profiles.
NAMED = {"S1002", "UIC60"}


def readme_commands() -> list[list[str]]:
    """The README's shell commands (comments and line continuations resolved), in order."""
    blocks = re.findall(r"```bash\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)
    commands = []
    for block in blocks:
        text = block.replace("\\\n", " ")
        for line in text.splitlines():
            line = line.split("  #")[0].strip()
            if line and not line.startswith("#"):
                commands.append(shlex.split(line.split(" > ")[0]) + (
                    ["--stdout-to", line.split(" > ")[1].strip()] if " > " in line else []))
    return commands


def files_of(argv: list[str]) -> tuple[list[str], list[str]]:
    """(input files, output files) a README command names."""
    inputs, outputs = [], []
    if argv[0] == "python":
        return [a for a in argv[1:] if a.endswith(".py")], []
    if argv[0] != "railhunt":
        return [], []
    command = argv[1] if len(argv) > 1 else ""
    skip = False
    for i, arg in enumerate(argv[2:], start=2):
        if skip:
            skip = False
            continue
        if arg.startswith("--"):
            value = argv[i + 1] if i + 1 < len(argv) else ""
            if arg in INPUT_OPTIONS and value not in NAMED | set(shipped_vehicles()):
                inputs.append(value)
            elif arg in OUTPUT_OPTIONS or arg == "--stdout-to":
                outputs.append(value)
            skip = bool(value) and not value.startswith("--") and arg not in (
                "--json", "--resume", "--quick", "--table1", "--overwrite")
        elif command in READS_POSITIONAL and "." in arg:
            inputs.append(arg)
    return inputs, outputs


def test_the_readme_starts_with_its_three_commands() -> None:
    first = [c[0] + " " + c[1] if len(c) > 1 else c[0] for c in readme_commands()[:3]]
    assert first == ["pip install", "railhunt critical-speed", "python -m"]


def test_every_file_a_readme_command_reads_ships_or_is_written_before() -> None:
    written: set[str] = set()
    missing = []
    checked = 0
    for argv in readme_commands():
        inputs, outputs = files_of(argv)
        for name in inputs:
            checked += 1
            if name not in written and not (ROOT / name).is_file():
                missing.append(f"{' '.join(argv)}: {name}")
        written.update(outputs)
    assert missing == []
    assert checked >= 8  # vehicle, wheel, rail, measured track, run.csv, table1.csv x2, ...


def test_the_readme_names_the_shipped_example_files() -> None:
    text = README.read_text(encoding="utf-8")
    for name in ("examples/data/my.toml", "examples/data/worn_s1002.prw",
                 "examples/data/my_rail.txt", "examples/data/track_alignment.csv",
                 "examples/data/worn.toml"):  # fmt: skip
        assert name in text
        assert (ROOT / name).is_file()
    for gone in ("--vehicle my.toml", "--wheel worn.prw", "measured.csv"):
        assert gone not in text


def test_the_readme_files_load() -> None:
    mine = railhunt.load_vehicle(ROOT / "examples/data/my.toml")
    assert (mine.M_c, mine.C_d1) == (34000.0, 220e3)
    worn = railhunt.load_vehicle(ROOT / "examples/data/worn.toml")
    assert worn.contact is not None and worn.contact.wheel.endswith("worn_s1002.prw")
    assert railhunt.read_profile(ROOT / "examples/data/worn_s1002.prw").kind == "wheel"
    assert railhunt.read_profile(ROOT / "examples/data/my_rail.txt", "rail").kind == "rail"
    track = railhunt.load_irregularity(ROOT / "examples/data/track_alignment.csv")
    assert track.length == pytest.approx(1500.0) and track.ds == pytest.approx(0.5)


def test_the_readme_toml_block_is_the_shipped_worn_vehicle() -> None:
    block = re.search(r"```toml\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)
    assert block is not None
    shipped = (ROOT / "examples/data/worn.toml").read_text(encoding="utf-8")
    assert block.group(1).strip() in shipped


def _run(argv: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    exe = ([sys.executable, "-c", "from railhunt.cli import main; main()"]
           if argv[0] == "railhunt" else argv[:1])
    return subprocess.run(exe + argv[1:], cwd=cwd, capture_output=True, text=True,
                          timeout=600)  # fmt: skip


def _commands_reading_shipped_files() -> list[list[str]]:
    out = []
    for argv in readme_commands():
        inputs, _ = files_of(argv)
        if argv[0] == "railhunt" and inputs and all((ROOT / n).is_file() for n in inputs):
            out.append(argv)
    return out


@pytest.mark.slow
@pytest.mark.parametrize("argv", _commands_reading_shipped_files(), ids=" ".join)
def test_readme_command_reading_a_shipped_file_runs(argv: list[str]) -> None:
    done = _run(argv, ROOT)
    assert done.returncode == 0, done.stderr
    assert "critical speed" in done.stdout or "conicity" in done.stdout


@pytest.mark.slow
def test_readme_simulate_then_spectrogram_runs(tmp_path: Path) -> None:
    commands = readme_commands()
    k = next(i for i, a in enumerate(commands) if a[:2] == ["railhunt", "spectrogram"])
    source = next(a for a in reversed(commands[:k])
                  if a[:2] == ["railhunt", "simulate"] and "run.csv" in a)  # fmt: skip
    chain = [source, commands[k]]
    assert "--spectrum" in source  # the README's irregular-track run
    for argv in chain:
        done = _run(argv, tmp_path)
        assert done.returncode == 0, done.stderr
    assert (tmp_path / "run.csv").is_file() and (tmp_path / "stft.png").is_file()
