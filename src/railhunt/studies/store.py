"""Result files of parameter studies: written task by task, resumable, readable.

A study's rows are appended to a CSV file as each task finishes (a task's points at once,
flushed and synced, so a killed process loses at most the task in flight). Beside it,
``<file>.sweep.json`` describes the study (vehicle, design, outputs, options and a
fingerprint of all of them); ``resume`` checks the fingerprint, drops a torn last line,
and reports which points are done, so that only missing points are computed and none is
written twice. When the study
finishes the file is rewritten sorted by point, so identical inputs give identical files.

For a ``.parquet`` file (needs pyarrow) the rows are journalled in ``<file>.journal.csv``;
the Parquet file is rewritten from the journal every few seconds and at the end, and the
journal is removed once the study is complete.
"""

from __future__ import annotations

import csv
import fcntl
import hashlib
import io
import json
import math
import numbers
import os
import time
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from railhunt.results import Columns, ResultDisplay, Row
from railhunt.studies.outputs import NEW_OUTPUT_COLUMNS
from railhunt.vehicle.parameters import PARAMETERS

#: Output name -> its columns, in file order.
OUTPUT_COLUMNS: dict[str, tuple[str, ...]] = {
    "critical_speed": ("critical_speed_kmh",),
    "linear_critical_speed": ("linear_critical_speed_kmh", "linear_frequency_hz"),
    "hunting_frequency": ("frequency_speed_kmh", "hunting_frequency_hz", "frequency_source"),
}
#: The default outputs of a sweep.
OUTPUTS = tuple(OUTPUT_COLUMNS)
OUTPUT_COLUMNS.update(NEW_OUTPUT_COLUMNS)
#: Every output a study can ask for (:mod:`railhunt.studies.outputs` adds the fold speed,
#: the least damping ratio and the curving outputs).
ALL_OUTPUTS = tuple(OUTPUT_COLUMNS)
TEXT_COLUMNS = frozenset({"line", "frequency_source", "status", "message"})
STATUS_OK, STATUS_NO_CRITICAL_SPEED, STATUS_FAILED = "ok", "no-critical-speed", "failed"
PARQUET_INTERVAL_S = 2.0


class ResultFileError(ValueError):
    """A results file that cannot be read, resumed or written."""


def columns_for(parameters: Sequence[str], outputs: Sequence[str]) -> list[str]:
    """Column names of a results file, in order.

    Parameters
    ----------
    parameters : sequence of str
        The parameter columns (SI values).
    outputs : sequence of str
        Output names (keys of :data:`OUTPUT_COLUMNS`).

    Returns
    -------
    list of str
        ``point``, ``line``, the parameters, the outputs' columns, ``status``, ``message``.
    """
    cols = ["point", "line", *parameters]
    for name in outputs:
        cols.extend(OUTPUT_COLUMNS[name])
    return [*cols, "status", "message"]


#: Keys of a study description that do not decide whether a file resumes: the fingerprint
#: itself, the provenance (the vehicle's name, which does not change the numbers) and the
#: timings of the last run (:meth:`ResultStore.note`).
UNFINGERPRINTED = frozenset({"fingerprint", "provenance", "timings"})


def column_unit(name: str) -> str:
    """Unit of a results column: a vehicle parameter's SI unit, or from its suffix."""
    if name in PARAMETERS:
        return PARAMETERS[name].unit
    for suffix, unit in (("_kmh", "km/h"), ("_hz", "Hz"), ("_m", "m"), ("_s", "s")):
        if name.endswith(suffix):
            return unit
    return ""


def sidecar_path(path: Path) -> Path:
    """``<file>.sweep.json``: the study description beside a results file."""
    return path.with_name(path.name + ".sweep.json")


def journal_path(path: Path) -> Path:
    """The CSV a study's rows are appended to: the file itself, or for Parquet a journal."""
    return path.with_name(path.name + ".journal.csv") if is_parquet(path) else path


def is_parquet(path: Path) -> bool:
    """Whether ``path`` names a Parquet file (by its suffix)."""
    return path.suffix.lower() in (".parquet", ".pq")


