"""How good are the work estimates? Each command's announced estimate against its time.

Run from the repository root::

    python benchmarks/workload.py             # every case once (a few minutes)
    python benchmarks/workload.py --only bifurcation

Each case runs the command in this process with the announcement threshold set to 0 s,
so that the estimate is printed whatever its size, after a first short run has loaded the
compiled code. The table shows the estimate, the measured wall time and their ratio; the
constants of ``railhunt/workload.py`` are fitted to these ratios (docs/workload.md). This
is a report, not a test: the exit code is 0 whatever the outcome.
"""

from __future__ import annotations

import argparse
import re
import tempfile
import time
from pathlib import Path

from click.testing import CliRunner

import railhunt.workload as workload
from railhunt.cli.app import main

#: name -> command-line arguments (OUT: a fresh file in a temporary folder).
CASES = {
    "critical-speed": ["critical-speed"],
    "critical-speed C_d1=300": ["critical-speed", "--set", "C_d1=20e3"],
    "frequency": ["frequency", "--from", "250", "--to", "450", "--step", "50"],
    "bifurcation --to 2000": ["bifurcation", "--to", "2000"],
    "simulate 100 s": ["simulate", "--speed", "300", "--duration", "100", "--output-dt",
                       "0.01"],
    "contact --step 0.01": ["contact", "--step", "0.01"],
    "sweep 4 points": ["sweep", "C_d1", "--from", "1e5", "--to", "4e5", "--num", "4",
                       "--workers", "1", "--out", "OUT"],
    "sweep --table1": ["sweep", "--table1", "--out", "OUT"],
}


def run(args: list[str], folder: Path) -> tuple[float | None, float, float, int]:
    """(estimated s, measured wall s, CPU s of this process, exit code) of one command."""
    args = [str(folder / f"out{time.monotonic_ns()}.csv") if a == "OUT" else a for a in args]
    workload.NOTICE_SECONDS = 0.0
    shown = workload.duration_text
    workload.duration_text = lambda seconds: f"{seconds:.4g} s"
    try:
        runner = CliRunner(mix_stderr=False)
    except TypeError:
        runner = CliRunner()
    start, cpu = time.perf_counter(), time.process_time()
    result = runner.invoke(main, args)
    elapsed, cpu = time.perf_counter() - start, time.process_time() - cpu
    workload.NOTICE_SECONDS = 60.0
    workload.duration_text = shown
    found = re.search(r"this will take about ([\d.e+-]+) s", result.stderr)
    estimate = float(found.group(1)) if found else None
    return estimate, elapsed, cpu, result.exit_code


def main_() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", help="run the cases whose name contains this text")
    opts = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        run(["simulate", "--speed", "300", "--duration", "1"], folder)  # load compiled code
        print(f"{'case':26s} {'estimate':>9s} {'wall':>8s} {'CPU':>8s} {'est/wall':>8s}")
        for name, args in CASES.items():
            if opts.only and opts.only not in name:
                continue
            est, took, cpu, code = run(args, folder)
            ratio = f"{est / took:8.2f}" if est else "       -"
            shown = f"{est:8.2f}s" if est is not None else "        -"
            print(f"{name:26s} {shown} {took:7.2f}s {cpu:7.2f}s {ratio}"
                  + (f"  exit {code}" if code else ""), flush=True)


if __name__ == "__main__":
    main_()
