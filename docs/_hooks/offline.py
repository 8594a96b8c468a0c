"""MkDocs hook: the built site loads nothing from the internet.

After the build, every HTML page is read and any script, style sheet, font, image or frame
taken from an ``http(s)://`` address is reported as a warning, which ``mkdocs build
--strict`` turns into a failure. (Links a reader may follow are fine; the theme's fonts
are off, ``theme.font: false``, so no page asks Google Fonts for them.)
"""

from __future__ import annotations

import logging
import re
from pathlib import Path
from typing import Any

log = logging.getLogger("mkdocs.hooks.offline")

_REMOTE = re.compile(
    r"""<(?:script|img|iframe|source|audio|video|embed)\b[^>]*\bsrc=["']?(https?:)?//"""
    r"""|<link\b[^>]*\bhref=["']?(https?:)?//"""
    r"""|@import\s+(?:url\()?["']?(https?:)?//"""
    r"""|url\(["']?(https?:)?//""",
    re.IGNORECASE,
)


def remote_loads(html: str) -> list[str]:
    """The snippets of a page that would fetch something from another host."""
    return [html[m.start():m.start() + 120] for m in _REMOTE.finditer(html)]


def on_post_build(config: Any, **kwargs: Any) -> None:
    """Warn about every remote load in the built site."""
    site = Path(config["site_dir"])
    for page in sorted(site.rglob("*.html")):
        for snippet in remote_loads(page.read_text(encoding="utf-8", errors="replace")):
            log.warning("%s loads a remote resource: %s", page.relative_to(site), snippet)
