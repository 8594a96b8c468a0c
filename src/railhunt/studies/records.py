"""The records of a reproduction run and how a row compares railhunt's value with the paper's.

:class:`Headline` is one row of the headline table, :class:`Step` one figure (or group of
figures), :class:`Report` the whole run (the content of ``headline.json``);
:class:`Settings` is the run's resolution and :class:`Context` what every step receives.
:func:`compare` and :func:`claim` build a row from the paper's entry
(:class:`railhunt.paper2019.Expected`) and railhunt's value. Both the steps
(:mod:`railhunt.studies.reproduce` and its ``reproduce_fig*`` modules) and the HTML writer
(:mod:`railhunt.studies.report`) import from here; this module imports neither.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from railhunt.paper2019 import Expected
    from railhunt.vehicle import Vehicle

__all__ = ["NOT_JUDGED", "Context", "Headline", "Report", "Settings", "Step", "claim", "compare",
           "compare_within", "not_judged", "show"]  # fmt: skip

#: The difference of a row whose verdict the run's resolution cannot give.
NOT_JUDGED = "not judged at this resolution"


@dataclass
class Headline:
    """One row of the headline table: a number (or a claim) of the paper beside railhunt's.

    Attributes
    ----------
    key : str
        Machine name, e.g. ``"nonlinear_critical_speed_kmh"`` (the key in headline.json).
    quantity : str
        What is compared.
    where : str
        Where the paper states it (section, figure).
    unit : str
        Unit of both values ("" for a type or a claim).
    paper : float or str
        The paper's value (a number in ``unit``, or text for a type or a claim).
    railhunt : float or str or None
        railhunt's value (None when the step was not available).
    difference : str
        ``railhunt - paper`` with the relative difference, or whether a claim holds.
    agrees : bool or None
        True when within the row's tolerance (or the claim holds), None when not computed
        or not judged at the run's resolution (:data:`NOT_JUDGED`).
    quote : str
        The paper's sentence the number is taken from.
    note : str
        Why railhunt differs, with the document that explains it ("" when it agrees).
    """

    key: str
    quantity: str
    where: str
    unit: str
    paper: float | str
    railhunt: float | str | None
    difference: str
    agrees: bool | None
    quote: str
    note: str = ""

    @property
    def paper_text(self) -> str:
        """The paper's value as shown in the table."""
        return show(self.paper)

    @property
    def railhunt_text(self) -> str:
        """railhunt's value as shown in the table ("not available" when not computed)."""
        return "not available" if self.railhunt is None else show(self.railhunt)


@dataclass
class Step:
    """One figure (or group of figures) of the reproduction.

    Attributes
    ----------
    name : str
        Short name (``"fig6"``, ``"fig7"``, ``"fig8"``, ``"fig10-12"``, ``"fig13"``).
    title : str
        Heading in the report.
    paper_caption : str
        The paper's caption of the figure(s).
    shows : str
        What railhunt's figure shows, with its main numbers.
    how : str
        How railhunt computed it (functions and settings).
    figures : list of pathlib.Path
        PNG files written.
    headline : list of Headline
        This step's rows of the headline table.
    seconds : float
        Run time of the step (s).
    status : str
        ``"ok"``, ``"not available"`` (a part railhunt does not have yet) or ``"failed"``.
    message : str
        Why the step is not available or failed ("" when ok).
    table : list of dict
        A table of railhunt's own results (column heading -> cell text, one dict per row)
        for a step beyond the paper, which has no headline rows; empty for the others.
    """

    name: str
    title: str
    paper_caption: str
    shows: str = ""
    how: str = ""
    figures: list[Path] = field(default_factory=list)
    headline: list[Headline] = field(default_factory=list)
    seconds: float = 0.0
    status: str = "ok"
    message: str = ""
    table: list[dict[str, Any]] = field(default_factory=list)


