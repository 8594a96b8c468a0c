"""The benchmark table: one row per case (its time, target and verdict), the median of
repeated timings, and the table printed (rich on a terminal, plain text otherwise).

Used by ``benchmarks/run.py`` and ``benchmarks/global_studies.py``.
"""

from __future__ import annotations

import math
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass

__all__ = ["Row", "fmt_time", "median_time", "print_table"]


@dataclass
class Row:
    case: str
    seconds: float
    target: float | None = None  # seconds; None: no target
    note: str = ""

    @property
    def verdict(self) -> str:
        if self.target is None:
            return "-"
        if not math.isfinite(self.seconds):
            return "FAIL"
        return "pass" if self.seconds <= self.target else "FAIL"


def median_time(fn: Callable[[], object], repeat: int) -> tuple[float, object]:
    """Median wall time (s) of ``fn`` over ``repeat`` calls after one warm-up call."""
    result = fn()  # warm-up: JIT compilation or cache load
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), result


def fmt_time(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "n/a"
    if seconds < 1.0:
        return f"{seconds * 1e3:.1f} ms"
    return f"{seconds:.2f} s"


def print_table(rows: list[Row]) -> None:
    headers = ("case", "time (median)", "target", "pass/fail")
    cells = [
        (
            r.case,
            fmt_time(r.seconds),
            "-" if r.target is None else f"<= {fmt_time(r.target)}",
            r.verdict,
        )
        for r in rows
    ]
    if sys.stdout.isatty():
        try:
            from rich.console import Console
            from rich.table import Table
        except ImportError:
            pass
        else:
            table = Table(title="railhunt benchmarks")
            for h in headers:
                table.add_column(h, justify="left" if h == "case" else "right")
            for c in cells:
                style = "red" if c[3] == "FAIL" else None
                table.add_row(*c, style=style)
            Console().print(table)
            return
    widths = [max(len(h), *(len(c[i]) for c in cells)) for i, h in enumerate(headers)]
    line = "  ".join(
        h.ljust(w) if i == 0 else h.rjust(w)
        for i, (h, w) in enumerate(zip(headers, widths, strict=True))
    )
    print(line)
    print("-" * len(line))
    for c in cells:
        print(
            "  ".join(
                s.ljust(w) if i == 0 else s.rjust(w)
                for i, (s, w) in enumerate(zip(c, widths, strict=True))
            )
        )
