"""MiniProf wheel (``.whl``) and rail (``.ban``) profile files: read, check, write.

MiniProf, the hand-held profile gauge common in railway maintenance, exports a profile as
text: header lines, then columns of points in millimetres. Two layouts are in use:

* the regular one: ``Key=Value`` header lines (``Filename=``, ``MPTypeNo=``,
  ``XYPoints=``, ``ColumnDef=X,Y`` ...), then the points;
* the old one (first lines ``#MINIWHEELPROF`` / ``MINIPROF ...``): free-text header
  lines (``Stock.......:``, ``(Sd/Sh/qR)``), a blank line, then the points.

A ``"`` starts a comment (to the end of the line, so a line starting with ``"`` is a
point switched off), as do ``!`` and ``%``. ``ColumnDef`` names the columns
(``X`` lateral, ``Y`` vertical, ``A`` angle, ``C`` curvature, ``N``, ``K``; default
``X,Y``); only ``X`` and ``Y`` are used. Numbers are separated by spaces, tabs, ``,`` or
``;``.

Orientation (MiniProf's own axes, ``Y`` upward for both kinds):

* wheel: ``X`` from the flange back (the wheel's inner face, ``X = 0``) toward the field
  side, ``Y`` up toward the flange tip (the radius increase). In railhunt's profile
  coordinates (:mod:`railhunt.contact.profiles`) ``y = X - flange_back`` (the tape circle
  ``flange_back`` = 70 mm from the inner face, EN 13715) and ``z = Y - Y(tape circle)``:
  ``z = 0`` at ``y = 0`` whatever height the gauge gave the tape line. The points on the
  back face itself (``X`` within :data:`BACK_FACE` of the flange back, where the gauge
  runs down the vertical face and ``X`` jitters back and forth) are dropped: no rail
  reaches them.
* rail: ``X`` lateral, the gauge face at the lower ``X`` (pass ``mirror_y`` for a file
  whose gauge face is at the higher ``X``), ``Y`` up; ``y = X``, ``z = Y_top - Y`` (depth
  below the highest point). The head must be upright in its own axes, as
  :func:`railhunt.contact_geometry` inclines it.

Everything else is checked and refused with one line naming the file and the line: a
point line that is not numbers, a number that is not finite, a column count that differs
from ``ColumnDef``, a header keyword among the points, a point that goes back against the
profile's direction (the profile folds back or crosses itself), too few points. The
checks of :mod:`railhunt.contact.profile_checks` (units, kind) follow in
:func:`railhunt.read_profile`. Nothing here imports :mod:`railhunt.contact.profiles`
(which calls it): errors are ``ValueError`` and arrays are SI (m).
"""

from __future__ import annotations

import math
import re

import numpy as np

__all__ = ["BACK_FACE", "EXTENSIONS", "is_miniprof", "miniprof_text", "parse_miniprof"]

#: File extensions of MiniProf exports: wheel and rail.
EXTENSIONS = {".whl": "wheel", ".ban": "rail"}
#: Lateral band (m) next to a wheel's flange back whose points lie on the back face.
BACK_FACE = 0.5e-3
#: How far (m) the flange-back end of a wheel's points may lie from ``X = 0``.
BACK_OFFSET_MAX = 2e-3
#: A lateral step (m) back against the profile's direction up to which a point is taken
#: as measured on a near-vertical face (the gauge's lateral reading jitters) and dropped;
#: a point further back is a fold of the profile.
JITTER = 0.05e-3

_NUMBER = re.compile(r"^[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?$")
_SPLIT = re.compile(r"[,;\s]+")
_KEY = re.compile(r"^\s*([A-Za-z_][\w .]*?)\s*=(.*)$")
_HEADER_MARKS = re.compile(r"^\s*(#MINIWHEELPROF|#MINIRAILPROF|MINIPROF\b|\[FileInfo\])",
                           re.IGNORECASE)  # fmt: skip
_KEYS = re.compile(r"^\s*(ColumnDef|XYPoints|MPTypeNo|MPSerNo|ProgramName|RefPoint\d)\s*=",
                   re.IGNORECASE | re.MULTILINE)  # fmt: skip


def is_miniprof(text: str, suffix: str) -> bool:
    """True for a MiniProf export: its extension (``.whl``, ``.ban``), the marks of its
    first lines (``#MINIWHEELPROF``, ``MINIPROF``) or MiniProf header keywords
    (``ColumnDef=``, ``XYPoints=``, ``MPTypeNo=`` ...)."""
    if suffix.lower() in EXTENSIONS:
        return True
    head = text.splitlines()[:3]
    return any(_HEADER_MARKS.match(line) for line in head) or bool(_KEYS.search(text))


def _strip(line: str) -> str:
    for mark in '"!%':
        line = line.split(mark, 1)[0]
    return line.strip()


def _columns(value: str, number: int, where: str) -> tuple[int, int, int]:
    names = [c.strip().upper() for c in _SPLIT.split(value.strip()) if c.strip()]
    if "X" not in names or "Y" not in names:
        raise ValueError(f"profile file {where!r}: line {number} ColumnDef={value.strip()!r} "
                         "names no X and Y column: a MiniProf profile needs both "
                         "(e.g. ColumnDef=X,Y)")  # fmt: skip
    return names.index("X"), names.index("Y"), len(names)


