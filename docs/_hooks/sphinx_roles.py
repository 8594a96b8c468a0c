"""Griffe extension for the docs build: numpydoc as written in railhunt, read by griffe.

Two rewrites of each docstring before griffe parses it:

* Sphinx roles (``:class:`Model```, ``:func:`~railhunt.sweep```) become code spans of the
  name (the last component when the target starts with ``~``, the text of
  ``text <target>``): mkdocstrings renders Markdown, where a role prints as written.
* A parameter entry that names several parameters (``start_kmh, step_kmh : float``) is
  split into one entry per name with the same description, because griffe gives every
  name of such an entry the default value of the first.
"""

from __future__ import annotations

import re
from typing import Any

import griffe

_ROLE = re.compile(r":(?:py:)?(?:class|func|meth|data|attr|mod|obj|exc|const):`([^`]+)`")


def convert(text: str) -> str:
    """The docstring text with every Sphinx role replaced by a code span."""

    def span(match: re.Match[str]) -> str:
        target = match.group(1).strip()
        label = re.match(r"^(.*?)\s*<[^>]+>$", target)
        if label:
            target = label.group(1)
        elif target.startswith("~"):
            target = target[1:].rsplit(".", 1)[-1]
        return f"`{target}`"

    return _ROLE.sub(span, text)


_GROUPED = re.compile(r"^(\s*)(\*{0,2}\w+(?:\s*,\s*\*{0,2}\w+)+)\s*:\s*(.*)$")
_PARAMETER_SECTIONS = {"Parameters", "Other Parameters"}


def split_grouped_parameters(text: str) -> str:
    """One entry per name in the Parameters sections (``a, b : float`` -> two entries)."""
    lines = text.splitlines()
    out: list[str] = []
    section = ""
    i = 0
    while i < len(lines):
        line = lines[i]
        if i + 1 < len(lines) and re.fullmatch(r"\s*-{3,}\s*", lines[i + 1]):
            section = line.strip()
        match = _GROUPED.match(line) if section in _PARAMETER_SECTIONS else None
        if match is None:
            out.append(line)
            i += 1
            continue
        indent, names, kind = match.groups()
        body = []
        i += 1
        while i < len(lines) and (not lines[i].strip() or
                                  len(lines[i]) - len(lines[i].lstrip()) > len(indent)):
            body.append(lines[i])
            i += 1
        while body and not body[-1].strip():
            i -= 1
            body.pop()
        for name in (n.strip() for n in names.split(",")):
            out.append(f"{indent}{name} : {kind}".rstrip())
            out.extend(body)
    return "\n".join(out)


class SphinxRoles(griffe.Extension):
    """Rewrite every docstring griffe loads (module docstring)."""

    def on_instance(self, *, obj: griffe.Object, **kwargs: Any) -> None:  # noqa: D102
        if obj.docstring is not None:
            obj.docstring.value = split_grouped_parameters(convert(obj.docstring.value))
