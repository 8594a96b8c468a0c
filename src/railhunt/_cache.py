"""A numba cache folder per version of railhunt's sources.

Numba's on-disk cache (``cache=True``) invalidates a compiled function only when *its own*
source file changes. Every compiled function of railhunt calls (and inlines) the one
right-hand side in :mod:`railhunt.model`, mostly from other files (the integrators, the
shooting flow, the derived channels), so after an edit of ``model.py`` (a ``git pull`` in a
development checkout, say) numba would silently reuse machine code built from the old
equations. To rule that out, the cache lives in a folder named after a hash of all the
package's sources: any change of any source gives a fresh cache.

The folder is ``$NUMBA_CACHE_DIR/railhunt-<hash>`` when ``NUMBA_CACHE_DIR`` is set, else
``$XDG_CACHE_HOME/railhunt/numba-<hash>`` (default ``~/.cache``); if that cannot be
created, numba's default (next to the sources) is kept. A ``NUMBA_CACHE_DIR`` that already
names this folder (inherited from a process that imported railhunt, as local Dask workers
inherit it) is kept as it is, so worker processes load the parent's compiled code instead
of compiling their own into a nested folder.
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path

_own_hash: str | None = None  # railhunt's own, hashed once: the sources this process runs


def source_hash(root: Path | None = None) -> str:
    """First 16 hex digits of the SHA-1 of a package's Python sources (names and bytes).

    ``root`` defaults to railhunt's own package folder, whose hash is computed once per
    process (at import: the sources the process runs, even if they are edited later;
    studies record it, and hashing some 200 files took 8 ms of each study).
    """
    global _own_hash
    if root is None:
        if _own_hash is None:
            _own_hash = _hash_sources(Path(__file__).resolve().parent)
        return _own_hash
    return _hash_sources(Path(root))


def _hash_sources(root: Path) -> str:
    digest = hashlib.sha1()
    for path in sorted(root.rglob("*.py")):
        digest.update(path.relative_to(root).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def configure() -> str | None:
    """Point numba's cache at the folder for these sources; returns it (None if unchanged)."""
    tag = source_hash()
    user = os.environ.get("NUMBA_CACHE_DIR")
    if user and Path(user).name in (f"railhunt-{tag}", f"numba-{tag}"):
        folder = Path(user)  # set by a parent process (a Dask worker): the same cache
    elif user:
        folder = Path(user) / f"railhunt-{tag}"
    else:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
        folder = base / "railhunt" / f"numba-{tag}"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    if "numba" in sys.modules:  # numba read its configuration already: update it
        from numba.core import config

        config.CACHE_DIR = str(folder)
    else:
        os.environ["NUMBA_CACHE_DIR"] = str(folder)
    return str(folder)