def _points(text: str, where: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict]:
    """The X, Y columns (mm), the line number of each point and the header values."""
    lines = text.splitlines()
    if lines and _HEADER_MARKS.match(lines[0]) and "[fileinfo]" in lines[0].lower():
        raise ValueError(f"profile file {where!r}: line 1 starts a multi-part MiniProf file "
                         "(.mpt, [FileInfo]): export each profile as a .whl or .ban "
                         "file")  # fmt: skip
    header: dict[str, str] = {}
    ix, iy, ncol, ncol_line = 0, 1, 0, 0
    xs, ys, where_from = [], [], []
    data_from = 0
    for number, raw in enumerate(lines, start=1):
        s = _strip(raw)
        if not s:
            continue
        key = _KEY.match(s)
        if key:
            if xs:
                raise ValueError(f"profile file {where!r}: line {number} {s!r} is a header "
                                 f"line among the points (which start at line {data_from}): "
                                 "is the file two files in one?")  # fmt: skip
            name, value = key.group(1).strip(), key.group(2).strip()
            header[name] = value
            if name.lower() == "columndef":
                ix, iy, ncol = _columns(value, number, where)
                ncol_line = number
            continue
        parts = [p for p in _SPLIT.split(s) if p]
        numeric = all(_NUMBER.match(p) for p in parts)
        if not xs:
            if not numeric or len(parts) < 2:
                continue  # a free-text header line (old layout)
            data_from = number
        if not numeric or len(parts) < 2:
            bad = next((p for p in parts if not _NUMBER.match(p)), parts[0])
            raise ValueError(f"profile file {where!r}: line {number} {s!r} is not a point: "
                             f"{bad!r} is not a number (the points, from line {data_from}, "
                             "are X Y in mm)")  # fmt: skip
        if ncol and len(parts) != ncol:
            hint = (" (decimal commas? write decimal points)" if "," in raw and
                    len(parts) == 2 * ncol else "")  # fmt: skip
            raise ValueError(f"profile file {where!r}: line {number} {s!r} has {len(parts)} "
                             f"values but ColumnDef (line {ncol_line}) names {ncol}{hint}")
        values = [float(p) for p in parts]
        if not all(math.isfinite(v) for v in values):
            raise ValueError(f"profile file {where!r}: line {number} {s!r} holds a value "
                             "that is not finite")  # fmt: skip
        if max(ix, iy) >= len(values):
            raise ValueError(f"profile file {where!r}: line {number} {s!r} has no column "
                             f"{max(ix, iy) + 1} (ColumnDef names X and Y there)")
        xs.append(values[ix])
        ys.append(values[iy])
        where_from.append(number)
    if not xs:
        raise ValueError(f"profile file {where!r} holds no points: a MiniProf file is header "
                         "lines, then lines of X Y in mm")  # fmt: skip
    return np.array(xs), np.array(ys), np.array(where_from), header


def _fold(y: np.ndarray, lines: np.ndarray, where: str, repair: bool,
          meta: dict) -> np.ndarray:  # fmt: skip
    """Indices of the points kept. A point less than :data:`JITTER` behind the furthest
    one so far is dropped (a near-vertical face, where the gauge's lateral reading
    jitters); one further back is a fold: refused, naming its line (with ``repair``,
    dropped)."""
    keep = np.ones(y.size, dtype=bool)
    top = y[0]
    folds = []
    for i in range(1, y.size):
        if y[i] <= top:
            keep[i] = False
            if top - y[i] > JITTER:
                if not repair:
                    raise ValueError(
                        f"profile file {where!r}: line {lines[i]}: the profile folds back: "
                        f"its lateral position {y[i] * 1e3:.4g} mm lies "
                        f"{(top - y[i]) * 1e3:.3g} mm behind a point before it (X "
                        f"{top * 1e3:.4g} mm), so it crosses itself or is not one profile; "
                        "fix the file, or read it with repair=True (--repair) to drop such "
                        "points")  # fmt: skip
                folds.append(int(lines[i]))
        else:
            top = y[i]
    if folds:
        meta["miniprof.dropped_fold_lines"] = folds
    if np.count_nonzero(~keep) > len(folds):
        meta["miniprof.dropped_jitter_points"] = int(np.count_nonzero(~keep)) - len(folds)
    return np.flatnonzero(keep)


def _ends(x: np.ndarray, h: np.ndarray) -> tuple[int, int]:
    """The points from the widest point at each end inward: a run beyond it that lies
    wholly lower (under a rail's head, a wheel's outer chamfer) is dropped."""
    lo, hi = int(np.argmin(x)), int(np.argmax(x))
    first = lo if lo > 0 and np.all(h[:lo] < h[lo]) else 0
    last = hi if hi < x.size - 1 and np.all(h[hi + 1:] < h[hi]) else x.size - 1
    return first, max(last, first)