def fingerprint(meta: Mapping[str, Any]) -> str:
    """SHA-256 of a study description.

    Parameters
    ----------
    meta : Mapping
        The description (JSON types).

    Returns
    -------
    str
        Hex digest of its canonical JSON (sorted keys).
    """
    text = json.dumps(meta, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def _cell(value: object) -> str:
    kind = type(value)
    if kind is float:  # the common cases first, by exact type
        return "nan" if value != value else repr(value)
    if kind is str:
        return " ".join(value.split())  # type: ignore[union-attr]
    if kind is int:
        return str(value)
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return str(int(value))
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        value = float(value)  # numpy scalars included: repr() of a float round-trips
        return "nan" if math.isnan(value) else repr(value)
    if value is None:
        return ""
    return " ".join(str(value).split())  # one line per point, whatever the message


def _parse(name: str, text: str) -> object:
    if name in TEXT_COLUMNS:
        return text
    if name == "point":
        return int(text)
    return float(text) if text != "" else math.nan


def _require_pyarrow() -> Any:
    try:
        import pyarrow  # noqa: F401
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise ResultFileError("writing or reading Parquet needs pyarrow (pip install pyarrow);"
                              " or use a .csv results file") from None  # fmt: skip
    return pyarrow


@dataclass(repr=False)
class SweepResults(ResultDisplay):
    """The rows of a study (one dict per point, sorted by point) and its description.

    Attributes
    ----------
    rows : list of dict
        Column name -> value: ``point`` int, ``line``/``status``/``message``/
        ``frequency_source`` str, the rest float (SI parameter values, km/h, Hz).
    meta : dict
        The study description of ``<file>.sweep.json`` (empty if there is none).
    path : Path, optional
        The results file.
    computed, resumed : int
        Points computed by this run, and found done in the file.
    lost_reasons : list of str
        Why each lost point was lost (its task could not finish; run again with
        ``resume=True``).
    elapsed_s : float
        Wall time of the run (s).
    evaluation_s : float
        Time (s) spent evaluating this run's points, summed over the processes that ran
        them: this one and forked local workers (a Dask cluster's workers are not timed).
        ``elapsed_s - evaluation_s / workers`` is what the study machinery cost.
    """

    rows: list[dict[str, Any]]
    meta: dict[str, Any] = field(default_factory=dict)
    path: Path | None = None
    computed: int = 0
    resumed: int = 0
    lost_reasons: list[str] = field(default_factory=list)
    elapsed_s: float = 0.0
    evaluation_s: float = 0.0

    @property
    def lost(self) -> int:
        """Points lost by this run (see ``lost_reasons``)."""
        return len(self.lost_reasons)

    @property
    def columns(self) -> list[str]:
        """Column names, in file order."""
        if self.meta.get("columns"):
            return list(self.meta["columns"])
        return list(self.rows[0]) if self.rows else []

    @property
    def parameters(self) -> list[str]:
        """The parameter columns (SI values)."""
        if "parameter_columns" in self.meta:
            return list(self.meta["parameter_columns"])
        known = {"point", "line", "status", "message"}
        for cols in OUTPUT_COLUMNS.values():
            known.update(cols)
        return [c for c in self.columns if c not in known]

    @property
    def lines(self) -> list[str]:
        """Distinct ``line`` values, in order of first appearance."""
        return list(dict.fromkeys(r["line"] for r in self.rows))

    def line(self, name: str) -> SweepResults:
        """The rows of one line (``line == name``), sorted by point."""
        if name not in self.lines:
            raise KeyError(f"no line {name!r} in the results (lines: {', '.join(self.lines)})")
        rows = [r for r in self.rows if r["line"] == name]
        return SweepResults(rows, self.meta, self.path)

    def column(self, name: str) -> Any:
        """One column: a float array, or a list of str for the text columns."""
        if name not in self.columns:
            raise KeyError(f"no column {name!r} (columns: {', '.join(self.columns)})")
        values = [r[name] for r in self.rows]
        if name in TEXT_COLUMNS:
            return values
        return np.asarray(values, dtype=int if name == "point" else float)

    def __len__(self) -> int:
        return len(self.rows)

    def _summary(self) -> list[Row]:
        statuses = [r.get("status", "") for r in self.rows]
        rows: list[Row] = [("points", len(self.rows), ""),
                           ("parameters", ", ".join(self.parameters) or "-", ""),
                           ("lines", len(self.lines) if self.rows else 0, ""),
                           ("ok", statuses.count(STATUS_OK), ""),
                           ("no critical speed", statuses.count(STATUS_NO_CRITICAL_SPEED), ""),
                           ("failed", statuses.count(STATUS_FAILED), "")]  # fmt: skip
        for name in ("critical_speed_kmh", "linear_critical_speed_kmh", "hunting_frequency_hz"):
            if name in self.columns and self.rows:
                values = np.asarray(self.column(name), dtype=float)
                if np.any(np.isfinite(values)):
                    unit = column_unit(name)
                    rows.append((name, f"{np.nanmin(values):.4g} to {np.nanmax(values):.4g}",
                                 unit))  # fmt: skip
        if self.path is not None:
            rows.append(("file", str(self.path), ""))
        if self.computed or self.resumed or self.lost:
            rows += [("computed / resumed / lost", f"{self.computed} / {self.resumed} / "
                      f"{self.lost}", ""), ("wall time", self.elapsed_s, "s")]  # fmt: skip
        return rows

    def _columns(self) -> Columns:
        """The rows of the results file, one per point (units: :func:`column_unit`)."""
        return {name: ([r.get(name) for r in self.rows], column_unit(name))
                for name in self.columns}  # fmt: skip

    def to_csv_text(self) -> str:
        """The rows as CSV text (header + one line per point)."""
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        cols = self.columns
        writer.writerow(cols)
        for row in self.rows:
            writer.writerow([_cell(row.get(c)) for c in cols])
        return buf.getvalue()


def _read_csv_rows(path: Path, repair: bool = False) -> tuple[list[str], list[dict[str, Any]]]:
    """Header and complete rows of a journal/results CSV.

    A torn last line (no newline: the process died while writing it) is dropped, and with
    ``repair`` cut off the file so that appending continues on a clean line.
    """
    data = path.read_bytes()
    if data and not data.endswith(b"\n"):
        cut = data.rfind(b"\n") + 1
        data = data[:cut]
        if repair:
            with open(path, "r+b") as fh:
                fh.truncate(cut)
    text = data.decode("utf-8")
    reader = csv.reader(io.StringIO(text))
    try:
        header = next(reader)
    except StopIteration:
        return [], []
    rows = []
    for lineno, cells in enumerate(reader, start=2):
        if len(cells) != len(header):
            raise ResultFileError(f"{path}: line {lineno} has {len(cells)} cells, the header "
                                  f"{len(header)}")  # fmt: skip
        try:
            rows.append({h: _parse(h, c) for h, c in zip(header, cells, strict=True)})
        except ValueError as exc:
            raise ResultFileError(f"{path}: line {lineno}: {exc}") from None
    return header, rows


def _read_parquet_rows(path: Path) -> tuple[list[str], list[dict[str, Any]]]:
    _require_pyarrow()
    import pyarrow.parquet as pq

    table = pq.read_table(path)
    header = table.column_names
    rows = []
    for rec in table.to_pylist():
        rows.append({h: (int(rec[h]) if h == "point" else
                         (rec[h] if h in TEXT_COLUMNS else
                          (math.nan if rec[h] is None else float(rec[h]))))
                     for h in header})  # fmt: skip
    return header, rows


def _unique_sorted(rows: Iterable[dict[str, Any]]) -> list[dict[str, Any]]:
    by_point: dict[int, dict[str, Any]] = {}
    for row in rows:
        by_point.setdefault(row["point"], row)
    return [by_point[k] for k in sorted(by_point)]


def _read_sidecar(path: Path) -> dict[str, Any] | None:
    """The study description, or None if it is missing or unreadable (torn by a kill)."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return data if isinstance(data, dict) else None


def _write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file and a rename (never torn)."""
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)


