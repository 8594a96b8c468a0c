"""Is a profile file what it claims to be? The checks :func:`read_profile` applies.

A profile file that parses is not yet a profile: decimal commas split every number in
two, a rail head passed as the wheel (or the other way round) gives a contact search
that fails far away, a profile in metres is a speck of a millimetre, coordinates a
million times too large ask for gigabytes. Each check below names the file and the
likely mistake; a single point far off its neighbours (a measuring spike) is kept with a
warning. Profile coordinates are SI (m) in the convention of
:mod:`railhunt.contact.profiles`.
"""

from __future__ import annotations

import re
import warnings

import numpy as np

__all__ = ["MIN_POINTS", "check_decimal_commas", "check_kind", "check_shape"]

#: Fewest points of a profile file: a wheel or rail is measured every 0.1-1 mm over
#: 70-150 mm, so a few points cannot give its contact angles.
MIN_POINTS = 20
#: Lateral extent (m) of a plausible profile: below it the values are metres read as mm,
#: above it they are not millimetres at all.
SPAN = (1e-3, 0.5)
#: Vertical extent (m) above which the values are not millimetres of a profile.
HEIGHT_MAX = 0.2
#: How far (m) both ends of a wheel must lie below a crown in its middle, or both ends of
#: a rail above a peak in its middle, for it to be the other kind of profile.
OTHER_KIND = 5e-3
#: A point that stands this far (m) above or below both its neighbours, a peak or a pit
#: between them, is a measuring spike.
SPIKE = 1e-3

_COMMA_NUMBER = r"[-+]?\d+,\d+"
_COMMA_ROW = re.compile(rf"^\s*{_COMMA_NUMBER}(?:\s*[;\t ]\s*{_COMMA_NUMBER})+\s*$")
_KINDS = {1: "wheel", 0: "rail"}


def check_decimal_commas(text: str, where: str) -> None:
    """Refuse ``y z`` rows written with decimal commas (``-30,5 1,25``): read as columns
    they would be four numbers, ``y = -30`` and ``z = 5``."""
    rows = [line for line in text.splitlines()
            if line.strip() and line.strip()[0] not in "#!%"]  # fmt: skip
    for number, line in enumerate(text.splitlines(), start=1):
        if _COMMA_ROW.match(line):
            fixed = line.strip().replace(",", ".")
            raise ValueError(
                f"profile file {where!r}: line {number} {line.strip()!r} writes decimal "
                f"commas ({sum(bool(_COMMA_ROW.match(r)) for r in rows)} of its "
                f"{len(rows)} rows); write decimal points ({fixed!r}), the columns "
                "separated by spaces, a tab, ';' or ','"
            )


def check_kind(meta: dict, kind: str, where: str) -> None:
    """Refuse a SIMPACK file whose header says the other kind (``type = 1`` wheel,
    ``0`` rail) than the one it is given as."""
    if "type" not in meta:
        return
    filed = _KINDS.get(int(meta["type"]))
    if filed is not None and filed != kind:
        raise ValueError(f"profile file {where!r} is a {filed} profile (SIMPACK header type = "
                         f"{int(meta['type'])}) but is given as the {kind}: give it as the "
                         f"{filed} (--{filed}), or give a {kind} profile file")  # fmt: skip


def check_shape(y: np.ndarray, z: np.ndarray, kind: str, where: str) -> None:
    """Refuse a profile whose points cannot be a ``kind`` profile in mm; warn about a
    single spike.

    Parameters
    ----------
    y, z : numpy.ndarray
        The file's points (m), in the file's order.
    kind : {"wheel", "rail"}
        What the profile is given as.
    where : str
        The file, for the messages.

    Raises
    ------
    ValueError
        Too few points, values in metres (or not in millimetres), or the shape of the
        other kind of profile.
    """
    n = y.size
    if n < MIN_POINTS:
        raise ValueError(f"profile file {where!r} has only {n} points: a {kind} profile is "
                         f"measured every 0.1-1 mm over 70-150 mm (at least {MIN_POINTS} "
                         "points) to give its contact angles; is it the right file?")  # fmt: skip
    span = float(np.max(y) - np.min(y))
    height = float(np.max(z) - np.min(z))
    if span < SPAN[0]:
        raise ValueError(f"profile file {where!r} spans only {span * 1e3:.3g} mm laterally: "
                         "are its values in metres? Profile files are in millimetres "
                         f"(a {kind} profile spans 70-150 mm); multiply them by 1000")  # fmt: skip
    if span > SPAN[1] or height > HEIGHT_MAX:
        raise ValueError(f"profile file {where!r} spans {span * 1e3:.4g} mm laterally and "
                         f"{height * 1e3:.4g} mm vertically: not millimetres of a {kind} "
                         "profile (70-150 mm wide, tens of mm high); check the file's "
                         "unit")  # fmt: skip
    order = np.argsort(y, kind="stable")
    ys, zs = y[order], z[order]
    ends = (float(zs[0]), float(zs[-1]))
    if kind == "wheel":
        i = int(np.argmin(zs))
        drop = (ends[0] - zs[i], ends[1] - zs[i])
        if min(drop) > OTHER_KIND:
            raise ValueError(
                f"profile file {where!r} given as the wheel looks like a rail head: a crown "
                f"at y = {ys[i] * 1e3:.3g} mm with both sides falling away by "
                f"{drop[0] * 1e3:.3g} and {drop[1] * 1e3:.3g} mm (a wheel rises only toward "
                "its flange); give it as the rail (--rail)"
            )
    else:
        j = int(np.argmax(zs))
        rise = (zs[j] - ends[0], zs[j] - ends[1])
        if min(rise) > OTHER_KIND:
            raise ValueError(
                f"profile file {where!r} given as the rail looks like a wheel: a flange at "
                f"y = {ys[j] * 1e3:.3g} mm standing {rise[0] * 1e3:.3g} and "
                f"{rise[1] * 1e3:.3g} mm above its two ends (a rail head falls away on "
                "both sides of its crown); give it as the wheel (--wheel)"
            )
    _warn_spikes(ys, zs, order, where)


def _warn_spikes(ys: np.ndarray, zs: np.ndarray, order: np.ndarray, where: str) -> None:
    """Warn about measuring spikes: points that stand more than :data:`SPIKE` above (or
    below) both neighbours. A profile's own peaks and pits (a flange tip, a hollow) are
    sampled finely enough to rise and fall far less from one point to the next."""
    if ys.size < 3:
        return
    before = zs[1:-1] - zs[:-2]
    after = zs[1:-1] - zs[2:]
    peak = (np.sign(before) == np.sign(after)) & (np.minimum(np.abs(before), np.abs(after))
                                                  > SPIKE)  # fmt: skip
    off = np.where(np.abs(before) < np.abs(after), before, after)
    spikes = np.flatnonzero(peak)
    if spikes.size == 0:
        return
    k = int(spikes[np.argmax(np.abs(off[spikes]))])
    point = int(order[k + 1]) + 1  # 1-based, in the file's order
    more = f" ({spikes.size} such points)" if spikes.size > 1 else ""
    warnings.warn(
        f"profile file {where!r}: point {point} (y = {ys[k + 1] * 1e3:.4g} mm) stands "
        f"{off[k] * 1e3:+.3g} mm off both its neighbours{more}: a measuring spike? "
        "It is kept; remove it from the file if it is one",
        stacklevel=5,
    )
