"""The numba cache follows the sources (railhunt/_cache.py)."""

import shutil
from pathlib import Path

import railhunt
from railhunt import _cache


def test_numba_uses_the_folder_of_these_sources():
    import numba.core.config as config

    import railhunt.model  # noqa: F401  (defines cached functions)

    assert railhunt.NUMBA_CACHE is not None
    assert config.CACHE_DIR == railhunt.NUMBA_CACHE
    assert _cache.source_hash() in railhunt.NUMBA_CACHE


def test_any_source_change_changes_the_folder(tmp_path):
    """Editing one file (here model.py) gives another hash, so no stale machine code of the
    old equations can be loaded by functions in other files that inline them."""
    package = Path(railhunt.__file__).resolve().parent
    copy = tmp_path / "railhunt"
    shutil.copytree(package, copy, ignore=shutil.ignore_patterns("__pycache__", "*.nb*"))
    before = _cache.source_hash(copy)
    assert before == _cache.source_hash(package)
    model = copy / "model.py"
    model.write_text(model.read_text() + "\n# an edit\n")
    assert _cache.source_hash(copy) != before


def test_a_worker_process_shares_its_parents_folder():
    """A process started from one that imported railhunt (a local Dask worker) inherits
    NUMBA_CACHE_DIR naming the folder: it must load that cache, not nest a cold one in it."""
    import os
    import subprocess
    import sys

    env = dict(os.environ, NUMBA_CACHE_DIR=railhunt.NUMBA_CACHE)
    child = subprocess.run([sys.executable, "-c", "import railhunt; print(railhunt.NUMBA_CACHE)"],
                           env=env, capture_output=True, text=True, check=True)  # fmt: skip
    assert child.stdout.strip() == railhunt.NUMBA_CACHE