def read_results(path: str | os.PathLike[str]) -> SweepResults:
    """Read a results file (CSV or Parquet) written by :func:`railhunt.sweep`.

    Parameters
    ----------
    path : path-like
        The results file; a study still running or interrupted is read from what it has
        written so far (its journal, for Parquet).

    Returns
    -------
    SweepResults
        Rows sorted by point (a point written twice is read once).
    """
    path = Path(path)
    journal = journal_path(path)
    header: list[str] = []
    rows: list[dict[str, Any]] = []
    if not path.exists() and not journal.exists():
        raise ResultFileError(f"{path}: no such results file")
    if is_parquet(path) and path.exists():
        header, rows = _read_parquet_rows(path)
    if journal != path and journal.exists():
        jh, jrows = _read_csv_rows(journal)
        header = header or jh
        rows += jrows
    elif journal == path:
        header, rows = _read_csv_rows(path)
    if not header or "point" not in header or "line" not in header:
        raise ResultFileError(f"{path}: not a railhunt results file (no 'point' and 'line' "
                              "columns)")  # fmt: skip
    meta = _read_sidecar(sidecar_path(path)) or {}
    meta.setdefault("columns", header)
    return SweepResults(_unique_sorted(rows), meta, path)


class ResultStore:
    """Writes a study's rows as points finish; knows which points a file already holds.

    Parameters
    ----------
    path : path-like
        Results file (``.csv``, or ``.parquet`` with pyarrow).
    meta : dict
        Study description; written to ``<file>.sweep.json`` and, on resume, compared
        with the one there.
    resume : bool
        Continue an existing file (only the points it lacks are to be computed).
    overwrite : bool
        Replace an existing file.
    """

    def __init__(self, path: str | os.PathLike[str], meta: dict[str, Any], resume: bool = False,
                 overwrite: bool = False) -> None:  # fmt: skip
        self.path = Path(path)
        self.journal = journal_path(self.path)
        self.side = sidecar_path(self.path)
        self.columns: list[str] = list(meta["columns"])
        self.meta = dict(meta)
        self.meta["fingerprint"] = fingerprint({k: v for k, v in meta.items()
                                                if k not in UNFINGERPRINTED})  # fmt: skip
        self.parquet = is_parquet(self.path)
        if self.parquet:
            _require_pyarrow()
        self.rows: dict[int, dict[str, Any]] = {}
        exists = self.path.exists() or self.journal.exists()
        if exists and not resume and not overwrite:
            raise ResultFileError(f"{self.path} exists: resume it (--resume / resume=True), "
                                  "overwrite it (--overwrite), or choose another file")  # fmt: skip
        if exists and not resume:
            for p in (self.path, self.journal):
                p.unlink(missing_ok=True)
        if not self.path.parent.is_dir():
            raise ResultFileError(f"{self.path}: folder {str(self.path.parent)!r} does not "
                                  "exist; create it first or choose another file")  # fmt: skip
        self.created = not self.journal.exists()
        self._fh = open(self.journal, "a", encoding="utf-8", newline="")  # noqa: SIM115
        try:  # one writer per file: a second sweep on it would duplicate points
            fcntl.flock(self._fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            self._fh.close()
            raise ResultFileError(f"another sweep is writing {self.journal}; wait for it or "
                                  "choose another file") from None  # fmt: skip
        try:
            if exists and resume:
                self._load_for_resume()  # under the lock: it may cut a torn last line
        except BaseException:
            self._fh.close()
            raise
        self.created = self.created and not self.rows
        new = self.journal.stat().st_size == 0
        _write_atomic(self.side, json.dumps(self.meta, indent=1) + "\n")
        self._writer = csv.writer(self._fh, lineterminator="\n")
        if new:
            self._writer.writerow(self.columns)
            self._sync()
        self._parquet_written = time.monotonic()

    @property
    def done(self) -> set[int]:
        """Points already in the file."""
        return set(self.rows)

    def _load_for_resume(self) -> None:
        old = _read_sidecar(self.side)
        if old is None:
            raise ResultFileError(f"cannot resume {self.path}: its study description "
                                  f"{self.side.name} is missing or unreadable")  # fmt: skip
        if old.get("fingerprint") != self.meta["fingerprint"]:
            differ = sorted(k for k in set(old) | set(self.meta)
                            if k not in UNFINGERPRINTED and old.get(k) != self.meta.get(k))
            raise ResultFileError(f"cannot resume {self.path}: it was written by a different "
                                  f"study (differs in: {', '.join(differ) or 'version'}); "
                                  "use another file or --overwrite")  # fmt: skip
        rows: list[dict[str, Any]] = []
        if self.parquet and self.path.exists():
            rows += _read_parquet_rows(self.path)[1]
        if self.journal.exists():
            header, jrows = _read_csv_rows(self.journal, repair=True)
            if header and header != self.columns:
                raise ResultFileError(f"cannot resume {self.journal}: its columns differ from "
                                      "the study's")  # fmt: skip
            rows += jrows
        if self.parquet and self.path.exists() and self.journal.stat().st_size == 0:
            # A finished Parquet study: start the (new, empty) journal with its rows.
            with open(self.journal, "w", encoding="utf-8", newline="") as fh:
                w = csv.writer(fh, lineterminator="\n")
                w.writerow(self.columns)
                for row in _unique_sorted(rows):
                    w.writerow([_cell(row.get(c)) for c in self.columns])
        for row in rows:
            self.rows.setdefault(row["point"], row)

    def _sync(self) -> None:
        self._fh.flush()
        os.fsync(self._fh.fileno())

    def write(self, row: Mapping[str, Any]) -> None:
        """Append one finished point (ignored if the point is already in the file)."""
        point = int(row["point"])
        if point in self.rows:
            return
        self._writer.writerow([_cell(row.get(c)) for c in self.columns])
        self._sync()
        self.rows[point] = dict(row)
        if self.parquet and time.monotonic() - self._parquet_written > PARQUET_INTERVAL_S:
            self._write_parquet()

    def note(self, **entries: Any) -> None:
        """Add ``entries`` (not fingerprinted: e.g. ``timings``) to the study description
        file ``<file>.sweep.json``."""
        for key in entries:
            if key not in UNFINGERPRINTED:
                raise ValueError(f"{key!r} would change the study's fingerprint: only "
                                 f"{', '.join(sorted(UNFINGERPRINTED))} can be noted")
        self.meta.update(entries)
        _write_atomic(self.side, json.dumps(self.meta, indent=1) + "\n")

    def write_many(self, rows: Iterable[Mapping[str, Any]]) -> None:
        """Append a task's finished points at once: one write and one ``fsync`` (points
        already in the file are ignored)."""
        fresh: dict[int, dict[str, Any]] = {}
        for row in rows:
            point = int(row["point"])
            if point not in self.rows and point not in fresh:
                fresh[point] = dict(row)
        if not fresh:
            return
        self._writer.writerows([_cell(row.get(c)) for c in self.columns]
                               for row in fresh.values())  # fmt: skip
        self._sync()
        self.rows.update(fresh)
        if self.parquet and time.monotonic() - self._parquet_written > PARQUET_INTERVAL_S:
            self._write_parquet()

    def results(self) -> SweepResults:
        """The rows written so far, sorted by point."""
        return SweepResults([self.rows[k] for k in sorted(self.rows)], self.meta, self.path)

    def _write_parquet(self) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq

        rows = self.results().rows
        arrays = {}
        for c in self.columns:
            values = [r.get(c) for r in rows]
            if c == "point":
                arrays[c] = pa.array(values, type=pa.int64())
            elif c in TEXT_COLUMNS:
                arrays[c] = pa.array(values, type=pa.string())
            else:
                arrays[c] = pa.array(values, type=pa.float64())
        tmp = self.path.with_name(self.path.name + ".tmp")
        pq.write_table(pa.table(arrays), tmp)
        os.replace(tmp, self.path)
        self._parquet_written = time.monotonic()

    def close(self, complete: bool) -> None:
        """Close the file; a complete study is rewritten sorted by point.

        Parameters
        ----------
        complete : bool
            Every point of the design is in the file.
        """
        self._fh.close()
        if not self.rows and self.created and not complete:
            # Nothing computed (e.g. the cluster could not be reached): leave no stub.
            for p in (self.journal, self.side):
                p.unlink(missing_ok=True)
            return
        if self.parquet:
            if self.rows:
                self._write_parquet()
            if complete:
                self.journal.unlink(missing_ok=True)
            return
        if complete:
            _write_atomic(self.path, self.results().to_csv_text())
