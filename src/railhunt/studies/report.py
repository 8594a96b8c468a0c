"""Self-contained HTML report of a reproduction run (:func:`railhunt.reproduce`).

One HTML file with everything inside: the figures as base64 ``data:`` URIs, the style
sheet inline, no scripts and no links to anything outside, so it opens in a browser with
no network and can be mailed as one attachment. Built with the standard library only
(:func:`html.escape`, :mod:`base64`).
"""

from __future__ import annotations

import base64
import html
import os
import struct
from pathlib import Path
from typing import TYPE_CHECKING

from railhunt.paper2019 import citation

if TYPE_CHECKING:
    from railhunt.studies.records import Headline, Report, Step

__all__ = ["PAPER", "build_html", "compact_difference", "data_uri", "headline_table", "png_size",
           "results_table", "write_html"]

#: The paper the report reproduces (as cited in docs/model.md; railhunt.paper2019.CITATION).
PAPER = citation()

_CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 2em auto;
       max-width: 72em; padding: 0 1em; color: #222; line-height: 1.45; }
h1 { font-size: 1.5em; margin-bottom: 0.2em; }
h2 { font-size: 1.2em; margin-top: 2em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.92em; }
th, td { border: 1px solid #ccc; padding: 0.3em 0.6em; vertical-align: top; text-align: left; }
th { background: #f0f0f0; }
td.num { text-align: right; }
table.headline { width: 100%; table-layout: fixed; font-size: 0.88em; }
table.headline td, table.headline th { padding: 0.3em 0.4em; overflow-wrap: anywhere; }
col.quantity { width: 19%; } col.value { width: 9%; } col.diff { width: 10%; }
col.unit { width: 7%; } col.where { width: 8%; } col.why { width: 38%; }
.scroll { overflow-x: auto; max-width: 100%; }
tr.agrees td.diff { background: #d9f2d9; }
tr.differs td.diff { background: #f8d7d3; }
tr.missing td.diff { background: #eee; color: #666; }
.note { color: #555; font-size: 0.9em; }
details summary { cursor: pointer; color: #555; font-size: 0.85em; }
figure { margin: 1em 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 0.92em; margin-top: 0.3em; }
.status { display: inline-block; padding: 0 0.5em; border-radius: 0.3em; font-size: 0.85em; }
.status.ok { background: #d9f2d9; }
.status.failed { background: #f8d7d3; }
.status.na { background: #eee; }
pre { background: #f6f6f6; padding: 0.5em; overflow-x: auto; font-size: 0.85em; }
.meta td:first-child { font-weight: bold; }
"""


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def data_uri(path: str | os.PathLike[str]) -> str:
    """The PNG file at ``path`` as a ``data:image/png;base64,...`` URI.

    Raises
    ------
    ValueError
        When the file is not a PNG (its first bytes are not the PNG signature).
    """
    raw = Path(path).read_bytes()
    if not raw.startswith(b"\x89PNG\r\n\x1a\n"):
        raise ValueError(f"{path}: not a PNG file (the report embeds PNG figures only)")
    return "data:image/png;base64," + base64.b64encode(raw).decode("ascii")


def png_size(path: str | os.PathLike[str]) -> tuple[int, int]:
    """Width and height (pixels) of the PNG file at ``path``, from its header."""
    head = Path(path).read_bytes()[:24]
    if len(head) < 24 or not head.startswith(b"\x89PNG\r\n\x1a\n") or head[12:16] != b"IHDR":
        raise ValueError(f"{path}: not a PNG file (the report embeds PNG figures only)")
    width, height = struct.unpack(">II", head[16:24])
    return int(width), int(height)


def _value(text: str) -> str:
    """``text`` escaped for a value cell, a percentage kept with its number.

    The cell wraps at the spaces of ``-20 (-6.2 %)`` or ``subcritical → supercritical (a)``
    but never between a number and its ``%``.
    """
    return _e(text).replace(" %", "&nbsp;%")


def compact_difference(row: Headline) -> str:
    """The difference as the table shows it: the unit, which has its own column, left out.

    ``-20 km/h (-6.2 %)`` with unit ``km/h`` becomes ``-20 (-6.2 %)``; a claim's verdict
    (``holds``) stays as it is.
    """
    text = row.difference
    if row.unit:
        text = text.replace(f" {row.unit} ", " ").replace(f" {row.unit}", "")
    return text


def _row_class(row: Headline) -> str:
    if row.agrees is None:
        return "missing"
    return "agrees" if row.agrees else "differs"


def headline_table(rows: list[Headline]) -> str:
    """HTML table of the headline rows: paper, railhunt, difference (coloured), unit, where.

    The difference cell is green when railhunt agrees with the paper within the row's
    tolerance (or the paper's statement holds), red when not, grey when not computed; the
    paper's sentence is folded under the quantity, the reason for a difference beside it.
    """
    out = ['<table class="headline">',
           '<colgroup><col class="quantity"><col class="value"><col class="value">'
           '<col class="diff"><col class="unit"><col class="where"><col class="why"></colgroup>',
           "<tr><th>quantity</th><th>paper</th><th>railhunt</th><th>difference</th>"
           "<th>unit</th><th>where in the paper</th><th>why railhunt differs</th></tr>"]
    for row in rows:
        out.append(
            f'<tr class="{_row_class(row)}" id="{_e(row.key)}">'
            f"<td>{_e(row.quantity)}<details><summary>the paper's sentence</summary>"
            f"<q>{_e(row.quote)}</q></details></td>"
            f'<td class="num">{_value(row.paper_text)}</td>'
            f'<td class="num">{_value(row.railhunt_text)}</td>'
            f'<td class="num diff">{_value(compact_difference(row))}</td>'
            f"<td>{_e(row.unit)}</td><td>{_e(row.where)}</td>"
            f'<td class="note">{_e(row.note)}</td></tr>'
        )
    out.append("</table>")
    return "\n".join(out)


def results_table(rows: list[dict[str, object]]) -> str:
    """HTML table of a step's own results: the columns of the first row, one row each."""
    heads = list(rows[0])
    out = ['<div class="scroll"><table class="results">',
           "<tr>" + "".join(f"<th>{_e(h)}</th>" for h in heads) + "</tr>"]
    for row in rows:
        cells = "".join(f'<td class="{"note" if h == "note" else "num"}">{_e(row.get(h, ""))}'
                        "</td>" for h in heads)  # fmt: skip
        out.append(f"<tr>{cells}</tr>")
    out.append("</table></div>")
    return "\n".join(out)


def _status(step: Step) -> str:
    css = {"ok": "ok", "failed": "failed"}.get(step.status, "na")
    return f'<span class="status {css}">{_e(step.status)}</span>'


def _step_html(step: Step) -> str:
    parts = [f'<section id="{_e(step.name)}">',
             f"<h2>{_e(step.title)} {_status(step)}</h2>"]  # fmt: skip
    if step.paper_caption:
        parts.append(f"<p><b>The paper's caption:</b> {_e(step.paper_caption)}</p>")
    for path in step.figures:
        width, height = png_size(path)
        parts.append(f'<figure><img src="{data_uri(path)}" width="{width}" height="{height}" '
                     f'alt="{_e(step.title)}: '
                     f'{_e(Path(path).name)}"><figcaption>{_e(Path(path).name)}'
                     "</figcaption></figure>")  # fmt: skip
    if step.table:
        parts.append(results_table(step.table))
    if step.shows:
        parts.append(f"<p><b>What railhunt shows:</b> {_e(step.shows)}</p>")
    if step.how:
        parts.append(f"<p><b>How computed:</b> {_e(step.how)} ({step.seconds:.1f} s)</p>")
    if step.message:
        parts.append(f"<pre>{_e(step.message)}</pre>")
    parts.append("</section>")
    return "\n".join(parts)


def _timings(report: Report) -> str:
    rows = "".join(f"<tr><td>{_e(s.title)}</td><td>{_status(s)}</td>"
                   f'<td class="num">{s.seconds:.1f}</td></tr>' for s in report.steps)
    return ("<table><tr><th>step</th><th>status</th><th>time (s)</th></tr>" + rows
            + f'<tr><th colspan="2">total</th><th class="num">{report.seconds:.1f}</th></tr>'
            "</table>")  # fmt: skip


def build_html(report: Report) -> str:
    """The whole report as one self-contained HTML document (str)."""
    rows = report.headline
    agree = sum(r.agrees is True for r in rows)
    differ = sum(r.agrees is False for r in rows)
    missing = sum(r.agrees is None for r in rows)
    minutes, seconds = divmod(report.seconds, 60.0)
    run_time = f"{int(minutes)} min {seconds:.0f} s" if minutes else f"{seconds:.1f} s"
    mode = "quick (coarser)" if report.quick else "full"
    workers = f"{report.workers} Dask workers" if report.workers else "this process only"
    meta = [("paper", PAPER), ("vehicle", report.vehicle), ("railhunt version", report.version),
            ("date (UTC)", report.date), ("run time", f"{run_time} ({mode}; {workers})")]
    meta_html = "".join(f"<tr><td>{_e(k)}</td><td>{_e(v)}</td></tr>" for k, v in meta)
    body = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>railhunt reproduction: {_e(report.vehicle)}</title>",
        f"<style>{_CSS}</style></head><body>",
        "<h1>railhunt: reproduction of the paper's results</h1>",
        f'<table class="meta">{meta_html}</table>',
        "<h2>Headline numbers</h2>",
        f"<p>{agree} agree with the paper (green: within the row's tolerance, 3 % for the "
        f"direct numbers, 5 % for the parameter studies, or the paper's statement holds), "
        f"{differ} differ (red; the last column says why), {missing} not computed or not "
        "judged at this run's resolution (grey).</p>",
        headline_table(rows),
        *(_step_html(s) for s in report.steps),
        "<h2>Timings</h2>",
        _timings(report),
        f"<p class=\"note\">Generated by railhunt {_e(report.version)} "
        "(<code>railhunt reproduce</code>); method and comparisons: docs/reproduce.md.</p>",
        "</body></html>",
    ]
    return "\n".join(body) + "\n"


def write_html(report: Report, path: str | os.PathLike[str]) -> Path:
    """Write :func:`build_html` of ``report`` to ``path`` (UTF-8) and return the path."""
    path = Path(path)
    path.write_text(build_html(report), encoding="utf-8")
    return path

