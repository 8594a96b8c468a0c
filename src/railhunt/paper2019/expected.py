"""What the reproduction compares against: the paper's words and its headline numbers.

Two files ship next to this module:

- ``paper.toml``: the paper's title, journal and year, the captions of the figures
  railhunt recomputes, and the sentences (quotations) its numbers are taken from;
- ``expected.toml``: one row per line of the headline table of ``railhunt reproduce``:
  what is compared, where the paper states it, the paper's value, the key of the
  quotation, the tolerance of the comparison and railhunt's note on why it differs.

The loaders check the files (every quotation and note a row names exists, every field is
known) and return read-only mappings; :mod:`railhunt.studies` builds its rows from them.
"""

from __future__ import annotations

import functools
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from importlib import resources
from types import MappingProxyType
from typing import Any

__all__ = ["KINDS", "OUTPUTS", "Expected", "captions", "citation", "expected", "notes",
           "quotations"]  # fmt: skip

#: Kinds of rows: a number compared within a tolerance, a statement judged by the step,
#: a trend along a parameter line (Figs. 10-11), a bound on a change over Table 1 (Fig. 12).
KINDS = ("number", "claim", "trend", "bound")
#: Sweep outputs a trend or a bound is about (the columns critical_speed_kmh and
#: hunting_frequency_hz of a sweep's results).
OUTPUTS = ("critical_speed", "hunting_frequency")


@dataclass(frozen=True)
class Expected:
    """One row of the headline table as the paper gives it (``expected.toml``).

    Attributes
    ----------
    key : str
        Machine name, the key in headline.json (e.g. ``"nonlinear_critical_speed_kmh"``).
    kind : str
        ``"number"``, ``"claim"``, ``"trend"`` or ``"bound"`` (see :data:`KINDS`).
    quantity : str
        What is compared.
    where : str
        Where the paper states it (section, figure).
    unit : str
        Unit of both values ("" for a type or a sequence).
    paper : float or str
        The paper's value: a number in ``unit`` (kind ``"number"``), ``"rises"`` or
        ``"falls"`` (``"trend"``), ``"> x"`` or ``"< x"`` (``"bound"``), or the statement.
    quote : str
        The paper's sentence the value is taken from (from ``paper.toml``).
    note : str
        Why railhunt differs, with the document that explains it ("" when none is given).
    rel_tol : float
        Relative tolerance of a number: it agrees when ``|railhunt - paper| <= rel_tol *
        |paper|``.
    digits : int
        Decimals of the difference shown for a number (railhunt's value keeps two more).
    line : str
        The parameter line of a trend or a bound (``"C_d1"``, ...; "" otherwise).
    output : str
        The sweep output of a trend or a bound (``"critical_speed"`` or
        ``"hunting_frequency"``; "" otherwise).
    hopf_types : tuple of str
        A claim about the bifurcation type in railhunt's names (``"subcritical"``,
        ``"supercritical-a"``, ``"supercritical-b"``); empty otherwise.
    """

    key: str
    kind: str
    quantity: str
    where: str
    unit: str
    paper: float | str
    quote: str
    note: str = ""
    rel_tol: float = 0.03
    digits: int = 1
    line: str = ""
    output: str = ""
    hopf_types: tuple[str, ...] = ()

    @property
    def bound(self) -> tuple[str, float]:
        """A bound's comparison and value: ``("<", 50.0)`` for ``paper = "< 50"``."""
        text = str(self.paper)
        return text[:1], float(text[2:])


def _read(name: str) -> dict[str, Any]:
    ref = resources.files("railhunt.paper2019") / name
    return tomllib.loads(ref.read_text(encoding="utf-8"))


def _error(name: str, why: str) -> RuntimeError:
    return RuntimeError(f"railhunt installation error: {name}: {why}")


@functools.cache
def _paper() -> dict[str, Any]:
    data = _read("paper.toml")
    for table in ("paper", "captions", "quotations"):
        if not isinstance(data.get(table), dict):
            raise _error("paper.toml", f"no [{table}] table")
    return data


