"""How long a computation will take, estimated before it starts.

Nearly all of railhunt's time goes into Runge-Kutta steps of the compiled model, so the
work of an analysis is the number of steps it takes: the simulated time it needs divided
by the step (:func:`railhunt.simulation.auto_step`, 1 ms for the paper's vehicle, far
less when a stiff yaw damper forces it down). :func:`workload` turns that into seconds
with :data:`SECONDS_PER_STEP`, measured on the reference machine; the typical simulated
time of each analysis is in :data:`SIMULATED_SECONDS`. The command line announces any
estimate above a minute before it starts, and refuses one above :data:`CONFIRM_SECONDS`
unless it is confirmed (``--yes``).

The constants are fitted to ``python benchmarks/workload.py``, which runs representative
commands and prints each estimate beside the measured time (CPU time of the process,
which a loaded machine does not inflate). On the 2-core reference machine the estimates
fall within a factor of 1.6 of the measurement either way: critical-speed 0.28 s
estimated / 0.30 s measured, simulate 100 s 0.25 / 0.19 s, frequency (5 speeds) 0.2 /
0.2 s, a 4-point sweep 1.4 / 1.25 s, bifurcation 200-2000 km/h 8.8 / 6.2 s (200-500 km/h:
9.8 s), contact at 2401 positions 5.0 / 5.0 s, and Table 1 (91 points, 2 workers) 16 / 21
s. A search's ``up to`` is its longest case (every trial to the longest run), not a
spread.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["CONFIRM_SECONDS", "NOTICE_SECONDS", "SECONDS_PER_CONTACT_POSITION", "SECONDS_PER_STEP",
           "SIMULATED_SECONDS", "Workload", "contact_workload", "workload"]  # fmt: skip

#: Wall time of one RK4 step of the 17-DOF model with its bookkeeping (s), fitted with
#: ``benchmarks/workload.py`` on the 2-core reference machine: 2.7 us in the
#: critical-speed search, 1.9 us in ``simulate`` with output every 10 ms.
SECONDS_PER_STEP = 2.5e-6

#: Wall time of the rigid contact search at one lateral position (s): 2401 positions of
#: S1002 on UIC60 took 5.0 s of CPU on the reference machine (``railhunt contact --step
#: 0.01``).
SECONDS_PER_CONTACT_POSITION = 2.1e-3

#: Estimated work above which the command line says so before it starts (s).
NOTICE_SECONDS = 60.0

#: Estimated work above which the command line asks for confirmation (``--yes``) (s).
CONFIRM_SECONDS = 3600.0

#: Typical simulated time (s) of one unit of each analysis, measured for the paper's
#: vehicle: a critical-speed trial (run over the defect until the verdict is clear,
#: 5 trials took 59 s), a hunting-frequency speed (the run and the shooting's
#: finite-difference Jacobians: 5 speeds in 0.2 s), a bifurcation diagram (the branch
#: following costs about the same whatever the speed range: 6-10 s of CPU for 200-500,
#: 200-1000 and 200-2000 km/h at 1 ms), a sweep point (a search, a frequency), and the
#: whole reproduction (66 s on 2 workers; ``quick``: 43 s in one process).
SIMULATED_SECONDS = {
    "critical-speed trial": 15.0,
    "frequency speed": 16.0,
    "bifurcation diagram": 3500.0,
    "bifurcation km/h": 3500.0 / 300.0,
    "sweep point": 8 * 15.0 + 16.0,
    "reproduce": 44_000.0,
    "reproduce quick": 14_000.0,
}


@dataclass(frozen=True)
class Workload:
    """An estimate of the work of a computation.

    Attributes
    ----------
    steps : float
        Runge-Kutta steps it takes.
    dt : float
        Their size (s).
    what : str
        What is counted, e.g. ``"8 trials of ~15 s simulated"``.
    workers : int
        Processes sharing the steps.
    most_steps : float or None
        Steps when every part runs as long as it may (None: unknown).
    per_step : float
        Wall time of one step (s).
    unit : str or None
        What a step is, in :meth:`describe` (default: ``"RK4 steps of <dt> s"``).
    """

    steps: float
    dt: float
    what: str
    workers: int = 1
    most_steps: float | None = None
    per_step: float = SECONDS_PER_STEP
    unit: str | None = None

    @property
    def seconds(self) -> float:
        """Estimated wall time (s)."""
        return self.steps * self.per_step / max(1, self.workers)

    @property
    def most_seconds(self) -> float:
        """Wall time when every part takes as long as it may (s); ``seconds`` if unknown."""
        steps = self.steps if self.most_steps is None else max(self.steps, self.most_steps)
        return steps * self.per_step / max(1, self.workers)

    @property
    def notable(self) -> bool:
        """True when the estimate (or its longest case) exceeds :data:`NOTICE_SECONDS`."""
        return self.most_seconds > NOTICE_SECONDS

    def describe(self) -> str:
        """One line: ``about 3 min (6e+07 RK4 steps of 1e-05 s: 8 trials ...)``, with ``up
        to ...`` when the longest case takes notably longer."""
        on = f" on {self.workers} workers" if self.workers > 1 else ""
        most = self.most_seconds
        upto = f", up to {duration_text(most)}" if most > 1.5 * self.seconds else ""
        unit = self.unit or f"RK4 steps of {self.dt:.2g} s"
        return (f"about {duration_text(self.seconds)}{upto}{on} ({self.steps:.2g} {unit}: "
                f"{self.what})")  # fmt: skip


def duration_text(seconds: float) -> str:
    """``"45 s"`` (below 2 min), ``"3 min"``, ``"2.5 h"`` or ``"4 days"``."""
    if not math.isfinite(seconds):
        return "forever"
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    if seconds < 3 * 86400:
        return f"{seconds / 3600:.1f} h"
    return f"{seconds / 86400:.0f} days"


def workload(simulated: float, dt: float, what: str, workers: int = 1,
             most_simulated: float | None = None) -> Workload:  # fmt: skip
    """The work of ``simulated`` seconds of model time at step ``dt`` (s).

    Parameters
    ----------
    simulated : float
        Simulated time (s), summed over every run of the computation.
    dt : float
        RK4 step (s).
    what : str
        What is counted (shown in :meth:`Workload.describe`).
    workers : int
        Processes sharing the work.
    most_simulated : float, optional
        Simulated time when every part runs as long as it may (s).
    """
    most = None if most_simulated is None else most_simulated / dt
    return Workload(simulated / dt, dt, what, workers, most)


def contact_workload(positions: int, what: str) -> Workload:
    """The work of the rigid contact search at ``positions`` lateral positions."""
    return Workload(float(positions), math.nan, what, per_step=SECONDS_PER_CONTACT_POSITION,
                    unit="contact positions")
