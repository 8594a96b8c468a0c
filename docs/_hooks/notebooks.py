"""Execute the worked examples once and keep the executed notebooks for the site and the tests.

Each ``examples/NN_name.py`` (jupytext percent format) is converted to a notebook and run
cell by cell in a fresh Jupyter kernel (nbclient), with ``examples/`` as the working
directory, as ``jupyter lab`` would run it; figures are captured as PNG (the kernel runs
with ``%matplotlib inline``, also when ``MPLBACKEND=Agg`` is set for everything else, so a
cell that returns a figure shows it, as a figure made with pyplot is shown). The
executed notebook is written to a build folder as ``NN_name.ipynb`` together with a
fingerprint of what its outputs depend on (the example, ``examples/data/`` and the package's
source), the seconds it took and the files it wrote into ``examples/`` (none allowed).

The documentation hook (``docs/_hooks/examples.py``) renders those outputs into the example
pages and ``tests/test_examples.py`` checks them; both reuse an executed notebook whose
fingerprint still matches and execute it otherwise, so one ``.ci/run`` executes each
example once. The build folder is ``$RAILHUNT_EXECUTED_EXAMPLES`` when set, else
``build/examples`` in the repository. From the repository's root::

    python docs/_hooks/notebooks.py            # execute the stale examples, print times
    python docs/_hooks/notebooks.py --force    # execute all of them
    python docs/_hooks/notebooks.py --jobs 1   # one at a time (default: the cores, at most 4)
"""

from __future__ import annotations

import argparse
import hashlib
import importlib.metadata
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import jupytext
import nbclient
import nbformat
from nbformat import NotebookNode

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
#: The environment variable naming the folder of executed notebooks.
ENV_VAR = "RAILHUNT_EXECUTED_EXAMPLES"
#: Seconds one cell may take before the run is abandoned.
CELL_TIMEOUT_S = 600
_INLINE = "module://matplotlib_inline.backend_inline"


def example_paths() -> list[Path]:
    """The example notebooks ``examples/NN_name.py``, in order."""
    return sorted(EXAMPLES.glob("[0-9][0-9]_*.py"))


def build_dir() -> Path:
    """The folder of executed notebooks: ``$RAILHUNT_EXECUTED_EXAMPLES`` or build/examples."""
    return Path(os.environ.get(ENV_VAR) or ROOT / "build" / "examples")


def _inputs(path: Path) -> list[Path]:
    src = ROOT / "src" / "railhunt"
    files = [path, Path(__file__), *(EXAMPLES / "data").rglob("*"), *src.rglob("*")]
    return sorted(p for p in files if p.is_file() and "__pycache__" not in p.parts)


#: Installed packages whose version is part of the fingerprint.
_PACKAGES = ("numpy", "scipy", "numba", "matplotlib", "pandas", "xarray", "dask", "ipykernel")


def fingerprint(path: Path) -> str:
    """SHA-256 over the example, its data folder, the package's source, this runner and the
    versions of Python and the main packages."""
    digest = hashlib.sha256(sys.version.encode())
    for name in _PACKAGES:
        try:
            digest.update(f"{name}=={importlib.metadata.version(name)}".encode())
        except importlib.metadata.PackageNotFoundError:
            digest.update(f"{name} missing".encode())
    for file in _inputs(path):
        digest.update(str(file.relative_to(ROOT)).encode())
        digest.update(file.read_bytes())
    return digest.hexdigest()


def _files_in(folder: Path) -> set[Path]:
    return {p for p in folder.rglob("*") if "__pycache__" not in p.parts
            and ".ipynb_checkpoints" not in p.parts}  # fmt: skip