@dataclass
class Report:
    """Outcome of :func:`reproduce`.

    Attributes
    ----------
    out_dir, html, json : pathlib.Path
        Output folder, ``report.html`` and ``headline.json``.
    steps : list of Step
        One per figure, in report order.
    vehicle : str
        Name of the vehicle.
    version : str
        railhunt version.
    date : str
        UTC time the run started (ISO 8601).
    quick : bool
        True for the coarser ``--quick`` run.
    seconds : float
        Total run time (s).
    workers : int
        Number of Dask workers used (0: none, everything in this process).
    vehicle_fingerprint : str
        Fingerprint of the vehicle's parameters (:func:`railhunt.provenance.vehicle_fingerprint`).
    """

    out_dir: Path
    html: Path
    json: Path
    steps: list[Step]
    vehicle: str
    version: str
    date: str
    quick: bool
    seconds: float
    workers: int = 0
    vehicle_fingerprint: str = ""

    @property
    def headline(self) -> list[Headline]:
        """All rows of the headline table, in step order."""
        return [row for step in self.steps for row in step.headline]

    @property
    def failed(self) -> list[Step]:
        """The steps that raised an error."""
        return [s for s in self.steps if s.status == "failed"]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (the content of headline.json)."""
        rows = []
        for row in self.headline:
            d = asdict(row)
            d["railhunt"] = _json_number(row.railhunt)
            d["paper"] = _json_number(row.paper)
            rows.append(d)
        return {
            "railhunt_version": self.version,
            "vehicle": self.vehicle,
            "vehicle_fingerprint": self.vehicle_fingerprint,
            "date": self.date,
            "quick": self.quick,
            "seconds": round(self.seconds, 2),
            "workers": self.workers,
            "values": {r["key"]: r["railhunt"] for r in rows},
            "headline": rows,
            "steps": [{"name": s.name, "title": s.title, "status": s.status,
                       "message": s.message, "seconds": round(s.seconds, 2),
                       "figures": [p.name for p in s.figures],
                       **({"table": s.table} if s.table else {})} for s in self.steps],
        }  # fmt: skip


@dataclass(frozen=True)
class Settings:
    """Resolution of the reproduction (the full run; :meth:`quick` for the coarse one).

    Attributes
    ----------
    fig6_duration : float
        Simulated time of the two Fig. 6 runs (s).
    diagram_range_kmh : (float, float)
        Speed range of the bifurcation diagrams (km/h).
    frequency_speeds_kmh : (float, float, float)
        First, last speed and step of the Fig. 7b frequency scan (km/h).
    jump_tol_kmh : float
        Resolution to which the frequency jump is bisected (km/h).
    initial_amplitude : float
        Initial lateral displacement of every wheelset for the frequency (m); the paper's 3 mm.
    family_kn : tuple of float
        Blow-off forces of the Fig. 13 family (kN; ``inf`` for no blow-off).
    sweep_points_per_section : int
        Points per Table 1 section of the Figs. 10–12 sweep, both ends included (each
        parameter line has ``3 * (n - 1) + 1`` points).
    map_radii : tuple of float
        Curve radii of the stability map beyond the paper (m; ``inf`` for straight track).
    map_cant : float
        Cant of those curves (m).
    map_nonlinear : bool
        Also the nonlinear critical speed of each radius (not only the linear one).
    coarse : bool
        A coarse run (``--quick``): rows whose verdict could change with a finer
        resolution say :data:`NOT_JUDGED` instead of a verdict.
    """

    fig6_duration: float = 20.0
    diagram_range_kmh: tuple[float, float] = (200.0, 500.0)
    frequency_speeds_kmh: tuple[float, float, float] = (250.0, 450.0, 5.0)
    jump_tol_kmh: float = 1.0
    initial_amplitude: float = 3e-3
    family_kn: tuple[float, ...] = (1.0, 2.0, 3.0, 5.0, 8.0, math.inf)
    sweep_points_per_section: int = 6
    map_radii: tuple[float, ...] = (2000.0, 4000.0, 8000.0, math.inf)
    map_cant: float = 0.15
    map_nonlinear: bool = True
    coarse: bool = False

    @classmethod
    def quick(cls) -> Settings:
        """Coarser settings for a run of under a minute (fewer speeds, a smaller family, the
        stability map without the nonlinear search)."""
        return cls(frequency_speeds_kmh=(300.0, 450.0, 10.0), jump_tol_kmh=2.5,
                   family_kn=(1.0, 3.0, math.inf), sweep_points_per_section=2,
                   map_nonlinear=False, coarse=True)  # fmt: skip


@dataclass
class Context:
    """What every step of the reproduction receives.

    Attributes
    ----------
    vehicle : Vehicle
        The vehicle (the paper's by default).
    out_dir : pathlib.Path
        Folder for the figures (and ``sweep.csv``).
    settings : Settings
        The run's resolution.
    client : dask.distributed.Client or None
        Runs the parallel parts as Dask tasks; None: everything in this process.
    shared : dict
        Results one step leaves for a later one (``"critical_speed"``, ``"diagram"``,
        ``"jump"``).
    """

    vehicle: Vehicle
    out_dir: Path
    settings: Settings
    client: Any = None
    shared: dict[str, Any] = field(default_factory=dict)


# --------------------------------------------------------------------------- comparisons


def show(value: float | str | None, fmt: str = ".4g") -> str:
    """A value as the table shows it: text as it is, a number to 4 significant digits.

    ``None`` is ``"n/a"``, a number that is not finite ``"none"``.
    """
    if value is None:
        return "n/a"
    if isinstance(value, str):
        return value
    if not math.isfinite(value):
        return "none"
    return format(value, fmt)


def _json_number(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def compare(expected: Expected, value: float) -> Headline:
    """A row for a number of the paper: agrees when ``|value - paper| <= rel_tol * |paper|``.

    Parameters
    ----------
    expected : railhunt.paper2019.Expected
        The paper's entry (kind ``"number"``): its value, ``rel_tol`` and ``digits``.
    value : float
        railhunt's value, in the entry's unit; rounded to ``digits + 2`` decimals. Not
        finite: "railhunt has none", which does not agree.

    Returns
    -------
    Headline
        The difference ``value - paper`` to ``digits`` decimals with the relative one;
        the entry's note only when railhunt differs.
    """
    e = expected
    paper, digits = float(e.paper), e.digits
    value = float(value)
    if not math.isfinite(value):
        return Headline(e.key, e.quantity, e.where, e.unit, paper, value, "railhunt has none",
                        False, e.quote, e.note)  # fmt: skip
    value = round(value, digits + 2)
    diff = value - paper
    rel = f" ({diff / paper * 100:+.1f} %)" if paper else ""
    unit_text = f" {e.unit}" if e.unit else ""
    agrees = bool(abs(diff) <= e.rel_tol * abs(paper))
    return Headline(e.key, e.quantity, e.where, e.unit, paper, value,
                    f"{diff:+.{digits}f}{unit_text}{rel}", agrees, e.quote,
                    "" if agrees else e.note)  # fmt: skip


def claim(expected: Expected, value: float | str, holds: bool) -> Headline:
    """A row for a statement of the paper (an inequality, a type, a sequence, a trend).

    Parameters
    ----------
    expected : railhunt.paper2019.Expected
        The paper's entry; its ``paper`` is shown as it is.
    value : float or str
        railhunt's value (a number is rounded to 3 decimals) or text.
    holds : bool
        Whether the statement holds for railhunt (judged by the step).

    Returns
    -------
    Headline
        "holds" or "does not hold"; the entry's note only when it does not hold.
    """
    e = expected
    holds = bool(holds)
    if not isinstance(value, str):
        value = round(float(value), 3)
    return Headline(e.key, e.quantity, e.where, e.unit, e.paper, value,
                    "holds" if holds else "does not hold", holds, e.quote,
                    "" if holds else e.note)  # fmt: skip


def not_judged(expected: Expected, value: float | str, why: str) -> Headline:
    """A row whose verdict the run's resolution cannot give: railhunt's value is shown, the
    difference says :data:`NOT_JUDGED` and ``why`` takes the note's place.

    Parameters
    ----------
    expected : railhunt.paper2019.Expected
        The paper's entry.
    value : float or str
        railhunt's value at this resolution (a number is rounded to 3 decimals).
    why : str
        What the resolution leaves open, e.g. "2 points per section: the total variation
        can only grow with more points".
    """
    e = expected
    if not isinstance(value, str):
        value = round(float(value), 3)
    return Headline(e.key, e.quantity, e.where, e.unit, e.paper, value, NOT_JUDGED, None,
                    e.quote, why)  # fmt: skip


def compare_within(expected: Expected, value: float, low: float, high: float,
                   why: str) -> Headline:  # fmt: skip
    """:func:`compare` for a value the run only knows within ``[low, high]`` (its resolution).

    The row agrees (or differs) only when the whole interval lies inside (or outside) the
    paper's tolerance; otherwise it is :func:`not_judged` with ``why``.
    """
    e = expected
    paper = float(e.paper)
    lo_ok, hi_ok = paper - e.rel_tol * abs(paper), paper + e.rel_tol * abs(paper)
    if not (math.isfinite(low) and math.isfinite(high)):
        return compare(e, value)
    if (lo_ok <= low and high <= hi_ok) or high < lo_ok or low > hi_ok:
        return compare(e, value)
    return not_judged(e, round(float(value), e.digits + 2), why)