def parse_miniprof(
    text: str, kind: str, where: str, *, flange_back: float = 0.070,
    mirror_y: bool = False, repair: bool = False,
) -> tuple[np.ndarray, np.ndarray, dict]:  # fmt: skip
    """Points of a MiniProf file in railhunt's profile coordinates (module docstring).

    Parameters
    ----------
    text : str
        The file's text.
    kind : {"wheel", "rail"}
        What the file is.
    where : str
        The file, for the messages.
    flange_back : float
        A wheel's tape circle from its flange back (m).
    mirror_y : bool
        Negate ``X`` first (a wheel measured with ``X`` negative toward the field side, a
        rail whose gauge face is at the higher ``X``).
    repair : bool
        Drop points that fold back (with the line of the first one in ``meta``) instead
        of refusing the file.

    Returns
    -------
    tuple
        ``(y, z, meta)``: lateral and vertical coordinates (m), ``y`` increasing, and
        the header values with what was done (``miniprof.*`` keys).

    Raises
    ------
    ValueError
        One line naming the file and the line (module docstring).
    """
    x_mm, y_mm, lines, header = _points(text, where)
    x = -x_mm * 1e-3 if mirror_y else x_mm * 1e-3
    h = y_mm * 1e-3
    meta: dict = {"format": "miniprof", **{f"miniprof.{k}": v for k, v in header.items()}}
    if x.size >= 2 and x[-1] < x[0]:  # points listed from the far end: run them up in X
        x, h, lines = x[::-1], h[::-1], lines[::-1]
    if kind == "wheel":
        tip = int(np.argmax(h))
        if x[tip] - x.min() > 0.5 * (x.max() - x.min()):
            raise ValueError(f"profile file {where!r}: line {lines[tip]}: the flange tip "
                             f"(highest point) is at X = {x_mm[np.argmax(y_mm)]:.4g} mm, on "
                             "the field side of the wheel: MiniProf wheels run from the "
                             "flange back (X = 0) to the field side; read a mirrored file "
                             "with mirror_y=True")  # fmt: skip
        back = float(x[:tip + 1].min())
        if abs(back) > BACK_OFFSET_MAX:
            raise ValueError(f"profile file {where!r}: line {lines[int(np.argmin(x))]}: the "
                             f"wheel's flange back is at X = {back * 1e3:.4g} mm, not at 0 "
                             f"(within {BACK_OFFSET_MAX * 1e3:g} mm): MiniProf measures X "
                             "from the flange back; is it a MiniProf wheel file?")  # fmt: skip
        on_face = np.flatnonzero(x[:tip] <= back + BACK_FACE)
        first = int(on_face[-1]) + 1 if on_face.size else 0
        if first:
            meta["miniprof.back_face_points"] = first
        x, h, lines = x[first:], h[first:], lines[first:]
    first, last = _ends(x, h)
    if first or last < x.size - 1:
        meta["miniprof.end_points_dropped"] = first + x.size - 1 - last
    x, h, lines = x[first:last + 1], h[first:last + 1], lines[first:last + 1]
    kept = _fold(x, lines, where, repair, meta)
    x, h = x[kept], h[kept]
    if x.size < 4:
        raise ValueError(f"profile file {where!r} has only {x.size} usable points: too few "
                         "for a profile")  # fmt: skip
    if kind == "wheel":
        y = x - flange_back
        if not (y[0] <= 0.0 <= y[-1]):
            raise ValueError(f"profile file {where!r}: the wheel's points span X = "
                             f"{x[0] * 1e3:.4g} to {x[-1] * 1e3:.4g} mm and miss its tape "
                             f"circle (X = {flange_back * 1e3:g} mm from the flange back)")
        tape = float(np.interp(0.0, y, h))
        meta["miniprof.tape_height_mm"] = tape * 1e3
        return y, h - tape, meta
    top = float(np.max(h))
    meta["miniprof.top_height_mm"] = top * 1e3
    return x, top - h, meta


def miniprof_text(y: np.ndarray, z: np.ndarray, kind: str, *, name: str = "",
                  comment: str = "", flange_back: float = 0.070) -> str:  # fmt: skip
    """A MiniProf file (regular layout) of a profile in railhunt's coordinates (m).

    The inverse of :func:`parse_miniprof`: ``X = y + flange_back``, ``Y = z`` for a wheel;
    ``X = y``, ``Y = -z`` for a rail; points with four decimals in mm (0.1 um), as
    MiniProf writes them. ``comment`` lines are written as ``"`` comments first.
    """
    y = np.asarray(y, dtype=np.float64)
    z = np.asarray(z, dtype=np.float64)
    if kind == "wheel":
        x_mm, h_mm = (y + flange_back) * 1e3, z * 1e3
    else:
        x_mm, h_mm = y * 1e3, -z * 1e3
    lines = [f'" {line}'.rstrip() for line in comment.splitlines()]
    lines += [f"Filename={name}", "ProgramName=railhunt", f"XYPoints={y.size}",
              "XOffset=0.0000", "YOffset=0.0000", "ColumnDef=X,Y", ""]  # fmt: skip
    lines += [f"{a:.4f} {b:.4f}" for a, b in zip(x_mm, h_mm, strict=True)]
    return "\n".join(lines) + "\n"
