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
