"""MkDocs hook: counts the pages state are generated from the code, not written by hand.

A page writes a count as ``<!--count:NAME-->56<!--/count-->``: the number between the
markers is what the source shows (kept current by ``tests/test_docs.py``), and the built
page shows the value this hook computes. An unknown ``NAME`` is a warning, so ``mkdocs
build --strict`` fails on it.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

log = logging.getLogger("mkdocs.hooks.counts")

ROOT = Path(__file__).resolve().parents[2]
COUNT = re.compile(r"<!--count:([\w-]+)-->(\d+)<!--/count-->")


def _parameters() -> int:
    from railhunt.vehicle.parameters import PARAMETERS

    return len(PARAMETERS)


def _derived() -> int:
    from railhunt.vehicle.parameters import DERIVED

    return len(DERIVED)


def _examples() -> int:
    return len(list((ROOT / "examples").glob("[0-9][0-9]_*.py")))


#: What each count name counts.
COUNTS: dict[str, Callable[[], int]] = {
    "parameters": _parameters,    # settable vehicle parameters (railhunt.vehicle.PARAMETERS)
    "derived": _derived,          # derived vehicle quantities (v_u, N)
    "examples": _examples,        # worked examples, examples/NN_name.py
}


def fill(markdown: str, where: str = "") -> str:
    """The Markdown with every count marker replaced by the computed number."""

    def number(match: re.Match[str]) -> str:
        name = match.group(1)
        if name not in COUNTS:
            log.warning("%s: unknown count %r (known: %s)", where, name, ", ".join(COUNTS))
            return match.group(2)
        return str(COUNTS[name]())

    return COUNT.sub(number, markdown)


def on_page_markdown(markdown: str, page: Any, config: Any, files: Any) -> str:
    """Fill in the counts of every page."""
    return fill(markdown, page.file.src_uri)