def citation() -> str:
    """The paper as the report cites it: ``"<title> (<journal>, <year>)"``."""
    paper = _paper()["paper"]
    return f"{paper['title']} ({paper['journal']}, {paper['year']})"


def captions() -> Mapping[str, str]:
    """The paper's captions of the figures railhunt recomputes (``"fig6"`` ... ``"fig13"``)."""
    return MappingProxyType(_paper()["captions"])


def quotations() -> Mapping[str, str]:
    """The paper's sentences that the headline numbers are taken from, by key."""
    return MappingProxyType(_paper()["quotations"])


@functools.cache
def _expected_file() -> dict[str, Any]:
    data = _read("expected.toml")
    for table in ("notes", "rows"):
        if not isinstance(data.get(table), dict):
            raise _error("expected.toml", f"no [{table}] table")
    return data


def notes() -> Mapping[str, str]:
    """railhunt's notes on why it differs from the paper, by key (``expected.toml``)."""
    return MappingProxyType(_expected_file()["notes"])


@functools.cache
def expected() -> Mapping[str, Expected]:
    """Every row of the headline table as the paper gives it, in figure order.

    Returns
    -------
    Mapping[str, Expected]
        Read-only mapping from the row's key (the key in headline.json) to its entry.

    Raises
    ------
    RuntimeError
        The shipped files are inconsistent (an installation error).
    """
    rows = _expected_file()["rows"]
    return MappingProxyType({key: _parse_row(key, row) for key, row in rows.items()})


_FIELDS = frozenset(("kind", "quantity", "where", "unit", "paper", "quote", "note", "rel_tol",
                     "digits", "line", "output", "hopf_types"))  # fmt: skip


def _parse_row(key: str, row: Mapping[str, Any]) -> Expected:
    """Check one row of ``expected.toml`` and resolve its quotation and note."""

    def bad(why: str) -> RuntimeError:
        return _error(f"expected.toml [rows.{key}]", why)

    unknown = sorted(set(row) - _FIELDS)
    if unknown:
        raise bad(f"unknown field(s) {', '.join(unknown)}")
    kind = row.get("kind")
    if kind not in KINDS:
        raise bad(f"kind {kind!r} is not one of {', '.join(KINDS)}")
    quote = quotations().get(row.get("quote", ""))
    if quote is None:
        raise bad(f"quote {row.get('quote')!r} is not a key of paper.toml [quotations]")
    note = ""
    if "note" in row:
        note = notes().get(row["note"])
        if note is None:
            raise bad(f"note {row['note']!r} is not a key of [notes]")
    paper = row.get("paper")
    extra: dict[str, Any] = {}
    if kind == "number":
        if isinstance(paper, bool) or not isinstance(paper, int | float):
            raise bad(f"a number's paper value must be a number, not {paper!r}")
        if "rel_tol" not in row or "digits" not in row:
            raise bad("a number needs rel_tol and digits")
        paper = float(paper)
        extra = {"rel_tol": float(row["rel_tol"]), "digits": int(row["digits"])}
    elif not isinstance(paper, str):
        raise bad(f"the paper value of a {kind} must be text, not {paper!r}")
    if kind in ("trend", "bound"):
        if row.get("output") not in OUTPUTS or not row.get("line"):
            raise bad(f"a {kind} needs a line and an output ({', '.join(OUTPUTS)})")
        extra.update(line=str(row["line"]), output=str(row["output"]))
    if kind == "trend" and paper not in ("rises", "falls"):
        raise bad(f"a trend is 'rises' or 'falls', not {paper!r}")
    if kind == "bound":
        try:
            float(str(paper)[2:])
        except ValueError:
            raise bad(f"a bound is '> x' or '< x', not {paper!r}") from None
        if str(paper)[:2] not in ("> ", "< "):
            raise bad(f"a bound is '> x' or '< x', not {paper!r}")
    return Expected(key=key, kind=kind, quantity=str(row["quantity"]), where=str(row["where"]),
                    unit=str(row["unit"]), paper=paper, quote=quote, note=note,
                    hopf_types=tuple(row.get("hopf_types", ())), **extra)  # fmt: skip
