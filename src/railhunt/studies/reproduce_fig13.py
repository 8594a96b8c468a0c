"""Reproduction step for the paper's Fig. 13: the bifurcation type versus the blow-off force.

One bifurcation diagram per blow-off force F_u of the family (:attr:`Settings.family_kn
<railhunt.studies.records.Settings.family_kn>`, ``inf`` for no blow-off, i.e.
:data:`railhunt.paper2019.NO_BLOWOFF`), as Dask tasks when a client is given; the member
of the default vehicle is the Fig. 7a diagram, reused. The headline rows judge the paper's
statements: the type sequence as F_u grows, the Hopf speed independent of F_u, and the
lowest limit cycle rising with F_u up to the Hopf point.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

import railhunt.paper2019 as paper2019
from railhunt.paper2019 import NO_BLOWOFF
from railhunt.studies.records import Context, Step, claim

if TYPE_CHECKING:
    from railhunt.vehicle import Vehicle

__all__ = ["fig13"]


def _diagram_task(vehicle: Vehicle, speed_range_kmh: tuple[float, float]) -> Any:
    """One family member (a top-level function, so that Dask can ship it to a worker)."""
    from railhunt.analysis.continuation import bifurcation_diagram

    return bifurcation_diagram(vehicle, speed_range_kmh)


def fig13(ctx: Context) -> Step:
    """Fig. 13: one bifurcation diagram per blow-off force, and the type sequence."""
    from railhunt.plots import plot_bifurcation_family

    s = ctx.settings
    step = Step("fig13", "Fig. 13: bifurcation type versus blow-off force F_u",
                paper2019.CAPTIONS["fig13"])
    forces = [NO_BLOWOFF if math.isinf(kn) else kn * 1e3 for kn in s.family_kn]
    known = ctx.shared.get("diagram")
    done: dict[float, Any] = {}
    if known is not None and known.speed_range_kmh == tuple(s.diagram_range_kmh):
        done[ctx.vehicle.F_u] = known  # the Fig. 7a diagram is this member: reuse it
    todo = [f for f in forces if f not in done]
    members = [ctx.vehicle.replace(F_u=f) for f in todo]
    if ctx.client is not None and todo:
        futures = [ctx.client.submit(_diagram_task, m, s.diagram_range_kmh, pure=False)
                   for m in members]  # fmt: skip
        done.update(zip(todo, ctx.client.gather(futures), strict=True))
        where = f"as {len(todo)} Dask tasks"
    else:
        done.update((f, _diagram_task(m, s.diagram_range_kmh))
                    for f, m in zip(todo, members, strict=True))  # fmt: skip
        where = "one after another in this process"
    family = [(f, done[f]) for f in forces]
    step.figures.append(plot_bifurcation_family(family, ctx.out_dir / "fig13.png",
                                                wheelset="largest"))  # as Fig. 7a
    types = [d.hopf_type for _, d in family]
    sequence = [t for i, t in enumerate(types) if i == 0 or t != types[i - 1]]
    hopf = np.array([d.hopf_speed_kmh for _, d in family])
    folds = np.array([d.fold_speed_kmh for _, d in family])
    label = [("no blow-off" if f >= NO_BLOWOFF else f"{f * 1e-3:g} kN") for f in forces]
    step.shows = "; ".join(f"F_u = {lab}: {t}, lowest limit cycle {v:.1f} km/h"
                           for lab, t, v in zip(label, types, folds, strict=True))
    step.shows += f". Hopf point {hopf.min():.1f}–{hopf.max():.1f} km/h for every member."
    step.how = (f"railhunt.bifurcation_diagram {s.diagram_range_kmh[0]:g}–"
                f"{s.diagram_range_kmh[1]:g} km/h for each F_u ({len(todo)} computed {where}"
                + (", the 3 kN member reused from Fig. 7a" if len(todo) < len(forces) else "")
                + "); type by classify_hopf (tolerance max(2 km/h, 1 %)); drawn with the "
                "largest wheelset's amplitude on one scale for all panels.")
    paper = paper2019.EXPECTED
    sequence_row = paper["fu_type_sequence"]
    spread = float(hopf.max() - hopf.min())
    rising = bool(np.all(np.diff(folds) >= -0.5))
    step.headline = [
        claim(sequence_row, " → ".join(sequence), sequence == list(sequence_row.hopf_types)),
        claim(paper["fu_hopf_spread_kmh"], spread, spread < 0.5),
        claim(paper["fu_vcr_rises"], " → ".join(f"{v:.1f}" for v in folds),
              rising and abs(folds[-1] - hopf[-1]) < 0.01 * hopf[-1]),
    ]  # fmt: skip
    return step