def execute(path: Path, out_dir: Path | None = None) -> NotebookNode:
    """Run one example as a notebook and write the executed notebook to ``out_dir``.

    Parameters
    ----------
    path : Path
        The example, ``examples/NN_name.py``.
    out_dir : Path, optional
        Where ``NN_name.ipynb`` is written; default :func:`build_dir`.

    Returns
    -------
    NotebookNode
        The executed notebook; ``metadata["railhunt"]`` holds ``fingerprint``, ``seconds``
        (wall-clock time, kernel start included) and ``wrote`` (files the run left in
        ``examples/``, relative paths).

    Raises
    ------
    nbclient.exceptions.CellExecutionError
        A cell raised (the message has the cell and its traceback).
    """
    out_dir = build_dir() if out_dir is None else out_dir
    stamp = fingerprint(path)
    nb = jupytext.read(path)
    before = _files_in(EXAMPLES)
    start = time.perf_counter()
    client = nbclient.NotebookClient(nb, timeout=CELL_TIMEOUT_S, kernel_name="python3",
                                     extra_arguments=["--matplotlib=inline"],
                                     resources={"metadata": {"path": str(EXAMPLES)}})
    client.execute(env={**os.environ, "MPLBACKEND": _INLINE})
    seconds = time.perf_counter() - start
    wrote = sorted(str(p.relative_to(EXAMPLES)) for p in _files_in(EXAMPLES) - before)
    nb.metadata["railhunt"] = {"source": f"examples/{path.name}", "fingerprint": stamp,
                               "seconds": round(seconds, 1), "wrote": wrote}
    out_dir.mkdir(parents=True, exist_ok=True)
    target = out_dir / f"{path.stem}.ipynb"
    partial = target.with_suffix(".ipynb.part")
    nbformat.write(nb, partial)
    partial.replace(target)
    return nb


def fresh(path: Path, out_dir: Path | None = None) -> NotebookNode | None:
    """The executed notebook of ``path`` in ``out_dir`` if its fingerprint matches, else None."""
    target = (build_dir() if out_dir is None else out_dir) / f"{path.stem}.ipynb"
    if target.is_file():
        nb = nbformat.read(target, as_version=4)
        if nb.metadata.get("railhunt", {}).get("fingerprint") == fingerprint(path):
            return nb
    return None


def executed(path: Path, out_dir: Path | None = None) -> NotebookNode:
    """The executed notebook of ``path``: reused when its fingerprint matches, else run."""
    nb = fresh(path, out_dir)
    return execute(path, out_dir) if nb is None else nb


def outputs(nb: NotebookNode) -> list[dict]:
    """Every output of the notebook's code cells, in order."""
    return [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]


def _previous_seconds(path: Path, out_dir: Path) -> float:
    """The seconds an earlier execution of ``path`` took (0 when none is recorded)."""
    target = out_dir / f"{path.stem}.ipynb"
    try:
        return float(nbformat.read(target, as_version=4).metadata["railhunt"]["seconds"])
    except (OSError, KeyError, ValueError, TypeError):
        return 0.0


def main(argv: list[str] | None = None) -> int:
    """Execute the examples (the stale ones, or all with ``--force``); print their times.

    Stale examples run ``--jobs`` at a time (each in its own kernel process; default: the
    machine's cores, at most 4), the longest by their last recorded time first.
    """
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--force", action="store_true", help="execute even fresh notebooks")
    parser.add_argument("--out", type=Path, default=None, help="folder of executed notebooks")
    parser.add_argument("--jobs", type=int, default=min(4, os.cpu_count() or 1),
                        help="examples executed at the same time (default: cores, at most 4)")
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error(f"--jobs must be at least 1, got {args.jobs}")
    out_dir = build_dir() if args.out is None else args.out
    failed = []
    total = time.perf_counter()
    stale = []
    for path in example_paths():
        nb = None if args.force else fresh(path, out_dir)
        if nb is None:
            stale.append(path)
        else:
            print(f"{path.name}: reused, {len(outputs(nb))} outputs", flush=True)
    stale.sort(key=lambda path: -_previous_seconds(path, out_dir))

    def run(path: Path) -> tuple[Path, NotebookNode | None, str, float]:
        start = time.perf_counter()
        try:
            nb = execute(path, out_dir)
        except nbclient.exceptions.CellExecutionError as error:
            return path, None, str(error), time.perf_counter() - start
        return path, nb, "", time.perf_counter() - start

    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for path, nb, error, seconds in pool.map(run, stale):
            if nb is None:
                print(f"{path.name}: FAILED\n{error}", file=sys.stderr)
                failed.append(path.name)
                continue
            print(f"{path.name}: {seconds:.1f} s (executed), {len(outputs(nb))} outputs",
                  flush=True)
    print(f"examples: {time.perf_counter() - total:.1f} s in all ({args.jobs} at a time) "
          f"-> {out_dir}")
    if failed:
        print(f"failed: {', '.join(failed)}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
