"""Output files: the checks before anything is computed, the overwrite policy, sidecars.

Every command that writes files checks them all with :func:`check_outputs` (or
:func:`check_output_folder` for a folder) before it computes anything, so that a run of
minutes never ends in an unwritable path. The overwrite policy is one for every command
(:data:`OVERWRITE_POLICY`): an existing output file is an error unless ``--overwrite`` is
given. :func:`write_sidecar` writes the metadata (:mod:`railhunt.provenance`) that every
CSV file carries in ``<file>.meta.json``. :mod:`railhunt.cli.options` shares these with the
commands.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import click

from railhunt.cli.errors import CliError

__all__ = ["OVERWRITE_POLICY", "SIDECAR_OPTIONS", "OutputPath", "check_output_folder",
           "check_outputs", "file_option",
           "overwrite_option", "sidecar_path", "write_sidecar"]  # fmt: skip

Decorator = Callable[[Callable[..., Any]], Callable[..., Any]]


class OutputPath(click.Path):
    """A click path for an output file or folder that refuses an empty name: ``--out ''``
    would otherwise be the current folder (``Path('')`` is ``.``)."""

    def __init__(self, *, folder: bool = False) -> None:
        super().__init__(file_okay=not folder, dir_okay=folder, path_type=Path)
        self.folder = folder

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> Any:  # fmt: skip
        if isinstance(value, str) and not value.strip():
            what = "folder" if self.folder else "file"
            self.fail(f"{value!r} is an empty name: give a {what} name (for the current "
                      f"folder, write '.')" if self.folder else
                      f"{value!r} is an empty name: give a {what} name", param, ctx)  # fmt: skip
        return super().convert(value, param, ctx)


def file_option(flag: str, dest: str, help: str, metavar: str | None = "FILE") -> Decorator:
    """An output file option (``--png FILE``, ``--csv FILE``, ...); see :func:`check_outputs`."""
    return click.option(flag, dest, type=OutputPath(), metavar=metavar, help=help)


#: The overwrite policy, shown by ``railhunt --help`` and ``--overwrite``'s help.
OVERWRITE_POLICY = ("An output file that exists is not replaced: the command stops before it "
                    "computes anything unless --overwrite is given.")  # fmt: skip

#: ``--overwrite``: the one flag of the overwrite policy (:data:`OVERWRITE_POLICY`).
overwrite_option = click.option(
    "--overwrite", is_flag=True,
    help="Replace output files that exist (without it, an existing output file is an error).")


def _writable_folder(folder: Path) -> str | None:
    """Why no file can be created in ``folder`` (None when one can): by trying to."""
    import tempfile

    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".railhunt-probe-")
    except OSError as exc:
        return exc.strerror or str(exc)
    os.close(fd)
    os.unlink(probe)
    return None


#: The output options whose file is written with its metadata sidecar (FILE.meta.json,
#: :func:`write_sidecar`): the sidecar is checked with its file.
SIDECAR_OPTIONS = frozenset({"csv"})


def check_outputs(*, overwrite: bool = False, **files: Path | None) -> None:
    """Check every output file before anything is computed (the overwrite policy included).

    Each given file must be creatable (its folder exists, is a folder and takes a new
    file) or, when it exists, be a file that can be written and ``overwrite`` must be set;
    no two options may name the same file. The file of an option of
    :data:`SIDECAR_OPTIONS` brings its sidecar ``FILE.meta.json``, which follows the same
    policy (a sidecar left from an earlier run is not replaced without ``overwrite``).

    Parameters
    ----------
    overwrite : bool
        ``--overwrite``: existing files may be replaced.
    **files : Path or None
        Output files by option name without the dashes (``csv=...``, ``png=...``).

    Raises
    ------
    CliError
        Naming the option, the file and what to do.
    """
    seen: dict[Path, str] = {}
    for option, path in _with_sidecars(files):
        flag = f"--{option}"
        real = path.resolve()
        if real in seen:
            raise CliError(f"{flag} and {seen[real]} both name {path}: give each its own file")
        seen[real] = flag
        folder = real.parent
        if not folder.exists():
            raise CliError(f"{flag} {path}: folder {str(path.parent)!r} does not exist")
        if not folder.is_dir():
            raise CliError(f"{flag} {path}: {str(path.parent)!r} is not a folder")
        if real.is_dir():
            raise CliError(f"{flag} {path}: is a folder; give a file name")
        if real.exists():
            if not overwrite:
                raise CliError(f"{flag} {path} exists: give --overwrite to replace it, or "
                               "choose another file")  # fmt: skip
            if not os.access(real, os.W_OK):
                raise CliError(f"{flag} {path}: the file cannot be written (permission "
                               "denied)")  # fmt: skip
            continue
        why = _writable_folder(folder)
        if why is not None:
            raise CliError(f"{flag} {path}: cannot write in folder {str(path.parent)!r} "
                           f"({why})")  # fmt: skip


def _with_sidecars(files: dict[str, Path | None]) -> list[tuple[str, Path]]:
    """``(option, path)`` of every given file, each followed by its sidecar (the option
    then reads like ``csv's metadata``, so that a message names both)."""
    out = []
    for option, path in files.items():
        if path is None:
            continue
        out.append((option, path))
        if option in SIDECAR_OPTIONS:
            out.append((f"{option} {path}: its metadata file", sidecar_path(path)))
    return out


def check_output_folder(flag: str, folder: Path, files: Iterable[str],
                        overwrite: bool) -> None:  # fmt: skip
    """Check an output folder (``reproduce --out DIR``) before anything is computed.

    The folder must be a folder (or creatable: its nearest existing parent is a folder
    that takes new entries); without ``overwrite`` it must not hold any of ``files``
    (names of what the command writes there) from an earlier run.
    """
    if folder.exists() and not folder.is_dir():
        raise CliError(f"{flag} {folder}: exists and is not a folder")
    if folder.is_dir():
        old = [name for name in files if (folder / name).exists()]
        if old and not overwrite:
            raise CliError(f"{flag} {folder} holds {', '.join(old)} of an earlier run: give "
                           "--overwrite to replace them, or choose another folder")  # fmt: skip
        target = folder
    else:
        target = folder.resolve().parent
        while not target.exists():
            target = target.parent
        if not target.is_dir():
            raise CliError(f"{flag} {folder}: {str(target)!r} is not a folder")
    why = _writable_folder(target)
    if why is not None:
        raise CliError(f"{flag} {folder}: cannot write in folder {str(target)!r} ({why})")


def sidecar_path(path: Path) -> Path:
    """``<file>.meta.json``: the metadata of an output file written beside it."""
    return path.with_name(path.name + ".meta.json")


def write_sidecar(path: Path, provenance: dict[str, Any], **details: Any) -> Path:
    """Write ``<file>.meta.json`` beside an output file: its provenance
    (:func:`railhunt.provenance.provenance`), the file's name and ``details`` (the command
    and its options, the columns ...). Returns the sidecar's path."""
    from railhunt.cli.output import json_safe

    side = sidecar_path(path)
    data = {**provenance, "file": path.name, **details}
    side.write_text(json.dumps(json_safe(data), indent=1) + "\n", encoding="utf-8")
    return side
